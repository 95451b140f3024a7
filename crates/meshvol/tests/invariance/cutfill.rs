//! `cutfill`: cut and fill of a terrain moved in plan (x and y swapped or flipped),
//! lifted and scaled, against the level moved with it, are the same volumes (s³) and
//! areas (s²), for any triangle order, corner order and vertex numbering; flipping z
//! swaps cut and fill. Across commands: the terrain closed down to a floor is a solid
//! whose part below the level is (level − floor)·footprint − fill and whose part above
//! is the cut, as `below` and `profile` measure it; and a flat design surface at the
//! level gives what the level gives.

use crate::common::XorShift;
use crate::solids::Shape;
use crate::transform::{transforms, Transform};
use crate::{assert_near, checked};
use meshvol::below::below;
use meshvol::cutfill::{cut_fill, CutFill, Design, Terrain};
use meshvol::grid::{profile, Axis, Levels};
use meshvol::section::Plane;
use meshvol::{mass_properties, Point};
use proptest::prelude::*;

const NX: usize = 5;
const NY: usize = 4;
const ORIGIN: [f64; 2] = [-1.0, 0.5];
const PITCH: [f64; 2] = [0.5, 0.25];
/// The floor of the terrain's solid.
const FLOOR: f64 = 0.0;

/// A terrain over a 5 × 4 grid of cells, heights between 1 and 2 in steps of 1/64,
/// each cell cut along alternating diagonals; and its solid: the terrain, walls down to
/// the floor and the floor (outward).
fn terrain() -> (Shape, Shape) {
    let mut rng = XorShift::new(26);
    let id = |i: usize, j: usize| (i * (NY + 1) + j) as u32;
    let mut positions: Vec<Point> = Vec::new();
    for i in 0..=NX {
        for j in 0..=NY {
            let z = 1.0 + rng.below(65) as f64 / 64.0;
            positions.push([ORIGIN[0] + i as f64 * PITCH[0], ORIGIN[1] + j as f64 * PITCH[1], z]);
        }
    }
    let mut top = Vec::new();
    for i in 0..NX {
        for j in 0..NY {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                top.extend([vec![a, b, c], vec![a, c, d]]);
            } else {
                top.extend([vec![a, b, d], vec![b, c, d]]);
            }
        }
    }
    let surface = Shape { positions: positions.clone(), faces: top.clone() };
    // The boundary counter-clockwise seen from above, each with a floor vertex below.
    let mut ring: Vec<u32> = (0..NX).map(|i| id(i, 0)).collect();
    ring.extend((0..NY).map(|j| id(NX, j)));
    ring.extend((1..=NX).rev().map(|i| id(i, NY)));
    ring.extend((1..=NY).rev().map(|j| id(0, j)));
    let floor: Vec<u32> = ring
        .iter()
        .map(|&v| {
            let p = positions[v as usize];
            positions.push([p[0], p[1], FLOOR]);
            positions.len() as u32 - 1
        })
        .collect();
    let n = ring.len();
    let mut faces = top;
    for k in 0..n {
        let l = (k + 1) % n;
        faces.push(vec![floor[k], floor[l], ring[l], ring[k]]);
    }
    faces.push(std::iter::once(floor[0]).chain(floor[1..].iter().rev().copied()).collect());
    (surface, Shape { positions, faces })
}

fn footprint() -> f64 {
    NX as f64 * PITCH[0] * NY as f64 * PITCH[1]
}

fn cutfill(shape: &Shape, level: f64) -> CutFill {
    cut_fill(&Terrain::new(&shape.mesh()).unwrap(), Design::Level(level))
}

/// `t` with z left up (or flipped): only x and y are permuted.
fn plan(mut t: Transform, swap: bool) -> Transform {
    t.axes = if swap { [1, 0, 2] } else { [0, 1, 2] };
    t
}

