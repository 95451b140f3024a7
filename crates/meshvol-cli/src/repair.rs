//! `meshvol repair FILE -o OUT`: write the solid the mesh most plausibly bounds, and say
//! exactly what was changed. Never silent.

use meshvol::topology::CheckOptions;
use meshvol::{mass_properties, Surface};
use meshvol_io::write::{self, PlyEncoding};
use std::io::BufWriter;
use std::path::Path;

/// Checks `file`, writes the repaired mesh to `out`, and prints what changed.
pub fn run(
    file: &Path,
    out: &Path,
    cap: bool,
    json: bool,
    options: &CheckOptions,
) -> Result<(), String> {
    let name = file.display().to_string();
    let loaded = crate::input::load(file)?;
    let checked =
        meshvol::topology::check(&loaded.surface, options).map_err(|e| format!("{name}: {e}"))?;
    let report = crate::check::report(&checked);
    let mesh = checked.solid_mesh(cap);
    let extension = out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let written = std::fs::File::create(out).and_then(|f| {
        let mut w = BufWriter::new(f);
        match extension.as_deref() {
            Some("stl") => write::stl_binary(&mut w, &mesh),
            Some("obj") => write::obj(&mut w, &mesh),
            Some("ply") => write::ply(&mut w, &mesh, PlyEncoding::BinaryLittleEndian),
            Some("glb") => write::glb(&mut w, &mesh),
            _ => Err(std::io::Error::other("the output must end in .stl, .obj, .ply or .glb")),
        }?;
        std::io::Write::flush(&mut w)
    });
    written.map_err(|e| format!("{}: {e}", out.display()))?;

    let (flipped, dropped, cap_triangles) = checked.repairs();
    let caps = if cap { cap_triangles } else { 0 };
    let before = mass_properties(&loaded.surface).signed_volume;
    let after = mass_properties(&mesh).signed_volume;
    let holes_left = if cap { 0 } else { report.boundary_loops };
    let summary = serde_json::json!({
        "file": name,
        "out": out.display().to_string(),
        "faces_in": loaded.surface.face_count(),
        "faces_out": mesh.face_count(),
        "faces_flipped": flipped,
        "degenerate_faces_removed": report.degenerate_faces,
        "duplicate_faces_removed": report.duplicate_faces,
        "faces_removed": dropped,
        "holes_capped": if cap { report.boundary_loops } else { 0 },
        "cap_triangles": caps,
        "holes_left": holes_left,
        "vertices_in": loaded.vertex_count(),
        "vertices_out": mesh.vertex_count(),
        "weld_tolerance": report.weld_tolerance,
        "signed_volume_before": before,
        "signed_volume_after": after,
        "verdict_before": report.verdict,
    });
    if json {
        println!("{summary}");
    } else {
        println!("{name} -> {}", out.display());
        println!("  before: {}", report.verdict);
        println!("  faces flipped      {flipped} (shells turned outward, cavities inward)");
        println!(
            "  faces removed      {} degenerate, {} duplicate",
            report.degenerate_faces, report.duplicate_faces
        );
        if cap {
            println!("  holes capped       {} ({caps} triangles)", report.boundary_loops);
        } else if holes_left > 0 {
            println!("  holes left open    {holes_left} (use --cap to close them)");
        }
        let weld = report.weld_tolerance.map_or("exactly".into(), |t| format!("within {t:.3e}"));
        println!(
            "  vertices           {} in, {} out (welded {weld})",
            loaded.vertex_count(),
            mesh.vertex_count()
        );
        println!("  signed volume      {before} before, {after} after");
    }
    Ok(())
}
