//! Folders as inputs: a folder argument stands for the files in it that the command
//! reads (by extension, compressed forms included: `meshvol_io::InputKind::accepts`),
//! sorted by path; `--recursive` also takes its subfolders' files, and `--glob PATTERN`
//! keeps only the files whose name matches (a pattern with a `/` is matched against the
//! path below the folder, as ripgrep's `-g` does; `!PATTERN` leaves files out). Hidden
//! files and folders (names starting with `.`) are passed over, as fd and ripgrep do.
//! Files named as arguments are always read, whatever the globs.
//!
//! A folder that gives no file is a failed input ("no mesh files in this folder"): the
//! run exits 1, after measuring the others.

use clap::Args;
use globset::{Glob, GlobMatcher};
use meshvol_io::InputKind;
use std::path::{Path, PathBuf};

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
    #[arg(long = "glob", short = 'g', value_name = "PATTERN", value_parser = parse_glob, allow_hyphen_values = true)]
    pub globs: Vec<Pattern>,
}

/// A `--glob` pattern.
#[derive(Clone, Debug)]
pub struct Pattern {
    text: String,
    matcher: GlobMatcher,
    /// `!PATTERN`: files that match are left out.
    exclude: bool,
    /// The pattern has a `/`: it is matched against the path below the folder.
    whole_path: bool,
}

fn parse_glob(s: &str) -> Result<Pattern, String> {
    let (exclude, body) = match s.strip_prefix('!') {
        Some(rest) => (true, rest),
        None => (false, s),
    };
    if body.is_empty() {
        return Err(format!("'{s}': an empty pattern"));
    }
    let glob = Glob::new(body).map_err(|e| format!("'{s}': {e}"))?;
    Ok(Pattern {
        text: s.to_string(),
        matcher: glob.compile_matcher(),
        exclude,
        whole_path: body.contains('/'),
    })
}

/// The files to read, and the folders that gave none (their names and errors).
#[derive(Debug, Default)]
pub struct Inputs {
    pub files: Vec<PathBuf>,
    pub problems: Vec<(String, String)>,
}

impl Inputs {
    /// Inputs that are files already (no folder to walk).
    pub fn plain(files: Vec<PathBuf>) -> Inputs {
        Inputs { files, problems: Vec::new() }
    }
}

impl WalkArgs {
    /// `arguments` with each folder replaced by the files in it that a command reading
    /// `kind` reads.
    pub fn expand(&self, arguments: &[PathBuf], kind: InputKind) -> Inputs {
        let mut inputs = Inputs::default();
        for arg in arguments {
            if crate::input::is_stdin(arg) || !arg.is_dir() {
                inputs.files.push(arg.clone());
                continue;
            }
            match self.walk(arg, kind) {
                Ok(found) if found.is_empty() => {
                    inputs.problems.push((arg.display().to_string(), self.none_found(arg, kind)))
                }
                Ok(found) => inputs.files.extend(found),
                Err(e) => inputs.problems.push((arg.display().to_string(), e)),
            }
        }
        inputs
    }

    /// The files below `folder` to read, sorted by path.
    fn walk(&self, folder: &Path, kind: InputKind) -> Result<Vec<PathBuf>, String> {
        let depth = if self.recursive { usize::MAX } else { 1 };
        let mut found = Vec::new();
        let walker = walkdir::WalkDir::new(folder)
            .min_depth(1)
            .max_depth(depth)
            .into_iter()
            .filter_entry(|e| !e.file_name().to_string_lossy().starts_with('.'));
        for entry in walker {
            let entry = entry.map_err(|e| {
                let at = e.path().unwrap_or(folder).display().to_string();
                format!(
                    "{at}: cannot read the folder: {}",
                    e.io_error().map_or(e.to_string(), |io| io.to_string())
                )
            })?;
            // Links to files are read; links to folders are not followed.
            let path = entry.path();
            let is_file =
                entry.file_type().is_file() || (entry.file_type().is_symlink() && path.is_file());
            if !is_file || !kind.accepts(path) {
                continue;
            }
            let below = path.strip_prefix(folder).unwrap_or(path);
            if self.keeps(below) {
                found.push(path.to_path_buf());
            }
        }
        found.sort();
        Ok(found)
    }

    /// Whether the globs keep the file at `below` (its path below the folder).
    fn keeps(&self, below: &Path) -> bool {
        let name = below.file_name().map(Path::new).unwrap_or(below);
        let matches = |p: &Pattern| p.matcher.is_match(if p.whole_path { below } else { name });
        let mut includes = self.globs.iter().filter(|p| !p.exclude).peekable();
        let included = includes.peek().is_none() || includes.any(matches);
        included && !self.globs.iter().filter(|p| p.exclude).any(matches)
    }

    /// The error for a folder that gave no file.
    fn none_found(&self, folder: &Path, kind: InputKind) -> String {
        let what = match kind {
            InputKind::Mesh => "mesh files",
            InputKind::Points => "point or mesh files",
            InputKind::Polygons => "polygon files",
        };
        let extensions: Vec<String> = kind.extensions().iter().map(|e| format!(".{e}")).collect();
        let mut s = format!(
            "{}: no {what} in this folder ({}, or those compressed as .gz, .bz2, .zst, .zip",
            folder.display(),
            extensions.join(", ")
        );
        if !self.globs.is_empty() {
            let globs: Vec<&str> = self.globs.iter().map(|p| p.text.as_str()).collect();
            s += &format!(", matching --glob {}", globs.join(" --glob "));
        }
        s += ")";
        if !self.recursive {
            s += "; --recursive also reads its subfolders";
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn walk(globs: &[&str]) -> WalkArgs {
        let globs = globs.iter().map(|g| parse_glob(g).unwrap()).collect();
        WalkArgs { recursive: true, globs }
    }

    #[test]
    fn globs_match_names_or_paths_below_the_folder() {
        let w = walk(&["*.stl", "!bad*"]);
        assert!(w.keeps(Path::new("sub/a.stl")));
        assert!(!w.keeps(Path::new("sub/bad.stl")));
        assert!(!w.keeps(Path::new("a.obj")));
        let w = walk(&["sub/*.obj"]);
        assert!(w.keeps(Path::new("sub/a.obj")) && !w.keeps(Path::new("a.obj")));
        assert!(walk(&[]).keeps(Path::new("x.ply")));
        assert!(walk(&["!*.ply"]).keeps(Path::new("x.stl")));
        assert!(parse_glob("!").is_err() && parse_glob("a[").is_err());
    }
}
