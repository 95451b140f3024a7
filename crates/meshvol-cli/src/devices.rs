//! `meshvol devices`: the OpenCL devices `grid --backend` can use, and the one `auto`
//! takes.

use clap::Args;
use meshvol_opencl::devices;
use meshvol_report::devices::DevicesReport;
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
    let report = DevicesReport::of(&listing);
    if args.json {
        match serde_json::to_string(&report) {
            Ok(json) => println!("{json}"),
            Err(e) => {
                eprintln!("meshvol: error: {e}");
                return ExitCode::from(2);
            }
        }
    } else {
        print!("{}", report.text());
    }
    ExitCode::SUCCESS
}
