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
    let out = if args.json { meshvol_report::json_line(&report) } else { Ok(report.text()) };
    match out {
        Ok(out) => print!("{out}"),
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            return ExitCode::from(2);
        }
    }
    ExitCode::SUCCESS
}
