//! `repair`: what writing the checked solid changed, said exactly.

use crate::number::{count, num};
use crate::subject::Source;
use crate::written::WrittenReport;
use crate::Report;
use meshvol::topology::Check;
use meshvol::{mass_properties, Mesh, Surface};
use serde::Serialize;
use std::fmt::Write;

/// The report. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct RepairReport {
    pub file: Option<String>,
    pub out: String,
    pub faces_in: usize,
    pub faces_out: usize,
    /// Faces turned so that shells face outward and cavities inward.
    pub faces_flipped: usize,
    pub degenerate_faces_removed: usize,
    pub duplicate_faces_removed: usize,
    pub faces_removed: usize,
    pub holes_capped: usize,
    pub cap_triangles: usize,
    pub holes_left: usize,
    pub vertices_in: usize,
    pub vertices_out: usize,
    pub weld_tolerance: Option<f64>,
    pub signed_volume_before: f64,
    pub signed_volume_after: f64,
    pub verdict_before: String,
    /// The reader's warnings, what the repaired mesh still lacks, and what writing
    /// changed when a lossy write was allowed.
    pub warnings: Vec<String>,
    /// The file as written, read back and measured: `written.volume` beside
    /// `written.intended_volume`, the volume of the solid meant.
    pub written: WrittenReport,
}

/// The report of writing `repaired` (the checked solid of `surface`, with caps when
/// `capped`) as `written` ([`crate::written::write_mesh`]).
pub fn repair<S: Surface>(
    source: &Source,
    surface: &S,
    check: &Check,
    repaired: &Mesh,
    capped: bool,
    written: WrittenReport,
) -> RepairReport {
    let (flipped, dropped, cap_triangles) = check.repairs();
    let holes_left = if capped { 0 } else { check.boundary_loops };
    let mut warnings = source.warnings.clone();
    if holes_left > 0 {
        warnings.push(format!(
            "{} left open (--cap closes them)",
            count(holes_left, "hole is", "holes are")
        ));
    }
    if !check.overlapping_bodies.is_empty() {
        // The file's objects were separate bodies; the mesh written is one object.
        warnings.push(format!(
            "{} of objects share volume, and the mesh is written as one object: read \
             back, a shell inside another is a cavity, not the sum `volume` reports",
            count(check.overlapping_bodies.len(), "pair", "pairs")
        ));
    }
    warnings.extend(written.warning());
    RepairReport {
        file: source.file.clone(),
        out: written.file.clone(),
        faces_in: surface.face_count(),
        faces_out: repaired.face_count(),
        faces_flipped: flipped,
        degenerate_faces_removed: check.degenerate_faces,
        duplicate_faces_removed: check.duplicate_faces,
        faces_removed: dropped,
        holes_capped: if capped { check.boundary_loops } else { 0 },
        cap_triangles: if capped { cap_triangles } else { 0 },
        holes_left,
        vertices_in: source.vertices,
        vertices_out: repaired.vertex_count(),
        weld_tolerance: check.weld_tolerance,
        signed_volume_before: mass_properties(surface).signed_volume,
        signed_volume_after: mass_properties(repaired).signed_volume,
        verdict_before: check.verdict(),
        warnings,
        written,
    }
}

impl Report for RepairReport {
    crate::file_and_warnings!("mesh");

    fn text(&self) -> String {
        let r = self;
        let mut s = String::new();
        let _ = writeln!(s, "{} -> {}", self.file(), r.out);
        let _ = writeln!(s, "  before: {}", r.verdict_before);
        let _ = writeln!(
            s,
            "  faces flipped      {} (shells turned outward, cavities inward)",
            r.faces_flipped
        );
        let _ = writeln!(
            s,
            "  faces removed      {} degenerate, {} duplicate",
            r.degenerate_faces_removed, r.duplicate_faces_removed
        );
        if r.holes_capped > 0 {
            let _ = writeln!(
                s,
                "  holes capped       {} ({})",
                r.holes_capped,
                count(r.cap_triangles, "triangle", "triangles")
            );
        } else if r.holes_left > 0 {
            let _ = writeln!(s, "  holes left open    {} (use --cap to close them)", r.holes_left);
        }
        let weld = r.weld_tolerance.map_or("exactly".into(), |t| format!("within {}", num(t, 4)));
        let _ = writeln!(
            s,
            "  vertices           {} in, {} out (welded {weld})",
            r.vertices_in, r.vertices_out
        );
        let _ = writeln!(
            s,
            "  signed volume      {} before, {} after",
            num(r.signed_volume_before, 15),
            num(r.signed_volume_after, 15)
        );
        let _ = writeln!(s, "  written            {}", r.written.text());
        s
    }
}
