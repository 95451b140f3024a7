//! The solid a checked surface bounds, as a [`Surface`] over the original one (faces
//! kept or dropped, each possibly reversed, plus cap triangles over holes), or as a
//! welded [`Mesh`] to write out.

use crate::assembly::Placement;
use crate::buckets::par_compact;
use crate::{Mesh, Point, Surface};
use rayon::prelude::*;

/// The checked surface's faces: which are kept and reversed, and their welded corners.
pub(crate) struct Faces<'a> {
    pub kept: &'a [bool],
    pub flip: &'a [bool],
    /// Each face's shell.
    pub shell: &'a [u32],
    /// Welded vertex of each corner; face f's corners are `start[f]..start[f + 1]`.
    pub corners: Vec<u32>,
    pub start: Vec<usize>,
}

/// Cap triangles over holes, as points and as vertex ids, wound as their shell was
/// propagated; `flip` turns a cap the way its shell is turned.
pub(crate) struct Caps<'a> {
    pub points: Vec<[Point; 3]>,
    pub ids: Vec<[u32; 3]>,
    pub flip: &'a [bool],
    /// Each cap triangle's shell.
    pub shell: &'a [u32],
}

/// A triangle the other way round, when `reverse`.
fn turn<T: Copy>(t: [T; 3], reverse: bool) -> [T; 3] {
    if reverse {
        [t[0], t[2], t[1]]
    } else {
        t
    }
}

/// Which faces of the checked surface make the solid, which way round, and the caps.
#[derive(Clone, Debug, Default)]
pub struct Solid {
    /// Kept faces, and whether each is reversed.
    faces: Vec<(usize, bool)>,
    caps: Vec<[Point; 3]>,
    /// The shell of each face of the solid (kept faces, then caps).
    shell: Vec<u32>,
    flipped: usize,
    dropped: usize,
    /// Welded vertices (cap centres last), the welded vertex of each corner of the
    /// checked surface (face f's are `start[f]..start[f + 1]`), and the caps, for
    /// [`Solid::mesh`].
    vertices: Vec<Point>,
    corners: Vec<u32>,
    start: Vec<usize>,
    cap_ids: Vec<[u32; 3]>,
    /// Whether `vertices` are the checked surface's corners welded exactly: one vertex
    /// per distinct position, at each of its corners' positions (up to the sign of
    /// zero). Not so when welded within a tolerance, or put together from an
    /// assembly's parts (a transform may round two of a part's vertices to one point).
    exact: bool,
    /// Every directed edge of the solid's faces is matched by its reverse, the corners
    /// exactly equal: its vector area is exactly zero (see [`Solid::mark_balanced`]).
    balanced: bool,
}

impl Solid {
    /// `exact`: `vertices` weld the corners exactly (see [`Solid::triangles`]).
    pub(crate) fn new(faces: Faces, vertices: Vec<Point>, caps: Caps, exact: bool) -> Solid {
        let Faces { kept, flip, shell, corners, start } = faces;
        let kept_faces = par_compact(kept.len(), |f| kept[f], |f| (f, flip[f]));
        let mut shell_of: Vec<u32> = Vec::with_capacity(kept_faces.len() + caps.shell.len());
        shell_of.par_extend(kept_faces.par_iter().map(|&(f, _)| shell[f]));
        shell_of.extend_from_slice(caps.shell);
        Solid {
            shell: shell_of,
            dropped: kept.len() - kept_faces.len(),
            flipped: flip.par_iter().filter(|&&x| x).count(),
            faces: kept_faces,
            caps: caps.points.into_iter().zip(caps.flip).map(|(c, &f)| turn(c, f)).collect(),
            vertices,
            corners,
            start,
            cap_ids: caps.ids.into_iter().zip(caps.flip).map(|(c, &f)| turn(c, f)).collect(),
            exact,
            balanced: false,
        }
    }

    /// Records that the kept faces are closed (every edge used by two of them) and
    /// consistently oriented (the two traverse it in opposite directions): with an exact
    /// weld and no caps, every directed edge of the solid is then matched by its
    /// reverse with exactly equal corners (a shell turned to its role is turned whole,
    /// and a face dropped for collapsing has no area), so its vector area is exactly
    /// zero.
    pub(crate) fn mark_balanced(&mut self, closed_and_consistently_oriented: bool) {
        self.balanced = self.exact && self.caps.is_empty() && closed_and_consistently_oriented;
    }

    /// See [`Solid::mark_balanced`].
    pub(crate) fn balanced(&self) -> bool {
        self.balanced
    }

    /// The solid as welded triangles, when it is exactly that: the vertices, and each
    /// face as the ids of its corners, in the order and winding of [`SolidView`]'s
    /// triangles (a reversed face (a, b, c) as (a, c, b)). `None` unless the weld was
    /// exact, every kept face a triangle and no hole capped (a cap's centre is a new
    /// point, which could fall on a vertex).
    pub(crate) fn triangles(&self) -> Option<(&[Point], Vec<[u32; 3]>)> {
        let start = &self.start;
        let fit = self.exact
            && self.caps.is_empty()
            && self.faces.par_iter().all(|&(f, _)| start[f + 1] - start[f] == 3);
        fit.then(|| {
            let triangles = self
                .faces
                .par_iter()
                .map(|&(f, reversed)| {
                    let c = &self.corners[start[f]..start[f] + 3];
                    turn([c[0], c[1], c[2]], reversed)
                })
                .collect();
            (&self.vertices[..], triangles)
        })
    }

