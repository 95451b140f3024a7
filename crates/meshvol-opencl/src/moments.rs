//! The host side of the cut cells (`grid --moments`): the core's
//! [`cut_cells_swept`] with its per-column stage on the device, a slab of x layers at a
//! time, one work item a tile; the x and y apertures and the surface centroids summed
//! after by the core on the CPU, from what the device wrote.

use crate::run::{input, on, scalars, Device, Options, Program};
use crate::slabs::{rows_per_slab, slabs};
use crate::Error;
use meshvol::grid::{
    cut_cells_swept, cut_tile_work, CutCells, Grid, Region, SweptCells, TileWork,
    OCCUPANCY_TOLERANCE,
};
use meshvol::progress::Progress;
use meshvol::Surface;
use opencl3::error_codes::ClError;
use opencl3::kernel::Kernel;
use opencl3::memory::{Buffer, ClMem};
use opencl3::types::{cl_double, CL_BLOCKING};

/// The cut cells' program: the polygons, the sweeps, the integrals over a part, the
/// moments' sink, the columns' finish and the kernel.
pub(crate) const MOMENTS: Program = Program {
    source: concat!(
        include_str!("cl/clip.cl"),
        include_str!("cl/sweeps.cl"),
        include_str!("cl/integrals.cl"),
        include_str!("cl/moments.cl")
    ),
    kernel: "tile_moments",
};

/// f64 a column needs on the device (`depth` cells, `areas` layers handed down): eleven
/// a cell (volume, centroid, surface area, vector and weighted centroid), the z
/// apertures (`depth + 1`), three sums a layer handed down, the area on the top face.
fn per_column(depth: usize, areas: usize) -> [usize; 2] {
    [11 * depth + depth + 1 + 3 * areas + 1, 3 * areas]
}

/// A slab's buffers on the device, allocated once for the largest slab: what it writes
/// for the host (the first six), and its columns' sums.
struct Buffers {
    volume: Buffer<f64>,
    centroid: Buffer<f64>,
    area: Buffer<f64>,
    vector: Buffer<f64>,
    weighted: Buffer<f64>,
    aperture_z: Buffer<f64>,
    handed: Buffer<f64>,
    on_top: Buffer<f64>,
}

impl Device {
    /// `meshvol::grid::cut_cells` on this device: the same bits.
    pub fn cut_cells<S: Surface + ?Sized>(
        &mut self,
        surface: &S,
        grid: &Grid,
        options: Options,
    ) -> Result<CutCells, Error> {
        self.cut_cells_region_with(surface, grid, &grid.counts.map(|n| 0..n), options, &())
    }

    /// `meshvol::grid::cut_cells_region` on this device: the same bits. The sweeps and
    /// each column's sums run on the device; the sums along x and y (the x and y
    /// apertures, the surface centroids) on the CPU, as `progress` is told.
    pub fn cut_cells_region_with<S: Surface + ?Sized>(
        &mut self,
        surface: &S,
        grid: &Grid,
        region: &Region,
        options: Options,
        progress: &dyn Progress,
    ) -> Result<CutCells, Error> {
        cut_cells_swept(surface, grid, region, progress, |reach, swept| {
            let built = self.moments.take();
            let kernel = self.kernel(built, MOMENTS, progress)?;
            self.sweep(&kernel, surface, grid, reach, swept, options, progress)?;
            self.moments = Some(kernel);
            Ok(())
        })
    }

