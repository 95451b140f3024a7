"""Grids beyond one machine: the cell volumes of Mesh.grid as a Dask array, each chunk
computed by a worker, exactly.

A block of the column-clamp grid is independent of the others once its columns get the
areas of the surface above it, and Mesh.grid(region=...) computes a block that way:
bit for bit the same cells as the whole grid. So

>>> import meshvol.dask                                         # doctest: +SKIP
>>> cells = meshvol.dask.grid("part.stl", cells=(1024, 1024, 1024), chunks=(128, 128, -1))
>>> cells.to_zarr("part-cells.zarr")                            # written chunk by chunk

computes the same array as load("part.stl").grid(cells=(1024, 1024, 1024)) on any
scheduler: threads, processes, or a dask.distributed cluster. The grid's bounds are
fixed once, on the client, so every chunk belongs to the same grid.

Needs the `dask` extra: pip install "meshvol[dask]" (dask[array,dataframe,distributed], zarr).

Many files, one table: meshvol.dask.measure("parts/**/*.stl") is meshvol.measure over a
cluster, a dask DataFrame with one row a file (each file read once, by one worker),
ready for .to_parquet(); meshvol.dask.measure(folder) computes the rows of
`meshvol volume -r folder --json`, in the same order.

There is no meshvol.dask.union: the union's cells are refined until the gap summed over
the whole grid is below a tolerance, a budget shared by every cell, so its blocks are
not independent (see docs/distributed.md).
"""

from __future__ import annotations

import functools
import os
import warnings
from typing import (
    TYPE_CHECKING,
    Any,
    Dict,
    Iterable,
    List,
    Literal,
    Optional,
    Sequence,
    Tuple,
    Union,
    overload,
)

import dask
import dask.array as da
import numpy as np

from . import Mesh, MeshError, MeshWarning, load
from ._batch import GlobArg, PathArg, _inputs, _reports

if TYPE_CHECKING:
    import dask.dataframe as dd
    import pandas

__all__ = ["grid", "measure"]

Bounds = Tuple[Sequence[float], Sequence[float]]
Backend = Literal["auto", "cpu", "opencl"]


@functools.lru_cache(maxsize=4)
def _load(path: str, mtime_ns: int, size: int) -> Mesh:
    """The mesh in `path`, read once per worker process and kept (keyed by the file's
    modification time and size as the client saw them, so a changed file is read again)."""
    return load(path)


def _mesh_at(path: str, stamp: Tuple[int, int]) -> Mesh:
    """The mesh in `path` if the file is the one the client planned the grid with."""
    info = os.stat(path)
    if (info.st_mtime_ns, info.st_size) != stamp:
        raise MeshError(f"{path}: the file changed after the grid was planned; plan it again")
    return _load(path, *stamp)


def _block(
    source: Union[Mesh, Tuple[str, Tuple[int, int]]],
    cells: Tuple[int, int, int],
    bounds: Tuple[Tuple[float, ...], Tuple[float, ...]],
    fraction: bool,
    check: bool,
    region: Tuple[Tuple[int, int], ...],
    backend: Backend = "auto",
) -> np.ndarray:
    """One chunk, on a worker (on its OpenCL device with backend='opencl' or 'auto')."""
    mesh = source if isinstance(source, Mesh) else _mesh_at(*source)
    with warnings.catch_warnings():
        # The client issued the mesh's warnings once, when it fixed the bounds.
        warnings.simplefilter("ignore", MeshWarning)
        block = mesh.grid(cells=cells, bounds=bounds, fraction=fraction, check=check, region=region, backend=backend)
        return block.values


def _cut_block(
    source: Union[Mesh, Tuple[str, Tuple[int, int]]],
    cells: Tuple[int, int, int],
    bounds: Tuple[Tuple[float, ...], Tuple[float, ...]],
    check: bool,
    region: Tuple[Tuple[int, int], ...],
    extras: Tuple[bool, bool],
    backend: Backend = "auto",
) -> Dict[str, np.ndarray]:
    """One chunk of the cut cells, on a worker (on its OpenCL device with
    backend='opencl' or 'auto'); each face array cut to the faces the chunk owns (its low
    faces, and its high faces where it ends the grid)."""
    mesh = source if isinstance(source, Mesh) else _mesh_at(*source)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        block = mesh.cells(cells=cells, bounds=bounds, check=check, region=region,
                           second_moments=extras[0], face_centroids=extras[1], backend=backend)
    arrays = dict(block)
    for name in arrays:
        a = _face_axis(name)
        if a is not None and region[a][1] < cells[a]:
            keep = [slice(None)] * 3
            keep[a] = slice(0, -1)
            arrays[name] = arrays[name][tuple(keep)]
    return arrays


