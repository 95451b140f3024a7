//! `intersect`: the volume of the intersection of two bodies as a certified interval,
//! with the union, the differences, IoU and Dice that follow from it, widened by the
//! caps' uncertainty, with the warnings that say when it is not certified.

use crate::number::num;
use crate::quantities::{Converter, Dimension::*, Quantities};
use crate::subject::{joined_names, Subject};
use crate::union::{footer_text, grid_text, uncertified, CertifiedInterval, Interval};
use crate::units::{Mass, UnitNames};
use crate::Report;
use meshvol::assembly::Affine;
use meshvol::grid::{intersection_placed as kernel, overlapping_boxes, Bounded};
use meshvol::overlap::Body;
use meshvol::progress::Progress;
use meshvol::Surface;
use rayon::prelude::*;
use serde::Serialize;
use std::fmt::Write;
use std::time::Instant;

/// The report. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct IntersectReport {
    /// The two inputs, joined by `, `.
    pub file: String,
    pub files: Vec<String>,
    /// `lower ≤ |A∩B| ≤ upper`, `certified` (the union's rule, each input one body),
    /// `uncertified_reason`, `volume` (the midpoint).
    #[serde(flatten)]
    pub interval: CertifiedInterval,
    /// |A| and |B|: the volumes of the two checked solids.
    pub volume_a: f64,
    pub volume_b: f64,
    /// |A∪B| = |A| + |B| − |A∩B|, and its interval.
    pub union: f64,
    pub union_lower: f64,
    pub union_upper: f64,
    /// |A∖B| = |A| − |A∩B| and |B∖A| = |B| − |A∩B|.
    pub a_minus_b: f64,
    pub b_minus_a: f64,
    /// |A∩B| / |A∪B| (0 when the union is empty), and its interval.
    pub iou: f64,
    pub iou_lower: f64,
    pub iou_upper: f64,
    /// 2|A∩B| / (|A| + |B|).
    pub dice: f64,
    /// The centroid of A∩B, and its inertia tensor about the centroid for unit density;
    /// `null` without volume or where the boundary could not be resolved everywhere.
    pub centroid: Option<[f64; 3]>,
    pub inertia: Option<[[f64; 3]; 3]>,
    /// The interface: the area of ∂A inside B plus ∂B inside A; ∫ n dA over ∂B inside A
    /// (n: B's outward normal), which is the rate of change of the overlap volume as B
    /// moves (`d|A∩B|/dt = e · contact_vector` for a motion `t·e` of B); and its
    /// direction (`null` when it is 0). 0 when the boxes are apart; `null` where the
    /// moments are.
    pub contact_area: Option<f64>,
    pub contact_vector: Option<[f64; 3]>,
    pub contact_normal: Option<[f64; 3]>,
    /// The bodies' boxes are apart (or only touch): the intersection is 0, found
    /// without a grid.
    pub disjoint: bool,
    pub cells_refined: usize,
    pub cells_resolved_exactly: usize,
    /// Grid columns left unresolved: their bounds stay in the interval.
    pub columns_unresolved: usize,
    /// Inputs (0: A, 1: B) wound inward, measured turned outward.
    pub flipped: Vec<usize>,
    /// How far the caps on the bodies' holes could put the volumes off; the intervals
    /// are widened by it (0 for closed bodies).
    pub volume_uncertainty: f64,
    /// How the interval was found: `boxes` (the boxes are apart or only touch: 0),
    /// `boundary` (from the parts of each body's faces inside the other, where the faces
    /// cross in general position and both checks vouch for the bodies) or `grid` (the
    /// grid method, which also settles touching and coplanar faces).
    pub method: &'static str,
    /// The base grid's cells (`[1, 1, 1]` when no grid was used).
    pub grid: [usize; 3],
    pub seconds: f64,
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    pub warnings: Vec<String>,
}

/// The intersection of `a` and `b`, each whole (every shell of an input is part of its
/// body), refined until `upper − lower ≤ tolerance · lower` where it can be.
pub fn intersect<S: Surface + Sync>(
    a: &Subject<'_, S>,
    b: &Subject<'_, S>,
    tolerance: f64,
) -> Result<IntersectReport, String> {
    intersect_with(a, b, tolerance, &())
}

