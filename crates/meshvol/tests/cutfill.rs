//! Cut and fill against closed forms and an independent per-triangle integration: a
//! sinusoidal terrain against a level, planes against planes (crossing, with different
//! triangulations), a pyramid against a finely triangulated plane, footprints that
//! overlap in part, folded sheets, per-cell sums, and the same bits at any thread count.

use meshvol::cutfill::{cell_cut_fill, cut_fill, Design, PlanGrid, Terrain, TerrainError};
use meshvol::Mesh;

/// A grid of `nx × ny` quads over [x0, x1] × [y0, y1] at heights `z(x, y)`, each quad
/// cut along one diagonal or the other (`flip`).
fn sheet(
    [x0, x1]: [f64; 2],
    [y0, y1]: [f64; 2],
    [nx, ny]: [usize; 2],
    flip: bool,
    z: impl Fn(f64, f64) -> f64,
) -> Mesh {
    let mut v = Vec::new();
    for i in 0..=nx {
        for j in 0..=ny {
            let x = x0 + (x1 - x0) * i as f64 / nx as f64;
            let y = y0 + (y1 - y0) * j as f64 / ny as f64;
            v.push([x, y, z(x, y)]);
        }
    }
    let at = |i: usize, j: usize| (i * (ny + 1) + j) as u32;
    let mut t = Vec::new();
    for i in 0..nx {
        for j in 0..ny {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if flip {
                t.extend([[a, b, d], [b, c, d]]);
            } else {
                t.extend([[a, b, c], [a, c, d]]);
            }
        }
    }
    Mesh::from_triangles(v, t).unwrap()
}

fn terrain(mesh: &Mesh) -> Terrain {
    Terrain::new(mesh).unwrap()
}

fn close(a: f64, b: f64, tolerance: f64) -> bool {
    (a - b).abs() <= tolerance
}

/// ∫ max(h, 0) and the area where h > 0 over a triangle of plan area `area` whose
/// linear h has corner values `h`, written separately from the library: with one
/// corner above, the part above is the triangle at that corner scaled by t_q and t_r
/// (where h reaches 0 along its edges), of area A·t_q·t_r and mean h_p/3; with two
/// above, it is the whole minus the part below, found the same way.
fn above(area: f64, h: [f64; 3]) -> (f64, f64) {
    let positive = h.iter().filter(|&&x| x > 0.0).count();
    let whole = area * (h[0] + h[1] + h[2]) / 3.0;
    let corner = |k: usize| {
        let p = h[k];
        let (q, r) = (h[(k + 1) % 3], h[(k + 2) % 3]);
        let scale = (p / (p - q)) * (p / (p - r));
        (area * scale * p / 3.0, area * scale)
    };
    match positive {
        0 => (0.0, 0.0),
        3 => (whole, area),
        1 => corner(h.iter().position(|&x| x > 0.0).unwrap()),
        _ => match h.iter().position(|&x| x <= 0.0).unwrap() {
            k if h[k] == 0.0 => (whole, area),
            k => {
                let (integral, a) = corner(k);
                (whole - integral, area - a)
            }
        },
    }
}

#[test]
fn a_sinusoidal_terrain_against_a_level_matches_a_per_triangle_integration() {
    let tau = std::f64::consts::TAU;
    let mesh = sheet([0.0, tau], [0.0, tau], [60, 45], false, |x, y| x.sin() * y.cos());
    let level = 0.3;
    let (mut cut, mut fill, mut area_cut, mut area_fill) = (0.0, 0.0, 0.0, 0.0);
    let p = mesh.positions();
    let meshvol::Faces::Triangles(faces) = mesh.faces() else { unreachable!() };
    for t in faces {
        let [a, b, c] = t.map(|i| p[i as usize]);
        let area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs();
        let h = [a[2] - level, b[2] - level, c[2] - level];
        let (v, s) = above(area, h);
        cut += v;
        area_cut += s;
        let (v, s) = above(area, h.map(|x| -x));
        fill += v;
        area_fill += s;
    }
    let r = cut_fill(&terrain(&mesh), Design::Level(level));
    let tolerance = 1e-12;
    assert!(close(r.cut, cut, tolerance), "{} vs {cut}", r.cut);
    assert!(close(r.fill, fill, tolerance), "{} vs {fill}", r.fill);
    assert!(close(r.area_cut, area_cut, tolerance), "{} vs {area_cut}", r.area_cut);
    assert!(close(r.area_fill, area_fill, tolerance), "{} vs {area_fill}", r.area_fill);
    assert!(close(r.footprint_area, tau * tau, 1e-12));
    // And near the smooth surface's own integral: ∫ (sin x cos y − 0.3) dA = −0.3·4π².
    assert!(close(r.cut - r.fill, -0.3 * tau * tau, 1e-2), "{}", r.cut - r.fill);
    let [[x0, y0], [x1, y1]] = r.footprint_bounds.unwrap();
    assert!(
        [x0, y0].iter().all(|x| x.abs() < 1e-14) && close(x1, tau, 1e-14) && close(y1, tau, 1e-14)
    );
}

