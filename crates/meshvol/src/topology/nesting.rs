//! Stage 6, nesting: which shells lie inside which, which overlap, and so each shell's
//! role (solid or cavity, reported as a [`Shell`]) and the solid's volume.
//!
//! Only orientable shells can contain anything: closed ones, and open ones mostly closed
//! by their own faces, through the caps over their holes (`holes.rs`) that close them as
//! the solid measures them ([`can_contain`]). For each shell, the candidates are those
//! whose boxes (caps included) overlap its own (a [`Bvh`] over the shells' boxes). From
//! the corners of up to [`NESTING_SAMPLES`] triangles spread over the shell, rays count
//! signed crossings (winding numbers, each crossing signed as its face was propagated,
//! or its cap's shell) with each candidate's faces and caps: along the six axis
//! directions in turn until one meets no edge or vertex, else an oblique segment to
//! beyond every box; a corner lying on another surface is skipped, and where no corner
//! could tell, the triangles' centroids are tried. Inside for every sample that could
//! tell: *nested*; inside for some and outside for others: the two *overlap*.
//!
//! A shell inside an odd number of others is a *cavity*; its parent is the smallest
//! shell containing it. The solid's volume is Σ ±|shell volume| in shell order (+ for
//! solids, − for cavities), and each shell is turned to its role: outward for a solid,
//! inward for a cavity, whatever its winding in the file.

use super::crossings::Triangles;
use super::euler::{self, ShellCounts};
use super::holes::Caps;
use super::loops::Loops;
use super::predicates;
use super::shells::Shells;
use super::weld::Welded;
use crate::accumulate::CompensatedSum;
use crate::bvh::Bvh;
use crate::properties::Bounds;
use crate::vector::{add, cross, norm, scale, sub};
use crate::Point;
use rayon::prelude::*;
use std::collections::BTreeSet;

/// One connected component of faces.
#[derive(Clone, Debug, PartialEq)]
pub struct Shell {
    /// Faces in the shell (flat faces included; collapsed and dropped duplicate faces
    /// are in no shell).
    pub faces: usize,
    /// Every edge used by exactly two faces.
    pub closed: bool,
    /// Orientation could be propagated consistently over the shell.
    pub orientable: bool,
    /// Its faces are consistently wound in the file.
    pub consistently_oriented: bool,
    /// Volume enclosed (holes capped), positive.
    pub volume: f64,
    /// The shell bounds a void inside another shell.
    pub cavity: bool,
    /// The smallest shell containing this one.
    pub parent: Option<usize>,
    /// Whether the file winds it the right way for its role (outward for a solid,
    /// inward for a cavity); `None` when not consistently oriented.
    pub wound_outward: Option<bool>,
    /// Boundary loops (holes) in this shell.
    pub boundary_loops: usize,
    /// V − E + F.
    pub euler_characteristic: i64,
    /// (2 − χ)/2 for closed orientable shells.
    pub genus: Option<i64>,
}

/// Triangles per shell whose corners are classified against other shells for nesting
/// and overlap.
const NESTING_SAMPLES: usize = 32;

/// Each shell's box, and the shells that [`can_contain`] others whose boxes overlap it
/// (its candidates for nesting and overlap), sorted.
pub(super) struct Candidates {
    /// `None` for a shell without kept faces, and for a lone shell (which has no
    /// candidate, so nothing reads its box).
    pub bounds: Vec<Option<Bounds>>,
    pub of_shell: Vec<Vec<usize>>,
}

impl Candidates {
    /// Whether any shell has a candidate, and so needs the triangles in space.
    pub fn any(&self) -> bool {
        self.of_shell.iter().any(|c| !c.is_empty())
    }
}

/// Whether shell `s`, its faces of area `face_area` and its caps of area `cap_area`, can
/// contain others. A non-orientable shell has no inside. A closed one is closed by its
/// faces; an open one by its faces and its caps, as the solid measures it (the edges an
/// orientable shell leaves open are the boundary of its faces as propagated, a cycle,
/// so they chain into loops that each close where they began, and every loop is capped,
/// `holes.rs`), when it is mostly closed by its own faces: caps of less than half their
/// area (a wall with holes in it, not a sheet or a scrap). A soup's scattered triangles
/// and folds, each a shell whose cap is about as large as itself, then contain
/// nothing, as before caps counted: every one a container, a 300k-triangle soup's check
/// took 24 s instead of 1.8.
fn can_contain(shells: &Shells, s: usize, face_area: f64, cap_area: f64) -> bool {
    shells.orientable[s] && (!shells.open[s] || cap_area < 0.5 * face_area)
}

