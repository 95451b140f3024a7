//! Which files a command reads from the paths it is given: the one walk behind the
//! command's folder arguments (`meshvol volume -r FOLDER`) and Python's
//! `meshvol.measure` and `meshvol.dask.measure`, so both read the same files in the same
//! order.
//!
//! A path that names a file is read as it is, whatever its name. A folder stands for the
//! files in it that the command reads ([`InputKind::accepts`]: by extension, any case,
//! compressed forms included), sorted by path; [`Walk::recursive`] also takes its
//! subfolders' files, and [`Walk::filters`] (`--glob`) keep only the files whose name
//! matches, in any case (a pattern with a `/` is matched against the path below the
//! folder, as ripgrep's `-g` does; `!PATTERN` leaves files out). Hidden files and folders (names
//! starting with `.`: `.git/` among them) are passed over, as fd and ripgrep do.
//!
//! With [`Walk::patterns`] (Python, whose callers have no shell to expand
//! `parts/**/*.stl`), a path that names nothing and holds `*`, `?` or `[` is a pattern:
//! `*` matches within one name, `**` any number of folders, as Python's
//! `glob(recursive=True)` does. It stands for the files it matches, chosen as a folder's
//! are (the same extensions and filters; hidden names below its fixed leading folders
//! passed over) and sorted by path.
//!
//! A folder or pattern that gives no file is a problem, named with an error that says
//! what was looked for, never silence: the command prints it as a failed input, Python
//! as a row with an `error`.

use crate::compressed::{self, Compression};
use globset::{GlobBuilder, GlobMatcher};
use std::path::{Path, PathBuf};

/// What a command reads, for choosing the files in a folder by their names
/// ([`InputKind::accepts`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputKind {
    /// Meshes ([`read`](crate::read)).
    Mesh,
    /// Point clouds ([`read_points`](crate::read_points)): text points and meshes.
    Points,
    /// Polygons ([`read_polygons`](crate::read_polygons)).
    Polygons,
}

/// The compressions of one stream, which keep the inner file's extension in the name
/// (`part.stl.gz`); a `.zip` names its member inside, so any `.zip` is read.
const STREAM_COMPRESSIONS: [&str; 3] = ["gz", "bz2", "zst"];

impl InputKind {
    /// The extensions read (without the dot, lower case), before compression.
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            InputKind::Mesh => &["stl", "obj", "off", "ply", "3mf", "gltf", "glb"],
            InputKind::Points => {
                &["xyz", "txt", "csv", "pts", "stl", "obj", "off", "ply", "3mf", "gltf", "glb"]
            }
            InputKind::Polygons => &["wkt", "geojson", "json", "txt", "xy", "csv"],
        }
    }

    /// Whether a file of this name is read: one of [`extensions`](Self::extensions), that
    /// compressed (`part.stl.gz`, `.bz2`, `.zst`), or a `.zip`.
    pub fn accepts(self, path: &Path) -> bool {
        let ext = |p: &Path| p.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        let known = |p: &Path| ext(p).is_some_and(|e| self.extensions().contains(&e.as_str()));
        match Compression::of_path(path) {
            Some(Compression::Zip) => true,
            Some(_) => known(&path.with_extension("")),
            None => known(path),
        }
    }

    /// [`accepts`](Self::accepts) as a list of name endings, lower case, for callers
    /// that test names as text (Python's `meshvol.MESH_EXTENSIONS`): `.stl`, ...,
    /// `.stl.gz`, `.stl.bz2`, `.stl.zst`, ..., `.zip`. A name (not hidden) is read when,
    /// lower-cased, it ends with one of them.
    pub fn name_endings(self) -> Vec<String> {
        let plain = self.extensions().iter().map(|e| format!(".{e}"));
        let streams = self
            .extensions()
            .iter()
            .flat_map(|e| STREAM_COMPRESSIONS.iter().map(move |c| format!(".{e}.{c}")));
        plain.chain(streams).chain([".zip".to_string()]).collect()
    }

    /// What a folder of this kind was searched for, in an error: "mesh files" and
    /// ".stl, ..., or those compressed as .gz, .bz2, .zst, .zip".
    fn wanted(self) -> (&'static str, String) {
        let what = match self {
            InputKind::Mesh => "mesh files",
            InputKind::Points => "point or mesh files",
            InputKind::Polygons => "polygon files",
        };
        let dotted = |list: &[&str]| list.iter().map(|e| format!(".{e}")).collect::<Vec<_>>();
        let names = format!(
            "{}, or those compressed as {}",
            dotted(self.extensions()).join(", "),
            dotted(&compressed::COMPRESSED_EXTENSIONS).join(", ")
        );
        (what, names)
    }
}