    /// The per-column stage of the cells of `reach` (which reaches the grid's far x and
    /// y faces) into `out`, a slab of x layers at a time.
    #[allow(clippy::too_many_arguments)]
    fn sweep<S: Surface + ?Sized>(
        &self,
        kernel: &Kernel,
        surface: &S,
        grid: &Grid,
        reach: &Region,
        out: SweptCells,
        options: Options,
        progress: &dyn Progress,
    ) -> Result<(), Error> {
        let [x, y, z] = reach.clone();
        let (width, depth, areas) = (y.len(), z.len(), grid.counts[2] + 1 - z.start);
        let budget = self.slab_budget(&options);
        let rows = rows_per_slab(&x, width, per_column(depth, areas), budget, &self.info.name)?;
        let buffers = self.buffers(rows * width, depth, areas)?;
        let SweptCells {
            volume, centroid, boundary_area, boundary_vector, boundary_centroid, ..
        } = out;
        let aperture_z = out.aperture_z;
        let mut triangles = None;
        for slab in slabs(&x, rows) {
            progress.stage("laying out the tiles (CPU)");
            let columns = slab.len() * width;
            let per_item = options.per_item(columns, self.units);
            let first = (slab.start - x.start) * width;
            let cells = first * depth..(first + columns) * depth;
            let points = 3 * cells.start..3 * cells.end;
            let planes = first * (depth + 1)..(first + columns) * (depth + 1);
            let work = cut_tile_work(surface, grid, &[slab, y.clone(), z.clone()], per_item)?;
            progress.stage("OpenCL: uploading");
            // Every slab's triangles are the same (the whole surface in grid units):
            // uploaded with the first.
            let triangles = match &triangles {
                Some(t) => t,
                None => triangles.insert(self.triangles_and_normals(&work)?),
            };
            self.run_moments(
                kernel,
                &work,
                triangles,
                &buffers,
                grid,
                options.work_group,
                progress,
            )?;
            progress.stage("OpenCL: reading back");
            let reads: [(&Buffer<f64>, &mut [f64], &'static str); 6] = [
                (&buffers.volume, &mut volume[cells.clone()], "clEnqueueReadBuffer (volumes)"),
                (
                    &buffers.centroid,
                    &mut centroid.as_flattened_mut()[points.clone()],
                    "clEnqueueReadBuffer (centroids)",
                ),
                (&buffers.area, &mut boundary_area[cells.clone()], "clEnqueueReadBuffer (areas)"),
                (
                    &buffers.vector,
                    &mut boundary_vector.as_flattened_mut()[points.clone()],
                    "clEnqueueReadBuffer (boundary vectors)",
                ),
                (
                    &buffers.weighted,
                    &mut boundary_centroid.as_flattened_mut()[points],
                    "clEnqueueReadBuffer (boundary centroids)",
                ),
                (&buffers.aperture_z, &mut aperture_z[planes], "clEnqueueReadBuffer (z apertures)"),
            ];
            for (buffer, into, what) in reads {
                // SAFETY: `into` is the slab's part of the array, no more than the buffer
                // holds; the read blocks until done.
                unsafe { self.queue.enqueue_read_buffer(buffer, CL_BLOCKING, 0, into, &[]) }
                    .map_err(on(&self.info.name, what))?;
            }
        }
        Ok(())
    }

    /// The buffers of a slab of `columns` columns, `depth` cells and `areas` layers
    /// handed down each.
    fn buffers(&self, columns: usize, depth: usize, areas: usize) -> Result<Buffers, Error> {
        let cells = columns * depth;
        Ok(Buffers {
            volume: self.scratch(self.cells_len(cells), "clCreateBuffer (cells)")?,
            centroid: self.scratch(3 * cells, "clCreateBuffer (centroids)")?,
            area: self.scratch(cells, "clCreateBuffer (boundary areas)")?,
            vector: self.scratch(3 * cells, "clCreateBuffer (boundary vectors)")?,
            weighted: self.scratch(3 * cells, "clCreateBuffer (boundary centroids)")?,
            aperture_z: self.scratch(columns * (depth + 1), "clCreateBuffer (z apertures)")?,
            handed: self.scratch(3 * columns * areas, "clCreateBuffer (column sums)")?,
            on_top: self.scratch(columns, "clCreateBuffer (top face areas)")?,
        })
    }

    /// The triangles of `work` and their faces' normals on the device.
    fn triangles_and_normals(&self, work: &TileWork) -> Result<[Buffer<f64>; 2], Error> {
        let triangles = self.triangles(work)?;
        self.fits("the triangles' normals", work.normals.len() * 4, 8)?;
        // An empty buffer is invalid in OpenCL: an unused entry stands in for none.
        let normals: &[f64] = match work.normals.is_empty() {
            true => &[0.0; 4],
            false => work.normals.as_flattened(),
        };
        let normals = input(&self.context, normals, &self.info.name, "clCreateBuffer (normals)")?;
        Ok([triangles, normals])
    }

    /// One slab: its tile lists uploaded, its arguments set, the kernel run.
    #[allow(clippy::too_many_arguments)]
    fn run_moments(
        &self,
        kernel: &Kernel,
        work: &TileWork,
        [triangles, normals]: &[Buffer<f64>; 2],
        b: &Buffers,
        grid: &Grid,
        work_group: Option<usize>,
        progress: &dyn Progress,
    ) -> Result<(), Error> {
        let (offsets, entries) = self.tile_lists(work)?;
        let set =
            |result: Result<(), ClError>| result.map_err(on(&self.info.name, "clSetKernelArg"));
        let [sx, sy, sz] =
            [grid.cell[1] * grid.cell[2], grid.cell[0] * grid.cell[2], grid.cell[0] * grid.cell[1]];
        let [ox, oy, oz] = grid.origin;
        let [dx, dy, dz] = grid.cell;
        let doubles: [cl_double; 11] =
            [ox, oy, oz, dx, dy, dz, grid.cell_volume(), OCCUPANCY_TOLERANCE, sx, sy, sz];
        let buffers = [
            triangles.get(),
            normals.get(),
            offsets.get(),
            entries.get(),
            b.volume.get(),
            b.centroid.get(),
            b.area.get(),
            b.vector.get(),
            b.weighted.get(),
            b.aperture_z.get(),
            b.handed.get(),
            b.on_top.get(),
        ];
        let scalars = scalars(work);
        // SAFETY: each argument has the type and order of `tile_moments`' parameters:
        // twelve buffers, twelve ulongs, eleven doubles.
        unsafe {
            for (k, buffer) in buffers.iter().enumerate() {
                set(kernel.set_arg(k as u32, buffer))?;
            }
            for (k, value) in scalars.iter().enumerate() {
                set(kernel.set_arg((buffers.len() + k) as u32, value))?;
            }
            for (k, value) in doubles.iter().enumerate() {
                set(kernel.set_arg((buffers.len() + scalars.len() + k) as u32, value))?;
            }
        }
        self.launch(kernel, work.tiles(), work_group, progress)
    }
}