def _face_axis(name: str) -> Optional[int]:
    """The axis of a face array (aperture_x, aperture_x_centroid, ...), else None."""
    if not name.startswith("aperture_"):
        return None
    return "xyz".index(name[len("aperture_")])


# The trailing axes of each cut-cell array beyond its cells or faces.
_TRAILING = {"centroid": (3,), "boundary_vector": (3,), "boundary_centroid": (3,),
             "inertia": (3, 3), "aperture_x_centroid": (3,), "aperture_y_centroid": (3,),
             "aperture_z_centroid": (3,)}


def _moments(
    where: Any,
    counts: Tuple[int, int, int],
    fixed: Tuple[Tuple[float, ...], Tuple[float, ...]],
    check: bool,
    chunks: Tuple[Tuple[int, ...], ...],
    extras: Tuple[bool, bool],
    backend: Backend,
) -> Dict[str, da.Array]:
    """The cut cells as a dict of lazy arrays, each chunk computed once by _cut_block."""
    source_key = dask.delayed(where, pure=True, traverse=False)
    block = dask.delayed(_cut_block, pure=True)
    starts = [np.cumsum((0,) + c)[:-1].tolist() for c in chunks]
    names = ["volume", "fraction", "centroid", "boundary_area", "boundary_vector",
             "boundary_centroid", "aperture_x", "aperture_y", "aperture_z"]
    if extras[0]:
        names.append("inertia")
    if extras[1]:
        names += ["aperture_x_centroid", "aperture_y_centroid", "aperture_z_centroid"]
    nested: Dict[str, List[Any]] = {name: [] for name in names}
    for i0, bx in zip(starts[0], chunks[0]):
        planes: Dict[str, List[Any]] = {name: [] for name in names}
        for j0, by in zip(starts[1], chunks[1]):
            lines: Dict[str, List[Any]] = {name: [] for name in names}
            for k0, bz in zip(starts[2], chunks[2]):
                region = ((i0, i0 + bx), (j0, j0 + by), (k0, k0 + bz))
                arrays = block(source_key, counts, fixed, check, region, extras, backend)
                for name in names:
                    shape: Tuple[int, ...] = (bx, by, bz)
                    a = _face_axis(name)
                    if a is not None:
                        end = region[a][1] == counts[a]
                        shape = tuple(n + (1 if d == a and end else 0) for d, n in enumerate(shape))
                    shape = shape + _TRAILING.get(name, ())
                    part: Any = da.from_delayed(arrays[name], shape, dtype=np.float64)
                    # da.block nests as deep as the arrays: one more list a trailing axis.
                    for _ in shape[3:]:
                        part = [part]
                    lines[name].append(part)
            for name in names:
                planes[name].append(lines[name])
        for name in names:
            nested[name].append(planes[name])
    return {name: da.block(nested[name]) for name in names}


@overload
def grid(
    source: Union[str, "os.PathLike[str]", Mesh],
    cells: Tuple[int, int, int],
    bounds: Optional[Bounds] = ...,
    chunks: Union[str, int, Sequence] = ...,
    check: bool = ...,
    fraction: bool = ...,
    moments: Literal[False] = ...,
    *,
    backend: Backend = ...,
) -> da.Array: ...


@overload
def grid(
    source: Union[str, "os.PathLike[str]", Mesh],
    cells: Tuple[int, int, int],
    bounds: Optional[Bounds] = ...,
    chunks: Union[str, int, Sequence] = ...,
    check: bool = ...,
    fraction: bool = ...,
    *,
    moments: Literal[True],
    second_moments: bool = ...,
    face_centroids: bool = ...,
    backend: Backend = ...,
) -> Dict[str, da.Array]: ...