/// A `--glob` pattern: which files of a folder are read. It matches in any case, as the
/// extensions that choose a folder's files do (`*.stl` keeps `PART.STL`).
#[derive(Clone, Debug)]
pub struct Filter {
    text: String,
    matcher: GlobMatcher,
    /// `!PATTERN`: files that match are left out.
    exclude: bool,
    /// The pattern has a `/`: it is matched against the path below the folder.
    whole_path: bool,
}

impl Filter {
    /// `PATTERN` or `!PATTERN`; an empty or malformed pattern is an error naming it.
    pub fn parse(s: &str) -> Result<Filter, String> {
        let (exclude, body) = match s.strip_prefix('!') {
            Some(rest) => (true, rest),
            None => (false, s),
        };
        if body.is_empty() {
            return Err(format!("'{s}': an empty pattern"));
        }
        let glob = GlobBuilder::new(body)
            .case_insensitive(true)
            .build()
            .map_err(|e| format!("'{s}': {e}"))?;
        Ok(Filter {
            text: s.to_string(),
            matcher: glob.compile_matcher(),
            exclude,
            whole_path: body.contains('/'),
        })
    }
}

/// The files to read, and the folders or patterns that gave none (their names and
/// errors).
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

/// How paths become files (the module's rules).
#[derive(Clone, Debug, Default)]
pub struct Walk {
    /// Folders: also read the files in their subfolders.
    pub recursive: bool,
    /// A file of a folder or pattern is read when it matches any filter that is not `!`
    /// (or there is none) and no `!` filter.
    pub filters: Vec<Filter>,
    /// A path that names nothing and holds `*`, `?` or `[` is a pattern.
    pub patterns: bool,
}

impl Walk {
    /// `arguments` with each folder (and pattern) replaced by the files in it that a
    /// command reading `kind` reads. `-` (standard input) is passed on as it is.
    pub fn expand(&self, arguments: &[PathBuf], kind: InputKind) -> Inputs {
        let mut inputs = Inputs::default();
        for arg in arguments {
            let stdin = arg.as_os_str() == "-";
            let pattern = self.patterns && !stdin && !arg.exists() && is_pattern(arg);
            if !pattern && (stdin || !arg.is_dir()) {
                inputs.files.push(arg.clone());
                continue;
            }
            let found = if pattern { self.matching(arg, kind) } else { self.folder(arg, kind) };
            let name = arg.display().to_string();
            match found {
                Ok(found) if found.is_empty() => {
                    inputs.problems.push((name, self.none_found(arg, kind, pattern)))
                }
                Ok(found) => inputs.files.extend(found),
                Err(e) => inputs.problems.push((name, e)),
            }
        }
        inputs
    }

    /// The files below `folder` to read, sorted by path.
    fn folder(&self, folder: &Path, kind: InputKind) -> Result<Vec<PathBuf>, String> {
        let depth = if self.recursive { usize::MAX } else { 1 };
        files_below(folder, depth, kind, |below| self.keeps(below))
    }

    /// The files `pattern` matches, sorted by path: the folders before its first
    /// component with `*`, `?` or `[` are walked, the rest is matched against the path
    /// below them.
    fn matching(&self, pattern: &Path, kind: InputKind) -> Result<Vec<PathBuf>, String> {
        let mut base = PathBuf::new();
        let mut rest: Vec<String> = Vec::new();
        for component in pattern.components() {
            let text = component.as_os_str().to_string_lossy();
            if rest.is_empty() && !has_magic(&text) {
                base.push(component);
            } else {
                rest.push(text.into_owned());
            }
        }
        let depth = if rest.iter().any(|c| c.contains("**")) { usize::MAX } else { rest.len() };
        // `*` stays within a name, as in Python's glob.
        let matcher = GlobBuilder::new(&rest.join("/"))
            .literal_separator(true)
            .build()
            .map_err(|e| format!("{}: not a pattern: {e}", pattern.display()))?
            .compile_matcher();
        // A relative pattern from the current folder gives relative names (`a.stl`, not
        // `./a.stl`), as Python's glob does.
        let here = base.as_os_str().is_empty();
        let root = if here { Path::new(".") } else { base.as_path() };
        if !root.is_dir() {
            return Ok(Vec::new());
        }
        let found =
            files_below(root, depth, kind, |below| matcher.is_match(below) && self.keeps(below))?;
        if here {
            return Ok(found
                .iter()
                .map(|p| p.strip_prefix(root).unwrap_or(p).to_path_buf())
                .collect());
        }
        Ok(found)
    }

