#!/usr/bin/env python3
"""Reference volumes for the shared corpus, from trimesh.

Writes crates/meshvol-io/tests/data/corpus-trimesh.json: for every mesh file under the
corpus (STL, OBJ, OFF, PLY, 3MF, glTF, GLB; zip archives are not read), trimesh's
signed volume, whether trimesh finds the mesh watertight and consistently wound, its
face count, or the error trimesh gave; and trimesh's version.
crates/meshvol-io/tests/corpus.rs compares meshvol's volume with it for the closed
meshes (watertight and consistently wound).

    scripts/corpus-reference.py [--python PYTHON] [--corpus DIR] [--out FILE]

Without --python, a virtual environment is made under target/corpus-reference-venv and
trimesh, numpy, networkx, lxml, pillow and scipy are installed into it with pip
(trimesh's 3MF reader needs networkx and lxml; without pillow and scipy it fails on
textured files and some PLYs). With --python, that interpreter (which must have them)
is used as it is.
"""

import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXTENSIONS = {".stl", ".obj", ".off", ".ply", ".3mf", ".gltf", ".glb"}
PACKAGES = ["trimesh", "numpy", "networkx", "lxml", "pillow", "scipy"]


def venv_python():
    """The venv's interpreter, made and provisioned on first use."""
    venv = os.path.join(ROOT, "target", "corpus-reference-venv")
    python = os.path.join(venv, "bin", "python")
    if not os.path.exists(python):
        subprocess.run([sys.executable, "-m", "venv", venv], check=True)
        subprocess.run([python, "-m", "pip", "install", "--quiet", *PACKAGES], check=True)
    return python


def mesh_files(corpus):
    out = []
    for directory, _, names in os.walk(corpus):
        for name in names:
            if os.path.splitext(name)[1].lower() in EXTENSIONS:
                out.append(os.path.relpath(os.path.join(directory, name), corpus))
    return sorted(out)


def measure(corpus, out):
    import trimesh

    results = {}
    for rel in mesh_files(corpus):
        path = os.path.join(corpus, rel)
        try:
            # Scenes (3MF, glTF) are flattened with their transforms applied.
            mesh = trimesh.load(path, force="mesh")
            if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
                results[rel] = {"faces": 0, "watertight": False, "winding_consistent": False, "volume": None}
                continue
            results[rel] = {
                "faces": int(len(mesh.faces)),
                "watertight": bool(mesh.is_watertight),
                "winding_consistent": bool(mesh.is_winding_consistent),
                "volume": float(mesh.volume),
            }
        except Exception as e:  # noqa: BLE001 - every failure is recorded, not fatal
            results[rel] = {"error": f"{type(e).__name__}: {e}"[:200]}
    document = {
        "generator": "scripts/corpus-reference.py",
        "trimesh_version": trimesh.__version__,
        "files": results,
    }
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out, "w") as f:
        json.dump(document, f, indent=1, sort_keys=True)
        f.write("\n")
    closed = sum(1 for r in results.values() if r.get("watertight") and r.get("winding_consistent"))
    print(f"{len(results)} files, {closed} watertight and consistently wound, written to {out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--python", help="an interpreter that has trimesh (no venv is made)")
    parser.add_argument("--corpus", default=os.path.join(ROOT, "..", "shared", "corpus"))
    parser.add_argument(
        "--out", default=os.path.join(ROOT, "crates", "meshvol-io", "tests", "data", "corpus-trimesh.json")
    )
    parser.add_argument("--measure", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if not os.path.isdir(args.corpus):
        sys.exit(f"no corpus at {args.corpus}")
    if args.measure:
        measure(os.path.abspath(args.corpus), os.path.abspath(args.out))
        return
    python = args.python or venv_python()
    subprocess.run(
        [python, os.path.abspath(__file__), "--measure", "--corpus", args.corpus, "--out", args.out],
        check=True,
    )


if __name__ == "__main__":
    main()
