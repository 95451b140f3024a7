//! Writers for per-cell grid values: NumPy `.npy`, VTK ImageData `.vti`, `.csv`, and a
//! `.png` picture of one slice.
//!
//! Every writer takes the [`Grid`] and its cell volumes in C order (`[i, j, k]` at
//! `(i·ny + j)·nz + k`, as [`meshvol::grid::cell_volumes`] returns them). Fractions are
//! volume / cell volume.
//!
//! - **`.npy`** (format 1.0): little-endian float64, shape `(nx, ny, nz)`, C order, so
//!   `numpy.load(f)[i, j, k]` is the cell starting at `origin + (i, j, k)·cell`.
//! - **`.vti`** (VTK XML ImageData, version 1.0): `WholeExtent="0 nx 0 ny 0 nz"` (point
//!   extents: the cells are `nx × ny × nz`), `Origin` and `Spacing` written as f64
//!   text that reads back to the same bits, and two `Float64` cell arrays, `volume`
//!   and `fraction`, in VTK's order (x fastest), as raw little-endian appended data with
//!   `UInt64` byte counts: ParaView, VisIt and `vtk` read it.
//! - **`.npz`**, `.vti`'s writer, and the cut-cell geometry as `.npz` or `.vti`: the
//!   `cut_cells` module.
//! - **`.csv`**: `i,j,k,volume,fraction` (and `mass` given a density), one row per non-empty cell (|volume| above
//!   [`OCCUPANCY_TOLERANCE`] of a cell), numbers in shortest round-trip form.
//! - **`.zarr`** (feature `zarr`): a Zarr v3 group (the array, its coordinates)
//!   written chunk by chunk, for grids larger than memory (the `zarr` module).
//! - **`.png`**: one slice of fractions, white (empty) to dark blue (full), red for
//!   negative (inward-wound) fractions, cells drawn to scale with borders where they are
//!   at least 6 pixels wide and high; a colour legend, the slice's coordinate, and the
//!   in-plane axes' names and ranges (layout in `picture.rs`). Image right is the
//!   slice's first in-plane axis (x for a z slice, y for an x slice, x for a y slice)
//!   and up the second. [`png_map`] draws any values the same way, with a title and
//!   legend of the caller's (a map of cut and fill).

mod cut_cells;
mod font;
mod picture;
#[cfg(feature = "zarr")]
pub mod zarr;

use meshvol::grid::{Grid, OCCUPANCY_TOLERANCE};
use std::io::{self, Write};

pub use cut_cells::{cut_cell_arrays, npz, npz_cut_cells, vti, vti_cut_cells, CellArray};
pub use picture::{png, png_map, Legend};

fn check_len(grid: &Grid, volumes: &[f64]) -> io::Result<()> {
    if volumes.len() != grid.cell_count() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} values for a grid of {} cells", volumes.len(), grid.cell_count()),
        ));
    }
    Ok(())
}

/// Writes f64 values as little-endian bytes, in blocks.
fn write_f64s(out: &mut impl Write, mut values: impl Iterator<Item = f64>) -> io::Result<()> {
    // A fixed block filled slot by slot: growing a vector 8 bytes at a time, writing the
    // 2 GB of a 256³ grid's cut cells took 1.1–1.4 s, against 0.95 s this way.
    let mut block = vec![0u8; 1 << 16];
    loop {
        let mut filled = 0;
        for (slot, v) in block.chunks_exact_mut(8).zip(&mut values) {
            slot.copy_from_slice(&v.to_le_bytes());
            filled += 8;
        }
        out.write_all(&block[..filled])?;
        if filled < block.len() {
            return Ok(());
        }
    }
}

/// What a one-array grid file (`.npy`, a `.zarr` array) holds in each cell, from the
/// cell's volume.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CellValues {
    /// The volume.
    Volume,
    /// Volume / cell volume.
    Fraction,
    /// Volume × this density (mass per volume unit of the values): the mass.
    Mass(f64),
}

impl CellValues {
    /// What a one-array file of a grid holds: fractions when asked for, else masses given
    /// a density (mass per volume unit), else volumes.
    pub fn asked(fraction: bool, density: Option<f64>) -> CellValues {
        match (fraction, density) {
            (true, _) => CellValues::Fraction,
            (false, Some(rho)) => CellValues::Mass(rho),
            (false, None) => CellValues::Volume,
        }
    }

