//! The OpenCL grid against the CPU kernel (itself tested against closed forms in
//! crates/meshvol/tests/grid.rs and cut_cells.rs): the same bits, cell for cell, on any
//! OpenCL device with f64 (PoCL's CPU device in CI), for several tilings and work-group
//! sizes, and a slab at a time: the cell volumes, and the cut cells (every array
//! `cut_cells` writes). Without an OpenCL library or such a device, each test says it
//! skipped.

#[path = "../../meshvol/tests/common/mod.rs"]
mod common;

use common::{bumpy_sphere, mapped, open_box, rotation, XorShift};
use meshvol::grid::{cell_volumes, cell_volumes_region, cut_cells_region, CutCells, Grid, Region};
use meshvol::shapes::{cuboid, torus, uv_sphere};
use meshvol::{Mesh, Surface};
use meshvol_opencl::{devices, Device, Listing, Options};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The first device with f64, or `None` (said on stderr) where there is none.
fn device() -> Option<Device> {
    let listed = match devices().expect("listing the OpenCL devices") {
        Listing::NoLibrary => {
            eprintln!("skipped: no OpenCL library (libOpenCL.so.1) could be loaded");
            return None;
        }
        Listing::Devices(d) => d,
    };
    let Some(index) = listed.iter().position(|d| d.fp64) else {
        eprintln!("skipped: no OpenCL device with f64 among {}", listed.len());
        return None;
    };
    Some(Device::open(index).expect("opening the OpenCL device"))
}

/// The tilings and work groups each grid runs with: none may change a bit.
const OPTIONS: [Options; 5] = [
    Options { columns_per_item: None, work_group: None, slab_bytes: None },
    Options { columns_per_item: Some(1), work_group: None, slab_bytes: None },
    Options { columns_per_item: Some(1), work_group: Some(1), slab_bytes: None },
    Options { columns_per_item: Some(3), work_group: Some(8), slab_bytes: None },
    Options { columns_per_item: Some(1000), work_group: Some(64), slab_bytes: None },
];

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// `surface` on `region` of `grid` (the whole grid with `None`) is the CPU's bits.
fn same_bits<S: Surface + ?Sized>(
    device: &mut Device,
    what: &str,
    surface: &S,
    grid: &Grid,
    region: Option<Region>,
) {
    let cpu = match &region {
        Some(r) => cell_volumes_region(surface, grid, r).unwrap(),
        None => cell_volumes(surface, grid).unwrap(),
    };
    assert!(cpu.iter().any(|&v| v != 0.0), "{what}: the grid misses the solid");
    for options in OPTIONS {
        let gpu = match &region {
            Some(r) => device.cell_volumes_region(surface, grid, r, options).unwrap(),
            None => device.cell_volumes(surface, grid, options).unwrap(),
        };
        assert_eq!(gpu.len(), cpu.len(), "{what}, {options:?}");
        if bits(&gpu) != bits(&cpu) {
            let k = (0..cpu.len()).find(|&k| gpu[k].to_bits() != cpu[k].to_bits()).unwrap();
            panic!(
                "{what}, {options:?}: cell {k} is {:e} on OpenCL, {:e} on the CPU",
                gpu[k], cpu[k]
            );
        }
    }
}

fn around(mesh: &Mesh, counts: [usize; 3], margin: f64) -> Grid {
    let b = meshvol::mass_properties(mesh).bounds.unwrap();
    Grid::from_bounds(b.min.map(|x| x - margin), b.max.map(|x| x + margin), counts).unwrap()
}