#[test]
fn planes_against_planes() {
    // z = 1 over the unit square against z = x: cut ∫ (1 − x) = 1/2 everywhere.
    let flat = terrain(&sheet([0.0, 1.0], [0.0, 1.0], [1, 1], false, |_, _| 1.0));
    let ramp = terrain(&sheet([0.0, 1.0], [0.0, 1.0], [1, 1], true, |x, _| x));
    let r = cut_fill(&flat, Design::Surface(&ramp));
    assert!(close(r.cut, 0.5, 1e-15) && r.fill == 0.0, "{r:?}");
    assert!(
        close(r.area_cut, 1.0, 1e-15) && r.area_fill == 0.0 && close(r.footprint_area, 1.0, 1e-15)
    );
    // Crossing: z = x against z = 1 − x (d = 2x − 1): a quarter of cut, a quarter of
    // fill, each over half the square; different diagonals and resolutions.
    let up = terrain(&sheet([0.0, 1.0], [0.0, 1.0], [3, 2], false, |x, _| x));
    let down = terrain(&sheet([0.0, 1.0], [0.0, 1.0], [2, 5], true, |x, _| 1.0 - x));
    let r = cut_fill(&up, Design::Surface(&down));
    for (value, expected) in [
        (r.cut, 0.25),
        (r.fill, 0.25),
        (r.area_cut, 0.5),
        (r.area_fill, 0.5),
        (r.footprint_area, 1.0),
    ] {
        assert!(close(value, expected, 1e-14), "{r:?}");
    }
    // Swapped, cut and fill swap.
    let s = cut_fill(&down, Design::Surface(&up));
    assert!(close(s.cut, r.fill, 1e-15) && close(s.fill, r.cut, 1e-15));
}

/// The pyramid z = 1 − max(|x|, |y|) over [−1, 1]²: four triangles from the apex.
fn pyramid() -> Mesh {
    let v = vec![
        [0.0, 0.0, 1.0],
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ];
    Mesh::from_triangles(v, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]]).unwrap()
}

#[test]
fn a_pyramid_against_a_finely_triangulated_plane() {
    // Above z = 1/2: the pyramid's top, base 1 × 1 and height 1/2 (volume 1/6); below:
    // the plane's 2 × 4 less the part of the pyramid's 4/3 under it (4/3 − 1/6).
    let plane = sheet([-1.0, 1.0], [-1.0, 1.0], [37, 23], false, |_, _| 0.5);
    let r = cut_fill(&terrain(&pyramid()), Design::Surface(&terrain(&plane)));
    let fill = 2.0 - (4.0 / 3.0 - 1.0 / 6.0);
    for (value, expected) in [
        (r.cut, 1.0 / 6.0),
        (r.fill, fill),
        (r.area_cut, 1.0),
        (r.area_fill, 3.0),
        (r.footprint_area, 4.0),
    ] {
        assert!(close(value, expected, 1e-13), "{value} vs {expected}: {r:?}");
    }
    // The plane as a level: the same numbers, by the other path.
    let level = cut_fill(&terrain(&pyramid()), Design::Level(0.5));
    assert!(close(level.cut, r.cut, 1e-14) && close(level.fill, r.fill, 1e-14));
}

