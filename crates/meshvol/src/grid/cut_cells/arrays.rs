//! The cut-cell arrays ([`CutCells`], [`Extras`]): a leaf the kernel and the apertures fill.

use crate::grid::{Grid, Region};
use crate::Point;

/// The cut-cell geometry of a grid; cell arrays in C order (see [`Grid`]).
#[derive(Clone, Debug, PartialEq)]
pub struct CutCells {
    pub grid: Grid,
    /// The cells held: the whole grid, or a block of it ([`cut_cells_region`](super::cut_cells_region)); arrays in
    /// C order over the region's shape.
    pub region: Region,
    /// The volume of the solid in each cell (the same bits as
    /// [`cell_volumes`](crate::grid::cell_volumes)).
    pub volume: Vec<f64>,
    /// The centroid of the solid in each cell.
    pub centroid: Vec<Point>,
    /// The area of the surface in each cell.
    pub boundary_area: Vec<f64>,
    /// `∫ n dA` over the surface in each cell (outward normal for an outward surface).
    pub boundary_vector: Vec<Point>,
    /// The centroid of the surface in each cell.
    pub boundary_centroid: Vec<Point>,
    /// The fraction of each cell face inside the solid: faces `x = x_i` with shape
    /// `(NX + 1, NY, NZ)`, `y = y_j` with `(NX, NY + 1, NZ)`, `z = z_k` with
    /// `(NX, NY, NZ + 1)`, C order (a region: its shape, plus one along the axis).
    pub aperture: [Vec<f64>; 3],
    /// With [`Extras::second_moments`] (else empty): the inertia tensor of the solid in
    /// each cell about its `centroid`, unit density, `I = tr(C)·𝟙 − C` for the covariance
    /// `C = ∫ (x − c)(x − c)ᵀ dV` (the convention of [`MassProperties::inertia`](crate::MassProperties));
    /// zero for an empty cell, the box's own for a full one. Signed like the volume.
    pub inertia: Vec<[[f64; 3]; 3]>,
    /// With [`Extras::face_centroids`] (else empty): the centroid (world) of the part of
    /// each cell face inside the solid, shaped as `aperture`; NaN where the aperture is
    /// within [`OCCUPANCY_TOLERANCE`](crate::grid::OCCUPANCY_TOLERANCE) of 0 (no wetted part),
    /// the face's middle where it is within it of ±1.
    pub aperture_centroid: [Vec<Point>; 3],
}

/// The cut-cell arrays computed beyond the default ones.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Extras {
    /// [`CutCells::inertia`].
    pub second_moments: bool,
    /// [`CutCells::aperture_centroid`].
    pub face_centroids: bool,
}

impl CutCells {
    /// The region's cells along each axis.
    pub fn shape(&self) -> [usize; 3] {
        self.region.clone().map(|r| r.len())
    }

    /// The position of grid cell `at` in the arrays, if the region holds it.
    pub fn local(&self, at: [usize; 3]) -> Option<usize> {
        let [_, by, bz] = self.shape();
        let mut l = [0; 3];
        for a in 0..3 {
            if !self.region[a].contains(&at[a]) {
                return None;
            }
            l[a] = at[a] - self.region[a].start;
        }
        Some((l[0] * by + l[1]) * bz + l[2])
    }

    /// The cells of `region` (inside this one's), a block of the same arrays.
    pub(super) fn cropped(&self, region: &Region) -> CutCells {
        let offset = [0, 1, 2].map(|a| region[a].start - self.region[a].start);
        let (cells, shape) = (self.shape(), region.clone().map(|r| r.len()));
        let faces = |a: usize, mut s: [usize; 3]| {
            s[a] += 1;
            s
        };
        CutCells {
            grid: self.grid,
            region: region.clone(),
            volume: block_of(&self.volume, cells, shape, offset),
            centroid: block_of(&self.centroid, cells, shape, offset),
            boundary_area: block_of(&self.boundary_area, cells, shape, offset),
            boundary_vector: block_of(&self.boundary_vector, cells, shape, offset),
            boundary_centroid: block_of(&self.boundary_centroid, cells, shape, offset),
            aperture: [0, 1, 2]
                .map(|a| block_of(&self.aperture[a], faces(a, cells), faces(a, shape), offset)),
            inertia: if self.inertia.is_empty() {
                Vec::new()
            } else {
                block_of(&self.inertia, cells, shape, offset)
            },
            aperture_centroid: [0, 1, 2].map(|a| {
                let centroids = &self.aperture_centroid[a];
                if centroids.is_empty() {
                    Vec::new()
                } else {
                    block_of(centroids, faces(a, cells), faces(a, shape), offset)
                }
            }),
        }
    }

    /// Volume / cell volume.
    pub fn fraction(&self) -> Vec<f64> {
        let v = self.grid.cell_volume();
        self.volume.iter().map(|x| x / v).collect()
    }

    /// Bytes of the arrays for `grid`: 14 f64 a cell (and one a face).
    pub fn bytes(grid: &Grid) -> u128 {
        Self::bytes_with(grid, Extras::default())
    }

    /// Bytes of the arrays for `grid` with `extras`, and of the scratch they need while
    /// computed (10 f64 a cell and 2 a z face): 9 more f64 a cell for the inertia, 3 more
    /// a face for the face centroids.
    pub fn bytes_with(grid: &Grid, extras: Extras) -> u128 {
        let [nx, ny, nz] = grid.counts.map(|n| n as u128);
        let (cells, faces) =
            (nx * ny * nz, (nx + 1) * ny * nz + nx * (ny + 1) * nz + nx * ny * (nz + 1));
        let mut f64s = 11 * cells + faces;
        if extras.second_moments || extras.face_centroids {
            f64s += 10 * cells + 2 * (cells + nx * ny);
        }
        if extras.second_moments {
            f64s += 9 * cells;
        }
        if extras.face_centroids {
            f64s += 3 * faces;
        }
        f64s * 8
    }
}

/// The entries `offset + (i, j, k)` for `(i, j, k)` in `to` of a C-order array of shape
/// `from`.
fn block_of<T: Copy>(values: &[T], from: [usize; 3], to: [usize; 3], offset: [usize; 3]) -> Vec<T> {
    let mut out = Vec::with_capacity(to.iter().product());
    for i in 0..to[0] {
        for j in 0..to[1] {
            let row = ((i + offset[0]) * from[1] + j + offset[1]) * from[2] + offset[2];
            out.extend_from_slice(&values[row..row + to[2]]);
        }
    }
    out
}
