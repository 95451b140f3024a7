//! The host side: a device opened with the grid kernel built, a region's cells a slab
//! at a time (`slabs.rs`), one work item a tile, each slab's cells read back into their
//! place in the region's array.

use crate::devices::{call, devices, DeviceInfo, Listing};
use crate::fault::{self, Fault};
use crate::slabs::{rows_per_slab, slabs, Budget};
use crate::Error;
use meshvol::grid::{check_region, tile_work, Grid, GridError, Region, TileWork};
use meshvol::progress::Progress;
use meshvol::Surface;
use opencl3::command_queue::CommandQueue;
use opencl3::context::Context;
use opencl3::error_codes::ClError;
use opencl3::kernel::Kernel;
use opencl3::memory::{Buffer, ClMem, CL_MEM_COPY_HOST_PTR, CL_MEM_READ_ONLY, CL_MEM_READ_WRITE};
use opencl3::types::{cl_double, cl_ulong, CL_BLOCKING};
use std::ptr;

/// The cell volumes' program: the polygons, the sweeps, the volumes' sink and kernel.
pub(crate) const VOLUMES: Program = Program {
    source: concat!(
        include_str!("cl/clip.cl"),
        include_str!("cl/sweeps.cl"),
        include_str!("cl/volumes.cl")
    ),
    kernel: "tile_volumes",
};

/// One of the grid's OpenCL programs: its source and its kernel's name.
#[derive(Clone, Copy)]
pub(crate) struct Program {
    pub(crate) source: &'static str,
    pub(crate) kernel: &'static str,
}

/// How the grid is cut into work: none of these changes a bit of the result.
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    /// Columns per work item; `None`: enough tiles for 64 work items per compute unit.
    pub columns_per_item: Option<usize>,
    /// Work items per work group; `None`: the driver's choice.
    pub work_group: Option<usize>,
    /// The most bytes one slab's cells and column area sums may take on the device
    /// (each buffer also within the device's largest allocation); `None`: half the
    /// device's global memory, the rest left for the triangles and their tile lists.
    pub slab_bytes: Option<u64>,
}

impl Options {
    /// The columns each work item takes of a slab of `columns`, on a device of `units`
    /// compute units: as asked, or enough tiles for 64 work items a unit, at least one.
    pub(crate) fn per_item(&self, columns: usize, units: usize) -> usize {
        self.columns_per_item.unwrap_or_else(|| columns.div_ceil(64 * units)).max(1)
    }
}

/// An OpenCL device, and the grid's kernels built for it, each the first time a grid
/// needs it (a build takes seconds on some drivers).
pub struct Device {
    pub(crate) info: DeviceInfo,
    pub(crate) units: usize,
    pub(crate) context: Context,
    pub(crate) queue: CommandQueue,
    /// The kernels built: taken out while a grid runs, put back after.
    pub(crate) volumes: Option<Kernel>,
    pub(crate) moments: Option<Kernel>,
}

/// The device buffers that hold a slab's results, allocated once for the largest slab.
struct Results {
    cells: Buffer<f64>,
    areas: Buffer<f64>,
}

impl Device {
    /// Device `index` of [`devices`]' listing; refused without f64.
    pub fn open(index: usize) -> Result<Device, Error> {
        let listed = match devices()? {
            Listing::NoLibrary => return Err(Error::NoLibrary),
            Listing::Devices(d) => d,
        };
        let count = listed.len();
        let info = listed.into_iter().nth(index).ok_or(Error::NoDevice { index, count })?;
        if !info.fp64 {
            return Err(Error::NoFp64 { index, name: info.name });
        }
        let name = info.name.clone();
        let device = opencl3::device::Device::new(info.id);
        let named = |call_name| on(&name, call_name);
        let units = device.max_compute_units().map_err(named("clGetDeviceInfo"))? as usize;
        let context = Context::from_device(&device).map_err(named("clCreateContext"))?;
        let queue = CommandQueue::create_default_with_properties(&context, 0, 0)
            .map_err(named("clCreateCommandQueueWithProperties"))?;
        Ok(Device { info, units: units.max(1), context, queue, volumes: None, moments: None })
    }