/// The candidates of each of `shells`, the kept faces of `loops` with their `caps`.
pub(super) fn candidates(
    loops: &Loops,
    welded: &Welded,
    kept: &[bool],
    shells: &Shells,
    caps: &Caps,
) -> Candidates {
    let shell_count = shells.count;
    if shell_count < 2 {
        return Candidates {
            bounds: vec![None; shell_count],
            of_shell: vec![Vec::new(); shell_count],
        };
    }
    let vid = |c: usize| welded.corner_vertex[c];
    // Each shell's box and, for an open one, its faces' area. (Boxes are minima and
    // maxima: the same in any order; areas are summed in fixed chunks.)
    let folded: Vec<(Option<Bounds>, f64)> = shells.fold_faces(
        kept,
        |(bounds, area): &mut (Option<Bounds>, f64), f| {
            for c in loops.face(f) {
                let p = welded.positions[vid(c) as usize];
                bounds.get_or_insert(Bounds::of(p)).include(p);
            }
            if shells.open[shells.of_face[f] as usize] {
                *area += 0.5 * norm(loops.doubled_vector_area(f, welded));
            }
        },
        |(all, area), (b, a)| {
            *area += a;
            if let Some(b) = b {
                match all {
                    Some(all) => all.merge(b),
                    None => *all = Some(*b),
                }
            }
        },
    );
    let (mut shell_bounds, face_area): (Vec<Option<Bounds>>, Vec<f64>) = folded.into_iter().unzip();
    // The rays meet a shell's caps as well as its faces, so its box holds both. (A cap's
    // centre lies in its rim's hull: the box can only grow by a rounding.)
    let mut cap_area = vec![0.0; shell_count];
    for (cap, &s) in caps.points.iter().zip(&caps.shell) {
        let bounds = shell_bounds[s as usize].get_or_insert(Bounds::of(cap[0]));
        cap.iter().for_each(|&p| bounds.include(p));
        cap_area[s as usize] += 0.5 * norm(cross(sub(cap[1], cap[0]), sub(cap[2], cap[0])));
    }
    // For each shell, the containing shells whose boxes overlap its own, found through a
    // hierarchy over their boxes (files with 100 000 parts are common), in spatial
    // order: over shells in file order, a soup of scattered open triangles made every
    // query walk most of the tree.
    let (containing, boxes): (Vec<usize>, Vec<Bounds>) = (0..shell_count)
        .filter(|&s| can_contain(shells, s, face_area[s], cap_area[s]))
        .filter_map(|s| shell_bounds[s].map(|b| (s, b)))
        .unzip();
    let (order, shell_tree) = Bvh::over_boxes(&boxes);
    let candidates: Vec<Vec<usize>> = (0..shell_count)
        .into_par_iter()
        .map(|a| {
            let mut near = Vec::new();
            if let Some(ba) = shell_bounds[a] {
                shell_tree.overlapping(&ba, |i| {
                    let b = containing[order[i] as usize];
                    if b != a {
                        near.push(b);
                    }
                });
            }
            near.sort_unstable();
            near
        })
        .collect();
    Candidates { bounds: shell_bounds, of_shell: candidates }
}

