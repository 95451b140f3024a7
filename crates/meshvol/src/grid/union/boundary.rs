//! The boundary of the union of several bodies, as the pieces of their surfaces that
//! exact resolution keeps: what the cut-cell geometry of a union is measured on
//! (`meshvol grid --union --moments`).
//!
//! # Method
//! ∂(A₁ ∪ … ∪ Aₙ) is the part of each body's surface outside every other body, a face
//! two bodies share the same way round counted once, and faces glued the opposite way
//! round not at all. Exact resolution ([`super::resolve`]) finds it one column of the
//! union's base grid at a time: each piece of a triangle in a cell two bodies touch is
//! split along the other bodies' surfaces into sub-pieces, and a sub-piece is kept when
//! it is on the union's boundary (a piece in a cell only its own body touches is kept, one
//! in a cell another body fills is dropped). Here every column is resolved and the kept
//! pieces themselves are kept, mapped back to world coordinates: convex planar polygons,
//! wound as their bodies (outward), that cover ∂(∪) once, so the surface they make is
//! closed as a set up to the rounding of the cut points. Any kernel that measures a
//! solid by the divergence theorem over its surface measures the union over them: the
//! cut cells ([`super::super::cut_cells`]) give its volumes, centroids, apertures and
//! surface integrals per cell, with no kernel of their own.
//!
//! Resolution sees a triangle through its plan projection: a vertical one not at all,
//! a steep one with the rounding of its cut points magnified by |N| / |N_z|. So, as for
//! the intersection's interface ([`contact`](crate::grid::intersect::contact)), a
//! triangle's pieces are taken from the one pass that counts it: the plan pass when
//! |N_z| ≥ 10⁻³ |N|, else a pass over the bodies with their axes turned cyclically so
//! that the larger of |N_x|, |N_y| is vertical, over the columns holding such triangles
//! only (a column's kept pieces depend on its own faces alone).
//!
//! # Exactness
//! Which pieces are kept is decided by exact predicates (a symbolic perturbation for a
//! ray through an edge); only the cut points are rounded. A column that resolution
//! cannot settle is resolved again on finer columns over it ([`finer`]: a piece cut into
//! more than 32 sides in the coarse column is smaller, and cut by fewer lines, in the
//! fine ones). One that still cannot be (or resolved volumes outside a cell's certified
//! bounds: bodies that are not solids) has no boundary to give, so then the whole is
//! refused ([`UnionError::Unresolved`]): never a boundary with a hole in it.

use super::frames::counted_columns;
use super::frames::Frame;
use super::{setup, Bodies, Grid, GridError, Rule, UnionError};
use crate::grid::intersect::turned_properties;
use crate::grid::union::{KeptPiece, KeptPieces};
use crate::progress::{Counter, Progress};
use crate::surface::{Moved, Oriented};
use crate::{mass_properties, MassProperties, Point, Surface};
use rayon::prelude::*;

/// The boundary of a union of bodies ([`union_boundary`]): convex planar polygons in
/// world coordinates, wound outward, as a [`Surface`] whose faces are the polygons.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UnionBoundary {
    points: Vec<Point>,
    /// Face `f` is `points[ends[f − 1]..ends[f]]` (from 0 for face 0).
    ends: Vec<usize>,
    /// Bodies wound inward, taken turned outward.
    pub flipped: Vec<usize>,
}

impl UnionBoundary {
    /// The corners of face `f`.
    fn polygon(&self, f: usize) -> &[Point] {
        let start = if f == 0 { 0 } else { self.ends[f - 1] };
        &self.points[start..self.ends[f]]
    }

    /// Appends the pieces of one column.
    fn append(&mut self, kept: Kept) {
        let offset = self.points.len();
        self.points.extend(kept.points);
        self.ends.extend(kept.ends.iter().map(|e| e + offset));
    }
}

impl Surface for UnionBoundary {
    fn face_count(&self) -> usize {
        self.ends.len()
    }

    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        let v = self.polygon(face);
        for k in 1..v.len().saturating_sub(1) {
            triangle(v[0], v[k], v[k + 1]);
        }
    }
}

