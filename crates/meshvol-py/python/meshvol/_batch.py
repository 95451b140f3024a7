"""meshvol.measure: many mesh files measured at once, as one pandas DataFrame.

The paths are expanded by the command's own walk (meshvol_io's, through
_meshvol._expand): meshvol.measure(folder) returns exactly the rows that
`meshvol volume -r folder --json` prints, in the same order.
"""

from __future__ import annotations

import json
import os
import warnings
from typing import TYPE_CHECKING, Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

from ._meshvol import MeshWarning, _expand, _measure_files, _mesh_name_endings

if TYPE_CHECKING:
    import pandas

__all__ = ["measure", "mesh_files", "MESH_EXTENSIONS"]

#: The endings of the file names a directory or pattern is searched for, lower case:
#: the command's rule, from the extension module (the formats meshvol.load reads, each
#: also compressed as .gz, .bz2 or .zst, and .zip). A name is read when, lower-cased, it
#: ends with one of them and does not start with '.'.
MESH_EXTENSIONS = tuple(_mesh_name_endings())

PathArg = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]
GlobArg = Union[str, Iterable[str], None]


def _inputs(paths: Union[PathArg, Iterable[PathArg]], recursive: bool,
            glob: GlobArg) -> Tuple[List[str], List[Dict[str, Any]]]:
    """The files to measure, and a row for each directory or pattern that gave none:
    the command's `{"file", "error"}` line for a folder that held no mesh file."""
    if isinstance(paths, (str, bytes, os.PathLike)):
        items: Iterable[PathArg] = [paths]
    else:
        items = paths
    globs = [glob] if isinstance(glob, str) else list(glob or [])
    files, problems = _expand([os.fsdecode(os.fspath(item)) for item in items], recursive, globs)
    return [os.fspath(f) for f in files], [{"file": name, "error": error} for name, error in problems]


def mesh_files(paths: Union[PathArg, Iterable[PathArg]], recursive: bool = True,
               glob: GlobArg = None) -> List[str]:
    """The files `paths` names, in order, as `meshvol volume` reads its arguments (with
    `-r` when recursive, `--glob` for each of glob): a file as it is; a directory, the
    mesh files in it (by extension, any case, compressed forms included: MESH_EXTENSIONS;
    hidden files and folders, .git/ among them, passed over; with recursive, in its
    subfolders too), sorted by path; a path that names nothing but holds '*', '?' or
    '[', a pattern ('*' within a name, '**' any number of folders): the mesh files it
    matches, chosen and sorted as a directory's. glob: a pattern or a list of them that
    a directory's or pattern's files must match (`*.stl`; with a '/', the path below
    the directory; '!' leaves matches out). A list is expanded item by item. A directory
    or pattern that gives no file: a MeshWarning naming it (meshvol.measure gives it a
    row with an 'error')."""
    files, failed = _inputs(paths, recursive, glob)
    for row in failed:
        warnings.warn(row["error"], MeshWarning, stacklevel=2)
    return files


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


def _reports(files: Sequence[str], workers: Optional[int], check: bool, density: Union[float, str],
             units: Optional[str], exact: bool, timings: bool = False) -> List[Dict[str, Any]]:
    lines = _measure_files(list(files), workers, check, density, units, exact, timings)
    return [json.loads(line) for line in lines]


def measure(
    paths: Union[PathArg, Iterable[PathArg]],
    workers: Optional[int] = None,
    check: bool = True,
    density: Union[float, str] = 1.0,
    units: Optional[str] = None,
    exact: bool = False,
    *,
    recursive: bool = True,
    glob: GlobArg = None,
    timings: bool = False,
) -> "pandas.DataFrame":
    """Measures many mesh files at once: a pandas DataFrame with one row a file, whose
    columns are the keys of `meshvol volume --json` flattened as
    pandas.json_normalize(report, sep='.') flattens them (nested objects become 'a.b'
    columns: 'bounds.min', 'units.volume'; lists stay one cell: 'centroid',
    'shell_details'). A file that cannot be read or measured is a row with its 'file'
    and an 'error' column (the command's message), never an exception.

    meshvol.measure(folder) is `meshvol volume -r folder --json`: the same rows, in the
    same order (recursive=False drops the `-r`; glob=['*.stl', '!old*'] is
    `--glob '*.stl' --glob '!old*'`).

    paths: a file, a directory, a glob pattern ('parts/**/*.stl'), or a list of any of
    these, expanded as mesh_files expands them: the command's walk (extensions in any
    case, compressed files included, hidden files and .git/ passed over), files in the
    input's order. A directory or pattern that gives no mesh file is a row with its
    name and an 'error' (the command's failed input), before the files' rows as the
    command prints it. An empty list: an empty DataFrame and a MeshWarning.
    workers: files measured at once (threads of a rayon pool, the GIL released); None,
    one per core; at most one a file and 8 a core. Each file is read once.
    check, density, units, exact: as Mesh.mass_properties (check=False is `--no-check`).
    recursive, glob: the command's -r and --glob, for directories and patterns.
    timings: the command's --timings: a 'timings' column, each file's stages
    (reading, checking and the check's own, measuring) as a list of {stage, wall_s,
    cpu_s, peak_mb} (a failed file's is NaN, as the command's error line has none).
    The rows' warnings are in the 'warnings' column; none is issued.
    """
    import pandas

    files, failed = _inputs(paths, recursive, glob)
    if not files and not failed:
        warnings.warn(f"no mesh files in {paths!r}: the DataFrame is empty", MeshWarning, stacklevel=2)
        return pandas.DataFrame()
    reports = failed + (_reports(files, workers, check, density, units, exact, timings) if files else [])
    return pandas.json_normalize(reports, sep=".")
