"""In-process timing of one peer tool's mass properties on arrays already in memory.

Usage: inprocess.py TOOL KIND TRIANGLES RUNS BUDGET_S
  TOOL: trimesh | numpy-stl | manifold3d;  KIND: sphere | torus | ...  (see meshgen.make)

Builds the mesh with meshgen (the same arrays as the files), then times one warm-up and
up to RUNS measured calls: min(RUNS, BUDGET_S // warm-up time) of them; when not even
one fits the budget, the warm-up is reported as the single sample. Whatever the tool must build before it can be asked (a Trimesh, a
numpy-stl Mesh, a manifold3d Mesh) is built outside the timer, fresh for every run, so
no cached result carries over from one run to the next. Prints one JSON object.
"""

import json
import os
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


CASES = {"trimesh": trimesh_case, "numpy-stl": numpystl_case, "manifold3d": manifold_case}


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

    def once():
        obj = setup()
        t0 = time.perf_counter()
        result = measure(obj)
        t1 = time.perf_counter()
        del obj
        return t1 - t0, result[0]

    warm, volume = once()
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