/// [`intersect`], telling `progress` the kernel's stages and how far each is.
pub fn intersect_with<S: Surface + Sync>(
    a: &Subject<'_, S>,
    b: &Subject<'_, S>,
    tolerance: f64,
    progress: &dyn Progress,
) -> Result<IntersectReport, String> {
    intersect_posed(a, b, [None, None], tolerance, progress)
}

/// How far a pose's rotation may be from orthonormal (each entry of `RᵀR − I`) and
/// still be taken as rigid: room for rotations rounded to float32. The volumes are
/// those of the bodies as moved (their coordinates after the pose, rounded to f64), so
/// a rotation that far off scales them by up to about 1.5·10⁻⁶ relative.
pub const POSE_TOLERANCE: f64 = 1e-6;

/// A 4×4 homogeneous matrix as a rigid motion (rotation, then translation), or why it is
/// not one: a non-finite entry, a last row other than `0 0 0 1`, a rotation part that is
/// not orthonormal within [`POSE_TOLERANCE`] (a scale or a shear), or a mirror.
pub fn rigid_pose(m: &[[f64; 4]; 4]) -> Result<Affine, String> {
    for (r, row) in m.iter().enumerate() {
        for (c, x) in row.iter().enumerate() {
            if !x.is_finite() {
                return Err(format!("entry [{r}][{c}] is {x}; a pose must be finite"));
            }
        }
    }
    if m[3] != [0.0, 0.0, 0.0, 1.0] {
        let row: Vec<String> = m[3].iter().map(|x| x.to_string()).collect();
        return Err(format!(
            "its last row is {}; a rigid pose's last row is 0 0 0 1",
            row.join(" ")
        ));
    }
    let pose = Affine([m[0], m[1], m[2]]);
    let mut defect: f64 = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..3).map(|k| m[k][i] * m[k][j]).sum();
            defect = defect.max((dot - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    let det = pose.determinant();
    if defect > POSE_TOLERANCE {
        return Err(format!(
            "its 3×3 part is not a rotation (RᵀR differs from the identity by {defect:.1e}: \
             a scale or a shear); a rigid pose's rotation must be orthonormal within \
             {POSE_TOLERANCE:e}"
        ));
    }
    if det < 0.0 {
        return Err(format!(
            "its 3×3 part has determinant {det}: a mirror, not a rotation (determinant +1)"
        ));
    }
    Ok(pose)
}

/// [`intersect_with`] with each body placed by a pose (`None`: where it is): each
/// body's checked solid, as the check made it, moved rigidly (nothing is checked
/// again), so a loop over poses reuses the checks. Poses must be rigid ([`rigid_pose`]):
/// a rigid motion keeps the solid, its winding and its caps' uncertainty.
pub fn intersect_posed<S: Surface + Sync>(
    a: &Subject<'_, S>,
    b: &Subject<'_, S>,
    poses: [Option<Affine>; 2],
    tolerance: f64,
    progress: &dyn Progress,
) -> Result<IntersectReport, String> {
    let bodies = prepare_pair(a, b);
    intersect_prepared(a, b, [bodies[0].as_ref(), bodies[1].as_ref()], poses, tolerance, progress)
}

/// [`prepare`] of two subjects side by side (each body the same whichever thread
/// prepares it).
pub fn prepare_pair<S: Surface + Sync>(
    a: &Subject<'_, S>,
    b: &Subject<'_, S>,
) -> [Option<Body>; 2] {
    let (a, b) = rayon::join(|| prepare(a), || prepare(b));
    [a, b]
}

/// A subject's checked solid prepared for the boundary method ([`Body`]), when its
/// check vouches for it: checked, manifold, with no self-intersection, no double walls
/// and no overlapping shells. The method takes insideness as the parity of crossings,
/// which is the solid's (winding number above 0) only where the surface never lies
/// over itself; a non-manifold edge is where it can fold onto itself without crossing
/// (a tetrahedron sharing a cube's corners, its faces on the cube's). `None` otherwise,
/// and unchecked: the grid method measures those.
pub fn prepare<S: Surface + Sync>(s: &Subject<'_, S>) -> Option<Body> {
    let check = s.check?;
    let simple = check.self_intersections == Some(0)
        && check.overlapping_shells.is_empty()
        && check.overlapping_bodies.is_empty()
        && check.non_manifold_edges == 0
        && check.double_wall_faces == 0;
    // The check's solid (as `whole()` measures it), from the check's own weld.
    simple.then(|| Body::of_solid(check, s.surface))
}

/// [`intersect_posed`] with the bodies already prepared ([`prepare`]; `None`: measured
/// by the grid method), so a loop over poses prepares nothing again.
pub fn intersect_prepared<S: Surface + Sync>(
    a: &Subject<'_, S>,
    b: &Subject<'_, S>,
    bodies: [Option<&Body>; 2],
    poses: [Option<Affine>; 2],
    tolerance: f64,
    progress: &dyn Progress,
) -> Result<IntersectReport, String> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(format!("tolerance must be a positive number; got {tolerance}"));
    }
    let subjects = [*a, *b];
    let mut warnings: Vec<String> = subjects
        .iter()
        .flat_map(|s| s.warnings().into_iter().map(|w| format!("{}: {w}", s.source.name())))
        .collect();
    let names: Vec<String> = subjects.iter().map(|s| s.source.name().to_string()).collect();
    let (surface_a, surface_b) = (a.whole().surface, b.whole().surface);
    let start = Instant::now();
    let mut i = kernel(&surface_a, &surface_b, bodies, poses, tolerance, progress)
        .map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    // Caps on holes are guesses: the intervals must hold whatever the missing faces were.
    let (ua, ub) = (a.volume_uncertainty(), b.volume_uncertainty());
    let uncertainty = ua + ub;
    if !i.disjoint {
        i.lower = (i.lower - uncertainty).max(0.0);
        i.upper += uncertainty;
    }
    i.error_a += ua;
    i.error_b += ub;
    // Boxes apart give 0 whatever the bodies are.
    let certification =
        if i.disjoint { None } else { uncertified(&subjects, true, i.bodies_not_solid.len()) };
    warnings.extend(
        Interval {
            names: &names,
            flipped: &i.flipped,
            flipped_note: "",
            not_solid: &i.bodies_not_solid,
            columns_unresolved: i.columns_unresolved,
            bounds: (i.lower, i.upper),
            tolerance,
            uncertainty,
        }
        .warnings(),
    );
    let (union, iou): (Bounded, Bounded) = (i.union(), i.iou());
    Ok(IntersectReport {
        file: joined_names(&subjects),
        files: names,
        interval: CertifiedInterval::new((i.lower, i.upper), i.volume(), certification),
        volume_a: i.volume_a,
        volume_b: i.volume_b,
        union: union.value,
        union_lower: union.lower,
        union_upper: union.upper,
        a_minus_b: i.a_minus_b().value,
        b_minus_a: i.b_minus_a().value,
        iou: iou.value,
        iou_lower: iou.lower,
        iou_upper: iou.upper,
        dice: i.dice().value,
        centroid: i.moments.map(|m| m.centroid),
        inertia: i.moments.map(|m| m.inertia),
        contact_area: i.contact.map(|c| c.area),
        contact_vector: i.contact.map(|c| c.vector),
        contact_normal: i.contact.and_then(|c| c.normal()),
        disjoint: i.disjoint,
        cells_refined: i.cells_refined,
        cells_resolved_exactly: i.cells_resolved_exactly,
        columns_unresolved: i.columns_unresolved,
        flipped: i.flipped,
        volume_uncertainty: uncertainty,
        method: i.method.name(),
        grid: i.grid.counts,
        seconds,
        units: None,
        mass: None,
        warnings,
    })
}