fn cut_and_fill_follow(t: &Transform, fraction: f64) {
    let (s, s3) = (t.scale, t.scale.powi(3));
    let (surface, _) = terrain();
    let level = 1.0 + (fraction * 64.0).round() / 64.0;
    let r0 = cutfill(&surface, level);
    let level1 = t.signs[2] * s * level + t.shift[2];
    let r1 = cutfill(&t.apply(&surface), level1);
    let (cut, fill) = if t.signs[2] < 0.0 { (r1.fill, r1.cut) } else { (r1.cut, r1.fill) };
    let (area_cut, area_fill) =
        if t.signs[2] < 0.0 { (r1.area_fill, r1.area_cut) } else { (r1.area_cut, r1.area_fill) };
    let what = |w: &str| format!("{w} at level {level} under {t:?}");
    let volume = r0.cut + r0.fill;
    assert_near(&what("cut"), cut, s3 * r0.cut, s3 * volume);
    assert_near(&what("fill"), fill, s3 * r0.fill, s3 * volume);
    let a = footprint();
    assert_near(&what("area cut"), area_cut, s * s * r0.area_cut, s * s * a);
    assert_near(&what("area fill"), area_fill, s * s * r0.area_fill, s * s * a);
    assert_near(&what("footprint"), r1.footprint_area, s * s * a, s * s * a);
}

/// The terrain's solid, moved by `t`, against its cut and fill at each profile level.
fn cutfill_below_profile_agree(t: &Transform, slabs: usize) {
    let (surface, solid) = terrain();
    let (surface, solid) = (t.apply(&surface), t.apply(&solid));
    let mesh = solid.mesh();
    let c = checked(&mesh);
    assert!(c.bounds_a_volume(), "the terrain's solid under {t:?}: {c:?}");
    let view = c.solid(&mesh);
    let volume = mass_properties(&view).signed_volume;
    let a = footprint() * t.scale * t.scale;
    let floor = t.scale * FLOOR + t.shift[2];
    let p = profile(&view, Axis::Z, Levels::Count(slabs)).unwrap();
    assert_eq!(p.levels[0], floor);
    let flat = |z: f64| {
        let q: Vec<Point> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .iter()
            .map(|&[u, v]| {
                let x = ORIGIN[0] + u * NX as f64 * PITCH[0];
                let y = ORIGIN[1] + v * NY as f64 * PITCH[1];
                let mut m = t.point([x, y, 0.0]);
                m[2] = z;
                m
            })
            .collect();
        meshvol::Mesh::from_triangles(q, vec![[0, 1, 2], [0, 2, 3]]).unwrap()
    };
    for k in 0..=slabs {
        let level = p.levels[k];
        let what = |w: &str| format!("{w} at level {k} of {slabs} ({level}) under {t:?}");
        let r = cutfill(&surface, level);
        let below_level = below(&view, &Plane::axis(2, level).unwrap()).part.signed_volume;
        assert_near(&what("cut against volume − below"), r.cut, volume - below_level, volume);
        let fill = (level - floor) * a - below_level;
        assert_near(&what("fill against (level − floor)·footprint − below"), r.fill, fill, volume);
        assert_near(
            &what("fill against the profile"),
            r.fill,
            (level - floor) * a - p.volume_below[k],
            volume,
        );
        let design = Terrain::new(&flat(level)).unwrap();
        let d = cut_fill(&Terrain::new(&surface.mesh()).unwrap(), Design::Surface(&design));
        assert_near(&what("cut against a flat design"), d.cut, r.cut, volume);
        assert_near(&what("fill against a flat design"), d.fill, r.fill, volume);
    }
}

proptest! {
    #![proptest_config(crate::cases(24))]

    #[test]
    fn cut_and_fill_move_with_the_terrain(t in transforms(), swap in any::<bool>(), fraction in 0.0f64..1.0) {
        cut_and_fill_follow(&plan(t, swap), fraction);
    }

    #[test]
    fn cut_and_fill_agree_with_below_and_profile(t in transforms(), swap in any::<bool>(), k in 1u32..4) {
        let mut t = plan(t, swap);
        t.signs[2] = 1.0;
        cutfill_below_profile_agree(&t, 1 << k);
    }
}
