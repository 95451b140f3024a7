//! Overlapping pairs of an existing and a design triangle that share a corner in plan.
//!
//! Near a corner v each triangle fills the sector between its two edges out of v
//! (narrower than π) and lies inside that sector's cone, so two triangles with a
//! corner at v overlap exactly when their sectors do (the argument of
//! [`super::overlaps`]). Within one surface the sectors around v are disjoint (it is a
//! height field), so sorted by their first edge each surface's sectors follow each
//! other around v without overlapping. The design sectors meeting an existing sector
//! `a` are then:
//!
//! - those starting in [a.start, a.end): a run of the design sectors in angular order,
//!   from the first one starting at or after a.start (binary search) until one starts
//!   at or past a.end;
//! - the one sector that a.start lies strictly inside, if any: the one just before that
//!   run (any sector starting between it and a.start would overlap it).
//!
//! A point shared by k existing and m design triangles costs (k + m) log m plus the
//! pairs found, which are at most k + m for sectors that interleave: two fans of 10⁵
//! slivers from one apex are a merge, not 10¹⁰ tests. Every comparison is an exact
//! `orient2d`. A pair sharing two or three corners is taken at the one with the
//! smallest number only.

use super::overlaps::{by_angle, first_half};
use super::plan::Facet;
use crate::bvh::NO_TAG;
use crate::vector::orient2d;
use rayon::prelude::*;
use std::collections::HashMap;
use std::ops::Range;

/// Corner uses per parallel task (whole corners only).
const USES_PER_TASK: usize = 4096;

/// Plan points numbered: each existing triangle's corners, and each design triangle's
/// corners that are also existing corners ([`NO_TAG`] for the others).
pub(super) struct Corners {
    pub existing: Vec<[u32; 3]>,
    pub design: Vec<[u32; 3]>,
    /// (point, side: 0 existing, 1 design, triangle, corner) for the points both
    /// surfaces have, sorted.
    uses: Vec<(u32, u8, u32, u8)>,
}

fn key(p: [f64; 2]) -> [u64; 2] {
    p.map(|x| (x + 0.0).to_bits()) // −0 and 0 alike
}

impl Corners {
    pub fn new(existing: &[Facet], design: &[Facet]) -> Corners {
        let mut ids: HashMap<[u64; 2], u32> = HashMap::with_capacity(existing.len());
        let existing_ids: Vec<[u32; 3]> = existing
            .iter()
            .map(|f| {
                f.xy.map(|p| {
                    let next = ids.len() as u32;
                    *ids.entry(key(p)).or_insert(next)
                })
            })
            .collect();
        let design_ids: Vec<[u32; 3]> = design
            .par_iter()
            .map(|f| f.xy.map(|p| ids.get(&key(p)).copied().unwrap_or(NO_TAG)))
            .collect();
        let mut shared = vec![false; ids.len()];
        design_ids
            .iter()
            .flatten()
            .filter(|&&t| t != NO_TAG)
            .for_each(|&t| shared[t as usize] = true);
        let uses_of = |side: u8, all: &[[u32; 3]]| {
            all.iter()
                .enumerate()
                .flat_map(|(f, ids)| (0..3u8).map(move |c| (ids[c as usize], side, f as u32, c)))
                .filter(|u| u.0 != NO_TAG && shared[u.0 as usize])
                .collect::<Vec<_>>()
        };
        let mut uses = uses_of(0, &existing_ids);
        uses.extend(uses_of(1, &design_ids));
        uses.par_sort_unstable();
        Corners { existing: existing_ids, design: design_ids, uses }
    }

    /// The tasks: ranges of `uses` holding whole points, about [`USES_PER_TASK`] each.
    pub fn tasks(&self) -> Vec<Range<usize>> {
        let mut tasks = Vec::new();
        let mut start = 0;
        for i in 1..=self.uses.len() {
            let end_of_point = i == self.uses.len() || self.uses[i].0 != self.uses[i - 1].0;
            if end_of_point && (i - start >= USES_PER_TASK || i == self.uses.len()) {
                tasks.push(start..i);
                start = i;
            }
        }
        tasks
    }

    /// Calls `each(e, g)` (triangle indices) for every overlapping pair at the points of
    /// `uses[range]`, in a fixed order; `scratch` is reused from point to point.
    pub fn pairs(
        &self,
        range: Range<usize>,
        existing: &[Facet],
        design: &[Facet],
        scratch: &mut Vec<Sector>,
        mut each: impl FnMut(usize, usize),
    ) {
        let uses = &self.uses[range];
        for around in uses.chunk_by(|a, b| a.0 == b.0) {
            let split = around.partition_point(|u| u.1 == 0);
            let (ours, theirs) = around.split_at(split);
            let Some(&(id, _, f, c)) = ours.first() else { continue };
            if theirs.is_empty() {
                continue;
            }
            let v = existing[f as usize].xy[c as usize];
            scratch.clear();
            scratch
                .extend(theirs.iter().map(|&(_, _, g, c)| Sector::of(&design[g as usize], g, c)));
            scratch.sort_by(|a, b| by_angle(v, a.start, b.start).then(a.facet.cmp(&b.facet)));
            for &(_, _, e, c) in ours {
                let a = Sector::of(&existing[e as usize], e, c);
                meeting(v, &a, scratch, |g| {
                    // Taken at the smallest point the two triangles share.
                    let ours = &self.existing[e as usize];
                    let first = self.design[g]
                        .iter()
                        .filter(|t| ours.contains(t))
                        .min()
                        .is_none_or(|&t| t == id);
                    if first {
                        each(e as usize, g);
                    }
                });
            }
        }
    }
}

/// One triangle's sector at a corner v: from the edge to `start` counter-clockwise to
/// the edge to `end`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Sector {
    start: [f64; 2],
    end: [f64; 2],
    facet: u32,
}

impl Sector {
    fn of(f: &Facet, facet: u32, corner: u8) -> Sector {
        let c = corner as usize;
        Sector { start: f.xy[(c + 1) % 3], end: f.xy[(c + 2) % 3], facet }
    }
}

/// Whether `p` is on the ray from `v` through `q`.
fn same_ray(v: [f64; 2], p: [f64; 2], q: [f64; 2]) -> bool {
    orient2d(v, p, q) == 0.0 && first_half(v, p) == first_half(v, q)
}

/// Whether direction `p` lies strictly inside sector `s` around `v`.
fn strictly_inside(v: [f64; 2], s: &Sector, p: [f64; 2]) -> bool {
    orient2d(v, s.start, p) > 0.0 && orient2d(v, p, s.end) > 0.0
}

/// Calls `each(facet)` for the sectors of `sorted` (disjoint, in angular order) whose
/// interiors meet sector `a`'s (see the module docs).
fn meeting(v: [f64; 2], a: &Sector, sorted: &[Sector], mut each: impl FnMut(usize)) {
    let n = sorted.len();
    let first = sorted.partition_point(|b| by_angle(v, b.start, a.start).is_lt());
    let mut run = 0;
    while run < n {
        let b = &sorted[(first + run) % n];
        if !(same_ray(v, b.start, a.start) || strictly_inside(v, a, b.start)) {
            break;
        }
        each(b.facet as usize);
        run += 1;
    }
    if run < n {
        let before = &sorted[(first + n - 1) % n];
        if strictly_inside(v, before, a.start) {
            each(before.facet as usize);
        }
    }
}
