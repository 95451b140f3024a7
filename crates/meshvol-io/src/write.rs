//! Small writers, for tests, benchmarks and examples: binary and ASCII STL, OBJ, PLY
//! (ASCII and binary) and GLB. Each writes what the matching reader reads back:
//!
//! - STL and GLB store `f32` coordinates (the formats' own type); STL stores each face's
//!   fan triangles with unshared vertices, GLB one indexed triangle primitive;
//! - OBJ and ASCII PLY write coordinates in Rust's shortest round-trip form, binary PLY as
//!   `double`: both read back exactly, polygon faces kept.
//!
//! [`MeshFormat`] names the formats a command writes a mesh in (`repair -o`, `hull
//! --out`, Python's `Mesh.save`) and [`mesh`] writes one. Whether the file holds the
//! solid that was meant is decided elsewhere (readers and writers never measure):
//! `meshvol_report::written` reads it back and compares.

use std::io::{self, Write};
use std::path::Path;

use meshvol::{Mesh, Surface};

/// A format a mesh is written in, chosen by the output's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// `.stl`: binary STL ([`stl_binary`]), float32 coordinates.
    Stl,
    /// `.obj` ([`obj`]): shortest round-trip decimals, float64 exactly.
    Obj,
    /// `.ply`: binary little-endian PLY ([`ply`]), float64 (`double`) coordinates.
    Ply,
    /// `.glb` ([`glb`]): float32 coordinates.
    Glb,
}

impl MeshFormat {
    /// The format of `path` by its extension (any case): `.stl`, `.obj`, `.ply`, `.glb`.
    pub fn of_path(path: &Path) -> Option<MeshFormat> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match extension.as_str() {
            "stl" => MeshFormat::Stl,
            "obj" => MeshFormat::Obj,
            "ply" => MeshFormat::Ply,
            "glb" => MeshFormat::Glb,
            _ => return None,
        })
    }

    /// The name messages use: `STL`, `OBJ`, `PLY`, `GLB`.
    pub fn name(self) -> &'static str {
        match self {
            MeshFormat::Stl => "STL",
            MeshFormat::Obj => "OBJ",
            MeshFormat::Ply => "PLY",
            MeshFormat::Glb => "GLB",
        }
    }

    /// Whether the format stores coordinates as float32 (rounding the mesh's float64
    /// ones): STL and GLB. OBJ and PLY as written here keep every bit.
    pub fn is_float32(self) -> bool {
        matches!(self, MeshFormat::Stl | MeshFormat::Glb)
    }

    /// The coordinates' type in the file: `float32` or `float64`.
    pub fn coordinates(self) -> &'static str {
        if self.is_float32() {
            "float32"
        } else {
            "float64"
        }
    }
}

/// Writes `mesh` in `format` (PLY binary little-endian).
pub fn mesh(out: &mut impl Write, mesh: &Mesh, format: MeshFormat) -> io::Result<()> {
    match format {
        MeshFormat::Stl => stl_binary(out, mesh),
        MeshFormat::Obj => obj(out, mesh),
        MeshFormat::Ply => ply(out, mesh, PlyEncoding::BinaryLittleEndian),
        MeshFormat::Glb => glb(out, mesh),
    }
}

/// A binary STL: an 80-byte header of spaces, the count, and every fan triangle.
pub fn stl_binary(out: &mut impl Write, surface: &impl Surface) -> io::Result<()> {
    let mut count = 0u32;
    for f in 0..surface.face_count() {
        surface.fan(f, |_, _, _| count = count.saturating_add(1));
    }
    out.write_all(&[b' '; 80])?;
    out.write_all(&count.to_le_bytes())?;
    let mut record = [0u8; 50];
    let mut result = Ok(());
    for f in 0..surface.face_count() {
        surface.fan(f, |a, b, c| {
            for (v, p) in [a, b, c].iter().enumerate() {
                for (k, x) in p.iter().enumerate() {
                    let at = 12 + 12 * v + 4 * k;
                    record[at..at + 4].copy_from_slice(&(*x as f32).to_le_bytes());
                }
            }
            if result.is_ok() {
                result = out.write_all(&record);
            }
        });
    }
    result
}

/// An ASCII STL solid named `name`, with zero normals.
pub fn stl_ascii(out: &mut impl Write, name: &str, surface: &impl Surface) -> io::Result<()> {
    writeln!(out, "solid {name}")?;
    let mut result = Ok(());
    for f in 0..surface.face_count() {
        surface.fan(f, |a, b, c| {
            if result.is_ok() {
                result = writeln!(
                    out,
                    "  facet normal 0 0 0\n    outer loop\n      vertex {:e} {:e} {:e}\n      \
                     vertex {:e} {:e} {:e}\n      vertex {:e} {:e} {:e}\n    endloop\n  endfacet",
                    a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]
                );
            }
        });
    }
    result?;
    writeln!(out, "endsolid {name}")
}

