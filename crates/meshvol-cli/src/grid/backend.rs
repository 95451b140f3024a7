//! `grid --backend`: the cell volumes and the cut cells (`--moments`) on the CPU or on
//! an OpenCL device (the same bits: crates/meshvol-opencl), and which one `auto` takes.

use crate::input::Progress;
use clap::{Args, ValueEnum};
use meshvol::grid::{cell_volumes_with, cut_cells_extras, CutCells, Extras, Grid};
use meshvol::Surface;
use meshvol_opencl::Where;

#[derive(Args)]
pub struct BackendArgs {
    /// Where the cell volumes (and with --moments the cut cells) are computed: `cpu`;
    /// `opencl`, an OpenCL device (any kind, PoCL's CPU device included; `meshvol
    /// devices` lists them); `auto`, an OpenCL GPU with f64 when there is one, else the
    /// CPU. The same bits either way. --second-moments, --face-centroids, --union and
    /// .zarr outputs run on the CPU.
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
    /// `what` names it (`"--union"`).
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

    /// The cut cells of `surface` on `grid` with `extras`, where the backend says (the
    /// extras, which only the CPU computes, on the CPU: `run` refused `opencl` for them).
    /// `auto` falls back to the CPU, with a warning, when the OpenCL device fails.
    pub fn cut_cells<S: Surface + ?Sized>(
        &self,
        surface: &S,
        grid: &Grid,
        extras: Extras,
        progress: &Progress,
    ) -> Result<CutCells, String> {
        let whole = grid.counts.map(|n| 0..n);
        let on_cpu = || {
            let hook = progress.kernel("computing the cut cells".to_string());
            cut_cells_extras(surface, grid, &whole, extras, &hook).map_err(|e| e.to_string())
        };
        if self.backend == Backend::Cpu || extras != Extras::default() {
            return on_cpu();
        }
        let warn = |e: &str| progress.warn("--backend auto", e);
        // The device's stages and the CPU's sums after them are the run's --timings.
        let hook = progress.kernel("computing the cut cells (OpenCL)".to_string());
        self.choice().cut_cells(surface, grid, &whole, &hook, on_cpu, warn)
    }
}