def grid(
    source: Union[str, "os.PathLike[str]", Mesh],
    cells: Tuple[int, int, int],
    bounds: Optional[Bounds] = None,
    chunks: Union[str, int, Sequence] = ("auto", "auto", -1),
    check: bool = True,
    fraction: bool = False,
    moments: bool = False,
    second_moments: bool = False,
    face_centroids: bool = False,
    *,
    backend: Backend = "auto",
) -> Union[da.Array, Dict[str, da.Array]]:
    """The volume of the solid in each cell of a grid as a lazy (nx, ny, nz) float64
    dask.array: Mesh.grid(cells, bounds, fraction=fraction, check=check), bit for bit,
    computed chunk by chunk with Mesh.grid(region=...).

    moments=True: the cut-cell geometry instead, Mesh.cells(cells, bounds, check=check)
    bit for bit, as a dict of lazy arrays with Mesh.cells's names and shapes (the
    apertures have one more face along their axis), each chunk computed once by
    Mesh.cells(region=...). A chunk's x and y apertures sum the surface from the grid's
    far faces, so a chunk costs the cells from it to those faces: split x and y in few
    chunks. second_moments=True and face_centroids=True (with moments=True) add the arrays
    Mesh.cells adds for them (inertia; aperture_x_centroid, ...), bit for bit too.

    source: a mesh file's path (each worker reads it once and keeps it; the file must be
    at that path on every worker, as on shared storage) or a Mesh (sent to each worker
    once, as its arrays).
    bounds: the grid's box ((x0, y0, z0), (x1, y1, z1)); by default the solid's bounding
    box, as Mesh.grid's, found here on the client (reading the file once) so that every
    chunk belongs to one grid.
    chunks: as dask.array takes them. The default spans the whole height, since a chunk
    cuts its columns' faces through every layer anyway (the layers above it hand their
    areas down): chunks split along z repeat that work.
    backend: as Mesh.grid's ('auto', 'cpu', 'opencl'), on each worker: the same bits;
    with moments=True as Mesh.cells' (second_moments and face_centroids on the CPU only:
    'opencl' is refused for them).
    """
    if backend not in ("auto", "cpu", "opencl"):
        raise ValueError(f"backend '{backend}': one of cpu, opencl, auto")
    counts = tuple(int(n) for n in cells)
    if len(counts) != 3 or min(counts) < 1:
        raise ValueError(f"cells must be three positive whole numbers; got {cells}")
    if isinstance(source, Mesh):
        mesh: Optional[Mesh] = source
        where: Union[Mesh, Tuple[str, Tuple[int, int]]] = source
    else:
        path = os.fspath(source)
        info = os.stat(path)
        stamp = (info.st_mtime_ns, info.st_size)
        mesh = _load(path, *stamp) if bounds is None else None
        where = (path, stamp)
    box: Any = bounds
    if box is None:
        assert mesh is not None
        # The measured solid's box: the bounds Mesh.grid takes by default.
        box = mesh.mass_properties(check=check).bounds
        if box is None:
            raise MeshError("no vertices: there is no surface to measure")
    fixed = (tuple(map(float, box[0])), tuple(map(float, box[1])))
    blocks: Tuple[Tuple[int, ...], ...] = da.core.normalize_chunks(chunks, counts, dtype=np.float64)
    if (second_moments or face_centroids) and not moments:
        raise ValueError("second_moments and face_centroids are cut-cell arrays: give moments=True")
    if moments:
        if fraction:
            raise ValueError("moments=True gives fraction among its arrays: leave fraction=False")
        if backend == "opencl" and (second_moments or face_centroids):
            raise ValueError("second_moments and face_centroids run on the CPU only: leave backend='auto' or give 'cpu'")
        return _moments(where, counts, fixed, check, blocks, (second_moments, face_centroids), backend)

    # One graph key holds the mesh (or its path): each worker receives it once.
    source_key = dask.delayed(where, pure=True, traverse=False)
    block = dask.delayed(_block, pure=True)
    starts = [np.cumsum((0,) + c)[:-1].tolist() for c in blocks]
    rows = []
    for i0, bx in zip(starts[0], blocks[0]):
        plane = []
        for j0, by in zip(starts[1], blocks[1]):
            line = []
            for k0, bz in zip(starts[2], blocks[2]):
                region = ((i0, i0 + bx), (j0, j0 + by), (k0, k0 + bz))
                values = block(source_key, counts, fixed, fraction, check, region, backend)
                line.append(da.from_delayed(values, (bx, by, bz), dtype=np.float64))
            plane.append(line)
        rows.append(plane)
    return da.block(rows)


# The optional keys (None in the sample report) whose values are text.
_TEXT = {"file", "format", "format_source", "density_unit", "mass_unit", "units.file_declared",
         "orientation", "winding", "error"}


