//! The randomized incremental hull (Clarkson–Shor) with conflict lists: see the module
//! doc of [`crate::hull`] for the method, its predicates and its cost.

use crate::progress::Progress;
use rayon::prelude::*;

use crate::vector::{cross, dot, orient2d, orient3d, sign, sub};
use crate::Point;

/// "No face" and "no point": the end of a conflict list, a point inside the hull.
const NONE: u32 = u32::MAX;

/// Relative error bound of the rounded plane test `((b − a) × (c − a)) · (q − a)`
/// against its permanent (the same expression over absolute values): each of its terms
/// passes through at most 8 roundings (three differences, two products, the cross
/// product's difference, the dot product's two sums), so the error is at most
/// γ₈ = 8u/(1 − 8u) < 8.9·10⁻¹⁶ times the permanent. The test bounds the permanent
/// Σₖ mₖ|dₖ| (mₖ: component k's two terms in absolute value) by max(mₖ)·Σₖ|dₖ|, one
/// number a face; 10⁻¹⁵ leaves room for the bound's own rounding.
const FILTER_BOUND: f64 = 1.0e-15;
/// Below this permanent, products may have underflowed, and the relative bound no
/// longer holds: the exact test decides.
const FILTER_FLOOR: f64 = 1.0e-200;

/// A hull triangle, wound counterclockwise seen from outside.
struct Face {
    vertices: [u32; 3],
    /// `neighbours[i]` is the face across the edge `vertices[i] → vertices[i + 1]`.
    neighbours: [u32; 3],
    /// This face's conflict list in [`Builder::lists`], or [`NONE`] while it has none.
    conflicts: u32,
    /// The insertion at which this face's visibility was last decided, and the answer.
    decided_at: u32,
    visible: bool,
    alive: bool,
}

/// A face's plane, for the filtered plane test: its vertices, the first one's
/// coordinates, the rounded outward normal (b − a) × (c − a), and the largest sum of
/// the absolute values of a normal component's two terms. Computed when needed rather
/// than stored, which would double a face's size: the faces a walk tests share
/// vertices with the last, in cache, and the new faces' planes are computed once for
/// all the points they take over.
struct Plane {
    vertices: [u32; 3],
    origin: Point,
    normal: Point,
    magnitude: f64,
}

impl Plane {
    fn of(points: &[Point], vertices: [u32; 3]) -> Plane {
        let [a, b, c] = vertices.map(|v| points[v as usize]);
        let (ab, ac) = (sub(b, a), sub(c, a));
        let magnitude = ((ab[1] * ac[2]).abs() + (ab[2] * ac[1]).abs())
            .max((ab[2] * ac[0]).abs() + (ab[0] * ac[2]).abs())
            .max((ab[0] * ac[1]).abs() + (ab[1] * ac[0]).abs());
        Plane { vertices, origin: a, normal: cross(ab, ac), magnitude }
    }

    /// Whether `q` lies strictly outside, on, or inside the plane: +1, 0 or −1, exactly.
    fn side(&self, points: &[Point], q: Point) -> f64 {
        let d = sub(q, self.origin);
        let value = dot(self.normal, d);
        let permanent = self.magnitude * (d[0].abs() + d[1].abs() + d[2].abs());
        if permanent > FILTER_FLOOR && value.abs() > FILTER_BOUND * permanent {
            return value.signum();
        }
        let [a, b, c] = self.vertices.map(|v| points[v as usize]);
        // orient3d is positive when q is on the side the normal points away from.
        -sign(orient3d(a, b, c, q))
    }
}

/// The hull under construction.
struct Builder<'a> {
    points: &'a [Point],
    faces: Vec<Face>,
    free_faces: Vec<u32>,
    /// Per point: the face whose conflict list holds it, or [`NONE`] once it is inserted
    /// or known to be inside.
    conflict_face: Vec<u32>,
    /// Conflict lists: points not yet inserted, strictly outside a face's plane, that
    /// are assigned to it (each point is on at most one list), with their coordinates,
    /// so that moving them reads memory in order. Most faces of a hull with many
    /// vertices never have conflicts, so faces refer to lists rather than own them.
    lists: Vec<Vec<(Point, u32)>>,
    /// Places in `lists` that no face refers to (their lists empty and freed).
    free_lists: Vec<u32>,
    /// Whether two neighbouring faces were ever made coplanar, the only way a vertex
    /// that is not a corner can arise (see [`Builder::non_corners`]).
    coplanar_neighbours: bool,
    /// Per vertex, during one insertion: the new face whose first vertex it is.
    new_face_from: Vec<u32>,
    insertion: u32,
    // Per-insertion scratch, kept to reuse its allocation.
    stack: Vec<u32>,
    visible: Vec<u32>,
    horizon: Vec<(u32, u32, u32)>,
    new_faces: Vec<u32>,
    displaced: Vec<(Point, u32)>,
    /// Per displaced point: the index in `new_faces` of the face it sees, or [`NONE`].
    targets: Vec<u32>,
}