    /// The value written for a cell of `volume` in a cell of volume `cell`.
    pub fn of(self, volume: f64, cell: f64) -> f64 {
        match self {
            CellValues::Volume => volume,
            CellValues::Fraction => volume / cell,
            CellValues::Mass(density) => volume * density,
        }
    }

    /// Its name in metadata: `volume`, `fraction` or `mass`.
    pub fn name(self) -> &'static str {
        match self {
            CellValues::Volume => "volume",
            CellValues::Fraction => "fraction",
            CellValues::Mass(_) => "mass",
        }
    }
}

/// A `.npy` file of the cells' `values` (from their volumes).
pub fn npy(
    out: &mut impl Write,
    grid: &Grid,
    volumes: &[f64],
    values: CellValues,
) -> io::Result<()> {
    check_len(grid, volumes)?;
    let cell = grid.cell_volume();
    npy_array(out, &grid.counts, volumes.iter().map(|&v| values.of(v, cell)))
}

/// A `.npy` file of float64 `values` in C order, of shape `shape` (their number must be
/// the product of its sizes).
pub fn npy_array(
    out: &mut impl Write,
    shape: &[usize],
    values: impl ExactSizeIterator<Item = f64>,
) -> io::Result<()> {
    if shape.iter().try_fold(1usize, |n, &k| n.checked_mul(k)) != Some(values.len()) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} values for an array of shape {shape:?}", values.len()),
        ));
    }
    let sizes: Vec<String> = shape.iter().map(|k| format!("{k}, ")).collect();
    let sizes = sizes.concat();
    // A 1-tuple keeps its comma, "(5,)"; longer ones drop the last: "(2, 3)".
    let sizes = if shape.len() == 1 { sizes.trim_end() } else { sizes.trim_end_matches(", ") };
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({sizes}), }}");
    // Magic (6) + version (2) + length (2) + header, padded with spaces to a multiple of
    // 64 bytes and ended by a newline.
    let unpadded = 10 + header.len() + 1;
    header.push_str(&" ".repeat(unpadded.next_multiple_of(64) - unpadded));
    header.push('\n');
    out.write_all(b"\x93NUMPY\x01\x00")?;
    out.write_all(&(header.len() as u16).to_le_bytes())?;
    out.write_all(header.as_bytes())?;
    write_f64s(out, values)
}

/// A named array of a `.vti` file: `values(c, m)` is component `m` of entry `c` (a cell
/// in C order for cell arrays; an index into the field array's own order otherwise).
pub struct VtiArray<'a> {
    pub name: &'a str,
    pub components: usize,
    pub values: &'a dyn Fn(usize, usize) -> f64,
}

/// A side array of a `.vti` file (VTK `FieldData`): `tuples` entries in the order given.
pub struct VtiField<'a> {
    pub array: VtiArray<'a>,
    pub tuples: usize,
}