/// The boundary of the union of `bodies` (each a closed surface; one wound inward is
/// turned outward and listed in `flipped`): the pieces of their surfaces outside the
/// other bodies (module docs). Measure it as any surface: its cut cells are the union's.
///
/// ```
/// use meshvol::grid::{cut_cells, union_boundary, Grid};
/// use meshvol::mass_properties;
/// use meshvol::shapes::cuboid;
/// // Two 2×2×2 boxes overlapping in a unit cube: 8 + 8 − 1, and 2·24 − 6 of surface.
/// let bodies = [cuboid([0.0; 3], [2.0; 3]), cuboid([1.0; 3], [3.0; 3])];
/// let boundary = union_boundary(&bodies).unwrap();
/// assert!((mass_properties(&boundary).signed_volume - 15.0).abs() < 1e-12);
/// let grid = Grid::new([0.0; 3], [1.0; 3], [3, 3, 3]).unwrap();
/// let cells = cut_cells(&boundary, &grid).unwrap();
/// assert!((cells.volume.iter().sum::<f64>() - 15.0).abs() < 1e-12);
/// assert!((cells.boundary_area.iter().sum::<f64>() - 42.0).abs() < 1e-12);
/// ```
pub fn union_boundary<S: Surface>(bodies: &[S]) -> Result<UnionBoundary, UnionError> {
    union_boundary_with(bodies, &())
}

/// [`union_boundary`], telling `progress` its stages (`bounds` and `resolving the
/// union's boundary`, once per pass) and, in each, the bodies or columns done.
pub fn union_boundary_with<S: Surface>(
    bodies: &[S],
    progress: &dyn Progress,
) -> Result<UnionBoundary, UnionError> {
    if bodies.is_empty() {
        return Err(UnionError::NoBodies);
    }
    let properties: Vec<MassProperties> = bodies.iter().map(|b| mass_properties(b)).collect();
    let flipped = (0..bodies.len()).filter(|&i| properties[i].signed_volume < 0.0).collect();
    let mut boundary = UnionBoundary { flipped, ..UnionBoundary::default() };
    for frame in [Frame::Identity, Frame::XUp, Frame::YUp] {
        let turned: Vec<Moved<&S>> = bodies.iter().map(|b| Moved::new(b, frame.turn())).collect();
        let properties: Vec<MassProperties> =
            properties.iter().map(|p| turned_properties(p, frame)).collect();
        kept_in_frame(&turned, &properties, frame, progress, &mut boundary)?;
    }
    Ok(boundary)
}

/// Appends to `boundary` the kept pieces of the triangles counted in `frame` of `bodies`
/// (turned into `frame`; `properties` theirs), column by column in column order.
fn kept_in_frame<S: Surface>(
    bodies: &[S],
    properties: &[MassProperties],
    frame: Frame,
    progress: &dyn Progress,
    boundary: &mut UnionBoundary,
) -> Result<(), UnionError> {
    let mut setup = setup(bodies, properties, Rule::Union);
    if setup.flat {
        return Ok(());
    }
    // Room on every side (10⁻⁶ of the longest side), as the intersection's grid has:
    // no piece lies on the grid's faces, where rounding could put it a hair outside
    // (a face on the top plane mapped a hair above it touches no cell, and a cell its
    // body fills would drop it) or cut it off (beside or below the grid).
    let longest = (0..3).map(|a| setup.max[a] - setup.min[a]).fold(0.0, f64::max);
    for a in 0..3 {
        setup.min[a] -= 1e-6 * longest;
        setup.max[a] += 1e-6 * longest;
    }
    let full = setup.grid()?;
    let grid = match frame {
        Frame::Identity => full,
        _ => match counted_columns(bodies, frame, &full)? {
            Some(grid) => grid,
            None => return Ok(()),
        },
    };
    let flips: Vec<bool> = properties.iter().map(|p| p.signed_volume < 0.0).collect();
    let oriented = || bodies.iter().zip(&flips).map(|(b, &f)| Oriented::new(b, f)).collect();
    let model = Bodies::new(oriented(), Rule::Union, grid, progress)?;
    progress.stage("resolving the union's boundary");
    let per_column = resolve_columns(&model, frame, progress);
    // Many columns failing is not a piece with too many sides but bodies that are not
    // solids (shells overlapping, faces crossing: the cells' bounds do not hold), which
    // finer columns cannot mend: refused at once.
    let failing = per_column.iter().filter(|k| k.is_none()).count();
    if failing > FINER_AT_MOST {
        return Err(UnionError::Unresolved { columns: failing });
    }
    let mut unresolved = 0;
    for (c, kept) in per_column.into_iter().enumerate() {
        match kept {
            Some(kept) => boundary.append(kept),
            None => match finer(&oriented, &grid, c, frame)? {
                Some(pieces) => pieces.into_iter().for_each(|kept| boundary.append(kept)),
                None => unresolved += 1,
            },
        }
    }
    if unresolved > 0 {
        return Err(UnionError::Unresolved { columns: unresolved });
    }
    Ok(())
}