    /// `built` (one of this device's kernels, taken out of its field), or `program`
    /// built now, telling `progress`.
    pub(crate) fn kernel(
        &self,
        built: Option<Kernel>,
        program: Program,
        progress: &dyn Progress,
    ) -> Result<Kernel, Error> {
        if let Some(kernel) = built {
            return Ok(kernel);
        }
        progress.stage("OpenCL: building the kernel");
        let name = &self.info.name;
        let source = match fault::asked() {
            Some(Fault::Build) => {
                format!("{}\n#error MESHVOL_OPENCL_FAULT=build\n", program.source)
            }
            _ => program.source.to_string(),
        };
        // No -cl-fast-relaxed-math, -cl-mad-enable or -cl-unsafe-math-optimizations: the
        // pragma in the source turns contraction off and IEEE rules hold.
        let built =
            opencl3::program::Program::create_and_build_from_source(&self.context, &source, "")
                .map_err(|log| Error::Build { device: name.clone(), log })?;
        Kernel::create(&built, program.kernel).map_err(on(name, "clCreateKernel"))
    }

    /// The device's name, as errors give it.
    pub fn name(&self) -> &str {
        &self.info.name
    }

    /// `meshvol::grid::cell_volumes` on this device: the same bits. `&mut`: a grid sets
    /// the kernel's arguments, so one grid at a time runs on a `Device`.
    pub fn cell_volumes<S: Surface + ?Sized>(
        &mut self,
        surface: &S,
        grid: &Grid,
        options: Options,
    ) -> Result<Vec<f64>, Error> {
        self.cell_volumes_region(surface, grid, &grid.counts.map(|n| 0..n), options)
    }

    /// `meshvol::grid::cell_volumes_region` on this device: the same bits.
    pub fn cell_volumes_region<S: Surface + ?Sized>(
        &mut self,
        surface: &S,
        grid: &Grid,
        region: &Region,
        options: Options,
    ) -> Result<Vec<f64>, Error> {
        self.cell_volumes_region_with(surface, grid, region, options, &())
    }

    /// [`Device::cell_volumes_region`], telling `progress` its stages (laying out each
    /// slab's tiles on the CPU, uploading, the kernel, reading back), so that a run's
    /// timings say where its time went.
    pub fn cell_volumes_region_with<S: Surface + ?Sized>(
        &mut self,
        surface: &S,
        grid: &Grid,
        region: &Region,
        options: Options,
        progress: &dyn Progress,
    ) -> Result<Vec<f64>, Error> {
        let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
        check_region(&grid, region)?;
        let [x, y, z] = region.clone();
        let (width, depth, areas) = (y.len(), z.len(), grid.counts[2] + 1 - z.start);
        let budget = self.slab_budget(&options);
        let rows = rows_per_slab(&x, width, [depth + areas, areas], budget, &self.info.name)?;
        let built = self.volumes.take();
        let kernel = self.kernel(built, VOLUMES, progress)?;
        let len = x.len() * width * depth;
        let mut volumes = bytemuck::allocation::try_zeroed_vec::<f64>(len)
            .map_err(|_| GridError::OutOfMemory { bytes: len as u128 * 8 })?;
        let results = self.results(rows * width * depth, rows * width * areas)?;
        let mut triangles = None;
        for slab in slabs(&x, rows) {
            progress.stage("laying out the tiles (CPU)");
            let columns = slab.len() * width;
            let per_item = options.per_item(columns, self.units);
            let at = (slab.start - x.start) * width * depth;
            let out = &mut volumes[at..at + columns * depth];
            let work = tile_work(surface, &grid, &[slab, y.clone(), z.clone()], per_item)?;
            progress.stage("OpenCL: uploading");
            // Every slab's triangles are the same (the whole surface in grid units):
            // uploaded with the first.
            let triangles = match &triangles {
                Some(t) => t,
                None => triangles.insert(self.triangles(&work)?),
            };
            self.run(&kernel, &work, triangles, &results, options.work_group, out, progress)?;
        }
        self.volumes = Some(kernel);
        Ok(volumes)
    }