#[test]
fn spheres_and_tori_match_the_cpu() {
    let Some(mut device) = device() else { return };
    let sphere = uv_sphere(1.0, 48, 25);
    same_bits(&mut device, "sphere 17×23×19", &sphere, &around(&sphere, [17, 23, 19], 0.05), None);
    same_bits(&mut device, "sphere 1×1×1", &sphere, &around(&sphere, [1, 1, 1], 0.0), None);
    same_bits(&mut device, "sphere 40×3×29", &sphere, &around(&sphere, [40, 3, 29], 0.1), None);
    let mut rng = XorShift::new(50);
    let r = rotation(&mut rng);
    let turned = mapped(&torus(2.0, 0.7, 40, 18), |p| {
        [0, 1, 2].map(|a| r[a][0] * p[0] + r[a][1] * p[1] + r[a][2] * p[2] + 0.3)
    });
    same_bits(
        &mut device,
        "turned torus 31×27×13",
        &turned,
        &around(&turned, [31, 27, 13], 0.2),
        None,
    );
    let bumpy = bumpy_sphere(&[1.0, 0.7, 1.3, 0.9], 2.0, [0.1, -0.2, 0.3]);
    same_bits(
        &mut device,
        "bumpy sphere 12×12×12",
        &bumpy,
        &around(&bumpy, [12, 12, 12], 0.0),
        None,
    );
}

#[test]
fn faces_on_grid_planes_polygons_and_inward_surfaces_match_the_cpu() {
    let Some(mut device) = device() else { return };
    // Every face on a plane of the grid: the degenerate and horizontal pieces.
    let cube = cuboid([1.0, 1.0, 1.0], [3.0, 4.0, 2.0]);
    let grid = Grid::new([0.0; 3], [1.0; 3], [5, 5, 5]).unwrap();
    same_bits(&mut device, "box on grid planes", &cube, &grid, None);
    // Polygon faces (fans of several triangles each), and an inward-wound surface.
    same_bits(&mut device, "box, quads", &cuboid([0.3, 0.2, 0.1], [2.7, 3.9, 4.4]), &grid, None);
    let sphere = uv_sphere(2.0, 20, 11);
    let inward = Mesh::from_polygons(
        sphere.positions().to_vec(),
        (0..sphere.face_count())
            .map(|f| sphere.face(f).iter().rev().copied().collect::<Vec<_>>())
            .collect::<Vec<_>>()
            .iter()
            .map(|f| &f[..]),
    )
    .unwrap();
    same_bits(&mut device, "inward sphere", &inward, &around(&inward, [9, 10, 11], 0.3), None);
}

#[test]
fn open_and_dirty_surfaces_match_the_cpu() {
    let Some(mut device) = device() else { return };
    let open = open_box([0.2, 0.1, 0.3], [2.9, 1.7, 2.2]);
    same_bits(&mut device, "open box", &open, &around(&open, [7, 6, 9], 0.4), None);
    // A sphere with faces missing, some doubled and some degenerate, vertices jittered.
    let sphere = uv_sphere(1.5, 30, 16).triangulated();
    let mut rng = XorShift::new(7);
    let positions: Vec<_> =
        sphere.positions().iter().map(|p| p.map(|x| x + 0.02 * (rng.unit() - 0.5))).collect();
    let mut triangles = Vec::new();
    for f in 0..sphere.face_count() {
        let t = sphere.face(f);
        match f % 11 {
            0 => {}
            3 => triangles.extend([[t[0], t[1], t[2]]; 2]),
            5 => triangles.push([t[0], t[0], t[1]]),
            _ => triangles.push([t[0], t[1], t[2]]),
        }
    }
    let dirty = Mesh::from_triangles(positions, triangles).unwrap();
    same_bits(&mut device, "dirty sphere", &dirty, &around(&dirty, [13, 11, 15], 0.1), None);
}

#[test]
fn bounds_partly_outside_and_blocks_match_the_cpu() {
    let Some(mut device) = device() else { return };
    let sphere = uv_sphere(1.0, 36, 19);
    // The grid covers part of the sphere: the rest is above, below and beside it.
    let grid = Grid::from_bounds([-0.4, -1.3, -0.55], [1.3, 0.6, 0.45], [11, 9, 7]).unwrap();
    same_bits(&mut device, "bounds partly outside", &sphere, &grid, None);
    let grid = around(&sphere, [14, 15, 16], 0.1);
    same_bits(&mut device, "block", &sphere, &grid, Some([3..9, 0..15, 5..11]));
    same_bits(&mut device, "one column", &sphere, &grid, Some([7..8, 7..8, 0..16]));
}