#[test]
fn footprints_that_overlap_in_part() {
    // z = x over [0, 2] × [0, 1] against z = 1 over [1, 3] × [0, 1]: only [1, 2] × [0, 1]
    // is common, where x ≥ 1: cut ∫ (x − 1) = 1/2.
    let ramp = terrain(&sheet([0.0, 2.0], [0.0, 1.0], [4, 3], false, |x, _| x));
    let flat = terrain(&sheet([1.0, 3.0], [0.0, 1.0], [3, 2], true, |_, _| 1.0));
    let r = cut_fill(&ramp, Design::Surface(&flat));
    assert!(close(r.cut, 0.5, 1e-15) && r.fill == 0.0 && close(r.footprint_area, 1.0, 1e-15));
    assert_eq!(r.footprint_bounds, Some([[1.0, 0.0], [2.0, 1.0]]));
    // An L-shaped design (the square [0, 2]² less its quarter [1, 2]²) against the
    // ramp over [1, 3] × [0, 3]: common [1, 2] × [0, 1] only, though the boxes share
    // [1, 2] × [0, 2].
    let l = sheet([0.0, 2.0], [0.0, 2.0], [2, 2], false, |_, _| 1.0);
    let meshvol::Faces::Triangles(faces) = l.faces() else { unreachable!() };
    let kept: Vec<[u32; 3]> = faces
        .iter()
        .copied()
        .filter(|t| !t.iter().all(|&i| l.positions()[i as usize].iter().take(2).all(|&c| c >= 1.0)))
        .collect();
    assert_eq!(kept.len(), 6);
    let l = terrain(&Mesh::from_triangles(l.positions().to_vec(), kept).unwrap());
    let ramp = terrain(&sheet([1.0, 3.0], [0.0, 3.0], [2, 3], false, |x, _| x));
    let r = cut_fill(&ramp, Design::Surface(&l));
    assert!(close(r.cut, 0.5, 1e-15) && close(r.footprint_area, 1.0, 1e-15), "{r:?}");
    assert_eq!(r.footprint_bounds, Some([[1.0, 0.0], [2.0, 1.0]]));
    // Disjoint footprints: nothing in common.
    let far = terrain(&sheet([5.0, 6.0], [0.0, 1.0], [1, 1], false, |_, _| 0.0));
    let r = cut_fill(&ramp, Design::Surface(&far));
    assert_eq!((r.cut, r.fill, r.footprint_area, r.footprint_bounds), (0.0, 0.0, 0.0, None));
}

#[test]
fn a_folded_sheet_is_not_a_height_field() {
    // The unit square at z = 0 (faces 0, 1), folded back over itself along x = 1 to
    // x = 0.5 at z = 1 (faces 2, 3): faces 2 and 3 lie over faces 0 and 1 in plan.
    let v = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.5, 0.0, 1.0],
        [0.5, 1.0, 1.0],
    ];
    let folded = Mesh::from_triangles(v, vec![[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]]).unwrap();
    let err = Terrain::new(&folded).unwrap_err();
    assert!(matches!(err, TerrainError::Overlap { first: 0 | 1, second: 2 | 3 }), "{err:?}");
    assert!(err.to_string().contains("not a height field"), "{err}");
    // A vertical wall between two levels is no fold: left out, and listed.
    let v = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [2.0, 0.0, 1.0],
        [2.0, 1.0, 1.0],
    ];
    let faces = vec![[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2], [4, 6, 7], [4, 7, 5]];
    let step = Terrain::new(&Mesh::from_triangles(v, faces).unwrap()).unwrap();
    assert_eq!(step.vertical_faces(), &[2, 3]);
    assert_eq!(step.plan_area(), 2.0);
    let r = cut_fill(&step, Design::Level(0.5));
    assert_eq!((r.cut, r.fill, r.footprint_area), (0.5, 0.5, 2.0));
}

#[test]
fn a_surface_facing_down_is_read_the_same() {
    let up = sheet([0.0, 1.0], [0.0, 1.0], [4, 4], false, |x, y| x * y);
    let r = cut_fill(&terrain(&up), Design::Level(0.25));
    let s = cut_fill(&terrain(&up.flipped()), Design::Level(0.25));
    assert_eq!(r, s);
    // Nothing to compare: an empty surface.
    let empty = Terrain::new(&Mesh::from_triangles(vec![], vec![]).unwrap()).unwrap();
    assert_eq!(cut_fill(&empty, Design::Level(0.0)).footprint_area, 0.0);
    assert_eq!(cut_fill(&terrain(&up), Design::Surface(&empty)).footprint_bounds, None);
}