/// An OBJ: `v` lines, then `f` lines (1-based).
pub fn obj(out: &mut impl Write, mesh: &Mesh) -> io::Result<()> {
    for p in mesh.positions() {
        writeln!(out, "v {} {} {}", p[0], p[1], p[2])?;
    }
    for f in 0..mesh.face_count() {
        out.write_all(b"f")?;
        for &i in mesh.face(f) {
            write!(out, " {}", u64::from(i) + 1)?;
        }
        out.write_all(b"\n")?;
    }
    Ok(())
}

/// How [`ply`] writes the data.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlyEncoding {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

/// A PLY with `x y z` (`double`) vertices and `vertex_indices` (`uchar` count, `uint`
/// indices) faces.
pub fn ply(out: &mut impl Write, mesh: &Mesh, encoding: PlyEncoding) -> io::Result<()> {
    let format = match encoding {
        PlyEncoding::Ascii => "ascii",
        PlyEncoding::BinaryLittleEndian => "binary_little_endian",
        PlyEncoding::BinaryBigEndian => "binary_big_endian",
    };
    write!(
        out,
        "ply\nformat {format} 1.0\ncomment meshvol-io\nelement vertex {}\nproperty double x\n\
         property double y\nproperty double z\nelement face {}\nproperty list uchar uint \
         vertex_indices\nend_header\n",
        mesh.vertex_count(),
        mesh.face_count()
    )?;
    let big = encoding == PlyEncoding::BinaryBigEndian;
    let f64_bytes = |x: f64| if big { x.to_be_bytes() } else { x.to_le_bytes() };
    let u32_bytes = |x: u32| if big { x.to_be_bytes() } else { x.to_le_bytes() };
    for p in mesh.positions() {
        match encoding {
            PlyEncoding::Ascii => writeln!(out, "{} {} {}", p[0], p[1], p[2])?,
            _ => {
                for x in p {
                    out.write_all(&f64_bytes(*x))?;
                }
            }
        }
    }
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        let n = u8::try_from(face.len()).map_err(|_| {
            io::Error::new(io::ErrorKind::InvalidInput, "a face of more than 255 vertices")
        })?;
        match encoding {
            PlyEncoding::Ascii => {
                write!(out, "{n}")?;
                for i in face {
                    write!(out, " {i}")?;
                }
                writeln!(out)?;
            }
            _ => {
                out.write_all(&[n])?;
                for &i in face {
                    out.write_all(&u32_bytes(i))?;
                }
            }
        }
    }
    Ok(())
}

/// A GLB holding the mesh's fan triangles as one indexed primitive of one node
/// (`f32` positions, `u32` indices).
pub fn glb(out: &mut impl Write, mesh: &Mesh) -> io::Result<()> {
    let triangles = mesh.triangulated();
    let positions = mesh.positions();
    let mut bin = Vec::with_capacity(12 * positions.len() + 12 * triangles.face_count());
    for p in positions {
        for x in p {
            bin.extend_from_slice(&(*x as f32).to_le_bytes());
        }
    }
    let index_offset = bin.len();
    for f in 0..triangles.face_count() {
        for &i in triangles.face(f) {
            bin.extend_from_slice(&i.to_le_bytes());
        }
    }
    let index_count = 3 * triangles.face_count();
    let (lo, hi) = positions.iter().fold(([f64::MAX; 3], [f64::MIN; 3]), |(lo, hi), p| {
        ([0, 1, 2].map(|k| lo[k].min(p[k])), [0, 1, 2].map(|k| hi[k].max(p[k])))
    });
    let (lo, hi) = if positions.is_empty() { ([0.0; 3], [0.0; 3]) } else { (lo, hi) };
    let mut json = format!(
        r#"{{"asset":{{"version":"2.0","generator":"meshvol-io"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0,"name":"mesh"}}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"mode":4}}]}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3","min":[{},{},{}],"max":[{},{},{}]}},{{"bufferView":1,"componentType":5125,"count":{index_count},"type":"SCALAR"}}],"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{index_offset}}},{{"buffer":0,"byteOffset":{index_offset},"byteLength":{}}}],"buffers":[{{"byteLength":{}}}]}}"#,
        positions.len(),
        lo[0] as f32,
        lo[1] as f32,
        lo[2] as f32,
        hi[0] as f32,
        hi[1] as f32,
        hi[2] as f32,
        bin.len() - index_offset,
        bin.len()
    )
    .into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let length = |n: usize| {
        u32::try_from(n)
            .map(u32::to_le_bytes)
            .map_err(|_| io::Error::new(io::ErrorKind::InvalidInput, "more than 4 GiB for a GLB"))
    };
    out.write_all(b"glTF")?;
    out.write_all(&2u32.to_le_bytes())?;
    out.write_all(&length(total)?)?;
    out.write_all(&length(json.len())?)?;
    out.write_all(b"JSON")?;
    out.write_all(&json)?;
    out.write_all(&length(bin.len())?)?;
    out.write_all(b"BIN\0")?;
    out.write_all(&bin)
}