/// `surface` on `region` of `grid` a slab of `rows` x layers at a time (the budget of
/// exactly that many layers, and of that many and most of one more): the CPU's bits, in
/// as many slabs as the region has runs of `rows` layers.
fn in_slabs<S: Surface + ?Sized>(
    device: &mut Device,
    what: &str,
    surface: &S,
    grid: &Grid,
    region: Region,
    rows: usize,
) {
    let cpu = cell_volumes_region(surface, grid, &region).unwrap();
    assert!(cpu.iter().any(|&v| v != 0.0), "{what}: the grid misses the solid");
    // A slab's device bytes: its cells, and the area sums of each column from the
    // region's first layer to above the grid's top.
    let [x, y, z] = region.clone();
    let layer = (y.len() * (z.len() + grid.counts[2] + 1 - z.start) * 8) as u64;
    for budget in [rows as u64 * layer, (rows as u64 + 1) * layer - 1] {
        let laid_out = AtomicUsize::new(0);
        let count = |stage: &'static str| {
            if stage.starts_with("laying out") {
                laid_out.fetch_add(1, Ordering::Relaxed);
            }
        };
        let options =
            Options { columns_per_item: Some(2), work_group: None, slab_bytes: Some(budget) };
        let gpu = device.cell_volumes_region_with(surface, grid, &region, options, &count).unwrap();
        assert_eq!(laid_out.into_inner(), x.len().div_ceil(rows), "{what}: slabs of {rows}");
        if bits(&gpu) != bits(&cpu) {
            let k = (0..cpu.len()).find(|&k| gpu[k].to_bits() != cpu[k].to_bits()).unwrap();
            panic!("{what}, slabs of {rows}: cell {k} is {:e}, {:e} on the CPU", gpu[k], cpu[k]);
        }
    }
}

#[test]
fn slabs_match_the_cpu() {
    let Some(mut device) = device() else { return };
    let sphere = uv_sphere(1.0, 40, 21);
    let grid = around(&sphere, [17, 23, 19], 0.05);
    let whole = grid.counts.map(|n| 0..n);
    // Slabs of one layer, of a few that do not divide 17 (the last slab shorter), and of
    // more than the grid: every boundary cuts through the sphere.
    for rows in [1, 2, 5, 16, 40] {
        in_slabs(&mut device, "sphere", &sphere, &grid, whole.clone(), rows);
    }
    // A block of the grid in slabs: its own first layer, and columns not from y = 0.
    in_slabs(&mut device, "block", &sphere, &grid, [3..14, 4..20, 6..13], 3);
    // A box over x cells 2..8 of 10 in slabs of 5: the mesh spans exactly one slab
    // boundary (x = 5); in slabs of 2, its x faces lie on slab boundaries (x = 2, 8).
    let cube = cuboid([2.0, 0.5, 0.25], [8.0, 3.5, 2.75]);
    let grid = Grid::new([0.0; 3], [1.0; 3], [10, 4, 3]).unwrap();
    in_slabs(&mut device, "box across x = 5", &cube, &grid, [0..10, 0..4, 0..3], 5);
    in_slabs(&mut device, "box on slab planes", &cube, &grid, [0..10, 0..4, 0..3], 2);
    // A turned torus, its triangles crossing many slabs each.
    let mut rng = XorShift::new(51);
    let r = rotation(&mut rng);
    let turned = mapped(&torus(2.0, 0.7, 30, 14), |p| {
        [0, 1, 2].map(|a| r[a][0] * p[0] + r[a][1] * p[1] + r[a][2] * p[2])
    });
    let grid = around(&turned, [21, 9, 12], 0.1);
    in_slabs(&mut device, "turned torus", &turned, &grid, grid.counts.map(|n| 0..n), 4);
}

#[test]
fn a_layer_over_the_slab_budget_is_refused_naming_the_device() {
    let Some(mut device) = device() else { return };
    let sphere = uv_sphere(1.0, 16, 9);
    let grid = around(&sphere, [6, 7, 8], 0.1);
    let layer = (7 * (8 + 8 + 1) * 8) as u64;
    let options = Options { slab_bytes: Some(layer - 1), ..Options::default() };
    let e = device.cell_volumes(&sphere, &grid, options).unwrap_err().to_string();
    assert!(e.contains(device.name()) && e.contains(&layer.to_string()), "{e}");
    // An empty region is the CPU's error, not an empty result.
    let e = device.cell_volumes_region(&sphere, &grid, &[2..2, 0..7, 0..8], options);
    let cpu = cell_volumes_region(&sphere, &grid, &[2..2, 0..7, 0..8]).unwrap_err();
    assert_eq!(e.unwrap_err().to_string(), cpu.to_string());
}