/// A `.vti` file with the given cell arrays (the first is the active scalars) and
/// field arrays, as raw appended data.
pub fn vti_arrays(
    out: &mut impl Write,
    grid: &Grid,
    cells: &[VtiArray],
    fields: &[VtiField],
) -> io::Result<()> {
    let [nx, ny, nz] = grid.counts;
    let [ox, oy, oz] = grid.origin;
    let [dx, dy, dz] = grid.cell;
    let declare = |a: &VtiArray, tuples: usize, offset: &mut u64| {
        let extra =
            if tuples == 0 { String::new() } else { format!(" NumberOfTuples=\"{tuples}\"") };
        let line = format!(
            "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\"{extra} format=\"appended\" offset=\"{offset}\"/>",
            a.name, a.components
        );
        let tuples = if tuples == 0 { grid.cell_count() } else { tuples };
        *offset += 8 + (tuples * a.components) as u64 * 8;
        line
    };
    let mut offset = 0;
    write!(
        out,
        "<?xml version=\"1.0\"?>\n\
<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n\
  <ImageData WholeExtent=\"0 {nx} 0 {ny} 0 {nz}\" Origin=\"{ox:?} {oy:?} {oz:?}\" Spacing=\"{dx:?} {dy:?} {dz:?}\">\n"
    )?;
    let mut field_lines = Vec::new();
    let mut cell_lines = Vec::new();
    for a in cells {
        cell_lines.push(declare(a, 0, &mut offset));
    }
    for f in fields {
        field_lines.push(declare(&f.array, f.tuples, &mut offset));
    }
    if !fields.is_empty() {
        writeln!(out, "    <FieldData>")?;
        for line in &field_lines {
            writeln!(out, "      {line}")?;
        }
        writeln!(out, "    </FieldData>")?;
    }
    writeln!(out, "    <Piece Extent=\"0 {nx} 0 {ny} 0 {nz}\">")?;
    let scalars = cells.iter().find(|a| a.name == "fraction").or(cells.first());
    writeln!(out, "      <CellData Scalars=\"{}\">", scalars.map_or("", |a| a.name))?;
    for line in &cell_lines {
        writeln!(out, "        {line}")?;
    }
    write!(
        out,
        "      </CellData>\n    </Piece>\n  </ImageData>\n  <AppendedData encoding=\"raw\">\n_"
    )?;
    // VTK orders cells with x fastest: (k·ny + j)·nx + i.
    let vtk_order = || {
        (0..nz).flat_map(move |k| {
            (0..ny).flat_map(move |j| (0..nx).map(move |i| (i * ny + j) * nz + k))
        })
    };
    for a in cells {
        out.write_all(&((grid.cell_count() * a.components) as u64 * 8).to_le_bytes())?;
        let values = vtk_order().flat_map(|c| (0..a.components).map(move |m| (c, m)));
        write_f64s(out, values.map(|(c, m)| (a.values)(c, m)))?;
    }
    for f in fields {
        let a = &f.array;
        out.write_all(&((f.tuples * a.components) as u64 * 8).to_le_bytes())?;
        let values = (0..f.tuples).flat_map(|c| (0..a.components).map(move |m| (c, m)));
        write_f64s(out, values.map(|(c, m)| (a.values)(c, m)))?;
    }
    out.write_all(b"\n  </AppendedData>\n</VTKFile>\n")
}

/// A `.csv` of the non-empty cells, with a `mass` column given a `density` (mass per
/// volume unit); returns how many rows were written.
pub fn csv(
    out: &mut impl Write,
    grid: &Grid,
    volumes: &[f64],
    density: Option<f64>,
) -> io::Result<usize> {
    check_len(grid, volumes)?;
    let [_, ny, nz] = grid.counts;
    let cell = grid.cell_volume();
    let tolerance = OCCUPANCY_TOLERANCE * cell;
    let mass_column = if density.is_some() { ",mass" } else { "" };
    writeln!(out, "i,j,k,volume,fraction{mass_column}")?;
    let mut rows = 0;
    for (c, &v) in volumes.iter().enumerate() {
        if v.abs() > tolerance {
            let (i, j, k) = (c / (ny * nz), c / nz % ny, c % nz);
            write!(out, "{i},{j},{k},{v:?},{:?}", v / cell)?;
            match density {
                Some(rho) => writeln!(out, ",{:?}", v * rho)?,
                None => writeln!(out)?,
            }
            rows += 1;
        }
    }
    Ok(rows)
}