/// [`intersect_prepared`] for many pairs of poses, in parallel over the pairs: each report
/// is the one [`intersect_posed`] gives for its pair alone, bit for bit, at any thread
/// count (the kernel's reductions are in a fixed order), in the order of `poses`.
pub fn intersect_poses<S: Surface + Sync>(
    a: &Subject<'_, S>,
    b: &Subject<'_, S>,
    bodies: [Option<&Body>; 2],
    poses: &[[Option<Affine>; 2]],
    tolerance: f64,
) -> Result<Vec<IntersectReport>, String> {
    poses.par_iter().map(|&pair| intersect_prepared(a, b, bodies, pair, tolerance, &())).collect()
}

/// The pairs `(i, j)`, `i < j`, of `subjects` (each measured whole) whose boxes overlap:
/// the only pairs that can hold common volume.
pub fn overlapping_pairs<S: Surface + Sync>(subjects: &[Subject<'_, S>]) -> Vec<(usize, usize)> {
    let boxes: Vec<_> =
        subjects.iter().map(|s| meshvol::mass_properties(&s.measured()).bounds).collect();
    overlapping_boxes(&boxes)
}

impl Report for IntersectReport {
    fn file(&self) -> &str {
        &self.file
    }

    fn warnings(&self) -> &[String] {
        &self.warnings
    }

    fn text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "intersection of {} and {}", self.files[0], self.files[1]);
        self.interval.text(&mut s, self.volume_uncertainty);
        if let Some(c) = self.centroid {
            let c: Vec<String> = c.iter().map(|&x| num(x, 10)).collect();
            let _ = writeln!(s, "  centroid         ({})", c.join(", "));
        }
        if let Some(m) = self.inertia {
            let d: Vec<String> = (0..3).map(|k| num(m[k][k], 10)).collect();
            let _ = writeln!(
                s,
                "  inertia (diag)   ({})  (about the centroid, unit density)",
                d.join(", ")
            );
        }
        if let (Some(area), Some(v)) = (self.contact_area, self.contact_vector) {
            let v: Vec<String> = v.iter().map(|&x| num(x, 10)).collect();
            let _ = writeln!(s, "  contact area     {}", num(area, 12));
            let _ = writeln!(s, "  contact vector   ({})  (∫ n dA over B inside A)", v.join(", "));
        }
        let _ = writeln!(s, "  IoU              {}", num(self.iou, 12));
        let _ = writeln!(s, "  Dice             {}", num(self.dice, 12));
        let _ = writeln!(s, "  volume A         {}", num(self.volume_a, 15));
        let _ = writeln!(s, "  volume B         {}", num(self.volume_b, 15));
        let _ = writeln!(s, "  A − B            {}", num(self.a_minus_b, 15));
        let _ = writeln!(s, "  B − A            {}", num(self.b_minus_a, 15));
        let _ = writeln!(s, "  union            {}", num(self.union, 15));
        if self.disjoint {
            let _ = writeln!(s, "  boxes apart      no grid needed");
        } else if self.method == "boundary" {
            let _ =
                writeln!(s, "  method           boundary (each face's part inside the other body)");
        } else {
            grid_text(&mut s, self.grid, self.cells_refined, self.cells_resolved_exactly);
        }
        footer_text(&mut s, self.seconds, &self.units, &self.mass);
        s
    }
}

