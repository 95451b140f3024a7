//! What the page's 3D view draws of a checked mesh (`meshvol serve`, `check --html`):
//! the solid the check made (welded, shells turned outward, holes capped), each triangle
//! with its shell, and the problems the check found as geometry: the rims of holes and
//! the non-manifold edges (found again here by counting the solid's edge uses, so the
//! view draws what is there), the crossing face pairs, the overlapping shells and the
//! cavities. Built once, here, for both.

use meshvol::topology::Check;
use meshvol::Surface;
use serde::Serialize;
use std::collections::HashMap;

/// Solids with more faces than this are reported without their geometry: a page
/// would have to hold tens of megabytes of JSON to draw them.
pub const MAX_VIEW_FACES: usize = 2_000_000;

/// The view of one checked mesh. Coordinates are the file's own (the view has no
/// units); arrays are flat (x y z, or vertex ids, one after another) for the page's
/// WebGL buffers.
#[derive(Clone, Debug, Default, Serialize)]
pub struct View {
    /// The solid's vertices, x y z each.
    pub positions: Vec<f32>,
    /// The solid's triangles (its faces' fans), three vertex ids each.
    pub triangles: Vec<u32>,
    /// The shell of each triangle (as `shell_details` numbers them).
    pub triangle_shells: Vec<u32>,
    /// The triangles from this one on are the caps over holes.
    pub cap_start: usize,
    /// Edges of the file's faces used once: the rims of holes, vertex id pairs.
    pub boundary_edges: Vec<u32>,
    /// Edges used by three or more faces, vertex id pairs.
    pub non_manifold_edges: Vec<u32>,
    /// Crossing face pairs (the check's `intersection_examples`).
    pub crossings: Vec<Crossing>,
    /// Pairs of shells that overlap (`overlapping_shells`).
    pub overlapping_shells: Vec<[usize; 2]>,
    /// The shells that bound cavities.
    pub cavities: Vec<usize>,
    /// Why the geometry is left out (the arrays are then empty), if it is.
    pub omitted: Option<String>,
}

/// Two crossing faces of the file, each as its fan's triangles (9 coordinates each).
#[derive(Clone, Debug, Serialize)]
pub struct Crossing {
    pub faces: [usize; 2],
    pub triangles: [Vec<f32>; 2],
}

/// The view of `surface`, checked as `check`.
pub fn view<S: Surface + ?Sized>(surface: &S, check: &Check) -> View {
    let mut view = View {
        overlapping_shells: check.overlapping_shells.clone(),
        cavities: (0..check.shells.len()).filter(|&s| check.shells[s].cavity).collect(),
        crossings: check
            .intersection_examples
            .iter()
            .map(|&[a, b]| Crossing {
                faces: [a, b],
                triangles: [fan(surface, a), fan(surface, b)],
            })
            .collect(),
        ..View::default()
    };
    let triangles = surface.face_count() + check.repairs().2;
    if triangles > MAX_VIEW_FACES {
        view.omitted = Some(format!("{triangles} faces: the view draws at most {MAX_VIEW_FACES}"));
        return view;
    }
    let mesh = check.solid_mesh(true);
    let shells = check.solid_face_shells();
    let caps_from = mesh.face_count() - check.repairs().2;
    view.positions = mesh.positions().iter().flat_map(|p| p.map(|x| x as f32)).collect();
    let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
    for f in 0..mesh.face_count() {
        if f == caps_from {
            view.cap_start = view.triangles.len() / 3;
        }
        let ids = mesh.face(f);
        for k in 1..ids.len().saturating_sub(1) {
            view.triangles.extend([ids[0], ids[k], ids[k + 1]]);
            view.triangle_shells.push(shells.get(f).copied().unwrap_or(0));
        }
        if f < caps_from {
            for (k, &a) in ids.iter().enumerate() {
                let b = ids[(k + 1) % ids.len()];
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
    }
    if caps_from == mesh.face_count() {
        view.cap_start = view.triangles.len() / 3;
    }
    let mut edges: Vec<((u32, u32), u32)> = uses.into_iter().collect();
    edges.sort_unstable();
    for ((a, b), n) in edges {
        match n {
            1 => view.boundary_edges.extend([a, b]),
            2 => {}
            _ => view.non_manifold_edges.extend([a, b]),
        }
    }
    view
}

/// Face `f` of `surface` as its fan's triangles, 9 coordinates each.
fn fan<S: Surface + ?Sized>(surface: &S, f: usize) -> Vec<f32> {
    let mut out = Vec::new();
    if f < surface.face_count() {
        surface.fan(f, |a, b, c| out.extend([a, b, c].iter().flat_map(|p| p.map(|x| x as f32))));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use meshvol::shapes::cuboid;
    use meshvol::topology::{check, CheckOptions};
    use meshvol::Mesh;

    /// A unit cube's six quads without the top one: one square hole, whose rim is the
    /// top face's 4 edges, capped by the check.
    #[test]
    fn a_cube_without_its_top_shows_the_four_rim_edges_and_a_cap() {
        let cube = cuboid([0.0; 3], [1.0; 3]);
        let quads: Vec<&[u32]> =
            (0..6).map(|f| cube.face(f)).filter(|q| *q != [4, 5, 6, 7]).collect();
        assert_eq!(quads.len(), 5);
        let open = Mesh::from_polygons(cube.positions().to_vec(), quads).unwrap();
        let c = check(&open, &CheckOptions::default()).unwrap();
        let v = view(&open, &c);
        assert_eq!(v.boundary_edges.len() / 2, 4);
        assert!(v.non_manifold_edges.is_empty());
        // Every rim edge lies in the plane of the missing face, z = 1.
        for &id in &v.boundary_edges {
            assert_eq!(v.positions[3 * id as usize + 2], 1.0);
        }
        assert_eq!(v.cap_start, 10, "five quads, two triangles each, come first");
        assert!(v.triangles.len() / 3 > 10, "the hole is capped");
        assert_eq!(v.triangle_shells.len(), v.triangles.len() / 3);
    }

    /// Two cubes overlapping: the shells overlap and some faces cross.
    #[test]
    fn overlapping_cubes_show_their_pair_and_crossing_faces() {
        let mesh = Mesh::concatenate(&[
            cuboid([0.0; 3], [2.0; 3]),
            cuboid([1.0, 1.3, 1.6], [3.1, 3.2, 3.3]),
        ]);
        let c = check(&mesh, &CheckOptions::default()).unwrap();
        let v = view(&mesh, &c);
        assert_eq!(v.overlapping_shells, vec![[0, 1]]);
        assert_eq!(c.intersection_examples.len(), v.crossings.len());
        assert!(!v.crossings.is_empty());
        assert!(v
            .crossings
            .iter()
            .all(|x| x.triangles.iter().all(|t| t.len() % 9 == 0 && !t.is_empty())));
        assert!(v.boundary_edges.is_empty() && v.non_manifold_edges.is_empty());
        assert_eq!(v.cap_start, 24);
    }
}