    /// The buffers of a slab's `cells` and area sums `areas` (each at least one value:
    /// an empty buffer is invalid in OpenCL).
    fn results(&self, cells: usize, areas: usize) -> Result<Results, Error> {
        Ok(Results {
            cells: self.scratch(self.cells_len(cells), "clCreateBuffer (cells)")?,
            areas: self.scratch(areas, "clCreateBuffer (column areas)")?,
        })
    }

    /// What one slab may take of the device: `options.slab_bytes`, or half its memory,
    /// each buffer within its largest allocation.
    pub(crate) fn slab_budget(&self, options: &Options) -> Budget {
        Budget {
            bytes: options.slab_bytes.unwrap_or(self.info.memory / 2),
            max_alloc: self.info.max_alloc,
        }
    }

    /// `cells`, or with `MESHVOL_OPENCL_FAULT=alloc` one value more than the device's
    /// largest allocation: the length of a grid's first results buffer.
    pub(crate) fn cells_len(&self, cells: usize) -> usize {
        match fault::asked() {
            Some(Fault::Alloc) => (self.info.max_alloc / 8 + 1) as usize,
            _ => cells,
        }
    }

    /// A device buffer of `len` doubles (at least one: an empty buffer is invalid in
    /// OpenCL) that the kernel writes, `what` naming it in an error.
    pub(crate) fn scratch(&self, len: usize, what: &'static str) -> Result<Buffer<f64>, Error> {
        // SAFETY: no host pointer; the device allocates `len` doubles.
        unsafe {
            Buffer::<f64>::create(&self.context, CL_MEM_READ_WRITE, len.max(1), ptr::null_mut())
        }
        .map_err(|e| call(&self.info.name, what, e))
    }

    /// The triangles of `work` on the device, checked against its largest allocation.
    pub(crate) fn triangles(&self, work: &TileWork) -> Result<Buffer<f64>, Error> {
        let name = &self.info.name;
        self.fits("the triangles", work.triangles.len() * 9, 8)?;
        // An empty buffer is invalid in OpenCL: an unused entry stands in for none.
        let triangles: &[f64] = match work.triangles.is_empty() {
            true => &[0.0; 9],
            false => work.triangles.as_flattened(),
        };
        input(&self.context, triangles, name, "clCreateBuffer (triangles)")
    }

    /// A clear refusal of a buffer over the device's largest allocation, instead of a
    /// driver's error code.
    pub(crate) fn fits(&self, what: &'static str, len: usize, size: usize) -> Result<(), Error> {
        let bytes = len as u128 * size as u128;
        if bytes > self.info.max_alloc as u128 {
            return Err(Error::TooLarge {
                device: self.info.name.clone(),
                what,
                bytes,
                limit: self.info.max_alloc,
            });
        }
        Ok(())
    }

    /// One slab: its tile lists uploaded, one work item a tile, its cells read into `out`.
    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        kernel: &Kernel,
        work: &TileWork,
        triangles: &Buffer<f64>,
        results: &Results,
        work_group: Option<usize>,
        out: &mut [f64],
        progress: &dyn Progress,
    ) -> Result<(), Error> {
        let name = &self.info.name;
        let named = |call_name| on(name, call_name);
        let (offsets, entries) = self.tile_lists(work)?;
        let scalars = scalars(work);
        let set = |result: Result<(), ClError>| result.map_err(named("clSetKernelArg"));
        // SAFETY: each argument has the type and order of `tile_volumes`' parameters.
        unsafe {
            set(kernel.set_arg(0, &triangles.get()))?;
            set(kernel.set_arg(1, &offsets.get()))?;
            set(kernel.set_arg(2, &entries.get()))?;
            set(kernel.set_arg(3, &results.cells.get()))?;
            set(kernel.set_arg(4, &results.areas.get()))?;
            for (k, value) in scalars.iter().enumerate() {
                set(kernel.set_arg(5 + k as u32, value))?;
            }
            let scale: cl_double = work.scale;
            set(kernel.set_arg(17, &scale))?;
        }
        self.launch(kernel, work.tiles(), work_group, progress)?;
        progress.stage("OpenCL: reading back");
        // SAFETY: `out` is the slab's cells, no more than the buffer holds; the read
        // blocks until done.
        unsafe { self.queue.enqueue_read_buffer(&results.cells, CL_BLOCKING, 0, out, &[]) }
            .map_err(named("clEnqueueReadBuffer (cells)"))?;
        Ok(())
    }
}

