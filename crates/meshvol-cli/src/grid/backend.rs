//! `grid --backend`: the cell volumes on the CPU or on an OpenCL device (the same
//! bits: crates/meshvol-opencl), and which one `auto` takes.

use crate::input::Progress;
use clap::{Args, ValueEnum};
use meshvol::grid::{cell_volumes_with, Grid};
use meshvol::Surface;
use meshvol_opencl::Where;

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
    /// The choice the OpenCL crate makes of these flags (the one Python's `backend=`
    /// makes too).
    pub fn choice(&self) -> Where {
        let backend = match self.backend {
            Backend::Cpu => meshvol_opencl::Backend::Cpu,
            Backend::Opencl => meshvol_opencl::Backend::Opencl,
            Backend::Auto => meshvol_opencl::Backend::Auto,
        };
        Where { backend, device: self.opencl_device }
    }

    /// Whether `--backend opencl` was asked for.
    pub fn forces_opencl(&self) -> bool {
        self.backend == Backend::Opencl
    }

    /// Refuses `--backend opencl` (or `--opencl-device`) for what only the CPU computes:
    /// `what` names it (`"--moments"`).
    pub fn cpu_only(&self, what: &str) -> Result<(), String> {
        self.choice().cpu_only(what, "leave out --backend opencl and --opencl-device")
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
        let whole = grid.counts.map(|n| 0..n);
        let warn = |e: &str| progress.warn("--backend auto", e);
        // The device's stages (slabs laid out, uploads, the kernel, reading back) are the
        // run's --timings.
        let device = (self.backend != Backend::Cpu)
            .then(|| progress.kernel("computing cell volumes (OpenCL)".to_string()));
        let hook: &dyn meshvol::progress::Progress = match &device {
            Some(device) => device,
            None => &(),
        };
        self.choice().cell_volumes(surface, grid, &whole, hook, on_cpu, warn)
    }
}
