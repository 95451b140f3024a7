//! Grids as Zarr v3, written chunk by chunk: a grid that does not fit in memory goes to
//! disk one slab of chunks (a *chunk row*: the chunks that share their x cells) at a
//! time.
//!
//! Each array of the cells (through the `zarrs` crate, filesystem store): float64,
//! regular chunks, the `bytes` codec (little-endian, no compression), fill value 0, chunk
//! keys `c/I/J/K`. What a Zarr array or group written at the same path before left there
//! (its chunks, its member arrays) is erased first. Chunks whose every value is +0.0 are
//! not stored (readers return the fill value), which leaves
//! the empty space around a solid off the disk; a chunk holding -0.0 is stored, so that
//! every value reads back as the same bits. Edge chunks are stored whole, padded with
//! zeros, as Zarr's regular grid has them.
//!
//! Either output is a group (attributes `origin` and `cell_size`: f64 numbers that read
//! back to the same bits) that `xarray.open_zarr` opens as one Dataset, named as
//! Python's `Grid.to_xarray()` and `CutCells.to_xarray()` name theirs: the coordinate
//! arrays `x`, `y`, `z` (the cells' centres, `origin + (i + 0.5) · cell_size`, one chunk
//! each), and, beside arrays on the faces, `x_face`, `y_face`, `z_face` (the faces'
//! planes, `origin + i · cell_size`); the members' metadata consolidated into the
//! group's `zarr.json` (`consolidated_metadata`, as zarr-python's
//! `consolidate_metadata` writes it), so that readers find every array in one read.
//!
//! - [`ZarrCells`]: one array of the cells, named after its values (`volume`, `fraction`
//!   or `mass`: [`CellValues`], also the group's attribute `values`), shape
//!   `(nx, ny, nz)`, dimension names `x`, `y`, `z`.
//! - [`ZarrGroup`]: named arrays over the cells ([`CellArray`]: the cut-cell geometry),
//!   named as in the `.npz`: chunks of the cells' chunk shape, and whole along the axes
//!   after the third (a vector's `component`; a tensor's `row` and `column`: the
//!   dimension names of `CutCells.to_xarray()`). An array on the faces across an axis
//!   has one more layer along it (`NX + 1` for the x faces), named `x_face`, `y_face` or
//!   `z_face`; the chunk row that ends the grid writes the far x faces.

use super::{CellArray, CellValues};
use meshvol::grid::Grid;
use rayon::prelude::*;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use zarrs::array::codec::CodecOptions;
use zarrs::array::{Array, ArrayBuilder, DataType};
use zarrs::filesystem::FilesystemStore;
use zarrs::group::GroupBuilder;
use zarrs::storage::{StorePrefix, WritableStorageTraits};

/// Chunks along each axis of a grid's cells, and the chunk rows they make.
#[derive(Clone, Copy)]
struct Rows {
    counts: [usize; 3],
    chunks: [usize; 3],
}

impl Rows {
    fn new(grid: &Grid, chunks: [usize; 3]) -> io::Result<Rows> {
        if (0..3).any(|a| chunks[a] == 0 || chunks[a] > grid.counts[a]) {
            return Err(invalid(format!(
                "chunks {chunks:?} must be between 1 and the grid's {:?}",
                grid.counts
            )));
        }
        Ok(Rows { counts: grid.counts, chunks })
    }

    fn row_cells(&self, row: usize) -> std::ops::Range<usize> {
        let start = row * self.chunks[0];
        start..(start + self.chunks[0]).min(self.counts[0])
    }

    fn rows(&self) -> usize {
        self.counts[0].div_ceil(self.chunks[0])
    }
}

