"""The package: docstrings on every public object, type stubs that match, examples that
run."""

import ast
import doctest
import inspect
import shutil
from pathlib import Path

import meshvol
import numpy as np
import pytest
from solids import box

PACKAGE = Path(meshvol.__file__).parent


def public_members(cls):
    return [name for name, _ in inspect.getmembers(cls) if not name.startswith("_")]


def sheet():
    """The unit square rising from z = 0 at y = 0 to z = 1 at y = 1 (a terrain)."""
    vertices = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0]])
    return meshvol.Mesh(vertices, np.array([[0, 1, 2], [0, 2, 3]]))


def samples():
    """One instance of each result class: their attributes are their reports' keys, which
    only instances list (in dir())."""
    mesh = meshvol.Mesh(*box())
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    return {
        "MassProperties": mesh.mass_properties(),
        "Check": mesh.check(),
        "Shell": mesh.check().shell_details[0],
        "Profile": mesh.profile(levels=2),
        "Union": meshvol.union(mesh),
        "Intersection": meshvol.intersection(mesh, mesh),
        "Hull": meshvol.convex_hull(mesh.vertices),
        "AreaProperties": meshvol.polygon_area(square),
        "Below": mesh.below(volume=0.5),
        "Section": mesh.section("z=0.5"),
        "CutFill": meshvol.cutfill(sheet(), level=0.5, cells=(2, 2)),
        "CutCells": mesh.cells(cells=(2, 2, 2)),
    }


def test_everything_public_has_a_docstring():
    missing = []
    for name in meshvol.__all__:
        obj = getattr(meshvol, name)
        if name == "__version__":
            continue
        if not (obj.__doc__ or "").strip():
            missing.append(name)
        if inspect.isclass(obj) and not issubclass(obj, Exception):
            for member in public_members(obj):
                doc = getattr(obj, member).__doc__
                if not (doc or "").strip():
                    missing.append(f"{name}.{member}")
    assert missing == []


# Where the names of meshvol.__all__ are typed: the extension's stubs, and the typed
# Python modules. stubtest (test_typing.py) checks signatures; this, the attributes only
# instances have (a report's keys).
TYPED = ("__init__.pyi", "_meshvol.pyi", "_batch.py", "_errors.py", "_grid.py")


def test_stubs_describe_the_runtime_api():
    body = [node for name in TYPED for node in ast.parse((PACKAGE / name).read_text()).body]
    classes = {node.name: node for node in body if isinstance(node, ast.ClassDef)}
    declared = {
        node.name: node
        for node in body
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)) and node.name in meshvol.__all__
    }

    def items(node):
        """A stub class's items, its stub-only bases' (such as _CheckFacts) included."""
        bases = [classes[b.id] for b in node.bases if isinstance(b, ast.Name) and b.id in classes]
        return [item for base in bases for item in items(base)] + node.body

    assert set(declared) == set(meshvol.__all__) - {"__version__"}
    instances = samples()
    for name, node in declared.items():
        if isinstance(node, ast.ClassDef) and not issubclass(getattr(meshvol, name), Exception):
            in_stub = {
                item.name if isinstance(item, ast.FunctionDef) else item.target.id
                for item in items(node)
                if isinstance(item, (ast.FunctionDef, ast.AnnAssign))
            }
            runtime = public_members(instances.get(name, getattr(meshvol, name)))
            # A dict's own methods (CutCells is a dict of arrays) are the dict's.
            if issubclass(getattr(meshvol, name), dict):
                runtime = [m for m in runtime if m not in dir(dict)]
            dunders = {n for n in in_stub if n.startswith("__")}  # __init__, __array__, ...
            # timings: an attribute only of reports made with timings=True.
            assert set(runtime) - {"timings"} == in_stub - dunders - {"timings"}, name
    assert (PACKAGE / "py.typed").exists()


def test_module_docstring_examples_run():
    failures, tried = doctest.testmod(meshvol)
    assert tried > 0 and failures == 0


ROOT = Path(__file__).resolve().parents[3]
# Every page whose ```python examples are doctests (`>>>` lines and their output). A page
# with a Python example that cannot run here says so beside it and shows it without `>>>`.
DOC_PAGES = ["README.md", *sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "docs").glob("*.md"))]


@pytest.mark.parametrize("page", DOC_PAGES)
def test_docs_examples_run(page, recwarn, tmp_path, monkeypatch):
    # Every `>>>` example in README.md and docs/*.md runs and prints what the page says.
    # They run in a temporary folder holding a copy of samples/ (the files the docs name
    # as samples/NAME); what they write (tetra.obj, cells.zarr) lands there too.
    shutil.copytree(ROOT / "samples", tmp_path / "samples")
    monkeypatch.chdir(tmp_path)
    results = doctest.testfile(
        str(ROOT / page), module_relative=False, optionflags=doctest.NORMALIZE_WHITESPACE
    )
    assert results.failed == 0, results
    if page in ("README.md", "docs/python.md"):
        assert results.attempted > 0, page


def test_docs_python_examples_are_doctests():
    # A ```python block either is a doctest or says, just before it, why it is not run.
    for page in DOC_PAGES:
        text = (ROOT / page).read_text()
        blocks = text.split("```python\n")[1:]
        before = text.split("```python\n")[:-1]
        for prefix, block in zip(before, blocks):
            code = block.split("```")[0]
            if ">>> " not in code:
                assert "Not run by the docs' tests" in prefix[-400:], (page, code[:80])
    assert "python.md" in " ".join(DOC_PAGES)