//! The crate's [`Error`]: a leaf, so the files that return it need not import lib.rs.

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