impl Device {
    /// The tile lists of `work` on the device: where each tile's entries start, and the
    /// triangles they name.
    pub(crate) fn tile_lists(&self, work: &TileWork) -> Result<TileLists, Error> {
        let name = &self.info.name;
        self.fits("the tiles' triangle lists", work.entries.len(), 4)?;
        // An empty buffer is invalid in OpenCL: an unused entry stands in for none.
        let entries: &[u32] = match work.entries.is_empty() {
            true => &[0],
            false => &work.entries,
        };
        let offsets = input(&self.context, &work.offsets, name, "clCreateBuffer (tile offsets)")?;
        let entries = input(&self.context, entries, name, "clCreateBuffer (tile triangles)")?;
        Ok((offsets, entries))
    }

    /// Runs `kernel` (its arguments set), one work item a tile, `work_group` items a
    /// group (`None`: the driver's choice), and waits for it.
    pub(crate) fn launch(
        &self,
        kernel: &Kernel,
        tiles: usize,
        work_group: Option<usize>,
        progress: &dyn Progress,
    ) -> Result<(), Error> {
        let named = |call_name| on(&self.info.name, call_name);
        let global = match work_group {
            Some(g) => tiles.div_ceil(g.max(1)) * g.max(1),
            None => tiles,
        };
        let local = work_group.map(|g| [g.max(1)]);
        progress.stage("OpenCL: the kernel");
        // SAFETY: the arguments are set; the sizes are one-dimensional.
        unsafe {
            self.queue.enqueue_nd_range_kernel(
                kernel.get(),
                1,
                ptr::null(),
                [global].as_ptr(),
                local.as_ref().map_or(ptr::null(), |l| l.as_ptr()),
                &[],
            )
        }
        .map_err(named("clEnqueueNDRangeKernel"))?;
        // Waited for here, not in the read, so that the kernel's time is its own stage.
        self.queue.finish().map_err(named("clFinish"))
    }
}

/// A slab's tile lists on the device: where each tile's entries start, the triangles.
pub(crate) type TileLists = (Buffer<u64>, Buffer<u32>);

/// The block's shape and the tiling of `work`, the kernels' integer arguments after
/// their buffers: tiles, columns per tile, columns; the grid's counts; the block's first
/// x and y cell, its width; its depth, its first layer, the area sums a column.
pub(crate) fn scalars(work: &TileWork) -> [cl_ulong; 12] {
    let u = |x: usize| x as cl_ulong;
    let [nx, ny, nz] = work.counts;
    [
        u(work.tiles()),
        u(work.per_tile),
        u(work.columns()),
        u(nx),
        u(ny),
        u(nz),
        u(work.start[0]),
        u(work.start[1]),
        u(work.shape[1]),
        u(work.shape[2]),
        u(work.start[2]),
        u(work.areas),
    ]
}

/// Turns an OpenCL error code into an error naming the device and the call.
pub(crate) fn on<'a>(device: &'a str, call_name: &'static str) -> impl Fn(ClError) -> Error + 'a {
    move |e| call(device, call_name, e)
}

/// A read-only device buffer holding a copy of `data` (not empty).
pub(crate) fn input<T>(
    context: &Context,
    data: &[T],
    device: &str,
    what: &'static str,
) -> Result<Buffer<T>, Error> {
    // SAFETY: `data` is `data.len()` initialised elements that outlive the call, and
    // COPY_HOST_PTR copies them during it; the device never writes them.
    unsafe {
        Buffer::<T>::create(
            context,
            CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
            data.len(),
            data.as_ptr() as *mut std::ffi::c_void,
        )
    }
    .map_err(on(device, what))
}
