//! The OpenCL platforms' devices, numbered in listing order, and the one `auto` takes.

use crate::Error;
use opencl3::device::{Device, CL_DEVICE_TYPE_ACCELERATOR, CL_DEVICE_TYPE_ALL};
use opencl3::device::{CL_DEVICE_TYPE_CPU, CL_DEVICE_TYPE_GPU};
use opencl3::error_codes::{ClError, DLOPEN_RUNTIME_LOAD_FAILED};
use opencl3::platform::get_platforms;
use opencl3::types::cl_device_id;
use std::sync::Mutex;

/// What kind of device OpenCL says it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeviceKind {
    Gpu,
    Cpu,
    Accelerator,
    Other,
}

impl DeviceKind {
    pub fn name(self) -> &'static str {
        match self {
            DeviceKind::Gpu => "GPU",
            DeviceKind::Cpu => "CPU",
            DeviceKind::Accelerator => "accelerator",
            DeviceKind::Other => "other",
        }
    }
}

/// One device, as `meshvol devices` lists it.
#[derive(Clone, Debug)]
pub struct DeviceInfo {
    pub platform: String,
    pub name: String,
    pub kind: DeviceKind,
    /// `cl_khr_fp64`: the grid runs only on such a device.
    pub fp64: bool,
    /// Global memory, and the largest single allocation, in bytes.
    pub memory: u64,
    pub max_alloc: u64,
    pub(crate) id: cl_device_id,
}

/// The devices, or the fact that no OpenCL library is installed.
#[derive(Clone, Debug)]
pub enum Listing {
    NoLibrary,
    Devices(Vec<DeviceInfo>),
}

/// Every device of every platform, in the order the platforms list them.
pub fn devices() -> Result<Listing, Error> {
    // One listing at a time in a process: PoCL 3.1 (Debian 12's) crashes in
    // clGetDeviceInfo when two threads list its devices at once (strlen on a name
    // another thread is still setting up; seen with this crate's tests in parallel).
    // A lock, not a cache: every call asks the drivers afresh.
    static LISTING: Mutex<()> = Mutex::new(());
    let _one_at_a_time = LISTING.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let platforms = match get_platforms() {
        Ok(p) => p,
        Err(ClError(DLOPEN_RUNTIME_LOAD_FAILED)) => return Ok(Listing::NoLibrary),
        Err(e) => return Err(call("the OpenCL library", "clGetPlatformIDs", e)),
    };
    let mut out = Vec::new();
    for platform in platforms {
        let platform_name = platform.name().unwrap_or_else(|_| "(unnamed platform)".into());
        // A platform with no device answers CL_DEVICE_NOT_FOUND: it lists none.
        let Ok(ids) = platform.get_devices(CL_DEVICE_TYPE_ALL) else { continue };
        for id in ids {
            let device = Device::new(id);
            let name = device.name().map_err(|e| call(&platform_name, "clGetDeviceInfo", e))?;
            let named = |e| call(&name, "clGetDeviceInfo", e);
            let kind = device.dev_type().map_err(named)?;
            let kind = if kind & CL_DEVICE_TYPE_GPU != 0 {
                DeviceKind::Gpu
            } else if kind & CL_DEVICE_TYPE_CPU != 0 {
                DeviceKind::Cpu
            } else if kind & CL_DEVICE_TYPE_ACCELERATOR != 0 {
                DeviceKind::Accelerator
            } else {
                DeviceKind::Other
            };
            out.push(DeviceInfo {
                platform: platform_name.clone(),
                kind,
                fp64: device.double_fp_config().map_err(named)? != 0,
                memory: device.global_mem_size().map_err(named)?,
                max_alloc: device.max_mem_alloc_size().map_err(named)?,
                name,
                id,
            });
        }
    }
    Ok(Listing::Devices(out))
}

/// The device `--backend auto` takes: the first GPU with f64, if any. A CPU device
/// (PoCL) is never chosen by itself: the CPU path is meshvol's own.
pub fn auto_choice(devices: &[DeviceInfo]) -> Option<usize> {
    devices.iter().position(|d| d.kind == DeviceKind::Gpu && d.fp64)
}

pub(crate) fn call(device: &str, call: &'static str, code: ClError) -> Error {
    Error::Call { device: device.to_string(), call, code: code.to_string() }
}