/// Every array of `cells`, named, as bits.
fn cut_bits(cells: &CutCells) -> Vec<(&'static str, Vec<u64>)> {
    let points = |p: &[[f64; 3]]| bits(p.as_flattened());
    vec![
        ("volume", bits(&cells.volume)),
        ("centroid", points(&cells.centroid)),
        ("boundary_area", bits(&cells.boundary_area)),
        ("boundary_vector", points(&cells.boundary_vector)),
        ("boundary_centroid", points(&cells.boundary_centroid)),
        ("aperture_x", bits(&cells.aperture[0])),
        ("aperture_y", bits(&cells.aperture[1])),
        ("aperture_z", bits(&cells.aperture[2])),
    ]
}

/// The cut cells of `surface` on `region` of `grid` (the whole grid with `None`) on the
/// device with each of `options` are the CPU's, array for array and bit for bit.
fn same_cut_cells<S: Surface + ?Sized>(
    device: &mut Device,
    what: &str,
    surface: &S,
    grid: &Grid,
    region: Option<Region>,
    options: &[Options],
) {
    let region = region.unwrap_or_else(|| grid.counts.map(|n| 0..n));
    let cpu = cut_cells_region(surface, grid, &region).unwrap();
    assert!(cpu.volume.iter().any(|&v| v != 0.0), "{what}: the grid misses the solid");
    assert!(cpu.boundary_area.iter().any(|&v| v != 0.0), "{what}: no surface in the grid");
    let want = cut_bits(&cpu);
    for &options in options {
        let gpu = device.cut_cells_region_with(surface, grid, &region, options, &()).unwrap();
        assert_eq!((&gpu.grid, &gpu.region), (&cpu.grid, &cpu.region), "{what}, {options:?}");
        for ((name, got), (_, want)) in cut_bits(&gpu).iter().zip(&want) {
            assert_eq!(got.len(), want.len(), "{what}, {options:?}: {name}");
            if let Some(k) = (0..want.len()).find(|&k| got[k] != want[k]) {
                let [g, w] = [got[k], want[k]].map(f64::from_bits);
                panic!("{what}, {options:?}: {name}[{k}] is {g:e} on OpenCL, {w:e} on the CPU");
            }
        }
    }
}

#[test]
fn cut_cells_of_solids_match_the_cpu() {
    let Some(mut device) = device() else { return };
    let sphere = uv_sphere(1.0, 32, 17);
    let grid = around(&sphere, [13, 11, 12], 0.05);
    same_cut_cells(&mut device, "sphere", &sphere, &grid, None, &OPTIONS);
    // Triangles (an indexed mesh: no polygon normals), and a block of the grid.
    let triangles = sphere.triangulated();
    same_cut_cells(&mut device, "sphere, triangles", &triangles, &grid, None, &OPTIONS[..2]);
    same_cut_cells(&mut device, "block", &sphere, &grid, Some([3..9, 2..11, 4..9]), &OPTIONS[3..]);
    // Every face on a plane of the grid, and a box filling the grid: its faces on the
    // far faces (the top one a part lying on the grid's top plane).
    let cube = cuboid([1.0, 1.0, 1.0], [3.0, 4.0, 2.0]);
    let grid = Grid::new([0.0; 3], [1.0; 3], [5, 5, 5]).unwrap();
    same_cut_cells(&mut device, "box on grid planes", &cube, &grid, None, &OPTIONS);
    let grid = Grid::new([1.0; 3], [0.5; 3], [4, 6, 2]).unwrap();
    same_cut_cells(&mut device, "box filling the grid", &cube, &grid, None, &OPTIONS[..3]);
    let mut rng = XorShift::new(52);
    let r = rotation(&mut rng);
    let turned = mapped(&torus(2.0, 0.7, 30, 14), |p| {
        [0, 1, 2].map(|a| r[a][0] * p[0] + r[a][1] * p[1] + r[a][2] * p[2] + 0.3)
    });
    let grid = around(&turned, [19, 17, 11], 0.2);
    same_cut_cells(&mut device, "turned torus", &turned, &grid, None, &OPTIONS[2..4]);
    // The grid over part of the sphere: parts above, below and beside it.
    let grid = Grid::from_bounds([-0.4, -1.3, -0.55], [1.3, 0.6, 0.45], [9, 8, 7]).unwrap();
    same_cut_cells(&mut device, "bounds partly outside", &sphere, &grid, None, &OPTIONS[..2]);
}

