//! The host side: a device opened with the grid kernel built, the buffers of one grid,
//! one work item a tile, the cells read back.

use crate::devices::{call, devices, DeviceInfo, Listing};
use crate::Error;
use meshvol::grid::{tile_work, Grid, GridError, Region, TileWork};
use meshvol::Surface;
use opencl3::command_queue::CommandQueue;
use opencl3::context::Context;
use opencl3::error_codes::ClError;
use opencl3::kernel::Kernel;
use opencl3::memory::{Buffer, ClMem, CL_MEM_COPY_HOST_PTR, CL_MEM_READ_ONLY, CL_MEM_READ_WRITE};
use opencl3::program::Program;
use opencl3::types::{cl_double, cl_ulong, CL_BLOCKING};
use std::ptr;

const SOURCE: &str = include_str!("grid.cl");

/// How the grid is cut into work: neither changes a bit of the result.
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    /// Columns per work item; `None`: enough tiles for 64 work items per compute unit.
    pub columns_per_item: Option<usize>,
    /// Work items per work group; `None`: the driver's choice.
    pub work_group: Option<usize>,
}

/// An OpenCL device with the grid kernel built for it.
pub struct Device {
    info: DeviceInfo,
    units: usize,
    context: Context,
    queue: CommandQueue,
    kernel: Kernel,
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
        // No -cl-fast-relaxed-math, -cl-mad-enable or -cl-unsafe-math-optimizations: the
        // pragma in the source turns contraction off and IEEE rules hold.
        let program = Program::create_and_build_from_source(&context, SOURCE, "")
            .map_err(|log| Error::Build { device: name.clone(), log })?;
        let kernel = Kernel::create(&program, "tile_volumes").map_err(named("clCreateKernel"))?;
        Ok(Device { info, units: units.max(1), context, queue, kernel })
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
        let columns = region[0].len() * region[1].len();
        let per_item =
            options.columns_per_item.unwrap_or_else(|| columns.div_ceil(64 * self.units)).max(1);
        let work = tile_work(surface, grid, region, per_item)?;
        self.run(&work, options.work_group)
    }

    fn run(&mut self, work: &TileWork, work_group: Option<usize>) -> Result<Vec<f64>, Error> {
        let name = &self.info.name;
        let named = |call_name| on(name, call_name);
        let [nx, ny, nz] = work.counts;
        let depth = work.shape[2];
        let columns = work.columns();
        let cells = columns * depth;
        let tiles = work.tiles();
        // The buffers' sizes, each checked against the device's largest allocation: a
        // clear refusal instead of a driver's error code.
        let fits = |what, len: usize, size: usize| {
            let bytes = len as u128 * size as u128;
            if bytes > self.info.max_alloc as u128 {
                return Err(Error::TooLarge {
                    device: name.clone(),
                    what,
                    bytes,
                    limit: self.info.max_alloc,
                });
            }
            Ok(())
        };
        fits("the cell volumes", cells, 8)?;
        fits("the column area sums", columns * work.areas, 8)?;
        fits("the triangles", work.triangles.len() * 9, 8)?;
        fits("the tiles' triangle lists", work.entries.len(), 4)?;
        // An empty buffer is invalid in OpenCL: an unused entry stands in for none.
        let triangles: &[f64] = match work.triangles.is_empty() {
            true => &[0.0; 9],
            false => work.triangles.as_flattened(),
        };
        let entries: &[u32] = match work.entries.is_empty() {
            true => &[0],
            false => &work.entries,
        };
        let triangles = input(&self.context, triangles, name, "clCreateBuffer (triangles)")?;
        let offsets = input(&self.context, &work.offsets, name, "clCreateBuffer (tile offsets)")?;
        let entries = input(&self.context, entries, name, "clCreateBuffer (tile triangles)")?;
        let scratch = |len: usize, what| {
            // SAFETY: no host pointer; the device allocates `len` doubles.
            unsafe { Buffer::<f64>::create(&self.context, CL_MEM_READ_WRITE, len, ptr::null_mut()) }
                .map_err(|e| call(name, what, e))
        };
        let out = scratch(cells, "clCreateBuffer (cells)")?;
        let areas = scratch(columns * work.areas, "clCreateBuffer (column areas)")?;
        let u = |x: usize| x as cl_ulong;
        let scalars = [
            u(tiles),
            u(work.per_tile),
            u(columns),
            u(nx),
            u(ny),
            u(nz),
            u(work.start[0]),
            u(work.start[1]),
            u(work.shape[1]),
            u(depth),
            u(work.start[2]),
            u(work.areas),
        ];
        let set = |result: Result<(), ClError>| result.map_err(named("clSetKernelArg"));
        // SAFETY: each argument has the type and order of `tile_volumes`' parameters.
        unsafe {
            set(self.kernel.set_arg(0, &triangles.get()))?;
            set(self.kernel.set_arg(1, &offsets.get()))?;
            set(self.kernel.set_arg(2, &entries.get()))?;
            set(self.kernel.set_arg(3, &out.get()))?;
            set(self.kernel.set_arg(4, &areas.get()))?;
            for (k, value) in scalars.iter().enumerate() {
                set(self.kernel.set_arg(5 + k as u32, value))?;
            }
            let scale: cl_double = work.scale;
            set(self.kernel.set_arg(17, &scale))?;
        }
        let global = match work_group {
            Some(g) => tiles.div_ceil(g.max(1)) * g.max(1),
            None => tiles,
        };
        let local = work_group.map(|g| [g.max(1)]);
        // SAFETY: the arguments are set; the sizes are one-dimensional.
        unsafe {
            self.queue.enqueue_nd_range_kernel(
                self.kernel.get(),
                1,
                ptr::null(),
                [global].as_ptr(),
                local.as_ref().map_or(ptr::null(), |l| l.as_ptr()),
                &[],
            )
        }
        .map_err(named("clEnqueueNDRangeKernel"))?;
        let mut volumes = Vec::new();
        let bytes = cells as u128 * 8;
        volumes.try_reserve_exact(cells).map_err(|_| GridError::OutOfMemory { bytes })?;
        volumes.resize(cells, 0.0);
        // SAFETY: `volumes` has the buffer's length; the read blocks until done.
        unsafe { self.queue.enqueue_read_buffer(&out, CL_BLOCKING, 0, &mut volumes, &[]) }
            .map_err(named("clEnqueueReadBuffer (cells)"))?;
        Ok(volumes)
    }
}

/// Turns an OpenCL error code into an error naming the device and the call.
fn on<'a>(device: &'a str, call_name: &'static str) -> impl Fn(ClError) -> Error + 'a {
    move |e| call(device, call_name, e)
}

/// A read-only device buffer holding a copy of `data` (not empty).
fn input<T>(
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
