//! `meshvol devices`: the OpenCL devices `grid --backend` can use, and the one `auto`
//! takes.

use clap::Args;
use meshvol_opencl::{auto_choice, devices, Listing};
use std::process::ExitCode;

#[derive(Args)]
pub struct DevicesArgs {
    /// Print one JSON object: `opencl` (whether an OpenCL library loaded), `devices`
    /// (index, platform, name, type, fp64, memory_bytes, max_alloc_bytes) and `auto`
    /// (the index `--backend auto` takes, or null: the CPU).
    #[arg(long)]
    json: bool,
}

pub fn run(args: DevicesArgs) -> ExitCode {
    let listing = match devices() {
        Ok(listing) => listing,
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            return ExitCode::from(2);
        }
    };
    let (library, list) = match listing {
        Listing::NoLibrary => (false, Vec::new()),
        Listing::Devices(list) => (true, list),
    };
    let auto = auto_choice(&list);
    if args.json {
        let devices: Vec<_> = list
            .iter()
            .enumerate()
            .map(|(index, d)| {
                serde_json::json!({
                    "index": index,
                    "platform": d.platform,
                    "name": d.name,
                    "type": d.kind.name(),
                    "fp64": d.fp64,
                    "memory_bytes": d.memory,
                    "max_alloc_bytes": d.max_alloc,
                })
            })
            .collect();
        let out = serde_json::json!({ "opencl": library, "devices": devices, "auto": auto });
        println!("{out}");
        return ExitCode::SUCCESS;
    }
    if !library {
        println!("{}: grid runs on the CPU", meshvol_opencl::Error::NoLibrary);
        return ExitCode::SUCCESS;
    }
    if list.is_empty() {
        println!("no OpenCL devices: grid runs on the CPU");
    }
    for (index, d) in list.iter().enumerate() {
        let memory = meshvol::grid::bytes_text(u128::from(d.memory));
        let fp64 = if d.fp64 { "f64" } else { "no f64 (not usable)" };
        let mark = if auto == Some(index) { "  [auto]" } else { "" };
        println!(
            "{index}  {:<11} {}  ({}), {fp64}, {memory}{mark}",
            d.kind.name(),
            d.name,
            d.platform
        );
    }
    if !list.is_empty() && auto.is_none() {
        println!("auto: the CPU (no OpenCL GPU with f64; --backend opencl uses a device above)");
    }
    ExitCode::SUCCESS
}
