//! Writing a mesh that is what the report says: every writer (`repair -o`, `hull --out`,
//! Python's `Mesh.save`) goes through [`write_mesh`], which writes the file beside its
//! destination, reads it back with meshvol's own reader, checks and measures it as
//! `meshvol volume OUT` would, and compares it with the solid that was meant.
//!
//! A format can change the solid: STL and GLB store float32 coordinates, and rounding a
//! mesh far from the origin (relative to its size) moves its vertices by a visible part
//! of the mesh, collapses faces (corners rounded onto each other) and makes faces
//! duplicates of others. When the file read back is not the same solid (see
//! [`WrittenReport::same_solid`]), it is removed and [`WriteError::Changed`] says what
//! changed, unless the caller allows a lossy write; then it is kept, and
//! [`WrittenReport::warning`] says what changed.
//!
//! The file appears at its destination only once it has passed (or been allowed): it is
//! written to a hidden file in the same folder and renamed over the destination, so a
//! refused or failed write leaves whatever was there before, and never a partial file.

use crate::number::{count, num};
use meshvol::topology::{check_assembled, Check, CheckOptions};
use meshvol::{mass_properties, Mesh, Surface};
use meshvol_io::write::{self, MeshFormat};
use serde::Serialize;
use std::fs::{File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// How far the volume of a mesh written with float32 coordinates may move, relative to
/// the volume, and still be the same solid.
///
/// float32 keeps 24 bits: rounding a coordinate moves it by at most 2⁻²⁴ ≈ 6e-8 of its
/// magnitude, so the volume moves by a few times 1e-8 of itself for a solid around the
/// origin, and by more the farther the solid is from the origin compared to its size.
/// Measured (float32 rounding of every coordinate of closed meshes, relative change of
/// the volume, worst of two directions of offset): an icosphere of 642 vertices
/// 1.6e-8 at the origin, 1.8e-8 one size away, 9.3e-8 at 10 sizes, 5.3e-7 at 100,
/// 1.9e-6 at 1000; a 256-sided cylinder 7.5e-9, 6.0e-8, 6.5e-7, 1.1e-5, 1.3e-5; boxes
/// and plates at most 3.2e-7. 1e-6 accepts what float32 does to any such solid within
/// about ten of its sizes of the origin (where STL files are normally made), and refuses
/// the changes that come from placing it hundreds of sizes away, which a user reading
/// the report's 15 digits would not expect.
pub const FLOAT32_RELATIVE_TOLERANCE: f64 = 1e-6;

/// What the written file holds, as meshvol reads it back, beside the solid that was
/// meant. Field names are the JSON keys (the `written` object of `repair` and `hull`).
#[derive(Clone, Debug, Serialize)]
pub struct WrittenReport {
    /// The file written, as named.
    pub file: String,
    /// The format read back: `stl-binary`, `obj`, `ply-binary-le`, `glb`.
    pub format: &'static str,
    /// How the format stores coordinates: `float32` (STL, GLB) or `float64` (OBJ, PLY).
    pub coordinates: &'static str,
    /// The volume of the solid meant (the mesh before writing), as `meshvol volume`
    /// measures it: the checked solid's volume.
    pub intended_volume: f64,
    /// The volume of the file as written, read back and measured the same way
    /// (`meshvol volume OUT`).
    pub volume: f64,
    /// How far `volume` may be from `intended_volume` for the same solid: both volumes'
    /// rounding bounds and cap uncertainties, and for float32 coordinates
    /// [`FLOAT32_RELATIVE_TOLERANCE`] of the volume.
    pub tolerance: f64,
    /// Triangles meant (the faces' fans) and triangles in the file.
    pub intended_triangles: usize,
    pub triangles: usize,
    /// Faces of the file collapsed (two corners rounded onto one vertex) beyond those
    /// of the solid meant.
    pub collapsed_faces: usize,
    /// Faces of the file with the same corners as another face, beyond those of the
    /// solid meant.
    pub duplicate_faces: usize,
    /// Whether the file's surface is closed.
    pub closed: bool,
    /// The file is the solid meant: its volume within `tolerance` of `intended_volume`,
    /// the same triangles, shells, boundary and non-manifold edges, and no face collapsed
    /// or duplicated by writing.
    pub same_solid: bool,
    /// What changed, one phrase each (empty when `same_solid`).
    #[serde(skip)]
    pub changes: Vec<String>,
    /// Why it changed: the format's float32 coordinates, and how far from the origin the
    /// mesh is for its size; or that a float64 file did not read back as written.
    #[serde(skip)]
    pub cause: String,
}

/// Why a mesh was not written. Either way nothing is left at the destination (a file
/// already there is untouched).
#[derive(Clone, Debug)]
pub enum WriteError {
    /// The file could not be created, written or renamed (an I/O error); the message
    /// names the file.
    Io(String),
    /// The format cannot be written, or the file written does not read back (or cannot
    /// be checked); the message names the file.
    Failed(String),
    /// The file read back is not the solid meant (and a lossy write was not allowed).
    Changed(Box<WrittenReport>),
}

impl WriteError {
    /// The error message; `allow` names how to write it anyway (`--allow-lossy`,
    /// `allow_lossy=True`).
    pub fn message(&self, allow: &str) -> String {
        match self {
            WriteError::Io(message) | WriteError::Failed(message) => message.clone(),
            WriteError::Changed(w) => format!(
                "{}: not written: {}: {}. Write it as .ply (binary, float64) or .obj, which \
                 keep every bit, or pass {allow} to write it anyway",
                w.file,
                w.cause,
                w.changes.join("; ")
            ),
        }
    }
}

impl WrittenReport {
    /// The warning a lossy write that was allowed gives; `None` for the same solid.
    pub fn warning(&self) -> Option<String> {
        (!self.same_solid).then(|| {
            format!(
                "{}: written as asked, but it is not the solid reported: {}: {}",
                self.file,
                self.cause,
                self.changes.join("; ")
            )
        })
    }

    /// One line for a text report: the file, and whether it reads back as the solid.
    pub fn text(&self) -> String {
        if self.same_solid {
            format!("{} (read back: the same solid, volume {})", self.file, num(self.volume, 15))
        } else {
            format!(
                "{} (read back: NOT the same solid: volume {}, intended {})",
                self.file,
                num(self.volume, 15),
                num(self.intended_volume, 15)
            )
        }
    }
}

/// What the comparison needs of a checked surface.
struct Measure {
    volume: f64,
    /// The volume's rounding bound plus the caps' uncertainty.
    bound: f64,
    triangles: usize,
    collapsed: usize,
    duplicates: usize,
    closed: bool,
    boundary_edges: usize,
    non_manifold_edges: usize,
    shells: usize,
}

/// Checks `surface` as `meshvol volume` does by default and measures its solid.
fn measure<S: Surface>(
    surface: &S,
    assembly: Option<&meshvol::assembly::Assembly>,
    triangles: usize,
) -> Result<Measure, String> {
    // One body, read back or in memory: the solid written is compared as a whole.
    let check: Check = check_assembled(surface, assembly, &[], &CheckOptions::default(), &())
        .map_err(|e| e.to_string())?;
    let solid = mass_properties(&check.solid(surface));
    Ok(Measure {
        volume: solid.signed_volume.abs(),
        bound: solid.volume_error_bound + check.volume_uncertainty,
        triangles,
        collapsed: check.degenerate_faces.saturating_sub(check.flat_faces),
        duplicates: check.duplicate_faces,
        closed: check.closed,
        boundary_edges: check.boundary_edges,
        non_manifold_edges: check.non_manifold_edges,
        shells: check.shells.len(),
    })
}

/// A file in the destination's folder, removed when dropped unless kept.
struct Temporary {
    path: PathBuf,
    kept: bool,
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if !self.kept {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// A new hidden file beside `out` whose name ends with `out`'s extension (so the reader
/// takes it for the same format): `.NAME.PID-N.tmp.EXT`.
fn beside(out: &Path) -> io::Result<(File, Temporary)> {
    let folder = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let name = out.file_name().map(|n| n.to_string_lossy()).unwrap_or_default();
    let extension = out.extension().map(|e| e.to_string_lossy()).unwrap_or_default();
    let mut attempt = 0u32;
    loop {
        let path = folder.join(format!(".{name}.{}-{attempt}.tmp.{extension}", std::process::id()));
        match OpenOptions::new().write(true).create_new(true).open(&path) {
            Ok(file) => return Ok((file, Temporary { path, kept: false })),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && attempt < 1000 => attempt += 1,
            Err(e) => return Err(e),
        }
    }
}

/// Writes `mesh` to `out` in the format its extension names (`.stl`, `.obj`, `.ply`,
/// `.glb`), reads it back, and compares it with `mesh` (both checked and measured as
/// `meshvol volume` does). The file is kept when it is the same solid, or when
/// `allow_lossy` (the report then says what changed); otherwise nothing is written and
/// the error says what changed.
pub fn write_mesh(mesh: &Mesh, out: &Path, allow_lossy: bool) -> Result<WrittenReport, WriteError> {
    let name = out.display().to_string();
    let failed = |e: &dyn std::fmt::Display| WriteError::Failed(format!("{name}: {e}"));
    let io = |e: io::Error| WriteError::Io(format!("{name}: {e}"));
    let format = MeshFormat::of_path(out)
        .ok_or_else(|| failed(&"cannot write this format: use .stl, .obj, .ply or .glb"))?;
    let intended = measure(mesh, None, mesh.triangle_count()).map_err(|e| failed(&e))?;

    let (file, mut temporary) = beside(out).map_err(io)?;
    let mut w = BufWriter::new(file);
    write::mesh(&mut w, mesh, format)
        .and_then(|()| w.flush())
        .and_then(|()| w.get_ref().sync_all())
        .map_err(io)?;
    drop(w);

    let written = {
        // Read, measured and dropped (a binary STL is memory-mapped) before the rename.
        let loaded = meshvol_io::read(&temporary.path).map_err(|e| {
            let e = meshvol_io::ReadError { path: out.to_path_buf(), ..e };
            WriteError::Failed(format!("{name}: not written: it does not read back: {e}"))
        })?;
        let m = measure(&loaded.surface, loaded.assembly.as_ref(), loaded.triangle_count())
            .map_err(|e| {
                WriteError::Failed(format!("{name}: not written: it cannot be checked: {e}"))
            })?;
        (loaded.format.name(), m)
    };
    let (read_format, file) = written;
    let report = compare(mesh, format, name.clone(), read_format, &intended, &file);
    if !report.same_solid && !allow_lossy {
        return Err(WriteError::Changed(Box::new(report)));
    }
    std::fs::rename(&temporary.path, out).map_err(io)?;
    temporary.kept = true;
    Ok(report)
}

/// The report of `file` (read back) against `intended`.
fn compare(
    mesh: &Mesh,
    format: MeshFormat,
    name: String,
    read_format: &'static str,
    intended: &Measure,
    file: &Measure,
) -> WrittenReport {
    let relative = if format.is_float32() { FLOAT32_RELATIVE_TOLERANCE } else { 0.0 };
    let tolerance = intended.bound + file.bound + relative * intended.volume;
    let difference = file.volume - intended.volume;
    let mut changes = Vec::new();
    // False for a NaN difference too: that is a change.
    let same_volume = difference.abs() <= tolerance;
    if !same_volume {
        let percent = if intended.volume != 0.0 {
            let sign = if difference > 0.0 { "+" } else { "" };
            format!(" ({sign}{}%)", num(100.0 * difference / intended.volume, 3))
        } else {
            String::new()
        };
        changes.push(format!(
            "volume {} intended, {} as written{percent}, beyond ± {}",
            num(intended.volume, 15),
            num(file.volume, 15),
            num(tolerance, 2)
        ));
    }
    let collapsed = file.collapsed.saturating_sub(intended.collapsed);
    if collapsed > 0 {
        changes.push(format!(
            "{} (corners rounded onto each other)",
            count(collapsed, "face collapsed", "faces collapsed")
        ));
    }
    let duplicates = file.duplicates.saturating_sub(intended.duplicates);
    if duplicates > 0 {
        changes.push(format!(
            "{} (the same corners as another face)",
            count(duplicates, "duplicate face", "duplicate faces")
        ));
    }
    if file.triangles != intended.triangles {
        changes.push(format!("{} triangles instead of {}", file.triangles, intended.triangles));
    }
    if file.closed != intended.closed || file.boundary_edges != intended.boundary_edges {
        changes.push(format!(
            "{} boundary edges instead of {}{}",
            file.boundary_edges,
            intended.boundary_edges,
            if intended.closed && !file.closed { " (no longer closed)" } else { "" }
        ));
    }
    if file.non_manifold_edges != intended.non_manifold_edges {
        changes.push(format!(
            "{} non-manifold edges instead of {}",
            file.non_manifold_edges, intended.non_manifold_edges
        ));
    }
    if file.shells != intended.shells {
        changes.push(format!("{} shells instead of {}", file.shells, intended.shells));
    }
    let cause = if format.is_float32() {
        let (far, size) = reach(mesh);
        let short = |x: f64| if x >= 1e5 { format!("{x:.2e}") } else { num(x, 3) };
        format!(
            "{} stores float32 coordinates, and rounding the mesh's coordinates to float32 \
             (they reach {} from the origin, for a solid {} across) changes the solid",
            format.name(),
            short(far),
            short(size)
        )
    } else {
        format!("the {} file does not read back as the solid written", format.name())
    };
    WrittenReport {
        file: name,
        format: read_format,
        coordinates: format.coordinates(),
        intended_volume: intended.volume,
        volume: file.volume,
        tolerance,
        intended_triangles: intended.triangles,
        triangles: file.triangles,
        collapsed_faces: collapsed,
        duplicate_faces: duplicates,
        closed: file.closed,
        same_solid: changes.is_empty(),
        changes,
        cause,
    }
}

/// The largest coordinate magnitude of `mesh`'s vertices and its bounding box diagonal.
fn reach(mesh: &Mesh) -> (f64, f64) {
    let mut far = 0.0f64;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in mesh.positions() {
        for k in 0..3 {
            far = far.max(p[k].abs());
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    (far, if size.is_finite() { size } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use super::*;
    use meshvol::shapes::cuboid;

    /// A closed box translated by `offset`, with coordinates that float32 cannot hold
    /// exactly far from the origin.
    fn shifted_box(offset: f64) -> Mesh {
        let mesh = cuboid([0.1, 0.2, 0.3], [1.3, 1.7, 2.9]);
        let positions = mesh.positions().iter().map(|p| p.map(|x| x + offset)).collect();
        Mesh::new(positions, mesh.faces().clone()).unwrap()
    }

    #[test]
    fn float64_formats_round_trip_and_float32_far_away_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        // (1.2 × 1.5 × 2.6 = 4.68, up to the rounding of the shifted coordinates.)
        let near = shifted_box(0.0);
        for name in ["a.ply", "a.obj", "a.stl", "a.glb"] {
            let out = dir.path().join(name);
            let w = write_mesh(&near, &out, false).unwrap();
            assert!(w.same_solid && out.exists(), "{name}: {w:?}");
            assert!((w.volume - 4.68).abs() < 1e-6, "{name}: {w:?}");
        }
        let far = shifted_box(3.0e7 + 0.1);
        let out = dir.path().join("far.stl");
        match write_mesh(&far, &out, false) {
            Err(e @ WriteError::Changed(_)) => {
                let message = e.message("--allow-lossy");
                assert!(message.contains("float32") && message.contains(".ply"), "{message}");
            }
            other => panic!("{other:?}"),
        }
        // Nothing left behind: not the file, not the temporary.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 4);
        let w = write_mesh(&far, &out, true).unwrap();
        assert!(!w.same_solid && w.warning().is_some() && out.exists());
        let w = write_mesh(&far, &dir.path().join("far.ply"), false).unwrap();
        assert!(w.same_solid && w.volume == w.intended_volume, "{w:?}");
    }
}
