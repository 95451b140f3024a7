//! Failures provoked on purpose, so that the tests can see what a failing device does
//! (`MESHVOL_OPENCL_FAULT`, read by the command and by Python alike). Each one makes
//! the driver itself fail, with its own error: nothing is faked past the OpenCL call.
//!
//! - `build`: the kernel's source with a line the compiler rejects (a build failure,
//!   with the driver's build log);
//! - `alloc`: the cells' buffer asked one value larger than the device's largest
//!   allocation (the driver's refusal, as when a device runs out of memory).

/// A failure to provoke.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Fault {
    Build,
    Alloc,
}

/// The failure `MESHVOL_OPENCL_FAULT` asks for, if any.
pub(crate) fn asked() -> Option<Fault> {
    match std::env::var("MESHVOL_OPENCL_FAULT").as_deref() {
        Ok("build") => Some(Fault::Build),
        Ok("alloc") => Some(Fault::Alloc),
        _ => None,
    }
}
