//! Folders as inputs: the arguments of `meshvol_io::walk` (the one walk, which Python's
//! `meshvol.measure` shares), as flags. A folder argument stands for the files in it
//! that the command reads (by extension, any case, compressed forms included), sorted by
//! path; `--recursive` also takes its subfolders' files, and `--glob PATTERN` keeps only
//! the files whose name matches. Hidden files and folders are passed over. Files named
//! as arguments are always read, whatever the globs.
//!
//! A folder that gives no file is a failed input ("no mesh files in this folder"): the
//! run exits 1, after measuring the others.

use clap::Args;
use meshvol_io::walk::{Filter, Walk};
use meshvol_io::InputKind;
use std::path::PathBuf;

pub use meshvol_io::walk::Inputs;

/// The options of a command that takes folders.
#[derive(Args, Clone, Debug, Default)]
pub struct WalkArgs {
    /// Folder arguments: also read the files in their subfolders (else only the files
    /// directly in them).
    #[arg(long, short)]
    pub recursive: bool,
    /// Folder arguments: read only the files whose name matches PATTERN (`*.stl`,
    /// `part-??.obj`, `{a,b}*`; with a `/`, the path below the folder: `2024/**/*.ply`);
    /// `!PATTERN` leaves matching files out. Repeatable: a file is read when it matches
    /// any pattern and no `!` pattern. Files named as arguments are always read.
    #[arg(long = "glob", short = 'g', value_name = "PATTERN", value_parser = Filter::parse, allow_hyphen_values = true)]
    pub globs: Vec<Filter>,
}

impl WalkArgs {
    /// `arguments` with each folder replaced by the files in it that a command reading
    /// `kind` reads. Shells expand patterns before the command sees them, so an argument
    /// is never taken for one.
    pub fn expand(&self, arguments: &[PathBuf], kind: InputKind) -> Inputs {
        let walk = Walk { recursive: self.recursive, filters: self.globs.clone(), patterns: false };
        walk.expand(arguments, kind)
    }
}
