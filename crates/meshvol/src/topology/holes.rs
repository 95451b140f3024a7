//! Stage 5, holes: the edges the faces leave open chained into loops, each capped with
//! a fan from its centroid, and each shell's volume with its holes capped.
//!
//! An edge is open where a face is alone at it (a boundary edge, or the odd face out at
//! a non-manifold edge: see `sheets.rs`), or where a sheet's two faces run it the same
//! way after orientation propagation (the seam of a non-orientable shell, where both
//! count). Each open edge is followed in the direction its face was given by
//! propagation, so a loop runs the way its shell does and the cap (centre, q, p) over
//! rim edge p → q closes the shell the same way round. With its caps every shell is then
//! closed, as a chain: each edge is run as often one way as the other, so every measure
//! taken of the solid (the volume about any point, a grid's columns, a profile's
//! slabs, a part below a plane) is one and the same integral, whatever the surface.
//!
//! A cap may be off by as much as its area times the rim's largest distance from the
//! cap's plane (along the unit normal of the cap's vector area): zero for a flat hole,
//! which is thus recovered exactly.
//!
//! A shell's volume is (1/6) Σ (a − r)·((b − r) × (c − r)) over the fan triangles of its
//! faces, as propagated, and of its caps, about the first corner r (terms the size of
//! the model, not of its offset), summed with compensation in face order.

use super::edges::{EdgeUse, Edges};
use super::loops::Loops;
use super::shells::Shells;
use super::weld::Welded;
use crate::accumulate::CompensatedSum;
use crate::vector::{add, cross, dot, norm, scale, sub};
use crate::{Point, Surface};
use rayon::prelude::*;

/// The fans capping boundary loops, as points and as vertex ids (each centre a new
/// vertex after the welded ones), with their shells.
pub(super) struct Caps {
    pub points: Vec<[Point; 3]>,
    pub ids: Vec<[u32; 3]>,
    pub centres: Vec<Point>,
    pub shell: Vec<u32>,
    /// Boundary loops per shell.
    pub per_shell: Vec<usize>,
    /// Per cap, its area times the rim's largest distance from its plane, summed.
    pub volume_uncertainty: f64,
}

/// The caps over the boundary loops of the `edges` (each its uses) of `shells`.
pub(super) fn caps(loops: &Loops, welded: &Welded, edges: &Edges, shells: &Shells) -> Caps {
    let vid = |c: usize| welded.corner_vertex[c];
    let (flip, shell_of_face) = (&shells.flip, &shells.of_face);
    // An edge use as its face runs it after propagation, with the face's shell.
    let directed = |e: &EdgeUse| {
        let (f, c) = (e.face() as usize, e.corner as usize);
        let n = loops.next(f, c);
        let (u, v) = if flip[f] { (vid(n), vid(c)) } else { (vid(c), vid(n)) };
        (u, v, shell_of_face[f])
    };
    // What the propagated faces leave open: each face alone at an edge, and both faces
    // of a sheet that propagation could not turn against each other (the seam of a
    // non-orientable shell).
    let after = |e: &EdgeUse| e.forward() ^ flip[e.face() as usize];
    let open = |sheet: &&[EdgeUse]| sheet.len() == 1 || after(&sheet[0]) == after(&sheet[1]);
    // (In parallel over the edges, collected in edge order.)
    let boundary: Vec<(u32, u32, u32)> = edges
        .par_iter()
        .flat_map_iter(|g| g.chunks(2).filter(open).flat_map(|sheet| sheet.iter().map(directed)))
        .collect();
    let loops_found = boundary_loops(&boundary);
    let mut caps: Vec<[Point; 3]> = Vec::new();
    // The same caps as vertex ids, each centre a new vertex after the welded ones.
    let mut cap_ids: Vec<[u32; 3]> = Vec::new();
    let mut centres: Vec<Point> = Vec::new();
    let mut cap_shell: Vec<u32> = Vec::new();
    let mut shell_loops = vec![0usize; shells.count];
    let mut volume_uncertainty = 0.0;
    for (shell, ring) in &loops_found {
        shell_loops[*shell as usize] += 1;
        let pts: Vec<Point> = ring.iter().map(|&v| welded.positions[v as usize]).collect();
        let centre = scale(pts.iter().fold([0.0; 3], |s, &p| add(s, p)), 1.0 / pts.len() as f64);
        let centre_id = (welded.positions.len() + centres.len()) as u32;
        centres.push(centre);
        let mut vector_area = [0.0; 3];
        for i in 0..pts.len() {
            let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
            // The cap traverses each rim edge against its face: (centre, q, p).
            caps.push([centre, q, p]);
            cap_ids.push([centre_id, ring[(i + 1) % ring.len()], ring[i]]);
            cap_shell.push(*shell);
            vector_area = add(vector_area, cross(sub(q, centre), sub(p, centre)));
        }
        let area = norm(vector_area) / 2.0;
        if area > 0.0 {
            let n = scale(vector_area, 0.5 / area);
            let thickness = pts.iter().map(|&p| dot(sub(p, centre), n).abs()).fold(0.0, f64::max);
            volume_uncertainty += area * thickness;
        }
    }
    Caps {
        points: caps,
        ids: cap_ids,
        centres,
        shell: cap_shell,
        per_shell: shell_loops,
        volume_uncertainty,
    }
}

