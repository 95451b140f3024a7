//! The triangle mesh that copies placed by affine transforms (3MF components, glTF
//! nodes) are gathered into, and the [`Assembly`] that says which part each copy is.

use std::collections::HashMap;

use meshvol::assembly::{Affine, Assembly, Placement};
use meshvol::{Mesh, Point};
use rayon::prelude::*;

use crate::object::Object;

/// Triangle meshes placed by transforms, gathered into one mesh, with the objects and the
/// bodies the reader names (see [`crate::Loaded::bodies`]).
pub(crate) struct Placed {
    positions: Vec<Point>,
    triangles: Vec<[u32; 3]>,
    objects: Vec<Object>,
    bodies: Vec<Object>,
    /// The parts and copies, when the reader asked for them.
    assembly: Option<Assembly>,
    /// The reader's name of each part recorded in `assembly`, and its index there.
    part_index: HashMap<PartKey, u32>,
}

/// What a reader calls a part: a 3MF object id, a glTF (mesh, primitive) pair.
pub(crate) type PartKey = (u64, u64);

/// Parts with fewer vertices and triangles than this are placed in one thread.
const PARALLEL_PART: usize = 1 << 14;

impl Placed {
    /// Reserves room for the totals, which the caller computes from what the file holds
    /// (never from unchecked counts): an error when they exceed 32-bit indices or memory.
    /// With `copies` (how many part copies will be added), the parts and copies are
    /// recorded too: for files that place a part more than once, whose check can then be
    /// one check of each part.
    pub fn with_capacity(
        vertices: u64,
        triangles: u64,
        copies: Option<u64>,
    ) -> Result<Placed, String> {
        if vertices > u64::from(u32::MAX) {
            return Err(format!(
                "the placed parts have {vertices} vertices in all, more than 32-bit indices hold"
            ));
        }
        let mut placed = Placed {
            positions: Vec::new(),
            triangles: Vec::new(),
            objects: Vec::new(),
            bodies: Vec::new(),
            assembly: None,
            part_index: HashMap::new(),
        };
        let cannot = |what: &str, n: u64| format!("cannot allocate memory for {n} {what}");
        placed
            .positions
            .try_reserve_exact(vertices as usize)
            .map_err(|_| cannot("vertices", vertices))?;
        let t = usize::try_from(triangles).map_err(|_| cannot("triangles", triangles))?;
        placed.triangles.try_reserve_exact(t).map_err(|_| cannot("triangles", triangles))?;
        if let Some(copies) = copies {
            let mut assembly = Assembly::default();
            let n = usize::try_from(copies).map_err(|_| cannot("placements", copies))?;
            assembly.placements.try_reserve_exact(n).map_err(|_| cannot("placements", copies))?;
            placed.assembly = Some(assembly);
        }
        Ok(placed)
    }

    /// Adds a copy of part `part`: `positions` moved by `placement`, and `triangles`
    /// indexing them (checked by the caller), wound the other way when `placement`
    /// mirrors, so that outward faces stay outward.
    pub fn add(
        &mut self,
        part: PartKey,
        positions: &[Point],
        triangles: &[[u32; 3]],
        placement: &Affine,
    ) {
        self.record(part, positions, triangles, placement);
        let base = self.positions.len() as u32;
        let mirrored = placement.determinant() < 0.0;
        let corners = |&[a, b, c]: &[u32; 3]| {
            if mirrored {
                [base + a, base + c, base + b]
            } else {
                [base + a, base + b, base + c]
            }
        };
        // Small parts in this thread: a file placing a tetrahedron 10⁶ times made 2·10⁶
        // parallel jobs of four items each, and the idle workers' spinning took 33 s.
        if positions.len() + triangles.len() < PARALLEL_PART {
            self.positions.extend(positions.iter().map(|&p| placement.apply(p)));
            self.triangles.extend(triangles.iter().map(corners));
            return;
        }
        if *placement == Affine::IDENTITY {
            self.positions.extend_from_slice(positions);
        } else {
            self.positions.par_extend(positions.par_iter().map(|&p| placement.apply(p)));
        }
        self.triangles.par_extend(triangles.par_iter().map(corners));
    }

    /// [`Placed::add`] for arrays the caller no longer needs: the first part, when it
    /// is not moved, is taken without a copy.
    pub fn add_owned(
        &mut self,
        part: PartKey,
        positions: Vec<Point>,
        triangles: Vec<[u32; 3]>,
        placement: &Affine,
    ) {
        if self.positions.is_empty() && self.triangles.is_empty() && *placement == Affine::IDENTITY
        {
            self.record(part, &positions, &triangles, placement);
            self.positions = positions;
            self.triangles = triangles;
        } else {
            self.add(part, &positions, &triangles, placement);
        }
    }

    /// Records a copy of `part` in the assembly, the part itself the first time.
    fn record(
        &mut self,
        part: PartKey,
        positions: &[Point],
        triangles: &[[u32; 3]],
        placement: &Affine,
    ) {
        let Some(assembly) = &mut self.assembly else { return };
        let index = match self.part_index.get(&part) {
            Some(&index) => index,
            None => match Mesh::from_triangles(positions.to_vec(), triangles.to_vec()) {
                Ok(mesh) => {
                    assembly.parts.push(mesh);
                    let index = assembly.parts.len() as u32 - 1;
                    self.part_index.insert(part, index);
                    index
                }
                // A part the whole mesh will refuse too: no assembly to speak of.
                Err(_) => return self.assembly = None,
            },
        };
        assembly.placements.push(Placement { part: index, transform: *placement });
    }

    /// The number of triangles added so far.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Names the triangles added since `first` as one object (nothing when there are
    /// none).
    pub fn close_object(&mut self, name: String, first: usize) {
        if self.triangles.len() > first {
            self.objects.push(Object { name, faces: first..self.triangles.len() });
        }
    }

    /// Names the triangles added since `first` as one body (nothing when there are none).
    pub fn close_body(&mut self, name: String, first: usize) {
        if self.triangles.len() > first {
            self.bodies.push(Object { name, faces: first..self.triangles.len() });
        }
    }

    /// The mesh, its objects and bodies, and its assembly when one was asked for and a
    /// part is placed more than once.
    pub fn finish(self) -> Result<Gathered, meshvol::MeshError> {
        let assembly = self.assembly.filter(Assembly::repeats_parts);
        let mesh = Mesh::from_triangles(self.positions, self.triangles)?;
        Ok(Gathered { mesh, objects: self.objects, bodies: self.bodies, assembly })
    }
}

/// What [`Placed`] gathered.
pub(crate) struct Gathered {
    pub mesh: Mesh,
    pub objects: Vec<Object>,
    pub bodies: Vec<Object>,
    pub assembly: Option<Assembly>,
}