/// A slice of the grid: all cells with index `index` along `axis` (0, 1, 2 for x, y, z).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Slice {
    pub axis: usize,
    pub index: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> Grid {
        Grid::new([0.5, -1.0, 2.0], [0.5, 0.25, 1.0], [2, 3, 4]).unwrap()
    }

    fn values(g: &Grid) -> Vec<f64> {
        (0..g.cell_count()).map(|c| c as f64 / 256.0).collect()
    }

    #[test]
    fn values_are_written_whole_across_blocks() {
        // Around the block's 8,192 values: none lost or repeated at its edges.
        for n in [0, 1, 8191, 8192, 8193, 16384, 20000] {
            let values: Vec<f64> = (0..n).map(|i| i as f64 * 0.5 - 7.0).collect();
            let mut out = Vec::new();
            write_f64s(&mut out, values.iter().copied()).unwrap();
            let back: Vec<f64> =
                out.chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().unwrap())).collect();
            assert_eq!((out.len(), back), (8 * n, values), "{n} values");
        }
    }

    #[test]
    fn npy_header_and_data() {
        let g = grid();
        let mut out = Vec::new();
        npy(&mut out, &g, &values(&g), CellValues::Volume).unwrap();
        assert_eq!(&out[..8], b"\x93NUMPY\x01\x00");
        let header_len = u16::from_le_bytes([out[8], out[9]]) as usize;
        assert_eq!((10 + header_len) % 64, 0);
        let header = std::str::from_utf8(&out[10..10 + header_len]).unwrap();
        assert!(header.contains("'shape': (2, 3, 4)") && header.ends_with('\n'), "{header}");
        let data = &out[10 + header_len..];
        assert_eq!(data.len(), 24 * 8);
        let at = |c: usize| f64::from_le_bytes(data[c * 8..c * 8 + 8].try_into().unwrap());
        assert_eq!(at(g.index([1, 2, 3])), g.index([1, 2, 3]) as f64 / 256.0);
        // Fractions: the cell volume is 0.125.
        let mut out = Vec::new();
        npy(&mut out, &g, &values(&g), CellValues::Fraction).unwrap();
        let data = &out[10 + header_len..];
        assert_eq!(f64::from_le_bytes(data[8..16].try_into().unwrap()), 8.0 / 256.0);
        // Any shape: a 1-tuple keeps its comma, as Python writes it.
        let mut out = Vec::new();
        npy_array(&mut out, &[3], [1.0, 2.0, 3.0].into_iter()).unwrap();
        assert!(String::from_utf8_lossy(&out).contains("'shape': (3,)"));
        assert!(npy_array(&mut Vec::new(), &[2, 2], [1.0].into_iter()).is_err());
    }

    #[test]
    fn csv_rows_for_non_empty_cells() {
        let g = grid();
        let mut v = vec![0.0; 24];
        v[g.index([1, 0, 2])] = 0.0625;
        let mut out = Vec::new();
        assert_eq!(csv(&mut out, &g, &v, None).unwrap(), 1);
        assert_eq!(String::from_utf8(out).unwrap(), "i,j,k,volume,fraction\n1,0,2,0.0625,0.5\n");
        // With a density, the mass: 0.0625 × 8.
        let mut out = Vec::new();
        csv(&mut out, &g, &v, Some(8.0)).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert_eq!(text, "i,j,k,volume,fraction,mass\n1,0,2,0.0625,0.5,0.5\n");
    }

    #[test]
    fn png_is_a_png_and_bad_slices_are_refused() {
        let g = grid();
        let mut out = Vec::new();
        png(&mut out, &g, &values(&g), Slice { axis: 2, index: 1 }).unwrap();
        assert_eq!(&out[..8], b"\x89PNG\r\n\x1a\n");
        let err = png(&mut Vec::new(), &g, &values(&g), Slice { axis: 2, index: 4 }).unwrap_err();
        assert!(err.to_string().contains("z=4 is outside the grid (0 to 3)"), "{err}");
        // A slice wider than 4096 cells is shrunk to fit, not cut off: its plot (every
        // cell full) is 4096 pixels wide, and the legend beside it.
        let wide = Grid::new([0.0; 3], [1.0; 3], [5000, 3, 1]).unwrap();
        let mut out = Vec::new();
        png(&mut out, &wide, &vec![1.0; 15000], Slice { axis: 2, index: 0 }).unwrap();
        let image = picture::tests::Image::decode(&out);
        let plot = image.plot_box();
        assert_eq!(plot.2, 4096, "{plot:?}");
        assert!(image.width > 4096 && image.width < 4096 + 200, "{}", image.width);
        assert_eq!(picture::colour(0.0, false), [255, 255, 255]);
        // A map of values: coloured as fractions of `full`, any title and legend.
        let plan = Grid::new([0.0; 3], [1.0; 3], [2, 1, 1]).unwrap();
        let legend =
            Legend { title: "cut (+) and fill (-)".into(), name: "depth".into(), full: 4.0 };
        let mut out = Vec::new();
        png_map(&mut out, &plan, &[4.0, -2.0], Slice { axis: 2, index: 0 }, &legend).unwrap();
        let image = picture::tests::Image::decode(&out);
        let (x, y, w, h) = image.plot_box();
        assert_eq!(image.at(x + w / 2, y + h / 2), picture::colour(1.0, false));
        assert_eq!(image.at(x + w + w / 2, y + h / 2), picture::colour(-0.5, false));
        assert_eq!(picture::colour(1.0, false), [24, 64, 160]);
    }
}
