//! meshvol's grid kernels (`meshvol::grid::cell_volumes`, and the cut cells'
//! per-column stage, `meshvol::grid::cut_cells_swept`) on an OpenCL device, with the
//! CPU's bits.
//!
//! # Design
//! Every cell of the column–clamp kernel is a sum whose terms and order the CPU fixes:
//! the pieces of the faces binned to its tile, in face order, then a compensated
//! suffix sum down its column. The device repeats exactly that, one work item per tile
//! of columns, so no two work items write the same cell and nothing is atomic:
//!
//! | stage | where | file |
//! |---|---|---|
//! | cut the region into slabs of x layers that fit the device (each slab below, in turn) | host | `slabs.rs` |
//! | map to grid units, drop triangles with no projected area | CPU, the core's own code | `meshvol/src/grid/tile_work.rs` (`Units`) |
//! | bin faces by tile, in face order | CPU, the core's own code | `tile_work.rs` (`cells::Bins`) |
//! | upload triangles, bins; one work item a tile | host | `run.rs` |
//! | strip, column and layer sweeps; the sink's sums | device | `cl/clip.cl`, `cl/sweeps.cl`, `cl/volumes.cl` (`cells.rs`, `clip.rs` ported) |
//! | compensated suffix sum per column, times dx·dy·dz | device | `cl/volumes.cl` (`finish_column`) |
//! | read each slab's cells back into its place | host | `run.rs` |
//!
//! The cut cells (`moments.rs`) are the same stages with the cut-cell kernel's sink
//! (`cl/integrals.cl`, `cl/moments.cl`: per cell the moments and the surface's sums,
//! per column the suffix sums, the volumes, centroids and z apertures), every triangle
//! kept with its face's normal (`cut_tile_work`); then the sums across columns (the x
//! and y apertures, the surface centroids) on the CPU, by the core's own code.
//!
//! The programs are compiled with `#pragma OPENCL FP_CONTRACT OFF` (the CPU code never
//! fuses, and uses no `mul_add`), f64 throughout (a device without `cl_khr_fp64` is
//! refused), and their integer casts saturate as Rust's do; each is built the first time
//! a grid needs it. The tiling is free: a cell's terms do not depend on it, nor on the
//! work-group size.
//!
//! No global state: [`Device`] is a handle the caller opens and passes in.

mod backend;
mod devices;
mod fault;
mod moments;
mod run;
mod slabs;

pub use backend::{Backend, Where};
pub use devices::{auto_choice, devices, DeviceInfo, DeviceKind, Listing};
pub use run::{Device, Options};

/// Why no OpenCL library loads. A statically linked musl binary (the release binary of
/// scripts/dist.sh) builds and runs, but musl's static `dlopen` loads nothing.
#[cfg(all(target_env = "musl", target_feature = "crt-static"))]
const NO_LIBRARY: &str = "this meshvol is statically linked (the release binary), which cannot load the OpenCL library: for OpenCL, build meshvol with cargo (cargo install --path crates/meshvol-cli) or use --backend cpu";
#[cfg(not(all(target_env = "musl", target_feature = "crt-static")))]
const NO_LIBRARY: &str = "no OpenCL library (libOpenCL.so.1) could be loaded: install an OpenCL driver (on Debian or Ubuntu, for the CPU: apt-get install pocl-opencl-icd ocl-icd-libopencl1), or use --backend cpu";

/// Why the OpenCL grid could not run.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("{NO_LIBRARY}")]
    NoLibrary,
    #[error("no OpenCL device {index}: {count} found (meshvol devices lists them)")]
    NoDevice { index: usize, count: usize },
    #[error("OpenCL device {index} ({name}) has no 64-bit floating point (cl_khr_fp64), which the grid needs: use another device or --backend cpu")]
    NoFp64 { index: usize, name: String },
    #[error("OpenCL {call} failed on {device}: {code}")]
    Call { device: String, call: &'static str, code: String },
    #[error("the grid kernel did not build for OpenCL device {device}: {log}")]
    Build { device: String, log: String },
    #[error("{what} needs {bytes} bytes on OpenCL device {device}, which allocates at most {limit} at once: use a coarser grid, a block of it, or --backend cpu")]
    TooLarge { device: String, what: &'static str, bytes: u128, limit: u64 },
    #[error("one x layer of the grid's cells, with their column sums, needs {bytes} bytes on OpenCL device {device}, over what a slab may take ({budget} bytes, at most {max_alloc} a buffer): use fewer cells along y or z, or --backend cpu")]
    SlabTooLarge { device: String, bytes: u128, budget: u64, max_alloc: u64 },
    #[error(transparent)]
    Grid(#[from] meshvol::grid::GridError),
}
