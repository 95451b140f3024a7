//! `meshvol devices`: the OpenCL devices `grid --backend` can use and the one `auto`
//! takes, as JSON and as text.

use meshvol_opencl::{auto_choice, DeviceInfo, Listing};
use serde::Serialize;

/// The devices listed, or none where no OpenCL library loaded.
#[derive(Serialize)]
pub struct DevicesReport {
    /// Whether an OpenCL library loaded.
    pub opencl: bool,
    pub devices: Vec<DeviceReport>,
    /// The index `--backend auto` takes, or null: the CPU.
    pub auto: Option<usize>,
}

/// One device, numbered as `--device` takes it.
#[derive(Serialize)]
pub struct DeviceReport {
    pub index: usize,
    pub platform: String,
    pub name: String,
    #[serde(rename = "type")]
    pub kind: &'static str,
    pub fp64: bool,
    pub memory_bytes: u64,
    pub max_alloc_bytes: u64,
}

impl DevicesReport {
    pub fn of(listing: &Listing) -> DevicesReport {
        let list: &[DeviceInfo] = match listing {
            Listing::NoLibrary => &[],
            Listing::Devices(list) => list,
        };
        let devices = list
            .iter()
            .enumerate()
            .map(|(index, d)| DeviceReport {
                index,
                platform: d.platform.clone(),
                name: d.name.clone(),
                kind: d.kind.name(),
                fp64: d.fp64,
                memory_bytes: d.memory,
                max_alloc_bytes: d.max_alloc,
            })
            .collect();
        let opencl = matches!(listing, Listing::Devices(_));
        DevicesReport { opencl, devices, auto: auto_choice(list) }
    }

    /// The listing as lines of text: one a device, `[auto]` on the one `auto` takes.
    pub fn text(&self) -> String {
        if !self.opencl {
            return format!("{}: grid runs on the CPU\n", meshvol_opencl::Error::NoLibrary);
        }
        let mut out = String::new();
        if self.devices.is_empty() {
            out.push_str("no OpenCL devices: grid runs on the CPU\n");
        }
        for d in &self.devices {
            let memory = meshvol::grid::bytes_text(u128::from(d.memory_bytes));
            let fp64 = if d.fp64 { "f64" } else { "no f64 (not usable)" };
            let mark = if self.auto == Some(d.index) { "  [auto]" } else { "" };
            out.push_str(&format!(
                "{}  {:<11} {}  ({}), {fp64}, {memory}{mark}\n",
                d.index, d.kind, d.name, d.platform
            ));
        }
        if !self.devices.is_empty() && self.auto.is_none() {
            out.push_str(
                "auto: the CPU (no OpenCL GPU with f64; --backend opencl uses a device above)\n",
            );
        }
        out
    }
}