    /// The solid as a welded mesh (unused vertices left out), with or without the caps.
    pub(crate) fn mesh(&self, with_caps: bool) -> Mesh {
        let cap_ids = if with_caps { &self.cap_ids[..] } else { &[] };
        let mut new_id = vec![u32::MAX; self.vertices.len()];
        let mut positions = Vec::new();
        let mut renumber = |v: u32| {
            if new_id[v as usize] == u32::MAX {
                new_id[v as usize] = positions.len() as u32;
                positions.push(self.vertices[v as usize]);
            }
            new_id[v as usize]
        };
        let mut indices = Vec::new();
        let mut offsets = vec![0];
        for &(f, reversed) in &self.faces {
            let ids = &self.corners[self.start[f]..self.start[f + 1]];
            if reversed {
                indices.extend(ids.iter().rev().map(|&v| renumber(v)));
            } else {
                indices.extend(ids.iter().map(|&v| renumber(v)));
            }
            offsets.push(indices.len());
        }
        for cap in cap_ids {
            indices.extend(cap.map(&mut renumber));
            offsets.push(indices.len());
        }
        Mesh::new(positions, crate::Faces::Polygons { offsets, indices })
            .expect("kept faces and caps index welded vertices")
    }

    /// The solid of an assembly whose copies are apart: each copy's part solid moved
    /// into place. `parts[i]` is part i's solid and `shells[i]` its shell count; copies
    /// follow one another in the expanded surface's faces, vertices and shells. A
    /// mirrored copy's triangles are reversed, as the reader reversed them.
    pub(crate) fn assembled(parts: &[&Solid], shells: &[usize], placements: &[Placement]) -> Solid {
        // Room for the totals first: growing arrays of millions of copies by doubling
        // costs more (copies and fresh pages) than filling them.
        let total = |size: fn(&Solid) -> usize| -> usize {
            placements.iter().map(|p| size(parts[p.part as usize])).sum()
        };
        let (faces, caps) = (total(|s| s.faces.len()), total(|s| s.caps.len()));
        let mut whole = Solid {
            faces: Vec::with_capacity(faces),
            caps: Vec::with_capacity(caps),
            shell: Vec::with_capacity(faces + caps),
            vertices: Vec::with_capacity(total(|s| s.vertices.len())),
            corners: Vec::with_capacity(total(|s| s.corners.len())),
            start: Vec::with_capacity(total(|s| s.start.len() - 1) + 1),
            cap_ids: Vec::with_capacity(caps),
            ..Solid::default()
        };
        whole.start.push(0);
        let mut cap_shell = Vec::with_capacity(caps);
        let mut shell_offset = 0u32;
        for placement in placements {
            let part = parts[placement.part as usize];
            let transform = &placement.transform;
            let mirrored = transform.determinant() < 0.0;
            let face_offset = whole.start.len() - 1;
            let vertex_offset = whole.vertices.len() as u32;
            let corner_offset = whole.corners.len();
            whole.faces.extend(part.faces.iter().map(|&(f, r)| (f + face_offset, r)));
            whole.shell.extend(part.shell[..part.faces.len()].iter().map(|&s| s + shell_offset));
            cap_shell.extend(part.shell[part.faces.len()..].iter().map(|&s| s + shell_offset));
            whole
                .caps
                .extend(part.caps.iter().map(|c| turn(c.map(|p| transform.apply(p)), mirrored)));
            whole
                .cap_ids
                .extend(part.cap_ids.iter().map(|c| turn(c.map(|v| v + vertex_offset), mirrored)));
            whole.vertices.extend(part.vertices.iter().map(|&p| transform.apply(p)));
            whole.start.extend(part.start[1..].iter().map(|&s| s + corner_offset));
            for f in 0..part.start.len() - 1 {
                let corners = &part.corners[part.start[f]..part.start[f + 1]];
                match corners.split_first() {
                    // The reader writes a mirrored copy of face (a, b, c, …) as (a, …, c, b).
                    Some((&first, rest)) if mirrored => {
                        whole.corners.push(first + vertex_offset);
                        whole.corners.extend(rest.iter().rev().map(|&v| v + vertex_offset));
                    }
                    _ => whole.corners.extend(corners.iter().map(|&v| v + vertex_offset)),
                }
            }
            whole.flipped += part.flipped;
            whole.dropped += part.dropped;
            shell_offset += shells[placement.part as usize] as u32;
        }
        whole.shell.extend(cap_shell);
        whole
    }

    pub(crate) fn view<'a, S: Surface + ?Sized>(&'a self, surface: &'a S) -> SolidView<'a, S> {
        SolidView { solid: self, surface }
    }

