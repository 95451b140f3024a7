//! Where a grid's cell volumes and cut cells run, as `grid --backend` and Python's
//! `backend=` ask: the one choice both make (`cpu`, `opencl`, `auto`), and the run with
//! `auto`'s fallback to the CPU.

use crate::{auto_choice, devices, Device, Error, Listing, Options};
use meshvol::grid::{CutCells, Grid, Region};
use meshvol::progress::Progress;
use meshvol::Surface;

/// Where the cell volumes are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// The CPU kernel.
    Cpu,
    /// An OpenCL device, of any kind (PoCL's CPU device included).
    Opencl,
    /// An OpenCL GPU with f64 when there is one, else the CPU; a device that fails
    /// falls back to the CPU with a warning.
    Auto,
}

impl std::str::FromStr for Backend {
    type Err = String;
    fn from_str(s: &str) -> Result<Backend, String> {
        match s {
            "cpu" => Ok(Backend::Cpu),
            "opencl" => Ok(Backend::Opencl),
            "auto" => Ok(Backend::Auto),
            _ => Err(format!("backend '{s}': one of cpu, opencl, auto")),
        }
    }
}

/// A backend and the device asked for (`--opencl-device`, `opencl_device=`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Where {
    pub backend: Backend,
    pub device: Option<usize>,
}

impl Where {
    /// Refuses an OpenCL device for `what` (`"--union"`), which only the CPU computes,
    /// saying `instead` (how the caller asks for the CPU); `auto` takes the CPU for it.
    pub fn cpu_only(&self, what: &str, instead: &str) -> Result<(), String> {
        if self.backend == Backend::Opencl || self.device.is_some() {
            return Err(format!(
                "{what} runs on the CPU only: {instead} (the OpenCL grid computes cell \
                 volumes, fractions and the cut cells' default arrays)"
            ));
        }
        Ok(())
    }

    /// The device the cell volumes run on (`None`: the CPU), before any work: `opencl`
    /// without an OpenCL library or an f64 device is an error naming what is missing;
    /// `auto` without one is the CPU.
    pub fn device(&self) -> Result<Option<usize>, String> {
        let listing = || devices().map_err(|e| e.to_string());
        match (self.backend, self.device) {
            (Backend::Cpu, _) => Ok(None),
            (Backend::Opencl, Some(n)) => match listing()? {
                Listing::NoLibrary => Err(Error::NoLibrary.to_string()),
                Listing::Devices(list) => match list.get(n) {
                    None => Err(Error::NoDevice { index: n, count: list.len() }.to_string()),
                    Some(d) if !d.fp64 => {
                        Err(Error::NoFp64 { index: n, name: d.name.clone() }.to_string())
                    }
                    Some(_) => Ok(Some(n)),
                },
            },
            (Backend::Opencl, None) => match listing()? {
                Listing::NoLibrary => Err(Error::NoLibrary.to_string()),
                Listing::Devices(list) => match list.iter().position(|d| d.fp64) {
                    Some(n) => Ok(Some(n)),
                    None => Err(format!(
                        "no OpenCL device with 64-bit floating point (cl_khr_fp64) among the {} \
                         found (meshvol devices lists them): use the CPU backend",
                        list.len()
                    )),
                },
            },
            (Backend::Auto, Some(n)) => Ok(Some(n)),
            (Backend::Auto, None) => match listing()? {
                Listing::NoLibrary => Ok(None),
                Listing::Devices(list) => Ok(auto_choice(&list)),
            },
        }
    }

    /// The cell volumes of `surface` on `region` of `grid` where this says: on the CPU
    /// by `cpu`, or on the device (the same bits; its stages told to `progress`). With
    /// `auto`, a device that cannot be listed or fails, at any stage of any slab, gives
    /// `warn` the reason and the CPU computes the whole region again: no cell of a
    /// failed run is kept.
    pub fn cell_volumes<S: Surface + ?Sized>(
        &self,
        surface: &S,
        grid: &Grid,
        region: &Region,
        progress: &dyn Progress,
        cpu: impl FnOnce() -> Result<Vec<f64>, String>,
        warn: impl Fn(&str),
    ) -> Result<Vec<f64>, String> {
        let gpu = |device: &mut Device| {
            device.cell_volumes_region_with(surface, grid, region, Options::default(), progress)
        };
        self.run(progress, gpu, cpu, warn)
    }

    /// The cut cells (`cut_cells_region`, no extras) of `surface` on `region` of `grid`
    /// where this says, as [`Where::cell_volumes`]: on the device, the sweeps and each
    /// column's sums, then the x and y apertures and the surface centroids on the CPU
    /// (the same bits); `auto`'s fallback recomputes it all on the CPU.
    pub fn cut_cells<S: Surface + ?Sized>(
        &self,
        surface: &S,
        grid: &Grid,
        region: &Region,
        progress: &dyn Progress,
        cpu: impl FnOnce() -> Result<CutCells, String>,
        warn: impl Fn(&str),
    ) -> Result<CutCells, String> {
        let gpu = |device: &mut Device| {
            device.cut_cells_region_with(surface, grid, region, Options::default(), progress)
        };
        self.run(progress, gpu, cpu, warn)
    }

    /// `gpu` on the device this chooses, or `cpu`; `auto` falls back to `cpu` (after
    /// `warn`) where the device cannot be listed, opened or run.
    fn run<T>(
        &self,
        progress: &dyn Progress,
        gpu: impl FnOnce(&mut Device) -> Result<T, Error>,
        cpu: impl FnOnce() -> Result<T, String>,
        warn: impl Fn(&str),
    ) -> Result<T, String> {
        let fallback = |e: String, cpu: Box<dyn FnOnce() -> Result<T, String> + '_>| {
            warn(&format!("{e}; computing on the CPU"));
            cpu()
        };
        let index = match (self.device(), self.backend) {
            (Ok(Some(index)), _) => index,
            (Ok(None), _) => return cpu(),
            (Err(e), Backend::Auto) => return fallback(e, Box::new(cpu)),
            (Err(e), _) => return Err(e),
        };
        progress.stage("OpenCL: opening the device");
        let result = Device::open(index).and_then(|mut device| gpu(&mut device));
        match (result, self.backend) {
            (Ok(values), _) => Ok(values),
            (Err(e), Backend::Auto) => fallback(e.to_string(), Box::new(cpu)),
            (Err(e), _) => Err(e.to_string()),
        }
    }
}