/// For each shell, the shells containing it, found by rays from its samples against the
/// `triangles` (spatially ordered, under `bvh`) and the `caps`; pairs of shells whose
/// samples disagree go to `overlapping_shells`.
pub(super) fn containers(
    triangles: &Triangles,
    bvh: &Bvh,
    shells: &Shells,
    caps: &Caps,
    candidates: &Candidates,
    overlapping_shells: &mut BTreeSet<[usize; 2]>,
) -> Vec<Vec<usize>> {
    let (shell_count, shell_of_face, flip) = (shells.count, &shells.of_face, &shells.flip);
    if !candidates.any() {
        return vec![Vec::new(); shell_count]; // nothing to contain or overlap
    }
    let candidate_caps = CandidateCaps::of(caps, candidates);
    let (candidates, shell_bounds) = (&candidates.of_shell, &candidates.bounds);
    // Sample up to NESTING_SAMPLES triangles' corners spread over each shell.
    let mut shell_triangles = vec![0usize; shell_count];
    for &f in &triangles.face {
        shell_triangles[shell_of_face[f as usize] as usize] += 1;
    }
    // Their centroids are samples too, for the candidates no corner could tell about:
    // a shell whose every corner lies on another surface (a cavity whose faces lie in
    // its container's faces) is still inside or outside it.
    let mut samples: Vec<Vec<Point>> = vec![Vec::new(); shell_count];
    let mut centres: Vec<Vec<Point>> = vec![Vec::new(); shell_count];
    let mut seen_in_shell = vec![0usize; shell_count];
    for (i, &f) in triangles.face.iter().enumerate() {
        let s = shell_of_face[f as usize] as usize;
        let stride = shell_triangles[s].div_ceil(NESTING_SAMPLES);
        if seen_in_shell[s].is_multiple_of(stride) && !candidates[s].is_empty() {
            let [a, b, c] = triangles.points(i);
            samples[s].extend([a, b, c]);
            centres[s].push([0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0));
        }
        seen_in_shell[s] += 1;
    }
    // Far enough that an oblique segment from any vertex leaves every shell's box.
    let reach = {
        let all = shell_bounds.iter().flatten().fold(None, |acc: Option<Bounds>, b| {
            let mut all = acc.unwrap_or(*b);
            all.merge(b);
            Some(all)
        });
        all.map_or(1.0, |b| 4.0 * norm(b.size()) + 1.0)
    };
    // For each shell, how many of `points` lie inside / outside each candidate.
    let tally = |a: usize, points: &[Point]| -> Vec<(usize, usize, usize)> {
        let candidates = &candidates[a];
        let mut counts: Vec<(usize, usize, usize)> =
            candidates.iter().map(|&b| (b, 0, 0)).collect();
        let mut winding = vec![0i64; candidates.len()];
        for &p in points {
            // Rays along each axis direction in turn, until one crosses cleanly; then
            // an oblique segment to beyond the mesh (it meets many boxes, so it is the
            // last resort, for symmetric meshes where every axis ray hits an edge).
            let clean = (0..=predicates::RAY_FRAMES.len()).any(|frame| {
                let oblique = frame == predicates::RAY_FRAMES.len();
                let q = add(p, scale(predicates::OBLIQUE, reach));
                let ray = if oblique {
                    let mut b = Bounds::of(p);
                    b.include(q);
                    b
                } else {
                    let (min, max) = predicates::ray_box(p, frame);
                    Bounds { min, max }
                };
                let crossing = |v: [Point; 3]| {
                    if oblique {
                        predicates::segment_crossing(p, q, v[0], v[1], v[2])
                    } else {
                        let rotate = predicates::RAY_FRAMES[frame];
                        let v = v.map(rotate);
                        predicates::ray_crossing(rotate(p), v[0], v[1], v[2])
                    }
                };
                winding.fill(0);
                let mut grazed = false;
                // A crossing with triangle v of shell s, signed as it runs once its shell
                // is propagated (`turned`: against its own winding).
                let mut count = |s: usize, v: [Point; 3], turned: bool| {
                    if grazed || s == a {
                        return;
                    }
                    let Ok(k) = candidates.binary_search(&s) else { return };
                    match crossing(v) {
                        Some(w) => winding[k] += if turned { -w } else { w } as i64,
                        None => grazed = true,
                    }
                };
                bvh.overlapping(&ray, |i| {
                    let face = triangles.face[i] as usize;
                    count(shell_of_face[face] as usize, triangles.points(i), flip[face]);
                });
                // A cap runs its rim as its shell was propagated: counted as is.
                candidate_caps.overlapping(&ray, |s, cap| count(s, cap, false));
                !grazed
            });
            if !clean {
                continue; // on another surface: this sample cannot tell
            }
            for (c, &w) in counts.iter_mut().zip(&winding) {
                if w != 0 {
                    c.1 += 1;
                } else {
                    c.2 += 1;
                }
            }
        }
        counts
    };
    // The corners first; the centroids for the candidates they told nothing about.
    let classify = |a: usize| -> Vec<(usize, usize, usize)> {
        let mut counts = tally(a, &samples[a]);
        if counts.iter().any(|c| c.1 == 0 && c.2 == 0) {
            let more = tally(a, &centres[a]);
            for (c, m) in counts.iter_mut().zip(more) {
                if c.1 == 0 && c.2 == 0 {
                    *c = m;
                }
            }
        }
        counts
    };
    let classified: Vec<Vec<(usize, usize, usize)>> =
        (0..shell_count).into_par_iter().map(classify).collect();
    // Inside every sample that could tell: nested. Inside for some, outside for others:
    // the surfaces cross, and the shells overlap.
    classified
        .iter()
        .enumerate()
        .map(|(a, counts)| {
            for &(b, inside, outside) in counts {
                if inside > 0 && outside > 0 {
                    overlapping_shells.insert([a.min(b), a.max(b)]);
                }
            }
            counts.iter().filter(|c| c.1 > 0 && c.2 == 0).map(|c| c.0).collect()
        })
        .collect()
}