impl Quantities for IntersectReport {
    fn convert(&mut self, to: &Converter) {
        self.interval.convert(to);
        to.interval(&mut self.union_lower, &mut self.union_upper);
        let volumes = [&mut self.volume_a, &mut self.volume_b, &mut self.union];
        to.all(Volume, volumes.into_iter().chain([&mut self.a_minus_b]));
        to.all(Volume, [&mut self.b_minus_a, &mut self.volume_uncertainty]);
        to.point(&mut self.centroid);
        to.all(VolumeMoment, self.inertia.iter_mut().flatten().flatten());
        to.some(Area, &mut self.contact_area);
        to.all(Area, self.contact_vector.iter_mut().flatten());
    }

    fn mass_basis(&self) -> f64 {
        self.interval.volume
    }

    crate::unit_slots!();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::subject::Source;
    use meshvol::shapes::cuboid;
    use meshvol::topology::{check, CheckOptions};

    fn translation(t: [f64; 3]) -> [[f64; 4]; 4] {
        let mut m = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0; 4]];
        m[3][3] = 1.0;
        (0..3).for_each(|k| m[k][3] = t[k]);
        m
    }

    #[test]
    fn a_pose_moves_the_checked_solid_as_moving_the_mesh_does() {
        let (a, b) = (cuboid([0.0; 3], [2.0; 3]), cuboid([0.0; 3], [1.0, 2.0, 2.0]));
        let moved_b = cuboid([1.5, 0.5, 0.5], [2.5, 2.5, 2.5]);
        let source = Source::arrays(8);
        let options = CheckOptions::default();
        let checks = [&a, &b, &moved_b].map(|m| check(m, &options).unwrap());
        let subject = |m, c| Subject { source: &source, surface: m, check: Some(c) };
        let (sa, sb, sm) =
            (subject(&a, &checks[0]), subject(&b, &checks[1]), subject(&moved_b, &checks[2]));
        let pose = rigid_pose(&translation([1.5, 0.5, 0.5])).unwrap();
        let posed = intersect_posed(&sa, &sb, [None, Some(pose)], 1e-9, &()).unwrap();
        let direct = intersect(&sa, &sm, 1e-9).unwrap();
        // 0.5 × 1.5 × 1.5 in common.
        assert!(posed.interval.lower <= 1.125 && 1.125 <= posed.interval.upper, "{posed:?}");
        assert_eq!(
            (posed.interval.lower, posed.interval.upper),
            (direct.interval.lower, direct.interval.upper)
        );
        assert_eq!(posed.centroid, direct.centroid);
        let far = rigid_pose(&translation([10.0, 0.0, 0.0])).unwrap();
        let apart = intersect_posed(&sa, &sb, [Some(far), None], 1e-9, &()).unwrap();
        assert!(apart.disjoint && apart.interval.upper == 0.0);
    }

    #[test]
    fn many_poses_give_what_each_pose_gives_alone() {
        let (a, b) = (cuboid([0.0; 3], [2.0; 3]), cuboid([0.0; 3], [1.0, 2.0, 2.0]));
        let source = Source::arrays(8);
        let options = CheckOptions::default();
        let checks = [&a, &b].map(|m| check(m, &options).unwrap());
        let (sa, sb) = (
            Subject { source: &source, surface: &a, check: Some(&checks[0]) },
            Subject { source: &source, surface: &b, check: Some(&checks[1]) },
        );
        let poses: Vec<[Option<Affine>; 2]> = (0..6)
            .map(|k| [None, Some(rigid_pose(&translation([0.5 * k as f64, 0.25, 0.0])).unwrap())])
            .collect();
        let bodies = [prepare(&sa), prepare(&sb)];
        let bodies = [bodies[0].as_ref(), bodies[1].as_ref()];
        let many = intersect_poses(&sa, &sb, bodies, &poses, 1e-9).unwrap();
        for (k, (report, pair)) in many.iter().zip(&poses).enumerate() {
            let alone = intersect_posed(&sa, &sb, *pair, 1e-9, &()).unwrap();
            assert_eq!(
                (report.interval.lower, report.interval.upper),
                (alone.interval.lower, alone.interval.upper),
                "pose {k}"
            );
            assert_eq!(report.contact_vector, alone.contact_vector, "pose {k}");
            // B (1 × 2 × 2) moved 0.5k along x into A (2 × 2 × 2), 0.25 along y: the
            // overlap is min(1, 2 − 0.5k)⁺ × 1.75 × 2.
            let exact = (2.0 - 0.5 * k as f64).clamp(0.0, 1.0) * 1.75 * 2.0;
            assert!(
                report.interval.lower <= exact && exact <= report.interval.upper,
                "pose {k}: {exact}"
            );
        }
    }

    #[test]
    fn poses_that_are_not_rigid_say_why() {
        let why = |m: [[f64; 4]; 4]| rigid_pose(&m).unwrap_err();
        let mut scaled = translation([0.0; 3]);
        scaled[0][0] = 2.0;
        assert!(why(scaled).contains("not a rotation"), "{}", why(scaled));
        let mut mirrored = translation([0.0; 3]);
        mirrored[2][2] = -1.0;
        assert!(why(mirrored).contains("mirror"));
        assert!(why(translation([f64::NAN, 0.0, 0.0])).contains("finite"));
        let mut projective = translation([0.0; 3]);
        projective[3][0] = 1.0;
        assert!(why(projective).contains("last row"));
        // A quarter turn is rigid, and exact.
        let turn = [
            [0.0, -1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        assert_eq!(rigid_pose(&turn).unwrap().apply([1.0, 2.0, 3.0]), [-2.0, 1.0, 3.0]);
    }
}
