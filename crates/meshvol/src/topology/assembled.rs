//! The check of an assembly (see [`crate::assembly`]) from one check of each part.
//!
//! When the copies' boxes are apart (no two closed boxes meet), no edge, vertex,
//! crossing or nesting joins two copies, so every fact of the whole is the copies' facts
//! put side by side: counts add up, shells follow one another (volumes scaled by
//! |det|), and a copy's solid is its part's solid moved. A non-degenerate affine map
//! keeps incidence, orientation and crossings, so each copy's facts are its part's.
//! What a transform could change only through rounding (a nearly flat face becoming
//! flat) is taken from the part.
//!
//! The whole is checked the ordinary way instead when that is not sure to agree: copies
//! whose boxes meet, a weld tolerance (welding within a distance is not preserved by
//! scaling), `Weld::Auto` with an open part (the whole would be welded again within a
//! tolerance), a degenerate or non-finite transform, or an assembly that does not
//! describe the surface's faces.

use super::{
    check, check_in_stages, solid::Solid, Check, CheckError, CheckOptions, Orientation,
    StageReport, Weld,
};
use crate::assembly::Assembly;
use crate::bvh::Bvh;
use crate::{Bounds, Surface};
use rayon::prelude::*;
use std::ops::Range;

/// [`check`] of `surface`, from one check of each part of `assembly` when it describes
/// how `surface` was assembled, repeats parts, and its copies are apart (see the module
/// docs); the same facts either way, at the cost of the parts instead of the copies.
/// `bodies` and `stage` are [`super::check_in_stages`]'s: copies apart share no volume,
/// so their bodies matter only to the ordinary check.
pub fn check_assembled<S: Surface + ?Sized>(
    surface: &S,
    assembly: Option<&Assembly>,
    bodies: &[Range<usize>],
    options: &CheckOptions,
    stage: StageReport<'_>,
) -> Result<Check, CheckError> {
    if let Some(assembly) = assembly.filter(|a| a.repeats_parts()) {
        super::enter(stage, "checking each placed part once")?;
        if let Some(whole) = from_parts(assembly, surface.face_count(), bodies, options)? {
            return Ok(whole);
        }
    }
    check_in_stages(surface, bodies, options, stage)
}

/// The whole's check from its parts', or `None` when it must be checked whole.
fn from_parts(
    assembly: &Assembly,
    faces: usize,
    bodies: &[Range<usize>],
    options: &CheckOptions,
) -> Result<Option<Check>, CheckError> {
    let placements = &assembly.placements;
    let usable = |p: &crate::assembly::Placement| {
        (p.part as usize) < assembly.parts.len()
            && p.transform.is_finite()
            && p.transform.determinant() != 0.0
    };
    if matches!(options.weld, Weld::Tolerance(_))
        || !placements.iter().all(usable)
        || assembly.face_count() != faces
        || !copies_apart(assembly)
    {
        return Ok(None);
    }
    let exact = CheckOptions { weld: Weld::Exact, ..*options };
    let parts: Vec<Check> =
        assembly.parts.par_iter().map(|m| check(m, &exact)).collect::<Result<_, _>>()?;
    if options.weld == Weld::Auto && parts.iter().any(|c| c.boundary_edges > 0) {
        return Ok(None);
    }
    Ok(Some(compose(assembly, &parts, bodies, options.examples)))
}

/// Whether no two copies' boxes meet (touching counts as meeting).
fn copies_apart(assembly: &Assembly) -> bool {
    let part_boxes: Vec<Option<Bounds>> =
        assembly.parts.iter().map(|p| Bounds::of_points(p.positions())).collect();
    let boxes: Vec<Bounds> = assembly
        .placements
        .iter()
        .filter_map(|p| part_boxes[p.part as usize].map(|b| p.transform.bounds(&b)))
        .collect();
    let (order, bvh) = Bvh::over_boxes(&boxes);
    let meet = |i: usize, j: usize| {
        let (a, b) = (&boxes[order[i] as usize], &boxes[order[j] as usize]);
        (0..3).all(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k])
    };
    bvh.first_overlapping_pair(None, meet).is_none()
}

