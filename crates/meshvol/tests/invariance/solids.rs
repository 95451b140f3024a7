//! The solids every invariance test runs on: generated ones (a box, a non-convex
//! L-shaped prism, a box with a cavity, an icosphere, a UV sphere, a torus) and hostile
//! constructions (an internal double wall, a sliver closing a T-junction, open parts
//! with a flat and a ragged rim, a box wound inward, two bodies apart, two bodies
//! touching along an edge).
//!
//! Every coordinate is a multiple of 2⁻³⁰ below 2⁴ in magnitude, so the transforms'
//! translations (±2ᵏ, k ≤ 12) and scalings (2ᵏ) are exact in f64: the transformed solid
//! is exactly the moved polyhedron. Curved solids are triangulated after snapping to
//! that grid; polygon faces are exactly planar (boxes and prisms), so that the fan from
//! any corner is the same face.

use meshvol::shapes::{cuboid, torus, uv_sphere};
use meshvol::{exact_signed_volume, Mesh, Point};
use std::collections::HashMap;
use std::sync::OnceLock;

/// Positions and faces (vertex index lists).
#[derive(Clone, Debug)]
pub struct Shape {
    pub positions: Vec<Point>,
    pub faces: Vec<Vec<u32>>,
}

impl Shape {
    pub fn of(mesh: &Mesh) -> Shape {
        let faces = (0..mesh.face_count()).map(|f| mesh.face(f).to_vec()).collect();
        Shape { positions: mesh.positions().to_vec(), faces }
    }

    pub fn mesh(&self) -> Mesh {
        Mesh::from_polygons(self.positions.clone(), self.faces.iter().map(|f| &f[..])).unwrap()
    }

    /// Every coordinate rounded to a multiple of 2⁻³⁰.
    fn snapped(mut self) -> Shape {
        let grid = (1u64 << 30) as f64;
        for p in &mut self.positions {
            *p = p.map(|x| (x * grid).round() / grid);
        }
        self
    }

    /// Every face replaced by its fan from its first corner.
    fn triangulated(self) -> Shape {
        Shape::of(&self.mesh().triangulated())
    }

    /// Equal positions merged into one vertex (two parts sharing corners).
    fn welded(self) -> Shape {
        let mut id: HashMap<[u64; 3], u32> = HashMap::new();
        let mut positions = Vec::new();
        let new: Vec<u32> = self
            .positions
            .iter()
            .map(|p| {
                *id.entry(p.map(f64::to_bits)).or_insert_with(|| {
                    positions.push(*p);
                    positions.len() as u32 - 1
                })
            })
            .collect();
        let faces = self.faces.iter().map(|f| f.iter().map(|&v| new[v as usize]).collect());
        Shape { positions, faces: faces.collect() }
    }

    fn join(parts: &[Shape]) -> Shape {
        let meshes: Vec<Mesh> = parts.iter().map(Shape::mesh).collect();
        Shape::of(&Mesh::concatenate(&meshes))
    }
}

/// What the check must find, from the construction.
#[derive(Clone, Copy, Debug)]
pub struct Facts {
    pub closed: bool,
    pub shells: usize,
    pub cavities: usize,
    pub bounds_a_volume: bool,
}

/// One solid of the catalogue.
pub struct Solid {
    pub name: &'static str,
    pub shape: Shape,
    /// The checked solid's volume, independently: a closed form or the exact rational
    /// volume of the construction; `None` where only the untransformed run can say.
    pub volume: Option<f64>,
    /// `None` where the construction does not settle them.
    pub facts: Option<Facts>,
    /// Its vertices are in strictly convex position and its faces are its hull's.
    pub convex: bool,
    /// Closed and manifold, so every command's column and slice sums describe the same
    /// solid (the identities between commands hold).
    pub solid: bool,
    /// It has a non-convex face, whose fan from some corners is not a triangulation of
    /// it (the triangles leave the face and cancel outside it).
    pub non_convex_faces: bool,
}

