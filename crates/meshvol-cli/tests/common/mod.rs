//! What every test of the command needs: running it, writing input files, reading
//! numbers out of its JSON. (Each test file uses some of these.)
#![allow(dead_code)]

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;
use std::time::SystemTime;

/// The `meshvol` command under test: the one cargo built for these tests or, when the
/// environment's `MESHVOL_BIN` names one, that one. CI names the release binary that
/// scripts/dist.sh has just built from the same tree: the suites then test the artifact
/// users install, at release speed (in the debug build these suites took 3.5 of CI's
/// 20 minutes). A named binary older than a source file of the workspace is refused, so
/// a stale one never passes for the tree.
pub fn bin() -> &'static Path {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        let Some(named) = std::env::var_os("MESHVOL_BIN") else {
            return PathBuf::from(env!("CARGO_BIN_EXE_meshvol"));
        };
        let named = PathBuf::from(named);
        // cargo runs the tests in the crate's folder, not where the variable was set.
        assert!(named.is_absolute(), "MESHVOL_BIN={} must be an absolute path", named.display());
        let built = std::fs::metadata(&named)
            .and_then(|m| m.modified())
            .unwrap_or_else(|e| panic!("MESHVOL_BIN={}: {e}", named.display()));
        // Every crate of the workspace, not a list of the command's own that a new
        // dependency could outgrow (the binding's and the benchmarks' only make it stricter).
        let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        for krate in std::fs::read_dir(&crates).unwrap() {
            let src = krate.unwrap().path().join("src");
            assert!(
                !src.is_dir() || newest(&src) <= built,
                "MESHVOL_BIN={} is older than the sources in {}: rebuild it or unset it",
                named.display(),
                src.display()
            );
        }
        named
    })
}

/// The latest modification time of the files under `dir`.
fn newest(dir: &Path) -> SystemTime {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let m = e.metadata().unwrap();
            if m.is_dir() {
                newest(&e.path())
            } else {
                m.modified().unwrap()
            }
        })
        .max()
        .unwrap_or(SystemTime::UNIX_EPOCH)
}

/// Runs the `meshvol` command under test ([`bin`]).
pub fn meshvol(args: &[&str]) -> Output {
    Command::new(bin()).args(args).output().expect("meshvol runs")
}

/// Writes `content` to `dir/name`.
pub fn write(dir: &Path, name: &str, content: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, content).unwrap();
    path
}

/// A path as a command-line argument.
pub fn p(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// A JSON number.
pub fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// A 3MF archive holding `model` as its model part.
pub fn three_mf(model: &str) -> Vec<u8> {
    use std::io::Write;
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default();
    zip.start_file("3D/3dmodel.model", options).unwrap();
    zip.write_all(model.as_bytes()).unwrap();
    zip.finish().unwrap().into_inner()
}

/// The values of a `.npy` file of float64 (its header checked) and its shape.
pub fn read_npy(path: &Path) -> (Vec<usize>, Vec<f64>) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
    let n = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = std::str::from_utf8(&bytes[10..10 + n]).unwrap();
    assert!(header.contains("'descr': '<f8'") && header.contains("'fortran_order': False"));
    let shape = header.split("'shape': (").nth(1).unwrap().split(')').next().unwrap();
    let shape = shape.split(',').filter(|s| !s.trim().is_empty());
    let values = bytes[10 + n..].chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().unwrap()));
    (shape.map(|s| s.trim().parse().unwrap()).collect(), values.collect())
}

/// The arrays of a `.npz`, each read back as a `.npy`.
pub fn read_npz(path: &Path) -> std::collections::BTreeMap<String, (Vec<usize>, Vec<f64>)> {
    let mut archive = zip::ZipArchive::new(std::fs::File::open(path).unwrap()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let mut arrays = std::collections::BTreeMap::new();
    for n in 0..archive.len() {
        let mut entry = archive.by_index(n).unwrap();
        let name = entry.name().trim_end_matches(".npy").to_string();
        let file = dir.path().join(&name);
        std::io::copy(&mut entry, &mut std::fs::File::create(&file).unwrap()).unwrap();
        arrays.insert(name, read_npy(&file));
    }
    arrays
}

/// An axis-aligned box as six OBJ quads (1-based from `base`), wound outward or inward;
/// without its top face when `open`.
pub fn box_obj(min: [f64; 3], max: [f64; 3], base: usize, outward: bool, open: bool) -> String {
    let mut s = String::new();
    for k in 0..8 {
        let q = [k & 1, (k >> 1) & 1, (k >> 2) & 1];
        let c: Vec<f64> = (0..3).map(|a| if q[a] == 1 { max[a] } else { min[a] }).collect();
        s += &format!("v {} {} {}\n", c[0], c[1], c[2]);
    }
    // Corners numbered by bits (x, y, z); each quad counter-clockwise seen from outside;
    // the second is the top.
    let quads =
        [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    for (n, q) in quads.into_iter().enumerate() {
        if open && n == 1 {
            continue;
        }
        let ids: Vec<usize> = q.iter().map(|&i| i + base).collect();
        let ids: Vec<usize> = if outward { ids } else { ids.into_iter().rev().collect() };
        s += &format!("f {} {} {} {}\n", ids[0], ids[1], ids[2], ids[3]);
    }
    s
}
pub mod server;