/// The caps of the shells that are some shell's candidates, under a hierarchy of their
/// own: they are not among the triangles in space, and few as caps are, one huge hole
/// (a terrain's rim) is capped by as many triangles as its rim has edges, of which a
/// ray should meet only those near it.
struct CandidateCaps<'a> {
    caps: &'a Caps,
    /// The tree's item k is cap `order[k]`.
    order: Vec<u32>,
    bvh: Bvh,
}

impl<'a> CandidateCaps<'a> {
    fn of(caps: &'a Caps, candidates: &Candidates) -> CandidateCaps<'a> {
        let mut is_candidate = vec![false; candidates.of_shell.len()];
        candidates.of_shell.iter().flatten().for_each(|&s| is_candidate[s] = true);
        let (listed, boxes): (Vec<u32>, Vec<Bounds>) = (caps.points.iter().zip(&caps.shell))
            .enumerate()
            .filter(|(_, (_, &s))| is_candidate[s as usize])
            .map(|(i, (&[a, b, c], _))| {
                let mut bounds = Bounds::of(a);
                bounds.include(b);
                bounds.include(c);
                (i as u32, bounds)
            })
            .unzip();
        let (order, bvh) = Bvh::over_boxes(&boxes);
        let order = order.iter().map(|&k| listed[k as usize]).collect();
        CandidateCaps { caps, order, bvh }
    }

    /// Calls `visit(shell, cap)` for each cap whose box meets `ray`, with its shell.
    fn overlapping(&self, ray: &Bounds, mut visit: impl FnMut(usize, [Point; 3])) {
        self.bvh.overlapping(ray, |k| {
            let cap = self.order[k] as usize;
            visit(self.caps.shell[cap] as usize, self.caps.points[cap]);
        });
    }
}

/// The shells in their roles, and what the solid makes of them.
pub(super) struct Roles {
    pub shells: Vec<Shell>,
    /// Per shell: turned over (as propagated) to face its role.
    pub flip_shell: Vec<bool>,
    /// Σ ±|shell volume|: the solid's volume.
    pub volume: f64,
}

/// Each shell's role from its `containers`, with its propagated volume `shell_signed`,
/// its `counts`, its holes `loops_per_shell` and whether any of its kept faces is
/// `face_inconsistent`.
pub(super) fn roles(
    containers: &[Vec<usize>],
    shell_signed: &[f64],
    shells: &Shells,
    counts: &[ShellCounts],
    loops_per_shell: &[usize],
    kept: &[bool],
    face_inconsistent: &[bool],
) -> Roles {
    let (shell_count, orientable) = (shells.count, &shells.orientable);
    let inconsistent: Vec<bool> =
        shells.fold_faces(kept, |any, f| *any |= face_inconsistent[f], |any, b| *any |= b);
    let mut roles = Vec::with_capacity(shell_count);
    let mut flip_shell = vec![false; shell_count];
    let mut volume = CompensatedSum::default();
    for s in 0..shell_count {
        let depth = containers[s].len();
        let cavity = depth % 2 == 1;
        let parent = containers[s]
            .iter()
            .copied()
            .min_by(|&a, &b| shell_signed[a].abs().total_cmp(&shell_signed[b].abs()));
        let positive_as_propagated = shell_signed[s] >= 0.0;
        // The first face keeps its file winding, so as-propagated is as-wound when the
        // shell is consistent.
        let wound_outward =
            (!inconsistent[s] && orientable[s]).then_some(positive_as_propagated != cavity);
        flip_shell[s] = positive_as_propagated == cavity;
        let v = shell_signed[s].abs();
        volume.add(if cavity { -v } else { v });
        let chi = counts[s].euler_characteristic;
        let closed = !shells.open[s];
        roles.push(Shell {
            faces: counts[s].faces,
            closed,
            orientable: orientable[s],
            consistently_oriented: !inconsistent[s],
            volume: v,
            cavity,
            parent,
            wound_outward,
            boundary_loops: loops_per_shell[s],
            euler_characteristic: chi,
            genus: euler::genus(closed, orientable[s], chi),
        });
    }
    Roles { shells: roles, flip_shell, volume: volume.value() }
}
