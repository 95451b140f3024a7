"""Mass properties of one mesh by meshvol and by trimesh, from the same NumPy arrays.

    python crates/meshvol-py/bench.py [TRIANGLES ...]

Needs meshvol (a release build: `pip install ./crates/meshvol-py`) and trimesh. The
mesh is a UV sphere of radius 1 centred at (1000, 2000, 3000) (default 1M and 10M
triangles). Each row times, best of a few runs,

- meshvol: `meshvol.Mesh(v, f).mass_properties()` (copying the arrays in, checking
  them, and measuring),
- trimesh: `trimesh.Trimesh(v, f, process=False).mass_properties`,

and the time of `mass_properties()` alone on a Mesh already built. Both volumes are
compared with the exact volume of the polyhedron the float64 coordinates describe
(meshvol's exact=True: integer-limb arithmetic, rounded once). The sphere sits far from
the origin, as parts in plant or survey coordinates do.
"""

import sys
import time

import numpy as np

import meshvol
import trimesh

CENTRE = np.array([1000.0, 2000.0, 3000.0])


def uv_sphere(triangles):
    """A closed, outward UV sphere of radius 1 around CENTRE with about `triangles`
    triangles (2 * segments * (rings - 1), segments = 2 * rings)."""
    rings = max(3, int(round(np.sqrt(triangles / 4))))
    segments = 2 * rings
    theta = np.linspace(0.0, np.pi, rings + 1)[1:-1]
    phi = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    circle = np.stack(
        [
            np.outer(np.sin(theta), np.cos(phi)),
            np.outer(np.sin(theta), np.sin(phi)),
            np.repeat(np.cos(theta)[:, None], segments, axis=1),
        ],
        axis=-1,
    ).reshape(-1, 3)
    vertices = np.vstack([[0.0, 0.0, 1.0], circle, [0.0, 0.0, -1.0]]) + CENTRE
    j = np.arange(segments)
    after = (j + 1) % segments
    south = 1 + (rings - 1) * segments
    faces = [np.stack([np.zeros(segments, dtype=np.int64), 1 + j, 1 + after], axis=1)]
    upper = 1 + np.arange(rings - 2)[:, None] * segments
    lower = upper + segments
    faces.append(np.stack([upper + j, lower + j, lower + after], axis=-1).reshape(-1, 3))
    faces.append(np.stack([upper + j, lower + after, upper + after], axis=-1).reshape(-1, 3))
    last = 1 + (rings - 2) * segments
    faces.append(np.stack([last + j, np.full(segments, south), last + after], axis=1))
    return vertices, np.concatenate(faces)


def best_time(run, repeats):
    best, result = float("inf"), None
    for _ in range(repeats):
        started = time.perf_counter()
        result = run()
        best = min(best, time.perf_counter() - started)
    return best, result


def main():
    sizes = [int(float(a)) for a in sys.argv[1:]] or [1_000_000, 10_000_000]
    print(f"meshvol {meshvol.__version__}, trimesh {trimesh.__version__}, numpy {np.__version__}")
    print(
        f"{'triangles':>10}  {'meshvol s':>9}  {'(measure)':>9}  {'trimesh s':>9}  "
        f"{'speed-up':>8}  {'meshvol dV/V':>12}  {'trimesh dV/V':>12}"
    )
    for size in sizes:
        vertices, faces = uv_sphere(size)
        repeats = 5 if len(faces) <= 2_000_000 else 2
        ours, mp = best_time(lambda: meshvol.Mesh(vertices, faces).mass_properties(), repeats)
        mesh = meshvol.Mesh(vertices, faces)
        measure, _ = best_time(mesh.mass_properties, repeats)
        theirs, props = best_time(
            lambda: trimesh.Trimesh(vertices, faces, process=False).mass_properties, repeats
        )
        exact = mesh.mass_properties(exact=True).volume
        print(
            f"{len(faces):>10}  {ours:>9.3f}  {measure:>9.3f}  {theirs:>9.3f}  "
            f"{theirs / ours:>7.1f}x  {abs(mp.volume - exact) / exact:>12.1e}  "
            f"{abs(props['volume'] - exact) / exact:>12.1e}"
        )


if __name__ == "__main__":
    main()