#[test]
fn cells_add_up_to_the_totals() {
    // z = 1 against z = x in 4 × 1 cells: cell i holds ∫ from i/4 to (i+1)/4 of (1 − x).
    let flat = terrain(&sheet([0.0, 1.0], [0.0, 1.0], [1, 1], false, |_, _| 1.0));
    let ramp = terrain(&sheet([0.0, 1.0], [0.0, 1.0], [3, 3], true, |x, _| x));
    let grid = PlanGrid::new([0.0, 0.0], [0.25, 1.0], [4, 1]).unwrap();
    let cells = cell_cut_fill(&flat, Design::Surface(&ramp), &grid);
    for i in 0..4 {
        let (a, b) = (i as f64 / 4.0, (i + 1) as f64 / 4.0);
        let expected = (b - a) - (b * b - a * a) / 2.0;
        assert!(close(cells.cut[i], expected, 1e-15), "{i}: {:?}", cells.cut);
    }
    assert_eq!(cells.fill, vec![0.0; 4]);
    // A sinusoidal terrain against a tilted sheet, in cells that match nothing.
    let tau = std::f64::consts::TAU;
    let land = terrain(&sheet([0.0, tau], [0.0, tau], [40, 30], false, |x, y| x.sin() * y.cos()));
    let design =
        terrain(&sheet([-0.5, 5.0], [0.3, 7.0], [17, 29], true, |x, y| 0.1 * x - 0.05 * y));
    let total = cut_fill(&land, Design::Surface(&design));
    let [[x0, y0], [x1, y1]] = total.footprint_bounds.unwrap();
    assert!(
        close(x0, 0.0, 1e-14)
            && close(x1, 5.0, 1e-14)
            && close(y0, 0.3, 1e-14)
            && close(y1, tau, 1e-14)
    );
    let grid = PlanGrid::new([x0, y0], [(x1 - x0) / 13.0, (y1 - y0) / 7.0], [13, 7]).unwrap();
    let cells = cell_cut_fill(&land, Design::Surface(&design), &grid);
    let (cut, fill): (f64, f64) = (cells.cut.iter().sum(), cells.fill.iter().sum());
    assert!(
        close(cut, total.cut, 1e-12) && close(fill, total.fill, 1e-12),
        "{cut} {fill} {total:?}"
    );
    assert!(cells.cut.iter().chain(&cells.fill).all(|&v| v >= -1e-15));
    // Against a level, in a grid of a pitch that overruns the footprint.
    let grid = PlanGrid::new([0.0, 0.0], [0.7, 0.7], [9, 9]).unwrap();
    let cells = cell_cut_fill(&land, Design::Level(0.2), &grid);
    let total = cut_fill(&land, Design::Level(0.2));
    let cut: f64 = cells.cut.iter().sum();
    assert!(close(cut, total.cut, 1e-12), "{cut} vs {}", total.cut);
}

#[test]
fn the_same_bits_at_any_thread_count() {
    let tau = std::f64::consts::TAU;
    let land = terrain(&sheet([0.0, tau], [0.0, tau], [120, 90], false, |x, y| x.sin() * y.cos()));
    let design = terrain(&sheet([-0.5, 5.0], [0.3, 7.0], [77, 59], true, |x, _| 0.1 * x));
    let grid = PlanGrid::new([0.0, 0.0], [0.5, 0.5], [12, 13]).unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            (
                cut_fill(&land, Design::Surface(&design)),
                cell_cut_fill(&land, Design::Surface(&design), &grid),
                cut_fill(&land, Design::Level(0.1)),
            )
        })
    };
    let one = run(1);
    for threads in [2, 5] {
        assert_eq!(run(threads), one, "{threads} threads");
    }
}

#[test]
fn far_from_the_origin() {
    // The crossing planes moved to map coordinates: the same quarter of cut and fill.
    let (x0, y0) = (512_345.0, 4_012_345.0);
    let up = terrain(&sheet([x0, x0 + 1.0], [y0, y0 + 1.0], [3, 2], false, |x, _| x - x0));
    let down = terrain(&sheet([x0, x0 + 1.0], [y0, y0 + 1.0], [2, 5], true, |x, _| 1.0 - (x - x0)));
    let r = cut_fill(&up, Design::Surface(&down));
    assert!(close(r.cut, 0.25, 1e-9) && close(r.fill, 0.25, 1e-9), "{r:?}");
}
