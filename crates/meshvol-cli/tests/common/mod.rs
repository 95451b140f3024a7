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

/// Reads a little-endian f64 array.
fn f64s(bytes: &[u8]) -> Vec<f64> {
    bytes.chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().unwrap())).collect()
}

/// The value of attribute `name` in the first tag that has it.
fn attribute<'a>(xml: &'a str, name: &str) -> &'a str {
    let start = xml.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
    &xml[start..start + xml[start..].find('"').unwrap()]
}

/// A `.vti` file read back: extent, origin, spacing, and its arrays by name (in VTK's
/// order, x fastest; components interleaved).
pub struct Vti {
    pub extent: Vec<usize>,
    pub origin: Vec<f64>,
    pub spacing: Vec<f64>,
    pub arrays: std::collections::BTreeMap<String, Vec<f64>>,
}

impl Vti {
    pub fn array(&self, name: &str) -> &[f64] {
        self.arrays.get(name).unwrap_or_else(|| panic!("no array {name} in the .vti"))
    }
}

pub fn read_vti(path: &Path) -> Vti {
    let bytes = std::fs::read(path).unwrap();
    let marker = b"<AppendedData encoding=\"raw\">\n_";
    let at = bytes.windows(marker.len()).position(|w| w == marker).unwrap();
    let xml = std::str::from_utf8(&bytes[..at]).unwrap();
    assert!(xml.contains("type=\"ImageData\"") && xml.contains("header_type=\"UInt64\""));
    let numbers =
        |s: &str| s.split_whitespace().map(|x| x.parse::<f64>().unwrap()).collect::<Vec<_>>();
    let data = &bytes[at + marker.len()..];
    let array = |offset: usize| {
        let n = u64::from_le_bytes(data[offset..offset + 8].try_into().unwrap()) as usize;
        f64s(&data[offset + 8..offset + 8 + n])
    };
    let arrays = xml
        .match_indices("<DataArray ")
        .map(|(i, _)| {
            let tag = &xml[i..i + xml[i..].find("/>").unwrap()];
            (attribute(tag, "Name").to_string(), array(attribute(tag, "offset").parse().unwrap()))
        })
        .collect();
    assert!(std::str::from_utf8(&bytes[bytes.len() - 30..]).unwrap().contains("</VTKFile>"));
    Vti {
        extent: numbers(attribute(xml, "WholeExtent")).iter().map(|&x| x as usize).collect(),
        origin: numbers(attribute(xml, "Origin")),
        spacing: numbers(attribute(xml, "Spacing")),
        arrays,
    }
}

pub fn numbers(v: &Value) -> Vec<usize> {
    v.as_array().unwrap().iter().map(|x| x.as_u64().unwrap() as usize).collect()
}

/// The whole array of a Zarr v3 array with the `bytes` codec (of any number of axes),
/// chunk by chunk: a missing chunk is the fill value, edge chunks are whole (padded).
pub fn read_zarr(path: &Path) -> (Value, Vec<f64>) {
    let meta: Value =
        serde_json::from_slice(&std::fs::read(path.join("zarr.json")).unwrap()).unwrap();
    assert_eq!(meta["zarr_format"], 3);
    assert_eq!(meta["node_type"], "array");
    assert_eq!(meta["data_type"], "float64");
    assert_eq!(meta["chunk_grid"]["name"], "regular");
    assert_eq!(meta["chunk_key_encoding"]["configuration"]["separator"], "/");
    assert_eq!(
        meta["codecs"],
        serde_json::json!([{"name": "bytes", "configuration": {"endian": "little"}}])
    );
    let fill = f(&meta["fill_value"]);
    let shape = numbers(&meta["shape"]);
    let chunk = numbers(&meta["chunk_grid"]["configuration"]["chunk_shape"]);
    let d = shape.len();
    let blocks: Vec<usize> = (0..d).map(|a| shape[a].div_ceil(chunk[a])).collect();
    // C-order index of `at` in an array of `shape`.
    let index = |at: &[usize], shape: &[usize]| at.iter().zip(shape).fold(0, |n, (i, s)| n * s + i);
    let unravel = |mut n: usize, shape: &[usize]| {
        let mut at = vec![0; shape.len()];
        for a in (0..shape.len()).rev() {
            at[a] = n % shape[a];
            n /= shape[a];
        }
        at
    };
    let mut out = vec![f64::NAN; shape.iter().product()];
    for b in 0..blocks.iter().product() {
        let block = unravel(b, &blocks);
        let key: Vec<String> = block.iter().map(|i| i.to_string()).collect();
        let file = path.join(format!("c/{}", key.join("/")));
        let values: Vec<f64> = match std::fs::read(&file) {
            Ok(bytes) => {
                assert_eq!(bytes.len(), chunk.iter().product::<usize>() * 8, "{file:?}");
                let v = bytes.chunks_exact(8);
                v.map(|b| f64::from_le_bytes(b.try_into().unwrap())).collect()
            }
            Err(_) => vec![fill; chunk.iter().product()],
        };
        for (n, &v) in values.iter().enumerate() {
            let local = unravel(n, &chunk);
            let g: Vec<usize> = (0..d).map(|a| block[a] * chunk[a] + local[a]).collect();
            if (0..d).all(|a| g[a] < shape[a]) {
                out[index(&g, &shape)] = v;
            }
        }
    }
    (meta, out)
}
