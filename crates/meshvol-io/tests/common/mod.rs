//! Helpers shared by the integration tests: independent volume sums, box and
//! tetrahedron fixtures written in each format, a deterministic RNG.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use meshvol::{Point, Surface};
use meshvol_io::{Loaded, ReadError};

/// Σ a·(b×c)/6 over every fan triangle: the signed volume, computed here without the
/// library's kernels.
pub fn volume(s: &impl Surface) -> f64 {
    let mut six = 0.0;
    for f in 0..s.face_count() {
        s.fan(f, |a, b, c| {
            six += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]);
        });
    }
    six / 6.0
}

/// Every fan triangle, in order.
pub fn triangles(s: &impl Surface) -> Vec<[Point; 3]> {
    let mut out = vec![];
    for f in 0..s.face_count() {
        s.fan(f, |a, b, c| out.push([a, b, c]));
    }
    out
}

pub fn assert_close(actual: f64, expected: f64, tol: f64) {
    assert!(
        (actual - expected).abs() <= tol,
        "got {actual}, expected {expected} (tolerance {tol})"
    );
}

/// The corners of the box `origin + [0, size]`, corner i at (i & 1, i >> 1 & 1, i >> 2 & 1).
pub fn box_corners(origin: Point, size: Point) -> Vec<Point> {
    (0..8)
        .map(|i| {
            [
                origin[0] + size[0] * (i & 1) as f64,
                origin[1] + size[1] * (i >> 1 & 1) as f64,
                origin[2] + size[2] * (i >> 2 & 1) as f64,
            ]
        })
        .collect()
}

/// The six faces of a box over [`box_corners`], counter-clockwise seen from outside.
pub const BOX_QUADS: [[usize; 4]; 6] =
    [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];

/// The box's twelve outward triangles as coordinates.
pub fn box_triangles(origin: Point, size: Point) -> Vec<[Point; 3]> {
    let c = box_corners(origin, size);
    BOX_QUADS
        .iter()
        .flat_map(|q| [[c[q[0]], c[q[1]], c[q[2]]], [c[q[0]], c[q[2]], c[q[3]]]])
        .collect()
}

/// The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), outward: volume 1/6.
pub fn tetra_triangles() -> Vec<[Point; 3]> {
    let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
        .iter()
        .map(|t| [p[t[0]], p[t[1]], p[t[2]]])
        .collect()
}