/// Columns that fail to resolve are resolved again on finer grids ([`finer`]) when
/// there are at most this many in a pass.
const FINER_AT_MOST: usize = 64;

/// Every column of `model`'s grid resolved, with its kept pieces of the triangles counted
/// in `frame` (`None` where it cannot be resolved), in column order.
fn resolve_columns<S: Surface>(
    model: &Bodies<'_, S>,
    frame: Frame,
    progress: &dyn Progress,
) -> Vec<Option<Kept>> {
    let grid = model.grid;
    let columns = grid.counts[0] * grid.counts[1];
    let done = Counter::new(progress, columns);
    (0..columns)
        .into_par_iter()
        .map(|c| {
            let mut kept =
                Kept { frame, origin: grid.origin, points: Vec::new(), ends: Vec::new() };
            let resolved = model.exact_column_with(c, Some(&mut kept));
            done.add(1);
            resolved.map(|_| kept)
        })
        .collect()
}

/// Column `c` of `grid` resolved again on finer grids over it (its cells cut into r³,
/// r = 2, 4, 8): smaller pieces are cut by fewer of the other bodies' triangles, so a
/// piece that needed more than 32 sides in the coarse column fits in the fine ones. The
/// fine columns' kept pieces, in column order; `None` when even the finest fails.
fn finer<'a, S: Surface + 'a>(
    oriented: &impl Fn() -> Vec<Oriented<'a, S>>,
    grid: &Grid,
    c: usize,
    frame: Frame,
) -> Result<Option<Vec<Kept>>, GridError> {
    let [_, ny, nz] = grid.counts;
    let (i, j) = (c / ny, c % ny);
    let origin = [
        grid.origin[0] + i as f64 * grid.cell[0],
        grid.origin[1] + j as f64 * grid.cell[1],
        grid.origin[2],
    ];
    for r in [2, 4, 8] {
        let cell = grid.cell.map(|h| h / r as f64);
        let fine = Grid::new(origin, cell, [r, r, nz * r])?;
        let model = Bodies::new(oriented(), Rule::Union, fine, &())?;
        let kept: Option<Vec<Kept>> = resolve_columns(&model, frame, &()).into_iter().collect();
        if kept.is_some() {
            return Ok(kept);
        }
    }
    Ok(None)
}

/// One column's kept pieces of the triangles counted in `frame`, in world coordinates
/// (`origin`: the frame grid's).
struct Kept {
    frame: Frame,
    origin: Point,
    points: Vec<Point>,
    ends: Vec<usize>,
}

impl KeptPieces for Kept {
    fn add(&mut self, piece: KeptPiece<'_>, cell: Point) {
        let (vertices, [p, q, r]) = (piece.vertices, *piece.triangle);
        if vertices.len() < 3 || !self.frame.counts(p, q, r) {
            return;
        }
        for v in vertices {
            let turned = [0, 1, 2].map(|a| self.origin[a] + v[a] * cell[a]);
            self.points.push(self.frame.back(turned));
        }
        self.ends.push(self.points.len());
    }
}