/// Per shell: its signed volume as propagated from its first face, holes capped.
pub(super) fn shell_volumes<S: Surface + ?Sized>(
    surface: &S,
    welded: &Welded,
    kept: &[bool],
    shells: &Shells,
    caps: &Caps,
) -> Vec<f64> {
    let flip = &shells.flip;
    // Per-shell signed volume (propagated orientation, holes capped), about a local point.
    let reference = welded.positions.first().copied().unwrap_or([0.0; 3]);
    let six_volume = |a: Point, b: Point, c: Point| {
        let (a, b, c) = (sub(a, reference), sub(b, reference), sub(c, reference));
        dot(a, cross(b, c))
    };
    let face_six = |f: usize| {
        let mut s = 0.0;
        surface.fan(f, |a, b, c| s += six_volume(a, b, c));
        if flip[f] {
            -s
        } else {
            s
        }
    };
    // In fixed chunks of faces, merged in order: the same bits at any thread count (a
    // serial sum over every face did not scale).
    let mut shell_six = shells.fold_faces(
        kept,
        |sum: &mut CompensatedSum, f| sum.add(face_six(f)),
        CompensatedSum::merge,
    );
    for (cap, &s) in caps.points.iter().zip(&caps.shell) {
        shell_six[s as usize].add(six_volume(cap[0], cap[1], cap[2]));
    }
    shell_six.iter().map(|s| s.value() / 6.0).collect()
}

/// Chains the open edges (u, v, shell) into loops of vertices, each in one shell,
/// following each edge's direction. Per shell the open edges are the boundary of its
/// faces as propagated, less the sheets that cancel: a cycle, so every vertex has as
/// many open edges leaving as arriving, and a walk can only end where it began.
fn boundary_loops(edges: &[(u32, u32, u32)]) -> Vec<(u32, Vec<u32>)> {
    // Every edge listed at its start: (vertex, shell, edge).
    let mut starts: Vec<(u32, u32, usize)> =
        edges.iter().enumerate().map(|(i, e)| (e.0, e.2, i)).collect();
    starts.sort_unstable();
    let mut used = vec![false; edges.len()];
    // Per (vertex, shell): how many of its leaving edges are used, so each is taken once.
    let mut taken = vec![0usize; edges.len()];
    let mut loops = Vec::new();
    for first in 0..edges.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let shell = edges[first].2;
        let mut ring = vec![edges[first].0];
        let mut at = edges[first].1;
        while at != edges[first].0 {
            ring.push(at);
            let from = starts.partition_point(|e| (e.0, e.1) < (at, shell));
            let leaving = starts[from..].iter().take_while(|e| (e.0, e.1) == (at, shell));
            let next = leaving.skip(taken[from]).find(|e| !used[e.2]);
            let Some(&(_, _, e)) = next else { break }; // not a cycle: close it here
            taken[from] += 1;
            used[e] = true;
            at = edges[e].1;
        }
        loops.push((shell, ring));
    }
    loops
}