/// A prism over the counter-clockwise ring `ring` (x, y) from z0 to z1, wound outward:
/// the top face is the ring, the bottom the ring reversed (both from the ring's first
/// corner), a quad per side.
pub fn prism(ring: &[[f64; 2]], z0: f64, z1: f64) -> Shape {
    let n = ring.len() as u32;
    let mut positions: Vec<Point> = ring.iter().map(|&[x, y]| [x, y, z0]).collect();
    positions.extend(ring.iter().map(|&[x, y]| [x, y, z1]));
    let bottom = std::iter::once(0).chain((1..n).rev()).collect();
    let mut faces = vec![bottom, (n..2 * n).collect()];
    faces.extend((0..n).map(|i| vec![i, (i + 1) % n, n + (i + 1) % n, n + i]));
    Shape { positions, faces }
}

/// An L-shaped ring (area 3), counter-clockwise, from a corner that sees all of it (the
/// fan from there is a triangulation; from (2, 1) or (1, 2) it is not).
pub const L_RING: [[f64; 2]; 6] =
    [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]];

/// An icosahedron subdivided `levels` times, projected on the sphere of `radius` about
/// `centre`.
fn icosphere(radius: f64, centre: Point, levels: u32) -> Shape {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut p: Vec<Point> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut next = Vec::new();
        for [a, b, c] in f {
            let mut m = |x: u32, y: u32| {
                *mid.entry((x.min(y), x.max(y))).or_insert_with(|| {
                    let (u, v) = (p[x as usize], p[y as usize]);
                    p.push([0, 1, 2].map(|k| 0.5 * (u[k] + v[k])));
                    p.len() as u32 - 1
                })
            };
            let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    let positions = p
        .iter()
        .map(|q| {
            let r = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            [0, 1, 2].map(|k| centre[k] + radius * q[k] / r)
        })
        .collect();
    Shape { positions, faces: f.iter().map(|t| t.to_vec()).collect() }
}

fn exact(shape: &Shape) -> f64 {
    exact_signed_volume(&shape.mesh()).unwrap()
}

fn facts(closed: bool, shells: usize, cavities: usize, bounds_a_volume: bool) -> Option<Facts> {
    Some(Facts { closed, shells, cavities, bounds_a_volume })
}

fn build() -> Vec<Solid> {
    let mut all = Vec::new();
    let mut add = |name, shape: Shape, volume: Option<f64>, facts, convex, solid| {
        let non_convex_faces = name == "L-shaped prism";
        all.push(Solid { name, shape, volume, facts, convex, solid, non_convex_faces })
    };
    let closed = facts(true, 1, 0, true);

    // Generated solids.
    let b = Shape::of(&cuboid([-1.0, -0.5, 0.25], [1.5, 2.0, 1.0]));
    add("box", b, Some(2.5 * 2.5 * 0.75), closed, true, true);
    add("L-shaped prism", prism(&L_RING, -0.5, 1.0), Some(3.0 * 1.5), closed, false, true);
    let cavity = Shape::join(&[
        Shape::of(&cuboid([0.0; 3], [2.0; 3])),
        Shape::of(&cuboid([0.5; 3], [1.5; 3]).flipped()),
    ]);
    add("box with a cavity", cavity, Some(7.0), facts(true, 2, 1, true), false, true);
    let ico = icosphere(1.5, [0.25, -0.125, 0.5], 2).snapped();
    let v = exact(&ico);
    add("icosphere", ico, Some(v), closed, true, true);
    let uv = Shape::of(&uv_sphere(1.25, 10, 6)).snapped().triangulated();
    let v = exact(&uv);
    add("UV sphere", uv, Some(v), closed, false, true);
    let tor = Shape::of(&torus(2.0, 0.75, 12, 6)).snapped().triangulated();
    let v = exact(&tor);
    add("torus", tor, Some(v), closed, false, true);

    // Hostile constructions.
    let wall = Shape::join(&[
        Shape::of(&cuboid([0.0; 3], [1.0; 3])),
        Shape::of(&cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0])),
    ])
    .welded();
    add("double wall", wall, Some(2.0), closed, false, true);
    add("sliver", sliver(), Some(1.0), closed, false, true);
    let open = cuboid([0.0; 3], [1.0, 1.5, 0.75]);
    let top = |f: &Vec<u32>| f.iter().all(|&v| open.positions()[v as usize][2] == 0.75);
    let mut open = Shape::of(&open);
    open.faces.retain(|f| !top(f));
    add("open box", open, Some(1.125), facts(false, 1, 0, false), false, true);
    let (ragged, capped) = ragged();
    add("ragged open box", ragged, Some(capped), facts(false, 1, 0, false), false, true);
    let inward = Shape::of(&cuboid([0.0; 3], [1.0, 0.5, 0.25]).flipped());
    add("box wound inward", inward, Some(0.125), closed, false, true);
    let apart = Shape::join(&[
        Shape::of(&cuboid([0.0; 3], [1.0; 3])),
        Shape::of(&meshvol::shapes::tetrahedron(
            [3.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [3.0, 1.0, 0.0],
            [3.0, 0.0, 1.0],
        )),
    ]);
    add("two bodies apart", apart, Some(1.0 + 1.0 / 6.0), facts(true, 2, 0, true), false, true);
    let touching = Shape::join(&[
        Shape::of(&cuboid([0.0; 3], [1.0; 3])),
        Shape::of(&cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0])),
    ])
    .welded();
    // The edge of four faces is paired into two sheets: two closed bodies (not
    // manifold, so not `bounds_a_volume`).
    let two = facts(false, 2, 0, false);
    add("two bodies touching along an edge", touching, Some(2.0), two, false, true);
    all
}