    /// Whether the filters keep the file at `below` (its path below the folder).
    fn keeps(&self, below: &Path) -> bool {
        let name = below.file_name().map(Path::new).unwrap_or(below);
        let matches = |p: &Filter| p.matcher.is_match(if p.whole_path { below } else { name });
        let mut includes = self.filters.iter().filter(|p| !p.exclude).peekable();
        let included = includes.peek().is_none() || includes.any(matches);
        included && !self.filters.iter().filter(|p| p.exclude).any(matches)
    }

    /// The error for a folder or pattern that gave no file.
    fn none_found(&self, arg: &Path, kind: InputKind, pattern: bool) -> String {
        let place = if pattern { "matching this pattern" } else { "in this folder" };
        let (what, names) = kind.wanted();
        let mut s = format!("{}: no {what} {place} ({names}", arg.display());
        if !self.filters.is_empty() {
            let globs: Vec<&str> = self.filters.iter().map(|p| p.text.as_str()).collect();
            s += &format!(", matching --glob {}", globs.join(" --glob "));
        }
        s += ")";
        if !self.recursive && !pattern {
            s += "; --recursive also reads its subfolders";
        }
        s
    }
}

/// The files below `root` (to `depth` levels), not hidden, that `kind` reads and `keep`
/// keeps (given the path below `root`), sorted by path. Links to files are read; links
/// to folders are not followed.
fn files_below(
    root: &Path,
    depth: usize,
    kind: InputKind,
    keep: impl Fn(&Path) -> bool,
) -> Result<Vec<PathBuf>, String> {
    let mut found = Vec::new();
    let walker = walkdir::WalkDir::new(root)
        .min_depth(1)
        .max_depth(depth)
        .into_iter()
        .filter_entry(|e| !e.file_name().to_string_lossy().starts_with('.'));
    for entry in walker {
        let entry = entry.map_err(|e| {
            let at = e.path().unwrap_or(root).display().to_string();
            format!(
                "{at}: cannot read the folder: {}",
                e.io_error().map_or(e.to_string(), |io| io.to_string())
            )
        })?;
        let path = entry.path();
        let is_file =
            entry.file_type().is_file() || (entry.file_type().is_symlink() && path.is_file());
        if is_file && kind.accepts(path) && keep(path.strip_prefix(root).unwrap_or(path)) {
            found.push(path.to_path_buf());
        }
    }
    found.sort();
    Ok(found)
}

fn has_magic(text: &str) -> bool {
    text.contains(['*', '?', '['])
}

fn is_pattern(path: &Path) -> bool {
    has_magic(&path.to_string_lossy())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn walk(globs: &[&str]) -> Walk {
        let filters = globs.iter().map(|g| Filter::parse(g).unwrap()).collect();
        Walk { recursive: true, filters, patterns: false }
    }

    #[test]
    fn filters_match_names_or_paths_below_the_folder() {
        let w = walk(&["*.stl", "!bad*"]);
        assert!(w.keeps(Path::new("sub/a.stl")));
        assert!(!w.keeps(Path::new("sub/bad.stl")));
        assert!(!w.keeps(Path::new("a.obj")));
        let w = walk(&["sub/*.obj"]);
        assert!(w.keeps(Path::new("sub/a.obj")) && !w.keeps(Path::new("a.obj")));
        assert!(walk(&[]).keeps(Path::new("x.ply")));
        assert!(walk(&["!*.ply"]).keeps(Path::new("x.stl")));
        assert!(Filter::parse("!").is_err() && Filter::parse("a[").is_err());
    }

    #[test]
    fn name_endings_are_the_rule_of_accepts() {
        // Names written out by hand, read or not; the endings must agree with accepts.
        let names = [
            ("a.stl", true),
            ("A.STL", true),
            ("a.Obj", true),
            ("a.stl.gz", true),
            ("a.PLY.BZ2", true),
            ("a.glb.zst", true),
            ("a.zip", true),
            ("A.ZIP", true),
            ("a.gz", false),
            ("a.txt", false),
            ("a.txt.gz", false),
            ("a.stl.tar", false),
            ("stl", false),
        ];
        let endings = InputKind::Mesh.name_endings();
        for (name, read) in names {
            assert_eq!(InputKind::Mesh.accepts(Path::new(name)), read, "{name}");
            let lower = name.to_ascii_lowercase();
            assert_eq!(endings.iter().any(|e| lower.ends_with(e.as_str())), read, "{name}");
        }
    }
}
