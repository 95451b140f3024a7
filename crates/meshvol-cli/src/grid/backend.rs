//! `grid --backend`: the cell volumes on the CPU or on an OpenCL device (the same
//! bits: crates/meshvol-opencl), and which one `auto` takes.

use crate::input::Progress;
use clap::{Args, ValueEnum};
use meshvol::grid::{cell_volumes_with, Grid};
use meshvol::Surface;
use meshvol_opencl::{auto_choice, devices, Device, Listing, Options};

#[derive(Args)]
pub struct BackendArgs {
    /// Where the cell volumes are computed: `cpu`; `opencl`, an OpenCL device (any kind,
    /// PoCL's CPU device included; `meshvol devices` lists them); `auto`, an OpenCL GPU
    /// with f64 when there is one, else the CPU. The same bits either way. --moments,
    /// --union and .zarr outputs run on the CPU.
    #[arg(long, value_enum, default_value_t = Backend::Auto)]
    backend: Backend,
    /// The OpenCL device to use, by its number in `meshvol devices` (default: the one
    /// `auto` takes, or with --backend opencl the first with f64).
    #[arg(long, value_name = "N")]
    opencl_device: Option<usize>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    Cpu,
    Opencl,
    Auto,
}

impl BackendArgs {
    /// Refuses `--backend opencl` (or `--opencl-device`) for what only the CPU computes:
    /// `what` names it (`"--moments"`).
    pub fn cpu_only(&self, what: &str) -> Result<(), String> {
        if self.backend == Backend::Opencl || self.opencl_device.is_some() {
            return Err(format!(
                "{what} runs on the CPU only: leave out --backend opencl and --opencl-device \
                 (the OpenCL grid computes cell volumes and fractions into .npy, .npz, .vti \
                 or .csv)"
            ));
        }
        Ok(())
    }

    /// The cell volumes of `surface` on `grid`, where the backend says. `auto` falls back
    /// to the CPU, with a warning, when the OpenCL device fails.
    pub fn cell_volumes<S: Surface + ?Sized>(
        &self,
        surface: &S,
        grid: &Grid,
        progress: &Progress,
    ) -> Result<Vec<f64>, String> {
        let on_cpu = || {
            let hook = progress.kernel("computing cell volumes".to_string());
            cell_volumes_with(surface, grid, &hook).map_err(|e| e.to_string())
        };
        let index = match self.backend {
            Backend::Cpu => return on_cpu(),
            Backend::Opencl => self.opencl_device.map_or_else(first_with_f64, Ok)?,
            Backend::Auto => match self.opencl_device.map_or_else(auto_device, |n| Ok(Some(n))) {
                Ok(Some(index)) => index,
                Ok(None) => return on_cpu(),
                Err(e) => {
                    progress.warn("--backend auto", &format!("{e}; computing on the CPU"));
                    return on_cpu();
                }
            },
        };
        progress.stage_all("computing cell volumes (OpenCL)");
        let gpu = Device::open(index)
            .and_then(|mut device| device.cell_volumes(surface, grid, Options::default()));
        match (gpu, self.backend) {
            (Ok(volumes), _) => Ok(volumes),
            (Err(e), Backend::Auto) => {
                progress.warn("--backend auto", &format!("{e}; computing on the CPU"));
                on_cpu()
            }
            (Err(e), _) => Err(e.to_string()),
        }
    }
}

/// `--backend opencl` without `--opencl-device`: the first device with f64.
fn first_with_f64() -> Result<usize, String> {
    match devices().map_err(|e| e.to_string())? {
        Listing::NoLibrary => Err(meshvol_opencl::Error::NoLibrary.to_string()),
        Listing::Devices(list) => list.iter().position(|d| d.fp64).ok_or_else(|| {
            format!(
                "no OpenCL device with 64-bit floating point (cl_khr_fp64) among the {} found \
                 (meshvol devices lists them): use --backend cpu",
                list.len()
            )
        }),
    }
}

/// `--backend auto`: the device `auto_choice` takes, or none.
fn auto_device() -> Result<Option<usize>, String> {
    match devices().map_err(|e| e.to_string())? {
        Listing::NoLibrary => Ok(None),
        Listing::Devices(list) => Ok(auto_choice(&list)),
    }
}