#[test]
fn cut_cells_of_open_and_inward_surfaces_match_the_cpu() {
    let Some(mut device) = device() else { return };
    // An open surface, as `--no-check` measures it: the box without its top.
    let open = open_box([0.2, 0.1, 0.3], [2.9, 1.7, 2.2]);
    same_cut_cells(&mut device, "open box", &open, &around(&open, [7, 6, 9], 0.4), None, &OPTIONS);
    let sphere = uv_sphere(2.0, 20, 11);
    let inward = Mesh::from_polygons(
        sphere.positions().to_vec(),
        (0..sphere.face_count())
            .map(|f| sphere.face(f).iter().rev().copied().collect::<Vec<_>>())
            .collect::<Vec<_>>()
            .iter()
            .map(|f| &f[..]),
    )
    .unwrap();
    let grid = around(&inward, [9, 10, 11], 0.3);
    same_cut_cells(&mut device, "inward sphere", &inward, &grid, None, &OPTIONS[1..3]);
}

#[test]
fn cut_cells_in_slabs_match_the_cpu() {
    let Some(mut device) = device() else { return };
    // A slab's device bytes: per column, 12 values a cell and one more, and three sums a
    // layer from the region's first to above the grid's top, and one more.
    let budget = |grid: &Grid, [_, y, z]: &Region, rows: usize| {
        let areas = grid.counts[2] + 1 - z.start;
        let column = 12 * z.len() + 1 + 3 * areas + 1;
        (rows * y.len() * column * 8) as u64
    };
    let slabs = |rows: usize, grid: &Grid, region: &Region| {
        let bytes = budget(grid, region, rows);
        [bytes, bytes + budget(grid, region, 1) - 1].map(|slab_bytes| Options {
            columns_per_item: Some(2),
            work_group: None,
            slab_bytes: Some(slab_bytes),
        })
    };
    let sphere = uv_sphere(1.0, 24, 13);
    let grid = around(&sphere, [11, 9, 10], 0.05);
    let whole = grid.counts.map(|n| 0..n);
    for rows in [1, 4, 16] {
        let options = slabs(rows, &grid, &whole);
        same_cut_cells(
            &mut device,
            &format!("sphere, slabs of {rows}"),
            &sphere,
            &grid,
            None,
            &options,
        );
        // As many slabs as the budget says (one tile layout each).
        let laid_out = AtomicUsize::new(0);
        let count = |stage: &'static str| {
            if stage.starts_with("laying out") {
                laid_out.fetch_add(1, Ordering::Relaxed);
            }
        };
        device.cut_cells_region_with(&sphere, &grid, &whole, options[1], &count).unwrap();
        assert_eq!(laid_out.into_inner(), 11usize.div_ceil(rows), "slabs of {rows}");
    }
    // A block in slabs: the region reaching the far faces is what the device sweeps.
    let block = [2..6, 3..9, 2..8];
    let reach = [2..11, 3..9, 2..8];
    let options = slabs(3, &grid, &reach);
    same_cut_cells(&mut device, "block in slabs", &sphere, &grid, Some(block), &options);
    // A box over x cells 2..8 of 10, in slabs of 2: its x faces on slab boundaries.
    let cube = cuboid([2.0, 0.5, 0.25], [8.0, 3.5, 2.75]);
    let grid = Grid::new([0.0; 3], [1.0; 3], [10, 4, 3]).unwrap();
    let options = slabs(2, &grid, &grid.counts.map(|n| 0..n));
    same_cut_cells(&mut device, "box on slab planes", &cube, &grid, None, &options);
}