/// A binary STL with the given 80-byte header text (padded with spaces).
pub fn binary_stl(header: &str, tris: &[[Point; 3]]) -> Vec<u8> {
    let mut out = header.as_bytes().to_vec();
    out.resize(80, b' ');
    out.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for t in tris {
        out.extend_from_slice(&[0u8; 12]);
        for p in t {
            for c in p {
                out.extend_from_slice(&(*c as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&[0u8; 2]);
    }
    out
}

/// An ASCII STL solid block: `solid {name}` ... `endsolid {name}`, lines ending `eol`.
pub fn ascii_solid(name: &str, tris: &[[Point; 3]], eol: &str) -> String {
    let mut s = format!("solid {name}{eol}").replace(&format!(" {eol}"), eol);
    for t in tris {
        s += &format!("  facet normal 0 0 0{eol}    outer loop{eol}");
        for p in t {
            s += &format!("      vertex {:e} {:e} {:e}{eol}", p[0], p[1], p[2]);
        }
        s += &format!("    endloop{eol}  endfacet{eol}");
    }
    s += format!("endsolid {name}").trim_end();
    s += eol;
    s
}

pub fn write_temp(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Reads bytes as a file of that name would be read.
pub fn read_as(name: &str, bytes: impl Into<Vec<u8>>) -> Result<Loaded, ReadError> {
    meshvol_io::read_bytes(Path::new(name), bytes.into())
}

/// Reads and expects an error; returns its display.
pub fn read_err(name: &str, bytes: impl Into<Vec<u8>>) -> ReadError {
    match read_as(name, bytes) {
        Ok(l) => panic!("{name}: expected an error, read {} faces as {}", l.face_count(), l.format),
        Err(e) => {
            let shown = e.to_string();
            assert!(shown.starts_with(&format!("{name}: ")), "{shown}");
            e
        }
    }
}

/// xorshift64*: deterministic pseudo-random numbers for the robustness tests.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Byte strings that steer mutations toward the parsers' edge cases.
const PIECES: &[&[u8]] = &[
    b" ",
    b"\n",
    b"\r\n",
    b"\t",
    b"#",
    b"/",
    b"//",
    b"-",
    b"+",
    b"0",
    b"-1",
    b"-99",
    b"4294967296",
    b"99999999999999999999",
    b"nan",
    b"inf",
    b"1e999",
    b"1e-999",
    b".",
    b"e",
    b"solid",
    b"endsolid",
    b"facet",
    b"endfacet",
    b"vertex",
    b"outer loop",
    b"endloop",
    b"v",
    b"f",
    b"l",
    b"p",
    b"OFF",
    b"COFF",
    b"4OFF",
    b"\xEF\xBB\xBF",
    b"\0",
    b"\xff\xff\xff\xff",
    b"\x7f\x80\x00\x00",
];

pub fn mutate(rng: &mut Rng, input: &[u8]) -> Vec<u8> {
    let mut out = input.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(out.len() + 1);
        match rng.below(8) {
            0 if !out.is_empty() => {
                let i = rng.below(out.len());
                out[i] ^= 1 << rng.below(8);
            }
            1 if !out.is_empty() => {
                let i = rng.below(out.len());
                out[i] = rng.next() as u8;
            }
            2 => {
                let end = (at + 1 + rng.below(16)).min(out.len());
                out.drain(at.min(end)..end);
            }
            3 => {
                let piece = PIECES[rng.below(PIECES.len())];
                out.splice(at..at, piece.iter().copied());
            }
            4 => out.truncate(at),
            5 => {
                let end = (at + rng.below(64)).min(out.len());
                let copy = out[at..end].to_vec();
                let to = rng.below(out.len() + 1);
                out.splice(to..to, copy);
            }
            6 if out.len() >= 84 => {
                // The binary STL count.
                let n = match rng.below(3) {
                    0 => rng.next() as u32,
                    1 => u32::MAX,
                    _ => (out.len() as u32).wrapping_sub(84) / 50 + rng.below(3) as u32,
                };
                out[80..84].copy_from_slice(&n.to_le_bytes());
            }
            _ => {
                let n = rng.below(8);
                let bytes: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
                out.splice(at..at, bytes);
            }
        }
    }
    out
}

/// The box of [`box_corners`] as a mesh of six outward quads.
pub fn box_mesh(origin: Point, size: Point) -> meshvol::Mesh {
    let quads: Vec<Vec<u32>> =
        BOX_QUADS.iter().map(|q| q.iter().map(|&i| i as u32).collect()).collect();
    meshvol::Mesh::from_polygons(box_corners(origin, size), quads.iter().map(|q| q.as_slice()))
        .unwrap()
}

/// The box of [`box_corners`] as OFF under `header` (the keyword and counts lines),
/// its quads with face colours.
pub fn box_off(header: &str, origin: Point, size: Point) -> String {
    let mut s = format!("{header}\n");
    for p in box_corners(origin, size) {
        s += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for q in BOX_QUADS {
        s += &format!("4 {} {} {} {} 0.1 0.2 0.3 1.0\n", q[0], q[1], q[2], q[3]);
    }
    s
}

/// A 3MF package holding `model` as its model part, with the relationships and content
/// types a 3MF needs.
pub fn three_mf(model: &str) -> Vec<u8> {
    use std::io::Write;
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    let parts = [
        (
            "[Content_Types].xml",
            r#"<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>"#,
        ),
        (
            "_rels/.rels",
            r#"<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>"#,
        ),
        ("3D/3dmodel.model", model),
    ];
    for (name, text) in parts {
        zip.start_file(name, options).unwrap();
        zip.write_all(text.as_bytes()).unwrap();
    }
    zip.finish().unwrap().into_inner()
}

/// A 3MF `<mesh>` of the box of [`box_triangles`].
pub fn three_mf_box_mesh(origin: Point, size: Point) -> String {
    let mut s = String::from("<mesh><vertices>");
    for p in box_corners(origin, size) {
        s += &format!(r#"<vertex x="{}" y="{}" z="{}"/>"#, p[0], p[1], p[2]);
    }
    s += "</vertices><triangles>";
    for q in BOX_QUADS {
        for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            s += &format!(r#"<triangle v1="{}" v2="{}" v3="{}"/>"#, t[0], t[1], t[2]);
        }
    }
    s + "</triangles></mesh>"
}

/// A zip archive of `members` (name, bytes), deflated.
pub fn zip_of(members: &[(&str, &[u8])]) -> Vec<u8> {
    use std::io::Write;
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (name, bytes) in members {
        zip.start_file(*name, options).unwrap();
        zip.write_all(bytes).unwrap();
    }
    zip.finish().unwrap().into_inner()
}
