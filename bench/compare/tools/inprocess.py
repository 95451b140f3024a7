"""In-process timing of one peer tool's mass properties on arrays already in memory.

Usage: inprocess.py TOOL KIND TRIANGLES RUNS BUDGET_S
  TOOL: meshvol-py | meshvol-py-mp | trimesh | numpy-stl | manifold3d | open3d | pymeshlab | vtk | trueform | meshlib
  KIND: sphere | torus | ...  (see meshgen.make)

Builds the mesh with meshgen (the same arrays as the files), then times one warm-up and
up to RUNS measured calls: min(RUNS, BUDGET_S // warm-up time) of them; when not even
one fits the budget, the warm-up is reported as the single sample. Whatever the tool must build before it can be asked (a Trimesh, a
numpy-stl Mesh, a manifold3d Mesh) is built outside the timer, fresh for every run, so
no cached result carries over from one run to the next.

Prints one JSON line when the mesh is built ({"ready": ...}), one after the warm-up
({"warmup_s": ...}), so that the harness can cut off a slow warm-up, then the result (or
{"refused": reason} when the tool declines the mesh).
"""

import json
import os
import re
import resource
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

import numpy as np  # noqa: E402

import meshgen  # noqa: E402


def trimesh_case(v, f):
    import trimesh

    def setup():
        return trimesh.Trimesh(vertices=v, faces=f, process=False)

    def measure(mesh):
        mp = mesh.mass_properties
        if hasattr(mp, "volume"):
            return float(mp.volume), mp.center_mass, mp.inertia
        return float(mp["volume"]), mp["center_mass"], mp["inertia"]

    return setup, measure, "trimesh.Trimesh(v, f, process=False) outside the timer; timed: .mass_properties"


def numpystl_case(v, f):
    from stl import mesh as stl_mesh

    tri = v[f].astype(np.float32)

    def setup():
        data = np.zeros(len(tri), dtype=stl_mesh.Mesh.dtype)
        data["vectors"] = tri
        return stl_mesh.Mesh(data)

    def measure(m):
        vol, cog, inertia = m.get_mass_properties()
        return float(vol), cog, inertia

    return setup, measure, "stl.mesh.Mesh(float32 triangles) outside the timer; timed: get_mass_properties()"


def manifold_case(v, f):
    import manifold3d

    vf = np.ascontiguousarray(v, dtype=np.float32)
    ff = np.ascontiguousarray(f, dtype=np.uint32)

    def setup():
        return manifold3d.Mesh(vert_properties=vf, tri_verts=ff)

    def measure(mesh):
        man = manifold3d.Manifold(mesh)
        status = man.status()
        if str(status).split(".")[-1] != "NoError":
            raise RuntimeError(f"manifold3d status {status}")
        vol = float(man.volume())
        man.surface_area()
        return vol, None, None

    return setup, measure, (
        "manifold3d.Mesh(float32 v, uint32 f) outside the timer; timed: Manifold(mesh) + "
        "volume() + surface_area() (it needs its half-edge build; no centroid or inertia)"
    )


def open3d_case(v, f):
    import open3d as o3d

    o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
    vv = o3d.utility.Vector3dVector(np.ascontiguousarray(v, dtype=np.float64))
    ff = o3d.utility.Vector3iVector(np.ascontiguousarray(f, dtype=np.int32))

    def setup():
        return o3d.geometry.TriangleMesh(vv, ff)

    def measure(mesh):
        return float(mesh.get_volume()), None, None

    return setup, measure, (
        "open3d.geometry.TriangleMesh(v, f) outside the timer; timed: get_volume(), which first "
        "checks is_watertight() (edge and vertex manifold, and an all-pairs self-intersection test)"
    )


def pymeshlab_case(v, f):
    import pymeshlab

    vf = np.ascontiguousarray(v, dtype=np.float64)
    ff = np.ascontiguousarray(f, dtype=np.int32)

    def setup():
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(vertex_matrix=vf, face_matrix=ff))
        return ms

    def measure(ms):
        g = ms.get_geometric_measures()
        if "mesh_volume" not in g:
            raise RuntimeError("no mesh_volume from get_geometric_measures (not closed two-manifold)")
        return float(g["mesh_volume"]), g["center_of_mass"], g["inertia_tensor"]

    return setup, measure, (
        "pymeshlab.MeshSet + add_mesh(Mesh(v, f)) outside the timer; timed: get_geometric_measures() "
        "(volume, area, centre of mass, inertia and more)"
    )


def vtk_case(v, f):
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.vtkFiltersCore import vtkMassProperties

    vf = np.ascontiguousarray(v, dtype=np.float64)
    conn = np.ascontiguousarray(f, dtype=np.int64).ravel()
    offsets = np.arange(0, len(conn) + 1, 3, dtype=np.int64)

    def setup():
        pts = vtkPoints()
        pts.SetData(numpy_to_vtk(vf, deep=True))
        cells = vtkCellArray()
        cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
                      numpy_to_vtkIdTypeArray(conn, deep=True))
        poly = vtkPolyData()
        poly.SetPoints(pts)
        poly.SetPolys(cells)
        return poly

    def measure(poly):
        mp = vtkMassProperties()
        mp.SetInputData(poly)
        mp.Update()
        return float(mp.GetVolume()), None, None

    return setup, measure, (
        "vtkPolyData from the numpy arrays outside the timer; timed: vtkMassProperties "
        "(volume and area; no centroid or inertia)"
    )