    /// (faces reversed, faces dropped, cap triangles added).
    pub(crate) fn changes(&self) -> (usize, usize, usize) {
        (self.flipped, self.dropped, self.caps.len())
    }

    /// The shell of each face of the solid: kept faces in order, then caps.
    pub(crate) fn face_shells(&self) -> &[u32] {
        &self.shell
    }

    /// The solid's faces grouped by `group` of their shell: lists of face indices of
    /// [`SolidView`], in face order, the groups numbered `0..groups`.
    pub(crate) fn faces_by(
        &self,
        groups: usize,
        group: impl Fn(usize) -> usize,
    ) -> Vec<Vec<usize>> {
        let mut faces = vec![Vec::new(); groups];
        for (f, &s) in self.shell.iter().enumerate() {
            faces[group(s as usize)].push(f);
        }
        faces
    }
}

/// A [`Solid`] read over the surface it was checked from.
#[derive(Debug)]
pub struct SolidView<'a, S: ?Sized> {
    solid: &'a Solid,
    surface: &'a S,
}

// Copy whatever `S` is: a view holds references only.
impl<S: ?Sized> Clone for SolidView<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S: ?Sized> Copy for SolidView<'_, S> {}

impl<S: ?Sized> SolidView<'_, S> {
    /// How many of the solid's faces are the checked surface's own: faces
    /// `0..surface_faces()`; the caps over its holes follow them.
    pub fn surface_faces(&self) -> usize {
        self.solid.faces.len()
    }
}

impl<S: Surface + ?Sized> Surface for SolidView<'_, S> {
    fn face_count(&self) -> usize {
        self.solid.faces.len() + self.solid.caps.len()
    }

    fn vector_area_is_zero(&self) -> bool {
        self.solid.balanced
    }

    #[inline]
    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        match self.solid.faces.get(face) {
            Some(&(f, true)) => self.surface.fan(f, |a, b, c| triangle(a, c, b)),
            Some(&(f, false)) => self.surface.fan(f, triangle),
            None => {
                let [a, b, c] = self.solid.caps[face - self.solid.faces.len()];
                triangle(a, b, c)
            }
        }
    }

    /// A kept face of a surface of triangles is one triangle (turned or not), and so is
    /// a cap: the mass properties then take their four-faces-a-step path, the same
    /// bits as face by face (on a 5M-triangle sphere with its collapsed pole triangles
    /// dropped, measuring took 0.09 s less).
    fn faces_are_triangles(&self) -> bool {
        self.surface.faces_are_triangles() || self.surface.indexed_triangles().is_some()
    }
}

/// What a measurement is taken of: the solid a check found (the default of every
/// measuring command), or the surface as its faces are wound.
#[derive(Debug)]
pub enum Measured<'a, S: ?Sized> {
    Solid(SolidView<'a, S>),
    AsWound(&'a S),
}

impl<S: ?Sized> Clone for Measured<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S: ?Sized> Copy for Measured<'_, S> {}

impl<S: Surface + ?Sized> Surface for Measured<'_, S> {
    fn face_count(&self) -> usize {
        match self {
            Measured::Solid(s) => s.face_count(),
            Measured::AsWound(s) => s.face_count(),
        }
    }

    #[inline]
    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        match self {
            Measured::Solid(s) => s.fan(face, triangle),
            Measured::AsWound(s) => s.fan(face, triangle),
        }
    }

    fn vector_area_is_zero(&self) -> bool {
        match self {
            Measured::Solid(s) => s.vector_area_is_zero(),
            Measured::AsWound(s) => s.vector_area_is_zero(),
        }
    }

    fn faces_are_triangles(&self) -> bool {
        match self {
            Measured::Solid(s) => s.faces_are_triangles(),
            Measured::AsWound(s) => s.faces_are_triangles(),
        }
    }
}

/// A checked surface as its faces are wound ([`crate::topology::Check::as_wound`]):
/// the surface itself, every fast path included, and what the check proved of its
/// vector area.
#[derive(Debug)]
pub struct AsWoundView<'a, S: ?Sized> {
    surface: &'a S,
    balanced: bool,
}

impl<'a, S: ?Sized> AsWoundView<'a, S> {
    /// `balanced`: every directed edge of the surface's faces is matched by its reverse
    /// with exactly equal corners.
    pub(crate) fn new(surface: &'a S, balanced: bool) -> Self {
        AsWoundView { surface, balanced }
    }
}

impl<S: Surface + ?Sized> Surface for AsWoundView<'_, S> {
    fn face_count(&self) -> usize {
        self.surface.face_count()
    }

    #[inline]
    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        self.surface.fan(face, triangle)
    }

    fn indexed_triangles(&self) -> Option<(&[Point], &[[u32; 3]])> {
        self.surface.indexed_triangles()
    }

    fn faces_are_triangles(&self) -> bool {
        self.surface.faces_are_triangles()
    }

    fn triangle_f32(&self, face: usize) -> Option<[[f32; 3]; 3]> {
        self.surface.triangle_f32(face)
    }

    fn vector_area_is_zero(&self) -> bool {
        self.balanced
    }
}
