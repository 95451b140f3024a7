//! What a check finds ([`Check`], [`Orientation`], [`BodyOverlap`]): a leaf below mod.rs.

use super::crossings::SpatialIndex;
use super::nesting::Shell;
use super::solid::{AsWoundView, Solid, SolidView};
use crate::Surface;

/// How the file's faces are wound.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Orientation {
    /// Every shell is wound so its normals point out of the solid (counter-clockwise
    /// seen from outside); cavities' normals point into the void.
    Outward,
    /// Every shell is wound the other way (clockwise seen from outside, as OpenSCAD's
    /// polyhedron() wants).
    Inward,
    /// Some shells one way, some the other, or faces within a shell disagree.
    Mixed,
}

impl Orientation {
    /// `outward`, `inward` or `mixed`: the names reports use.
    pub fn name(self) -> &'static str {
        match self {
            Orientation::Outward => "outward",
            Orientation::Inward => "inward",
            Orientation::Mixed => "mixed",
        }
    }

    /// The winding seen from outside: `ccw` for outward normals, `cw` for OpenSCAD's
    /// convention; `None` when shells disagree.
    pub fn winding(self) -> Option<&'static str> {
        match self {
            Orientation::Outward => Some("ccw"),
            Orientation::Inward => Some("cw"),
            Orientation::Mixed => None,
        }
    }
}

/// Two bodies whose solids share volume: their surfaces cross, or one lies inside the
/// other's material.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct BodyOverlap {
    /// The two bodies, numbered as the runs of faces given to the check, smaller first.
    pub bodies: [usize; 2],
    /// A shell of one lies wholly inside the other's material, no surface crossing it
    /// (a part in its packaging); otherwise their surfaces cross.
    pub nested: bool,
}

/// The facts [`check`](super::check) finds. See [the module docs](super) for the
/// definitions.
#[derive(Clone, Debug)]
pub struct Check {
    /// The weld tolerance used; `None` for exact welding.
    pub weld_tolerance: Option<f64>,
    /// Welded vertices used by faces.
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    /// Every edge used by exactly two faces (after dropping collapsed and duplicate
    /// faces; flat faces count), and at least one face.
    pub closed: bool,
    pub boundary_edges: usize,
    pub boundary_loops: usize,
    pub non_manifold_edges: usize,
    /// Faces left alone at non-manifold edges: where an odd number of faces meet, the
    /// faces are paired into sheets by their order around the edge and one is left over
    /// (a fin, a T-shaped wall); its edge there is capped like a hole's.
    pub unpaired_at_non_manifold_edges: usize,
    pub non_manifold_vertices: usize,
    /// Faces with a repeated welded vertex (collapsed by welding; left out of
    /// everything) plus flat faces.
    pub degenerate_faces: usize,
    /// Faces with distinct vertices but zero vector area (slivers: a corner on the
    /// segment between two others). They count among `degenerate_faces`, and stay in
    /// the edges, shells and solid: only the crossing search and nesting rays skip them.
    pub flat_faces: usize,
    /// Faces dropped for having the vertex set of another face: copies wound the same
    /// way beyond the first, and both faces of each opposite pair (`double_wall_faces`).
    pub duplicate_faces: usize,
    /// Faces dropped because they cancelled in pairs with a copy wound the opposite
    /// way: an internal double wall, such as the shared face of two boxes exported
    /// with both boxes. Counted in `duplicate_faces` too.
    pub double_wall_faces: usize,
    /// Every manifold edge's two faces traverse it in opposite directions.
    pub consistently_oriented: bool,
    /// `None` when there is no shell to judge.
    pub orientation: Option<Orientation>,
    pub shells: Vec<Shell>,
    pub cavities: usize,
    /// Pairs of shells of one body whose surfaces cross.
    pub overlapping_shells: Vec<[usize; 2]>,
    /// Pairs of the file's objects (the bodies given to the check) that share volume:
    /// their surfaces cross, or one lies inside the other. The volume is their sum.
    pub overlapping_bodies: Vec<BodyOverlap>,
    /// Crossing face pairs within a shell; `None` when not looked for.
    pub self_intersections: Option<usize>,
    /// A few crossing face pairs, each once: within shells first, then between shells.
    pub intersection_examples: Vec<[usize; 2]>,
    /// V − E + F of the whole surface.
    pub euler_characteristic: i64,
    /// The solid's volume: Σ ±|shell volume| (cavities negative), holes capped.
    pub volume: f64,
    /// How much the caps on holes could be off (0 when closed).
    pub volume_uncertainty: f64,
    pub(super) solid: Solid,
    /// With [`super::CheckOptions::keep_spatial_index`]: the crossing search's triangles
    /// in space, for a body of the solid.
    pub(super) spatial_index: Option<SpatialIndex>,
    /// With bodies given: each shell's body, which [`Check::bodies`] names.
    pub(super) object_of_shell: Option<Vec<usize>>,
}

