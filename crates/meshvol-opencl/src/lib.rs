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
mod error;
mod fault;
mod moments;
mod run;
mod slabs;

pub use backend::{Backend, Where};
pub use devices::{auto_choice, devices, DeviceInfo, DeviceKind, Listing};
pub use error::Error;
pub use run::{Device, Options};