impl Builder<'_> {
    fn plane(&self, f: u32) -> Plane {
        Plane::of(self.points, self.faces[f as usize].vertices)
    }

    /// Whether `q` lies strictly outside, on, or inside the plane of face `f`: +1, 0 or
    /// −1, exactly.
    fn side(&self, f: u32, q: Point) -> f64 {
        self.plane(f).side(self.points, q)
    }

    fn new_face(&mut self, vertices: [u32; 3], neighbours: [u32; 3]) -> u32 {
        let face = Face {
            vertices,
            neighbours,
            conflicts: NONE,
            decided_at: 0,
            visible: false,
            alive: true,
        };
        match self.free_faces.pop() {
            Some(f) => {
                self.faces[f as usize] = face;
                f
            }
            None => {
                self.faces.push(face);
                (self.faces.len() - 1) as u32
            }
        }
    }

    fn push_conflict(&mut self, f: u32, q: u32, at: Point) {
        self.conflict_face[q as usize] = f;
        let mut list = self.faces[f as usize].conflicts;
        if list == NONE {
            list = self.free_lists.pop().unwrap_or_else(|| {
                self.lists.push(Vec::new());
                (self.lists.len() - 1) as u32
            });
            self.faces[f as usize].conflicts = list;
        }
        self.lists[list as usize].push((at, q));
    }

    /// The tetrahedron on `corners` (not coplanar), with every other point on the
    /// conflict list of the first of its faces it sees.
    fn start(&mut self, corners: [u32; 4]) {
        let p = corners.map(|v| self.points[v as usize]);
        let mut faces = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]].map(|t| t.map(|i| corners[i]));
        // Wind each face so that the fourth corner is inside.
        if orient3d(p[0], p[1], p[2], p[3]) < 0.0 {
            faces.iter_mut().for_each(|t| t.swap(1, 2));
        }
        for t in faces {
            self.new_face(t, [NONE; 3]);
        }
        for f in 0..4 {
            for i in 0..3 {
                let (u, w) = (faces[f][i], faces[f][(i + 1) % 3]);
                let g = (0..4).find(|&g| g != f && edge_index(&faces[g], w, u).is_some());
                self.faces[f].neighbours[i] = g.expect("a tetrahedron is closed") as u32;
            }
        }
        let planes: Vec<Plane> = (0..4).map(|f| self.plane(f)).collect();
        let first_seen: Vec<u32> = (0..self.points.len() as u32)
            .into_par_iter()
            .map(|q| {
                if corners.contains(&q) {
                    return NONE;
                }
                let q = self.points[q as usize];
                planes
                    .iter()
                    .position(|plane| plane.side(self.points, q) > 0.0)
                    .map_or(NONE, |f| f as u32)
            })
            .collect();
        for (q, f) in first_seen.into_iter().enumerate() {
            if f != NONE {
                self.push_conflict(f, q as u32, self.points[q]);
            }
        }
    }

    /// Adds point `p`, which is strictly outside the hull: removes the faces it sees,
    /// joins it to their boundary (the horizon), and moves their conflicts to the new
    /// faces, dropping those that are now inside.
    fn insert(&mut self, p: u32) {
        self.insertion += 1;
        let start = self.conflict_face[p as usize];
        self.conflict_face[p as usize] = NONE;
        self.faces[start as usize].decided_at = self.insertion;
        self.faces[start as usize].visible = true;
        self.stack.push(start);
        while let Some(f) = self.stack.pop() {
            self.visible.push(f);
            for i in 0..3 {
                let g = self.faces[f as usize].neighbours[i];
                if self.faces[g as usize].decided_at != self.insertion {
                    let side = self.side(g, self.points[p as usize]);
                    // p in the plane of a face it keeps: the new face there is coplanar
                    // with it.
                    self.coplanar_neighbours |= side == 0.0;
                    let visible = side > 0.0;
                    let face = &mut self.faces[g as usize];
                    face.decided_at = self.insertion;
                    face.visible = visible;
                    if visible {
                        self.stack.push(g);
                    }
                }
                if !self.faces[g as usize].visible {
                    let t = self.faces[f as usize].vertices;
                    self.horizon.push((t[i], t[(i + 1) % 3], g));
                }
            }
        }
        for &f in &self.visible {
            let face = &mut self.faces[f as usize];
            face.alive = false;
            let list = std::mem::replace(&mut face.conflicts, NONE);
            if list != NONE {
                // Freed rather than kept for reuse: kept lists of every size class
                // held about twice the memory (1.2 -> 2 GB for 5M points on a sphere).
                let conflicts = std::mem::take(&mut self.lists[list as usize]);
                self.displaced.extend(conflicts.into_iter().filter(|&(_, q)| q != p));
                self.free_lists.push(list);
            }
            self.free_faces.push(f);
        }
        self.visible.clear();
        // The visible faces form a disc, so the horizon is one cycle: each of its vertices
        // starts exactly one horizon edge, and the new faces link up through it.
        let mut horizon = std::mem::take(&mut self.horizon);
        for &(u, w, kept) in &horizon {
            let f = self.new_face([u, w, p], [kept, NONE, NONE]);
            let back = edge_index(&self.faces[kept as usize].vertices, w, u)
                .expect("the face behind a horizon edge has the edge reversed");
            self.faces[kept as usize].neighbours[back] = f;
            self.new_face_from[u as usize] = f;
            self.new_faces.push(f);
        }
        horizon.clear();
        self.horizon = horizon;
        for &f in &self.new_faces {
            let next = self.new_face_from[self.faces[f as usize].vertices[1] as usize];
            self.faces[f as usize].neighbours[1] = next;
            self.faces[next as usize].neighbours[2] = f;
            let beyond = self.points[self.faces[next as usize].vertices[1] as usize];
            self.coplanar_neighbours |= self.side(f, beyond) == 0.0;
        }
        // A point that saw a removed face is outside a new face or inside the new hull:
        // the segment from it to a removed face's interior (inside the new hull) leaves
        // the new hull through the part that is not the old one, which new faces bound.
        let displaced = std::mem::take(&mut self.displaced);
        let new_faces = std::mem::take(&mut self.new_faces);
        let planes: Vec<Plane> = new_faces.iter().map(|&f| self.plane(f)).collect();
        // Counted first, so that each new list is allocated once at its size.
        let mut targets = std::mem::take(&mut self.targets);
        let target = |&(at, _): &(Point, u32)| {
            let sees = |plane: &Plane| plane.side(self.points, at) > 0.0;
            planes.iter().position(sees).map_or(NONE, |i| i as u32)
        };
        // The first insertions move most of the points: those are shared among threads.
        if displaced.len() >= PARALLEL_DISPLACED {
            targets.par_extend(displaced.par_iter().map(target));
        } else {
            targets.extend(displaced.iter().map(target));
        }
        let mut counts = vec![0; new_faces.len()];
        targets.iter().filter(|&&i| i != NONE).for_each(|&i| counts[i as usize] += 1);
        for (&f, &count) in new_faces.iter().zip(&counts).filter(|(_, &c)| c > 0) {
            let list = self.free_lists.pop().unwrap_or_else(|| {
                self.lists.push(Vec::new());
                (self.lists.len() - 1) as u32
            });
            self.lists[list as usize] = Vec::with_capacity(count);
            self.faces[f as usize].conflicts = list;
        }
        for (&(at, q), &target) in displaced.iter().zip(&targets) {
            match target {
                NONE => self.conflict_face[q as usize] = NONE,
                i => {
                    let f = new_faces[i as usize];
                    self.conflict_face[q as usize] = f;
                    self.lists[self.faces[f as usize].conflicts as usize].push((at, q));
                }
            }
        }
        targets.clear();
        self.targets = targets;
        self.displaced = displaced;
        self.displaced.clear();
        self.new_faces = new_faces;
        self.new_faces.clear();
    }

    /// Whether some vertex is not a corner of the hull: it lies inside a flat face or on
    /// an edge of it (coplanar points can make such a vertex, when it went in before the
    /// points that flatten its neighbourhood). A corner's triangles span three or more
    /// planes; a vertex in a face's interior has triangles in one plane, one in an
    /// edge's interior in two. Neither can happen without two neighbouring triangles in
    /// one plane, which the first pass looks for.
    fn non_corners(&self) -> Vec<bool> {
        let alive = || self.faces.iter().enumerate().filter(|(_, face)| face.alive);
        let coplanar_with = |f: usize, g: u32| {
            let plane = &self.faces[f].vertices;
            self.faces[g as usize]
                .vertices
                .iter()
                .all(|&v| plane.contains(&v) || self.side(f as u32, self.points[v as usize]) == 0.0)
        };
        let mut suspects = vec![false; self.points.len()];
        for (f, face) in alive() {
            for i in 0..3 {
                if coplanar_with(f, face.neighbours[i]) {
                    suspects[face.vertices[i] as usize] = true;
                    suspects[face.vertices[(i + 1) % 3] as usize] = true;
                }
            }
        }
        let mut non_corner = vec![false; self.points.len()];
        // Each suspect's triangles, found through a compact index.
        let mut slot = vec![NONE; self.points.len()];
        let mut incident: Vec<(u32, Vec<u32>)> = Vec::new();
        for (f, face) in alive() {
            for &v in face.vertices.iter().filter(|&&v| suspects[v as usize]) {
                if slot[v as usize] == NONE {
                    slot[v as usize] = incident.len() as u32;
                    incident.push((v, Vec::new()));
                }
                incident[slot[v as usize] as usize].1.push(f as u32);
            }
        }
        for (v, faces) in &incident {
            let first = faces[0] as usize;
            let second = faces.iter().find(|&&g| !coplanar_with(first, g));
            non_corner[*v as usize] = match second {
                None => true,
                Some(&second) => faces
                    .iter()
                    .all(|&g| coplanar_with(first, g) || coplanar_with(second as usize, g)),
            };
        }
        non_corner
    }

    fn triangles(&self) -> Vec<[u32; 3]> {
        self.faces.iter().filter(|f| f.alive).map(|f| f.vertices).collect()
    }
}