def _schema(check: bool, density: Union[float, str], units: Optional[str], exact: bool,
            timings: bool) -> "pandas.DataFrame":
    """The columns of meshvol.measure's frame for these options, as an empty frame with
    one dtype per column: a report of a tetrahedron (with units, so that the units'
    columns exist; with timings, 'timings'), flattened, plus 'objects' (files with named
    parts) and 'error'.
    Integers are Int64 and booleans boolean (nullable: a failed file has neither)."""
    import pandas

    tetra = Mesh([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sample = tetra.mass_properties(density=density, check=check, units=units or "m", exact=exact,
                                      timings=timings).to_dict()
    flat = pandas.json_normalize([sample], sep=".").iloc[0].to_dict()
    columns: Dict[str, Any] = {}
    for key, value in flat.items():
        if key == "units":
            continue
        columns[key] = value
        if key == "warnings" and "objects" not in flat:
            columns["objects"] = None
    columns["error"] = None
    dtypes: Dict[str, Any] = {}
    for key, value in columns.items():
        if isinstance(value, (bool, np.bool_)):
            dtypes[key] = "boolean"
        elif isinstance(value, (int, np.integer)):
            dtypes[key] = "Int64"
        elif isinstance(value, (float, np.floating)) or (value is None and key not in _TEXT and key != "objects"):
            dtypes[key] = "float64"
        else:
            dtypes[key] = "object"
    return pandas.DataFrame({k: pandas.Series([], dtype=t) for k, t in dtypes.items()})


def _measure_partition(
    files: List[str],
    meta: "pandas.DataFrame",
    threads: Optional[int],
    check: bool,
    density: float,
    units: Optional[str],
    exact: bool,
    timings: bool,
    failed: Sequence[Dict[str, Any]] = (),
) -> "pandas.DataFrame":
    """One partition, on a worker: meshvol.measure's rows (the `failed` rows of the
    directories and patterns that gave no file first), in meta's columns and dtypes."""
    import pandas

    rows = list(failed) + (_reports(files, threads, check, density, units, exact, timings) if files else [])
    if not rows:
        return meta
    frame = pandas.json_normalize(rows, sep=".")
    frame = frame.reindex(columns=meta.columns)
    return frame.astype(meta.dtypes.to_dict())


def measure(
    paths_or_glob: Union[PathArg, Iterable[PathArg]],
    files_per_partition: int = 1000,
    threads: Optional[int] = None,
    check: bool = True,
    density: Union[float, str] = 1.0,
    units: Optional[str] = None,
    exact: bool = False,
    *,
    recursive: bool = True,
    glob: GlobArg = None,
    timings: bool = False,
) -> "dd.DataFrame":
    """meshvol.measure as a lazy dask DataFrame: one row a file, in the order of the
    files found, each partition `files_per_partition` files measured by one task (one
    worker reads each file once, its files in parallel on `threads` threads; None, one
    per core of the worker). Write it with .to_parquet(path), or filter it
    (df[df.closed & (df.volume > 1)]) before .compute(). Computed, it holds
    meshvol.measure's rows for the same arguments: for a folder, those of
    `meshvol volume -r folder --json`, in the same order.

    paths_or_glob, recursive, glob: as meshvol.measure (files, directories, glob
    patterns; the command's walk), expanded here on the client: the files must be at
    the same paths on every worker (shared storage). A directory or pattern that gives
    no mesh file is a row with an 'error', in the first partition, as in
    meshvol.measure. The columns are meshvol.measure's for these options, fixed
    whatever the files hold: the volume report's keys flattened ('bounds.min',
    'units.volume', ...), 'objects' and 'error'; counts are Int64 and facts boolean
    (nullable, for failed files). timings=True adds meshvol.measure's 'timings' column
    (each file's stages, timed on the worker that measured it; as the other list
    columns, text under dask's default `dataframe.convert-string`, which lets
    to_parquet infer one schema). An empty list: an empty frame and a MeshWarning.
    """
    import dask.dataframe as ddf
    import pandas

    if files_per_partition < 1:
        raise ValueError(f"files_per_partition must be at least 1; got {files_per_partition}")
    files, failed = _inputs(paths_or_glob, recursive, glob)
    meta = _schema(check, density, units, exact, timings)
    if not files and not failed:
        warnings.warn(f"no mesh files in {paths_or_glob!r}: the DataFrame is empty", MeshWarning, stacklevel=2)
        return ddf.from_pandas(meta, npartitions=1)
    chunks = [files[i : i + files_per_partition] for i in range(0, len(files), files_per_partition)] or [[]]
    frames = [
        dask.delayed(_measure_partition, pure=True)(
            chunk, meta, threads, check, density, units, exact, timings, failed if k == 0 else []
        )
        for k, chunk in enumerate(chunks)
    ]
    return ddf.from_delayed(frames, meta=meta, verify_meta=False)