fn failed(e: impl std::fmt::Display) -> io::Error {
    io::Error::other(e.to_string())
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// The filesystem store at `path` (a directory; made if missing).
fn store_at(path: &Path, what: &str) -> io::Result<Arc<FilesystemStore>> {
    if path.is_file() {
        return Err(io::Error::new(
            io::ErrorKind::AlreadyExists,
            format!("is a file: a Zarr {what} is a directory"),
        ));
    }
    std::fs::create_dir_all(path)?;
    let store = Arc::new(FilesystemStore::new(path).map_err(failed)?);
    erase_earlier(path, &store)?;
    Ok(store)
}

/// Erases what a Zarr node written at `path` before left there, so that none of it is
/// read with (or kept on disk beside) the new one: an array's chunks, a group's member
/// nodes (each a folder with its own `zarr.json`). Nothing that is not Zarr's is touched.
fn erase_earlier(path: &Path, store: &FilesystemStore) -> io::Result<()> {
    let node_type = |at: &Path| {
        let bytes = std::fs::read(at.join("zarr.json")).ok()?;
        let meta: serde_json::Value = serde_json::from_slice(&bytes).ok()?;
        meta["node_type"].as_str().map(String::from)
    };
    let erase = |prefix: &str| {
        let prefix = StorePrefix::new(prefix).map_err(failed)?;
        store.erase_prefix(&prefix).map_err(failed)
    };
    match node_type(path).as_deref() {
        Some("array") => erase("c/"),
        Some("group") => {
            for entry in std::fs::read_dir(path)? {
                let entry = entry?;
                let name = entry.file_name();
                match name.to_str() {
                    Some(name) if entry.path().is_dir() && node_type(&entry.path()).is_some() => {
                        erase(&format!("{name}/"))?
                    }
                    _ => {}
                }
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

/// Writes the group's metadata (a group at the store's root, with `attributes`).
fn create_group(store: &Arc<FilesystemStore>, attributes: serde_json::Value) -> io::Result<()> {
    let group = GroupBuilder::new()
        .attributes(attributes.as_object().cloned().unwrap_or_default())
        .build(store.clone(), "/")
        .map_err(failed)?;
    group.store_metadata().map_err(failed)
}

/// Writes the coordinate arrays of `grid` (module docs): `x`, `y`, `z`, and with
/// `faces` `x_face`, `y_face`, `z_face`; returns their names.
fn coordinates(store: &Arc<FilesystemStore>, grid: &Grid, faces: bool) -> io::Result<Vec<String>> {
    let mut names = Vec::new();
    for a in 0..3 {
        let axis = ["x", "y", "z"][a];
        let (origin, cell, n) = (grid.origin[a], grid.cell[a], grid.counts[a]);
        let centres: Vec<f64> = (0..n).map(|i| origin + (i as f64 + 0.5) * cell).collect();
        let mut wanted = vec![(axis.to_string(), centres)];
        if faces {
            let planes = (0..=n).map(|i| origin + i as f64 * cell).collect();
            wanted.push((format!("{axis}_face"), planes));
        }
        for (name, values) in wanted {
            let len = values.len() as u64;
            let array = ArrayBuilder::new(vec![len], vec![len], DataType::Float64, 0.0f64)
                .dimension_names(Some(vec![name.clone()]))
                .build(store.clone(), &format!("/{name}"))
                .map_err(failed)?;
            array.store_metadata().map_err(failed)?;
            array.store_chunk_elements(&[0], &values).map_err(failed)?;
            names.push(name);
        }
    }
    Ok(names)
}

/// Copies the metadata of the group's `members` into the group's `zarr.json`, as
/// `consolidated_metadata` (kind `inline`), the form zarr-python and xarray read.
fn consolidate<'a>(path: &Path, members: impl Iterator<Item = &'a str>) -> io::Result<()> {
    let read = |at: &Path| -> io::Result<serde_json::Value> {
        serde_json::from_slice(&std::fs::read(at.join("zarr.json"))?).map_err(failed)
    };
    let mut root = read(path)?;
    let mut metadata = serde_json::Map::new();
    for name in members {
        metadata.insert(name.to_string(), read(&path.join(name))?);
    }
    root["consolidated_metadata"] = serde_json::json!({
        "kind": "inline",
        "must_understand": false,
        "metadata": metadata,
    });
    let text = serde_json::to_vec_pretty(&root).map_err(failed)?;
    std::fs::write(path.join("zarr.json"), text)
}

/// One float64 array over the cells (or faces) of a grid, chunked along its first three
/// axes and whole along the others.
struct RowArray {
    array: Array<FilesystemStore>,
    shape: Vec<usize>,
    chunks: Vec<usize>,
}

impl RowArray {
    fn create(
        store: Arc<FilesystemStore>,
        at: &str,
        shape: &[usize],
        chunks: [usize; 3],
        dimensions: Vec<String>,
        attributes: serde_json::Value,
    ) -> io::Result<RowArray> {
        let chunks: Vec<usize> =
            (0..shape.len()).map(|a| if a < 3 { chunks[a] } else { shape[a] }).collect();
        let array = ArrayBuilder::new(
            shape.iter().map(|&n| n as u64).collect::<Vec<_>>(),
            chunks.iter().map(|&n| n as u64).collect::<Vec<_>>(),
            DataType::Float64,
            0.0f64,
        )
        .dimension_names(Some(dimensions))
        .attributes(attributes.as_object().cloned().unwrap_or_default())
        .build(store, at)
        .map_err(failed)?;
        array.store_metadata().map_err(failed)?;
        Ok(RowArray { array, shape: shape.to_vec(), chunks })
    }

    /// Writes the chunk rows holding layers `layers` along the first axis (from a chunk
    /// row's start to another's, or to the array's end) from `values` (those layers in C
    /// order, `map` applied to each). Each row's chunks are encoded and written in
    /// parallel.
    fn write_layers(
        &self,
        layers: std::ops::Range<usize>,
        values: &[f64],
        map: impl Fn(f64) -> f64 + Sync,
    ) -> io::Result<()> {
        let (shape, chunks) = (&self.shape, &self.chunks);
        let (ny, nz, cy, cz) = (shape[1], shape[2], chunks[1], chunks[2]);
        // Values per (i, j, k): the components along the last axes, whole in each chunk.
        let inner: usize = shape[3..].iter().product();
        let cx = chunks[0];
        let aligned = layers.start.is_multiple_of(cx)
            && (layers.end.is_multiple_of(cx) || layers.end == shape[0]);
        if !aligned
            || layers.is_empty()
            || layers.end > shape[0]
            || values.len() != layers.len() * ny * nz * inner
        {
            return Err(invalid(format!(
                "{} values for layers {layers:?} of an array of shape {shape:?} in chunks {chunks:?}",
                values.len()
            )));
        }
        let (columns, levels) = (ny.div_ceil(cy), nz.div_ceil(cz));
        // One thread per chunk already: the codec need not split a chunk further.
        let mut options = CodecOptions::default();
        options.set_concurrent_target(1);
        let rows = layers.start / cx..layers.end.div_ceil(cx);
        let chunk_len = cx * cy * cz * inner;
        (0..rows.len() * columns * levels).into_par_iter().try_for_each(|c| {
            let row = rows.start + c / (columns * levels);
            let (bj, bk) = (c / levels % columns, c % levels);
            let (i0, j0, k0) = (row * cx, bj * cy, bk * cz);
            let (i1, j1, k1) = ((i0 + cx).min(shape[0]), (j0 + cy).min(ny), (k0 + cz).min(nz));
            let mut chunk = vec![0.0f64; chunk_len];
            for i in i0..i1 {
                for j in j0..j1 {
                    let from = (((i - layers.start) * ny + j) * nz + k0) * inner;
                    let to = (((i - i0) * cy + j - j0) * cz) * inner;
                    let run = (k1 - k0) * inner;
                    for (out, &v) in chunk[to..to + run].iter_mut().zip(&values[from..from + run]) {
                        *out = map(v);
                    }
                }
            }
            let mut at = vec![row as u64, bj as u64, bk as u64];
            at.resize(shape.len(), 0);
            self.array.store_chunk_elements_opt(&at, &chunk, &options).map_err(failed)
        })
    }
}

/// A Zarr array of a grid's cells, its metadata written, its chunks written by rows.
pub struct ZarrCells {
    array: RowArray,
    rows: Rows,
    /// What is stored of each volume.
    values: CellValues,
    cell: f64,
}

impl ZarrCells {
    /// Creates the array at `path` (a directory; made if missing) for the cells of
    /// `grid` in chunks of `chunks` cells (each at least 1, at most the grid's count on
    /// its axis), and writes its metadata.
    pub fn create(
        path: &Path,
        grid: &Grid,
        chunks: [usize; 3],
        values: CellValues,
    ) -> io::Result<ZarrCells> {
        let rows = Rows::new(grid, chunks)?;
        let store = store_at(path, "group")?;
        let attributes = serde_json::json!({
            "origin": grid.origin,
            "cell_size": grid.cell,
            "values": values.name(),
        });
        create_group(&store, attributes)?;
        let names = ["x", "y", "z"].map(String::from).to_vec();
        let at = format!("/{}", values.name());
        let array = RowArray::create(
            store.clone(),
            &at,
            &grid.counts,
            chunks,
            names,
            serde_json::json!({}),
        )?;
        let members = coordinates(&store, grid, false)?;
        consolidate(path, members.iter().map(String::as_str).chain([values.name()]))?;
        Ok(ZarrCells { array, rows, values, cell: grid.cell_volume() })
    }

    /// Cells along x of chunk row `row`: the rows of cells [`ZarrCells::write_row`] takes.
    pub fn row_cells(&self, row: usize) -> std::ops::Range<usize> {
        self.rows.row_cells(row)
    }

    /// The number of chunk rows.
    pub fn rows(&self) -> usize {
        self.rows.rows()
    }

    /// Writes chunk row `row` from `volumes`: the cells of [`ZarrCells::row_cells`]
    /// along x and every cell along y and z, in C order. The row's chunks are encoded
    /// and written in parallel.
    pub fn write_row(&self, row: usize, volumes: &[f64]) -> io::Result<()> {
        let (values, cell) = (self.values, self.cell);
        self.array.write_layers(self.row_cells(row), volumes, |v| values.of(v, cell))
    }
}

/// A Zarr group of named arrays over a grid's cells ([module docs](self)), written by
/// chunk rows in any order; its arrays are made from the first row written.
pub struct ZarrGroup {
    path: PathBuf,
    grid: Grid,
    store: Arc<FilesystemStore>,
    rows: Rows,
    arrays: Vec<(&'static str, RowArray)>,
}

impl ZarrGroup {
    /// Creates the group at `path` (a directory; made if missing) for the cells of
    /// `grid` in chunks of `chunks` cells (as [`ZarrCells::create`]), and writes its
    /// metadata. What a Zarr array or group written there before left is erased.
    pub fn create(path: &Path, grid: &Grid, chunks: [usize; 3]) -> io::Result<ZarrGroup> {
        let rows = Rows::new(grid, chunks)?;
        let store = store_at(path, "group")?;
        let attributes = serde_json::json!({ "origin": grid.origin, "cell_size": grid.cell });
        create_group(&store, attributes)?;
        Ok(ZarrGroup { path: path.to_path_buf(), grid: *grid, store, rows, arrays: Vec::new() })
    }

    /// Cells along x of chunk row `row`: the cells of the arrays [`ZarrGroup::write_row`]
    /// takes.
    pub fn row_cells(&self, row: usize) -> std::ops::Range<usize> {
        self.rows.row_cells(row)
    }

    /// The number of chunk rows.
    pub fn rows(&self) -> usize {
        self.rows.rows()
    }

    /// Writes chunk row `row` of every array from `arrays`: over the cells of
    /// [`ZarrGroup::row_cells`] along x and every cell along y and z, an array on the x
    /// faces with the faces on both sides of them (the far one is the next row's, and
    /// written here only by the row that ends the grid). The same arrays, in the same
    /// order, every row.
    pub fn write_row(&mut self, row: usize, arrays: &[CellArray]) -> io::Result<()> {
        if row >= self.rows() {
            return Err(invalid(format!("no chunk row {row}: the grid has {}", self.rows())));
        }
        let cells = self.row_cells(row);
        let [nx, ny, nz] = self.rows.counts;
        let mismatch = |a: &CellArray| {
            let extra = a.shape[0].checked_sub(cells.len());
            a.values.len() != a.shape.iter().product::<usize>()
                || extra.is_none_or(|e| e > 1)
                || a.shape[1..3].iter().zip([ny, nz]).any(|(&s, n)| s != n && s != n + 1)
        };
        if let Some(a) = arrays.iter().find(|a| a.shape.len() < 3 || mismatch(a)) {
            return Err(invalid(format!(
                "array {} of shape {:?} is not over the {} × {ny} × {nz} cells of chunk row {row}",
                a.name,
                a.shape,
                cells.len()
            )));
        }
        let counts = [nx, ny, nz];
        if self.arrays.is_empty() {
            for a in arrays {
                let mut shape = a.shape.clone();
                shape[0] += nx - cells.len();
                let mut names: Vec<String> = (0..3)
                    .map(|d| {
                        let axis = ["x", "y", "z"][d];
                        if shape[d] == counts[d] + 1 {
                            format!("{axis}_face")
                        } else {
                            axis.into()
                        }
                    })
                    .collect();
                // As `CutCells.to_xarray()` names them in Python.
                names.extend(match shape.len() {
                    4 => vec!["component".to_string()],
                    5 => vec!["row".to_string(), "column".to_string()],
                    n => (3..n).map(|d| format!("component_{}", d - 2)).collect(),
                });
                let at = format!("/{}", a.name);
                let chunks = self.rows.chunks;
                let array = RowArray::create(
                    self.store.clone(),
                    &at,
                    &shape,
                    chunks,
                    names,
                    serde_json::json!({}),
                )?;
                self.arrays.push((a.name, array));
            }
            let faces = self.arrays.iter().any(|(_, a)| (0..3).any(|d| a.shape[d] != counts[d]));
            let members = coordinates(&self.store, &self.grid, faces)?;
            let arrays = self.arrays.iter().map(|(name, _)| *name);
            consolidate(&self.path, members.iter().map(String::as_str).chain(arrays))?;
        }
        if self.arrays.len() != arrays.len()
            || self.arrays.iter().zip(arrays).any(|((name, _), a)| *name != a.name)
        {
            return Err(invalid(format!("chunk row {row}: not the arrays of the rows before")));
        }
        for ((_, array), a) in self.arrays.iter().zip(arrays) {
            // The row's own layers; the far faces with the row that ends the grid.
            let extra = a.shape[0] - cells.len();
            let layers =
                if cells.end == nx { cells.start..cells.end + extra } else { cells.clone() };
            let per_layer = a.values.len() / a.shape[0].max(1);
            let (written_as, cell) = (a.written_as, a.cell);
            array.write_layers(layers.clone(), &a.values[..layers.len() * per_layer], |v| {
                written_as.of(v, cell)
            })?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use zarrs::array_subset::ArraySubset;

    /// A 5-axis array on the x faces (a 2 × 3 block per face, value = its C-order index
    /// in the whole array), written by rows from the far face down, reads back whole.
    #[test]
    fn face_arrays_of_any_rank_come_back_whole() {
        let dir = tempfile::tempdir().unwrap();
        let grid = Grid::new([0.0; 3], [1.0; 3], [5, 3, 4]).unwrap();
        let [nx, ny, nz] = grid.counts;
        let whole = [nx + 1, ny, nz, 2, 3];
        let per_layer: usize = whole[1..].iter().product();
        let all: Vec<f64> = (0..whole.iter().product::<usize>()).map(|n| n as f64).collect();
        let mut group = ZarrGroup::create(dir.path(), &grid, [2, 2, 3]).unwrap();
        for row in (0..group.rows()).rev() {
            let cells = group.row_cells(row);
            // The row's faces and the one beyond it, as the cut cells of a row hold them.
            let values = &all[cells.start * per_layer..(cells.end + 1) * per_layer];
            let shape = vec![cells.len() + 1, ny, nz, 2, 3];
            let array = CellArray {
                name: "faces",
                shape,
                values,
                written_as: CellValues::Volume,
                cell: 1.0,
            };
            group.write_row(row, &[array]).unwrap();
        }
        let store = Arc::new(FilesystemStore::new(dir.path()).unwrap());
        let array = Array::open(store, "/faces").unwrap();
        let shape: Vec<u64> = whole.iter().map(|&n| n as u64).collect();
        assert_eq!(array.shape(), shape.as_slice());
        let names: Vec<String> = array
            .dimension_names()
            .clone()
            .unwrap()
            .into_iter()
            .map(|n| n.unwrap_or_default())
            .collect();
        assert_eq!(names, ["x_face", "y", "z", "row", "column"]);
        let back: Vec<f64> =
            array.retrieve_array_subset_elements(&ArraySubset::new_with_shape(shape)).unwrap();
        assert_eq!(back, all);
        // Misuse is an error, not a panic: a row past the grid, arrays that change.
        let plain = CellValues::Volume;
        let array = CellArray {
            name: "faces",
            shape: vec![1, ny, nz],
            values: &[],
            written_as: plain,
            cell: 1.0,
        };
        assert!(group.write_row(3, &[array]).is_err());
        let values = vec![0.0; 2 * ny * nz];
        let other = CellArray {
            name: "other",
            shape: vec![2, ny, nz],
            values: &values,
            written_as: plain,
            cell: 1.0,
        };
        assert!(group.write_row(0, &[other]).is_err());
    }
}