/// The index i of the edge `vertices[i] → vertices[i + 1]` that runs from u to w.
fn edge_index(vertices: &[u32; 3], u: u32, w: u32) -> Option<usize> {
    (0..3).find(|&i| vertices[i] == u && vertices[(i + 1) % 3] == w)
}

/// A fixed-seed permutation of `0..n` (Fisher–Yates driven by splitmix64), so the
/// insertion order is random but the hull is the same on every run.
fn shuffled(n: usize) -> Vec<u32> {
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = move || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    };
    let mut order: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        let j = ((next() as u128 * (i as u128 + 1)) >> 64) as usize;
        order.swap(i, j);
    }
    order
}

/// Displaced points from which their new faces are found in parallel.
const PARALLEL_DISPLACED: usize = 1 << 15;

/// Rounds of the insertion order smaller than this stay in random order.
const SMALLEST_SORTED_ROUND: usize = 64;

/// A biased randomized insertion order (Amenta, Choi and Rote 2003): a fixed-seed
/// random permutation cut into rounds of doubling size, each round sorted along a Morton
/// curve. Every round is still a random sample of the points, which keeps the expected
/// O(n log n) bound of random order, and consecutive points are close, so the faces
/// one insertion touches are mostly in cache from the last.
fn insertion_order(points: &[Point]) -> Vec<u32> {
    let order = shuffled(points.len());
    let (low, high) =
        points.iter().fold(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]), |(low, high), p| {
            (std::array::from_fn(|k| low[k].min(p[k])), std::array::from_fn(|k| high[k].max(p[k])))
        });
    // 21 bits an axis; a flat axis maps to 0. (high − low can overflow to infinity,
    // which only makes the key coarser.)
    let scale: [f64; 3] = std::array::from_fn(|k| {
        let extent = high[k] - low[k];
        if extent > 0.0 {
            ((1 << 21) - 1) as f64 / extent
        } else {
            0.0
        }
    });
    let key = |i: u32| {
        let p = points[i as usize];
        let cell = |k: usize| spread_bits(((p[k] - low[k]) * scale[k]) as u64);
        (cell(0) | cell(1) << 1 | cell(2) << 2, i)
    };
    let mut keyed: Vec<(u64, u32)> = order.par_iter().map(|&i| key(i)).collect();
    let mut end = points.len();
    while end / 2 >= SMALLEST_SORTED_ROUND {
        keyed[end / 2..end].par_sort_unstable();
        end /= 2;
    }
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// The low 21 bits of x, spread to every third bit.
fn spread_bits(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// The first four points that span space (the caller has checked that some do).
fn first_tetrahedron(points: &[Point]) -> [u32; 4] {
    let a = points[0];
    let find = |spans: &dyn Fn(Point) -> bool, what| {
        points.iter().position(|&p| spans(p)).expect(what) as u32
    };
    let b = find(&|p| p != a, "not all points coincide");
    let pb = points[b as usize];
    let c = find(&|p| !collinear(a, pb, p), "not all points are collinear");
    let pc = points[c as usize];
    let d = find(&|p| orient3d(a, pb, pc, p) != 0.0, "not all points are coplanar");
    [0, b, c, d]
}

/// Points inserted between two progress reports.
const POINTS_PER_REPORT: usize = 4096;

/// One randomized incremental pass over `points` (not all coplanar): the hull's
/// triangles over indices into `points`, and its vertices that are not corners.
/// Reports the points inserted so far (in insertion order) to `progress`.
fn hull_pass(points: &[Point], progress: &dyn Progress) -> (Vec<[u32; 3]>, Vec<u32>) {
    let n = points.len();
    let order = insertion_order(points);
    // Renumbered in insertion order, so that the pass reads its per-point arrays in order.
    let ranked: Vec<Point> = order.iter().map(|&i| points[i as usize]).collect();
    let mut builder = Builder {
        points: &ranked,
        // A hull of n points has at most 2n − 4 faces, and removed faces' places are
        // reused: reserving once spares copying a growing array.
        faces: Vec::with_capacity(2 * n),
        free_faces: Vec::new(),
        conflict_face: vec![NONE; n],
        lists: Vec::new(),
        free_lists: Vec::new(),
        coplanar_neighbours: false,
        new_face_from: vec![NONE; n],
        insertion: 0,
        stack: Vec::new(),
        visible: Vec::new(),
        horizon: Vec::new(),
        new_faces: Vec::new(),
        displaced: Vec::new(),
        targets: Vec::new(),
    };
    builder.start(first_tetrahedron(&ranked));
    for p in 0..n as u32 {
        if (p as usize).is_multiple_of(POINTS_PER_REPORT) {
            progress.advance(u64::from(p), n as u64);
        }
        if builder.conflict_face[p as usize] != NONE {
            builder.insert(p);
        }
    }
    progress.advance(n as u64, n as u64);
    let non_corners = match builder.coplanar_neighbours {
        true => {
            let non_corners = builder.non_corners();
            (0..n).filter(|&v| non_corners[v]).map(|v| order[v]).collect()
        }
        false => Vec::new(),
    };
    let triangles = builder.triangles().into_iter().map(|t| t.map(|v| order[v as usize])).collect();
    (triangles, non_corners)
}

/// The convex hull of `points` (not all coplanar) as outward triangles over indices
/// into `points`, its vertices exactly the hull's corners; stages and points inserted
/// go to `progress`.
pub(super) fn hull_triangles(points: &[Point], progress: &dyn Progress) -> Vec<[u32; 3]> {
    progress.stage("inserting points");
    let (triangles, non_corners) = hull_pass(points, progress);
    if non_corners.is_empty() {
        return triangles;
    }
    // Hull the corners again: all of them are extreme points, and a hull vertex that
    // is an extreme point is a corner, so the second pass has no other vertices.
    let mut skip = vec![false; points.len()];
    non_corners.iter().for_each(|&v| skip[v as usize] = true);
    let mut corners = Vec::new();
    for v in triangles.into_iter().flatten() {
        if !std::mem::replace(&mut skip[v as usize], true) {
            corners.push(v);
        }
    }
    let corner_points: Vec<Point> = corners.iter().map(|&v| points[v as usize]).collect();
    progress.stage("inserting the corners again");
    let (triangles, _) = hull_pass(&corner_points, progress);
    triangles.into_iter().map(|t| t.map(|v| corners[v as usize])).collect()
}

/// Whether a, b, c lie on one line, exactly: all three coordinate-plane projections are
/// collinear.
pub(super) fn collinear(a: Point, b: Point, c: Point) -> bool {
    [[0, 1], [1, 2], [2, 0]]
        .iter()
        .all(|&[i, j]| orient2d([a[i], a[j]], [b[i], b[j]], [c[i], c[j]]) == 0.0)
}