/// The unit cube whose top face has an extra corner m on its front edge (a T-junction
/// against the front face), closed by a sliver triangle (t00, t10, m) of no area.
fn sliver() -> Shape {
    let cube = cuboid([0.0; 3], [1.0; 3]);
    let mut shape = Shape::of(&cube);
    let at = |p: Point| shape.positions.iter().position(|&q| q == p).unwrap() as u32;
    let (t00, t10, t11, t01) =
        (at([0.0, 0.0, 1.0]), at([1.0, 0.0, 1.0]), at([1.0, 1.0, 1.0]), at([0.0, 1.0, 1.0]));
    shape.positions.push([0.5, 0.0, 1.0]);
    let m = shape.positions.len() as u32 - 1;
    let top =
        shape.faces.iter().position(|f| f.iter().all(|&v| shape.positions[v as usize][2] == 1.0));
    shape.faces[top.unwrap()] = vec![t00, m, t10, t11, t01];
    shape.faces.push(vec![t00, t10, m]);
    shape
}

/// A box without its top whose rim is not flat (corner heights 1, 1.25, 1, 1.375), and
/// the exact volume of it closed as the check closes a hole: a fan from the mean of the
/// rim (dyadic here, so exactly the same point).
fn ragged() -> (Shape, f64) {
    let positions = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.25],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.375],
    ];
    let faces: Vec<Vec<u32>> = vec![
        vec![0, 3, 2, 1],
        vec![0, 1, 5, 4],
        vec![1, 2, 6, 5],
        vec![2, 3, 7, 6],
        vec![3, 0, 4, 7],
    ];
    let open = Shape { positions, faces };
    let mut closed = open.clone();
    closed.positions.push([0.5, 0.5, (1.0 + 1.25 + 1.0 + 1.375) / 4.0]);
    closed.faces.extend([[4, 5, 8], [5, 6, 8], [6, 7, 8], [7, 4, 8]].map(|t| t.to_vec()));
    (open, exact(&closed))
}

/// The catalogue, built once.
pub fn catalogue() -> &'static [Solid] {
    static ALL: OnceLock<Vec<Solid>> = OnceLock::new();
    ALL.get_or_init(build)
}