impl Check {
    /// The surface bounds a volume: closed, manifold, orientable, without crossings.
    pub fn bounds_a_volume(&self) -> bool {
        self.closed
            && self.non_manifold_edges == 0
            && self.shells.iter().all(|s| s.orientable)
            && self.overlapping_shells.is_empty()
            && self.overlapping_bodies.is_empty()
            && self.self_intersections.unwrap_or(0) == 0
    }

    /// The solid as a surface over `surface` (which must be the one checked): shells
    /// turned outward (cavities inward), collapsed and duplicate faces dropped, holes
    /// capped.
    pub fn solid<'a, S: Surface + ?Sized>(&'a self, surface: &'a S) -> SolidView<'a, S> {
        self.solid.view(surface)
    }

    /// The checked surface as its faces are wound, with what the check proved of it:
    /// measuring it ([`crate::mass_properties`]) gives the surface's own numbers, and
    /// skips the move to the origin where its vector area is exactly zero. That is so
    /// when [`Check::vector_area_is_zero`] and no face was dropped as a duplicate: the
    /// solid then differs from the surface only by whole shells turned (a closed shell
    /// turned stays balanced) and collapsed faces left out (their cross products are
    /// exactly zero).
    pub fn as_wound<'a, S: Surface + ?Sized>(&'a self, surface: &'a S) -> AsWoundView<'a, S> {
        let balanced = self.vector_area_is_zero() && self.duplicate_faces == 0;
        AsWoundView::new(surface, balanced)
    }

    /// Whether the solid's vector area is exactly zero, so that its volume about any
    /// point is its volume about the origin: the weld exact, the kept faces closed and
    /// consistently oriented, no hole capped. [`Check::solid`] says so to
    /// [`crate::mass_properties`] ([`Surface::vector_area_is_zero`]), which then keeps
    /// the sum about the first vertex and its bound, without the move to the origin
    /// (whose bound grows with the distance from it).
    pub fn vector_area_is_zero(&self) -> bool {
        self.solid.balanced()
    }

    /// The solid as welded triangles when it is exactly that (see [`Solid::triangles`]):
    /// the vertices, and each face of [`Check::solid`] as its corners' vertex ids.
    pub(crate) fn solid_triangles(&self) -> Option<(&[crate::Point], Vec<[u32; 3]>)> {
        self.solid.triangles()
    }

    /// The crossing search's spatial order and hierarchy, when the check was asked to
    /// keep them ([`super::CheckOptions::keep_spatial_index`]).
    pub(crate) fn spatial_index(&self) -> Option<&SpatialIndex> {
        self.spatial_index.as_ref()
    }

    /// The solid as a welded mesh, ready to write: shells turned outward (cavities
    /// inward), collapsed and duplicate faces dropped, and, with `with_caps`, holes
    /// capped.
    pub fn solid_mesh(&self, with_caps: bool) -> crate::Mesh {
        self.solid.mesh(with_caps)
    }

    /// The shell of each face of [`Check::solid_mesh`] (and [`Check::solid`]): kept
    /// faces in order, then the caps (the last `repairs().2` faces), numbered as
    /// [`Check::shells`].
    pub fn solid_face_shells(&self) -> &[u32] {
        self.solid.face_shells()
    }

    /// What [`Check::solid`] changes: (faces flipped, faces dropped, cap triangles).
    pub fn repairs(&self) -> (usize, usize, usize) {
        self.solid.changes()
    }
}