/// The copies' facts side by side; each copy's shells in the body of its first face.
fn compose(
    assembly: &Assembly,
    parts: &[Check],
    bodies: &[Range<usize>],
    examples: usize,
) -> Check {
    let copies = || assembly.placements.iter().map(|p| (&parts[p.part as usize], p.transform));
    let sum = |fact: fn(&Check) -> usize| copies().map(|(c, _)| fact(c)).sum::<usize>();
    let mut shells = Vec::with_capacity(sum(|c| c.shells.len()));
    let (mut overlapping_shells, mut intersection_examples) = (Vec::new(), Vec::new());
    let (mut volume, mut volume_uncertainty, mut face_offset) = (0.0, 0.0, 0);
    let mut object_of_shell = Vec::new();
    for (part, transform) in copies() {
        let (scale, shell_offset) = (transform.determinant().abs(), shells.len());
        shells.extend(part.shells.iter().map(|s| super::Shell {
            volume: s.volume * scale,
            parent: s.parent.map(|p| p + shell_offset),
            ..s.clone()
        }));
        let moved = |pair: &[usize; 2], by: usize| pair.map(|x| x + by);
        overlapping_shells.extend(part.overlapping_shells.iter().map(|p| moved(p, shell_offset)));
        let room = examples.saturating_sub(intersection_examples.len());
        let pairs = part.intersection_examples.iter().take(room);
        intersection_examples.extend(pairs.map(|p| moved(p, face_offset)));
        volume += part.volume * scale;
        volume_uncertainty += part.volume_uncertainty * scale;
        // A body is a run of whole copies (a 3MF mesh placed, a glTF node's primitives).
        let object = super::bodies::of_face(bodies, face_offset);
        object_of_shell.extend(part.shells.iter().map(|_| object));
        face_offset += part.faces;
    }
    let placed: Vec<&Check> = copies().map(|(c, _)| c).collect();
    let orientations = placed.iter().filter_map(|c| c.orientation);
    let orientation = orientations.reduce(|a, b| if a == b { a } else { Orientation::Mixed });
    let self_intersections = placed.iter().map(|c| c.self_intersections).sum::<Option<usize>>();
    let part_solids: Vec<&Solid> = parts.iter().map(|c| &c.solid).collect();
    let part_shells: Vec<usize> = parts.iter().map(|c| c.shells.len()).collect();
    Check {
        weld_tolerance: None,
        vertices: sum(|c| c.vertices),
        edges: sum(|c| c.edges),
        faces: sum(|c| c.faces),
        closed: placed.iter().all(|c| c.closed),
        boundary_edges: sum(|c| c.boundary_edges),
        boundary_loops: sum(|c| c.boundary_loops),
        non_manifold_edges: sum(|c| c.non_manifold_edges),
        unpaired_at_non_manifold_edges: sum(|c| c.unpaired_at_non_manifold_edges),
        non_manifold_vertices: sum(|c| c.non_manifold_vertices),
        degenerate_faces: sum(|c| c.degenerate_faces),
        flat_faces: sum(|c| c.flat_faces),
        duplicate_faces: sum(|c| c.duplicate_faces),
        double_wall_faces: sum(|c| c.double_wall_faces),
        consistently_oriented: placed.iter().all(|c| c.consistently_oriented),
        orientation,
        cavities: sum(|c| c.cavities),
        shells,
        overlapping_shells,
        // Copies apart share no volume.
        overlapping_bodies: Vec::new(),
        self_intersections,
        intersection_examples,
        euler_characteristic: placed.iter().map(|c| c.euler_characteristic).sum(),
        volume,
        volume_uncertainty,
        solid: Solid::assembled(&part_solids, &part_shells, &assembly.placements),
        // Not exactly welded (a transform may round two of a part's points to one).
        spatial_index: None,
        object_of_shell: (!bodies.is_empty()).then_some(object_of_shell),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::{Affine, Placement};
    use crate::shapes::{cuboid, tetrahedron, uv_sphere};
    use crate::{mass_properties, Mesh};

    /// The expanded mesh, built as the readers build it: each copy's corners moved, its
    /// triangles reversed when the transform mirrors.
    fn expand(assembly: &Assembly) -> Mesh {
        let (mut positions, mut triangles) = (Vec::new(), Vec::new());
        for p in &assembly.placements {
            let part = &assembly.parts[p.part as usize];
            let base = positions.len() as u32;
            positions.extend(part.positions().iter().map(|&x| p.transform.apply(x)));
            for f in 0..part.face_count() {
                let [a, b, c] = <[u32; 3]>::try_from(part.face(f)).unwrap().map(|v| v + base);
                let mirrored = p.transform.determinant() < 0.0;
                triangles.push(if mirrored { [a, c, b] } else { [a, b, c] });
            }
        }
        Mesh::from_triangles(positions, triangles).unwrap()
    }

    fn shift(t: [f64; 3]) -> Affine {
        Affine([[1.0, 0.0, 0.0, t[0]], [0.0, 1.0, 0.0, t[1]], [0.0, 0.0, 1.0, t[2]]])
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0)
    }

    /// The facts from the parts against the facts of the whole, checked the ordinary way.
    fn assert_same(fast: &Check, full: &Check, mesh: &Mesh) {
        let counts = |c: &Check| (c.vertices, c.edges, c.faces, c.boundary_edges, c.boundary_loops);
        assert_eq!(counts(fast), counts(full));
        let more = |c: &Check| {
            (
                c.closed,
                c.non_manifold_edges,
                c.non_manifold_vertices,
                c.degenerate_faces,
                c.flat_faces,
                c.duplicate_faces,
                c.double_wall_faces,
                c.consistently_oriented,
                c.orientation,
                c.cavities,
                c.euler_characteristic,
                c.weld_tolerance,
            )
        };
        assert_eq!(more(fast), more(full));
        assert_eq!(
            (&fast.overlapping_shells, fast.self_intersections),
            (&full.overlapping_shells, full.self_intersections)
        );
        assert_eq!(fast.shells.len(), full.shells.len());
        for (a, b) in fast.shells.iter().zip(&full.shells) {
            assert!(close(a.volume, b.volume), "{} {}", a.volume, b.volume);
            assert_eq!(super::super::Shell { volume: b.volume, ..a.clone() }, *b);
        }
        assert!(
            close(fast.volume, full.volume)
                && close(fast.volume_uncertainty, full.volume_uncertainty)
        );
        assert_eq!(fast.repairs(), full.repairs());
        assert_eq!(fast.bodies(), full.bodies());
        let (a, b) = (mass_properties(&fast.solid(mesh)), mass_properties(&full.solid(mesh)));
        assert!(close(a.signed_volume, b.signed_volume));
        assert_eq!(a.bounds, b.bounds);
        // Cap centres differ in the last bits: the centroid moved, against the centroid
        // of the moved rim.
        let (a, b) = (fast.solid_mesh(true), full.solid_mesh(true));
        assert_eq!(a.faces(), b.faces());
        let near = |p: &[f64; 3], q: &[f64; 3]| (0..3).all(|k| close(p[k], q[k]));
        assert!(a.positions().iter().zip(b.positions()).all(|(p, q)| near(p, q)));
    }

    fn parts() -> Vec<Mesh> {
        let tet = tetrahedron([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.75]);
        // A box with a cavity, both wound outward in the file: the cavity gets flipped.
        let hollow = Mesh::concatenate(&[cuboid([0.0; 3], [2.0; 3]), cuboid([0.5; 3], [1.5; 3])]);
        // Two boxes that overlap: overlapping shells within the part.
        let pair = Mesh::concatenate(&[cuboid([0.0; 3], [1.0; 3]), cuboid([0.5; 3], [1.5; 3])]);
        [tet, hollow.triangulated(), pair.triangulated(), uv_sphere(0.9, 12, 6).triangulated()]
            .into()
    }

    fn placements() -> Vec<Placement> {
        let turn = Affine([[0.0, -1.0, 0.0, 30.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);
        let mirror = Affine([[-1.0, 0.0, 0.0, 40.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);
        let scale = Affine([[2.0, 0.0, 0.0, 50.0], [0.0, 0.5, 0.0, 0.0], [0.0, 0.0, 3.0, 0.0]]);
        let mut all = Vec::new();
        for part in 0..4u32 {
            let y = 10.0 * part as f64;
            for (i, t) in [shift([0.0; 3]), shift([10.0, 0.0, 0.0]), turn, mirror, scale]
                .into_iter()
                .enumerate()
            {
                let t = t.then(&shift([0.0, y, 5.0 * i as f64]));
                all.push(Placement { part, transform: t });
            }
        }
        all
    }

    #[test]
    fn copies_apart_get_the_facts_of_the_whole() {
        let assembly = Assembly { parts: parts(), placements: placements() };
        let mesh = expand(&assembly);
        for intersections in [true, false] {
            for weld in [Weld::Exact, Weld::Auto] {
                let options = CheckOptions { weld, intersections, ..CheckOptions::default() };
                let fast = from_parts(&assembly, mesh.face_count(), &[], &options).unwrap();
                let fast = fast.expect("the copies are apart");
                assert_same(&fast, &check(&mesh, &options).unwrap(), &mesh);
            }
        }
    }

    #[test]
    fn open_parts_are_composed_when_welded_exactly_only() {
        let open = cuboid([0.0; 3], [1.0; 3]).triangulated();
        let faces: Vec<[u32; 3]> =
            (1..open.face_count()).map(|f| open.face(f).try_into().unwrap()).collect();
        let open = Mesh::from_triangles(open.positions().to_vec(), faces).unwrap();
        let placements = (0..20)
            .map(|i| Placement { part: 0, transform: shift([2.0 * i as f64, 0.0, 0.0]) })
            .collect();
        let assembly = Assembly { parts: vec![open], placements };
        let mesh = expand(&assembly);
        let exact = CheckOptions { weld: Weld::Exact, ..CheckOptions::default() };
        let fast = from_parts(&assembly, mesh.face_count(), &[], &exact).unwrap().unwrap();
        assert_same(&fast, &check(&mesh, &exact).unwrap(), &mesh);
        assert_eq!(fast.boundary_loops, 20);
        // Auto would weld the whole again within a tolerance: checked whole.
        let auto = CheckOptions::default();
        assert!(from_parts(&assembly, mesh.face_count(), &[], &auto).unwrap().is_none());
        let tolerance = CheckOptions { weld: Weld::Tolerance(1e-6), ..auto };
        assert!(from_parts(&assembly, mesh.face_count(), &[], &tolerance).unwrap().is_none());
    }

    #[test]
    fn copies_that_meet_are_checked_whole() {
        let cube = cuboid([0.0; 3], [1.0; 3]).triangulated();
        let options = CheckOptions::default();
        // Overlapping, touching face to face (a double wall), and the same place twice.
        for offset in [0.5, 1.0, 0.0] {
            let placements = vec![
                Placement { part: 0, transform: Affine::IDENTITY },
                Placement { part: 0, transform: shift([offset, 0.0, 0.0]) },
            ];
            let assembly = Assembly { parts: vec![cube.clone()], placements };
            let mesh = expand(&assembly);
            assert!(from_parts(&assembly, mesh.face_count(), &[], &options).unwrap().is_none());
            let c = check_assembled(&mesh, Some(&assembly), &[], &options, &|_| {}).unwrap();
            assert_same(&c, &check(&mesh, &options).unwrap(), &mesh);
        }
        // A degenerate transform, and an assembly that is not this surface's.
        let flat = Affine([[1.0, 0.0, 0.0, 5.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0]]);
        let placements = vec![
            Placement { part: 0, transform: Affine::IDENTITY },
            Placement { part: 0, transform: flat },
        ];
        let assembly = Assembly { parts: vec![cube.clone()], placements };
        assert!(from_parts(&assembly, 24, &[], &options).unwrap().is_none());
        assert!(from_parts(&assembly, 25, &[], &options).unwrap().is_none());
    }

    #[test]
    fn many_copies_cost_their_part_once() {
        // 10⁵ tetrahedra of volume 1/8 on a grid: the volume is exactly 12500.
        let tet = tetrahedron([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.75]);
        let placements = (0..100_000)
            .map(|i| {
                let (x, y) = ((i % 1000) as f64, (i / 1000) as f64);
                Placement { part: 0, transform: shift([2.0 * x, 2.0 * y, 0.0]) }
            })
            .collect();
        let assembly = Assembly { parts: vec![tet], placements };
        let mesh = expand(&assembly);
        let c = from_parts(&assembly, mesh.face_count(), &[], &CheckOptions::default());
        let c = c.unwrap().expect("the copies are apart");
        assert!(c.bounds_a_volume());
        assert_eq!((c.shells.len(), c.faces, c.volume), (100_000, 400_000, 12500.0));
        let m = mass_properties(&c.solid(&mesh));
        assert!((m.signed_volume - 12500.0).abs() <= m.volume_error_bound);
    }
}