def meshvol_case(v, f):
    import meshvol

    # The arrays trueform is given (float64 points, int32 faces): the same bytes to read.
    vf = np.ascontiguousarray(v, dtype=np.float64)
    ff = np.ascontiguousarray(f, dtype=np.int32)

    def setup():
        return vf, ff

    def measure(arrays):
        # As wound, like every peer here (none checks the surface first); the default,
        # check=True, would also weld, orient and search for crossings. The arrays are
        # read in place (float64 and int32, C-contiguous): nothing to build first.
        volume, _bound = meshvol.volume(*arrays, check=False)
        return float(volume), None, None

    return setup, measure, (
        "nothing built outside the timer; timed: meshvol.volume(float64 v, int32 f, check=False) "
        "(signed volume and its rounding bound, the arrays read in place; trueform's arrays)"
    )


def meshvol_mp_case(v, f):
    import meshvol

    vf = np.ascontiguousarray(v, dtype=np.float64)
    ff = np.ascontiguousarray(f, dtype=np.int64)

    def setup():
        return meshvol.Mesh(vf, ff)

    def measure(mesh):
        # As wound, like every peer here (none checks the surface first).
        mp = mesh.mass_properties(check=False)
        return float(mp.signed_volume), mp.centroid, mp.inertia

    return setup, measure, (
        "meshvol.Mesh(v, f) (the Python binding, crates/meshvol-py) outside the timer; timed: "
        "mass_properties(check=False) (as `meshvol volume --no-check`: volume, bound, area, "
        "centroid, inertia)"
    )


def trueform_case(v, f):
    import trueform as tf

    vf = np.ascontiguousarray(v, dtype=np.float64)  # trueform takes float32 or float64 points
    ff = np.ascontiguousarray(f, dtype=np.int32)

    def setup():
        return tf.Mesh(ff, vf)

    def measure(mesh):
        return float(tf.signed_volume(mesh)), None, None

    return setup, measure, (
        "trueform.Mesh(f, float64 v) outside the timer; timed: signed_volume(mesh) (no centroid "
        "or inertia)"
    )


def meshlib_case(v, f):
    from meshlib import mrmeshnumpy as mn

    vf = np.ascontiguousarray(v, dtype=np.float32)  # MeshLib's points are float32
    ff = np.ascontiguousarray(f, dtype=np.int32)

    def setup():
        return mn.meshFromFacesVerts(ff, vf)

    def measure(mesh):
        return float(mesh.volume()), None, None

    return setup, measure, (
        "mrmeshnumpy.meshFromFacesVerts(f, float32 v) (its half-edge build) outside the timer; "
        "timed: Mesh.volume() (no centroid or inertia)"
    )


CASES = {"meshvol-py": meshvol_case, "meshvol-py-mp": meshvol_mp_case, "trimesh": trimesh_case, "numpy-stl": numpystl_case, "manifold3d": manifold_case,
         "open3d": open3d_case, "pymeshlab": pymeshlab_case, "vtk": vtk_case,
         "trueform": trueform_case, "meshlib": meshlib_case}


def peak_rss_mb():
    """This process's peak RSS. VmHWM belongs to the address space made at exec, so unlike
    ru_maxrss it does not include the memory of the harness this process was forked from."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def main():
    tool, kind, tris = sys.argv[1], sys.argv[2], int(sys.argv[3])
    runs_max, budget = int(sys.argv[4]), float(sys.argv[5])
    v, f, _ = meshgen.make(kind, tris)
    setup, measure, note = CASES[tool](v, f)
    rss_setup = peak_rss_mb()
    print(json.dumps({"ready": True, "triangles": int(len(f))}), flush=True)

    def once():
        obj = setup()
        t0 = time.perf_counter()
        result = measure(obj)
        t1 = time.perf_counter()
        del obj
        return t1 - t0, result[0]

    try:
        warm, volume = once()
    except RuntimeError as e:
        reason = re.sub(r"\x1b\[[0-9;]*m", "", str(e)).strip()
        reason = re.sub(r"^\[Open3D Error\] \(.*?\) \S+:\d+: ", "", reason)
        print(json.dumps({"refused": reason}), flush=True)
        return
    print(json.dumps({"warmup_s": warm}), flush=True)
    runs = min(runs_max, int(budget // warm)) if warm > 0 else runs_max
    times = [once()[0] for _ in range(runs)] if runs > 0 else [warm]
    print(json.dumps({
        "tool": tool,
        "kind": kind,
        "triangles": int(len(f)),
        "times": times,
        "warmup_s": warm,
        "warmup_is_sample": runs <= 0,
        "volume": volume,
        "peak_rss_mb": peak_rss_mb(),
        "rss_before_timing_mb": rss_setup,
        "note": note,
    }))


if __name__ == "__main__":
    main()
