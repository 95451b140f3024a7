//! The walk of folders and patterns (`meshvol_io::walk`) on a folder built here: which
//! files each rule gives, written out by hand.

use meshvol_io::walk::{Filter, Inputs, Walk};
use meshvol_io::InputKind;
use std::fs;
use std::path::{Path, PathBuf};

/// A folder of mesh names in every case and compressed form, with hidden files, a
/// version-control folder, files that are not meshes, a subfolder, an empty folder and
/// a folder of hidden files and files that are not meshes.
/// The contents do not matter: the walk chooses by name.
fn tree() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let files = [
        "b.stl",
        "A.STL",
        "c.stl.gz",
        "d.zip",
        "e.OBJ.BZ2",
        "notes.txt",
        "x.gz",
        ".hidden.stl",
        ".hidden/f.stl",
        ".git/objects/g.stl",
        "sub/h.ply",
        "sub/bad.stl",
        "sub/deeper/i.glb",
        "quiet/.x.stl",
        "quiet/.git/y.stl",
        "quiet/readme.txt",
    ];
    for name in files {
        let path = dir.path().join(name);
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(&path, b"solid x\nendsolid x\n").unwrap();
    }
    fs::create_dir(dir.path().join("empty")).unwrap();
    dir
}

fn walk(recursive: bool, globs: &[&str], patterns: bool) -> Walk {
    let filters = globs.iter().map(|g| Filter::parse(g).unwrap()).collect();
    Walk { recursive, filters, patterns }
}

/// The files found, below `root`, as text with `/`.
fn below(root: &Path, inputs: &Inputs) -> Vec<String> {
    let relative = |p: &PathBuf| p.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
    inputs.files.iter().map(relative).collect()
}

const TOP: [&str; 5] = ["A.STL", "b.stl", "c.stl.gz", "d.zip", "e.OBJ.BZ2"];

#[test]
fn a_folder_gives_its_mesh_files_in_any_case_and_compressed_not_hidden() {
    let dir = tree();
    let root = dir.path();
    let flat = walk(false, &[], false).expand(&[root.to_path_buf()], InputKind::Mesh);
    assert_eq!(below(root, &flat), TOP);
    assert!(flat.problems.is_empty());
    let deep = walk(true, &[], false).expand(&[root.to_path_buf()], InputKind::Mesh);
    let mut expected: Vec<&str> = TOP.to_vec();
    expected.extend(["sub/bad.stl", "sub/deeper/i.glb", "sub/h.ply"]);
    assert_eq!(below(root, &deep), expected);
}

#[test]
fn globs_keep_names_or_paths_and_leave_out_with_a_bang() {
    let dir = tree();
    let root = [dir.path().to_path_buf()];
    let found = |globs: &[&str]| {
        below(dir.path(), &walk(true, globs, false).expand(&root, InputKind::Mesh))
    };
    // Globs match names in any case, as the extensions that choose the files do.
    assert_eq!(found(&["*.stl"]), ["A.STL", "b.stl", "sub/bad.stl"]);
    assert_eq!(found(&["*.STL", "!BAD*"]), ["A.STL", "b.stl"]);
    assert_eq!(found(&["a.*"]), ["A.STL"]);
    assert_eq!(found(&["*.stl", "*.ply"]), ["A.STL", "b.stl", "sub/bad.stl", "sub/h.ply"]);
    assert_eq!(found(&["sub/**"]), ["sub/bad.stl", "sub/deeper/i.glb", "sub/h.ply"]);
    assert_eq!(found(&["!sub/**", "!*.zip"]), ["A.STL", "b.stl", "c.stl.gz", "e.OBJ.BZ2"]);
    let none = walk(true, &["*.3mf"], false).expand(&root, InputKind::Mesh);
    assert!(none.files.is_empty());
    assert_eq!(none.problems.len(), 1);
    assert!(none.problems[0].1.ends_with(", matching --glob *.3mf)"), "{:?}", none.problems);
}

#[test]
fn a_folder_without_files_is_a_problem_naming_it() {
    let dir = tree();
    let empty = dir.path().join("empty");
    let hidden_only = dir.path().join("quiet");
    for recursive in [false, true] {
        let inputs = walk(recursive, &[], false)
            .expand(&[empty.clone(), hidden_only.clone()], InputKind::Mesh);
        assert!(inputs.files.is_empty());
        let names: Vec<&str> = inputs.problems.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, [empty.display().to_string(), hidden_only.display().to_string()]);
        for (name, error) in &inputs.problems {
            assert!(error.starts_with(&format!("{name}: no mesh files in this folder (.stl,")));
            assert!(error.contains("or those compressed as .gz, .bz2, .zst, .zip"));
            assert_eq!(error.ends_with("--recursive also reads its subfolders"), !recursive);
        }
    }
}

#[test]
fn named_files_are_read_whatever_their_names_and_the_globs() {
    let dir = tree();
    let named: Vec<PathBuf> =
        ["notes.txt", ".hidden/f.stl", "missing.stl"].iter().map(|n| dir.path().join(n)).collect();
    let inputs = walk(true, &["*.obj"], true).expand(&named, InputKind::Mesh);
    assert_eq!(inputs.files, named);
    assert!(inputs.problems.is_empty());
    let stdin = walk(false, &[], true).expand(&[PathBuf::from("-")], InputKind::Mesh);
    assert_eq!(stdin.files, [PathBuf::from("-")]);
}

#[test]
fn patterns_match_as_pythons_glob_with_the_folders_rules() {
    let dir = tree();
    let root = dir.path();
    let found = |pattern: &str, patterns: bool| {
        walk(false, &[], patterns).expand(&[root.join(pattern)], InputKind::Mesh)
    };
    // `*` within a name; the extensions' rule still applies (notes.txt, x.gz are not
    // meshes), and hidden names are passed over.
    assert_eq!(below(root, &found("*", true)), TOP);
    assert_eq!(below(root, &found("*.stl", true)), ["b.stl"]);
    assert_eq!(below(root, &found("*/*.stl", true)), ["sub/bad.stl"]);
    // `**`: any number of folders, none included; never into `.hidden/` or `.git/`.
    assert_eq!(below(root, &found("**/*.stl", true)), ["b.stl", "sub/bad.stl"]);
    assert_eq!(below(root, &found("s?b/**/[hi].*", true)), ["sub/deeper/i.glb", "sub/h.ply"]);
    // A hidden folder named in the pattern's fixed part is walked.
    assert_eq!(below(root, &found(".hidden/*.stl", true)), [".hidden/f.stl"]);
    // `--glob` filters apply to a pattern's files too.
    let filtered = walk(false, &["!b*"], true).expand(&[root.join("*.stl")], InputKind::Mesh);
    assert!(filtered.files.is_empty() && filtered.problems.len() == 1);
    // No match, or no such folder: a problem naming the pattern.
    for pattern in ["*.3mf", "nowhere/*.stl"] {
        let inputs = found(pattern, true);
        let name = root.join(pattern).display().to_string();
        assert!(inputs.files.is_empty());
        assert_eq!(inputs.problems.len(), 1);
        assert_eq!(inputs.problems[0].0, name);
        assert!(inputs.problems[0]
            .1
            .starts_with(&format!("{name}: no mesh files matching this pattern (")));
    }
    // Without `patterns` (the command: the shell expands them), a pattern is a file name.
    assert_eq!(found("*.stl", false).files, [root.join("*.stl")]);
}
