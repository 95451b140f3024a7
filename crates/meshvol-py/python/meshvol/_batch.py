"""meshvol.measure: many mesh files measured at once, as one pandas DataFrame."""

from __future__ import annotations

import glob
import json
import os
import warnings
from typing import TYPE_CHECKING, Any, Dict, Iterable, List, Optional, Sequence, Union

from ._meshvol import MeshWarning, _measure_files

if TYPE_CHECKING:
    import pandas

__all__ = ["measure", "mesh_files", "MESH_EXTENSIONS"]

#: The extensions a directory or glob is searched for (as meshvol.load reads them).
MESH_EXTENSIONS = (".stl", ".obj", ".off", ".ply", ".3mf", ".gltf", ".glb")

PathArg = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]


def _has_magic(text: str) -> bool:
    return any(c in text for c in "*?[")


def _is_mesh(path: str) -> bool:
    return path.lower().endswith(MESH_EXTENSIONS)


def mesh_files(paths: Union[PathArg, Iterable[PathArg]]) -> List[str]:
    """The files `paths` names, in order: a file as it is; a directory, its mesh files
    (by extension, recursively, sorted); a glob pattern ('*', '?', '[...]'; '**' for
    any depth), the mesh files it matches, sorted. A list is expanded item by item."""
    if isinstance(paths, (str, bytes, os.PathLike)):
        items: Iterable[PathArg] = [paths]
    else:
        items = paths
    found: List[str] = []
    for item in items:
        path = os.fsdecode(os.fspath(item))
        if os.path.isdir(path):
            inside = []
            for root, _dirs, files in os.walk(path):
                inside.extend(os.path.join(root, f) for f in files if _is_mesh(f))
            found.extend(sorted(inside))
        elif not os.path.exists(path) and _has_magic(path):
            found.extend(sorted(p for p in glob.glob(path, recursive=True) if _is_mesh(p) and os.path.isfile(p)))
        else:
            found.append(path)
    return found


def _flatten(report: Dict[str, Any]) -> Dict[str, Any]:
    """pandas.json_normalize's rule (sep='.'): nested dicts become 'a.b' keys, lists stay
    one value. Used without pandas, and by meshvol.dask."""
    flat: Dict[str, Any] = {}

    def walk(prefix: str, value: Dict[str, Any]) -> None:
        for key, v in value.items():
            name = f"{prefix}{key}"
            if isinstance(v, dict) and v:
                walk(name + ".", v)
            else:
                flat[name] = v

    walk("", report)
    return flat


def _reports(files: Sequence[str], workers: Optional[int], check: bool, density: float,
             units: Optional[str], exact: bool) -> List[Dict[str, Any]]:
    lines = _measure_files(list(files), workers, check, density, units, exact)
    return [json.loads(line) for line in lines]


def measure(
    paths: Union[PathArg, Iterable[PathArg]],
    workers: Optional[int] = None,
    check: bool = True,
    density: Union[float, str] = 1.0,
    units: Optional[str] = None,
    exact: bool = False,
) -> "pandas.DataFrame":
    """Measures many mesh files at once: a pandas DataFrame with one row a file, in the
    input's order, whose columns are the keys of `meshvol volume --json` flattened as
    pandas.json_normalize(report, sep='.') flattens them (nested objects become 'a.b'
    columns: 'bounds.min', 'units.volume'; lists stay one cell: 'centroid',
    'shell_details'). A file that cannot be read or measured is a row with its 'file'
    and an 'error' column (the command's message), never an exception.

    paths: a file, a directory (its mesh files, recursively, sorted), a glob pattern
    ('parts/**/*.stl'), or a list of any of these. No files: an empty DataFrame and a
    MeshWarning.
    workers: files measured at once (threads of a rayon pool, the GIL released); None,
    one per core; at most one a file and 8 a core. Each file is read once.
    check, density, units, exact: as Mesh.mass_properties (check=False is `--no-check`).
    The rows' warnings are in the 'warnings' column; none is issued.
    """
    import pandas

    files = mesh_files(paths)
    if not files:
        warnings.warn(f"no mesh files in {paths!r}: the DataFrame is empty", MeshWarning, stacklevel=2)
        return pandas.DataFrame()
    reports = _reports(files, workers, check, density, units, exact)
    return pandas.json_normalize(reports, sep=".")
