"""Test solids built with NumPy alone, each with closed-form properties to compare with."""

import numpy as np

# Box corners are numbered x + 2y + 4z; each quad is counter-clockwise seen from outside.
BOX_QUADS = np.array(
    [
        [0, 2, 3, 1],  # z = 0, normal -z
        [4, 5, 7, 6],  # z = 1, normal +z
        [0, 1, 5, 4],  # y = 0, normal -y
        [2, 6, 7, 3],  # y = 1, normal +y
        [0, 4, 6, 2],  # x = 0, normal -x
        [1, 3, 7, 5],  # x = 1, normal +x
    ]
)

# Each quad (a, b, c, d) as the triangles (a, b, c) and (a, c, d).
BOX_TRIANGLES = np.concatenate([BOX_QUADS[:, [0, 1, 2]], BOX_QUADS[:, [0, 2, 3]]])

# The unit cube as OpenSCAD's polyhedron() wants it (clockwise seen from outside): the
# signed volume is -1.
OPENSCAD_CUBE_POINTS = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
    dtype=float,
)
OPENSCAD_CUBE_FACES = np.array(
    [
        [0, 1, 2], [0, 2, 3], [4, 6, 5], [4, 7, 6], [0, 5, 1], [0, 4, 5],
        [1, 6, 2], [1, 5, 6], [2, 7, 3], [2, 6, 7], [3, 4, 0], [3, 7, 4],
    ]
)

# A tetrahedron over corners 0..3 with outward faces.
TETRA_FACES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def box_vertices(lo=(0.0, 0.0, 0.0), hi=(1.0, 1.0, 1.0)):
    """The 8 corners of the box [lo, hi], numbered x + 2y + 4z."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    unit = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float)
    return lo + unit * (hi - lo)


def box(lo=(0.0, 0.0, 0.0), hi=(1.0, 1.0, 1.0)):
    """The box [lo, hi] as (vertices, outward triangles)."""
    return box_vertices(lo, hi), BOX_TRIANGLES.copy()


def box_inertia(size, density=1.0):
    """The inertia tensor of a solid box of the given edge lengths about its centroid."""
    a, b, c = size
    mass = density * a * b * c
    return np.diag([b * b + c * c, a * a + c * c, a * a + b * b]) * mass / 12.0


def uv_sphere(radius=1.0, rings=32, segments=64, centre=(0.0, 0.0, 0.0)):
    """A closed, outward UV sphere: poles, rings - 1 latitude circles of `segments`
    points, 2 * segments * (rings - 1) triangles."""
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
    vertices = np.vstack([[0.0, 0.0, 1.0], circle, [0.0, 0.0, -1.0]]) * radius + centre
    j = np.arange(segments)
    after = (j + 1) % segments
    south = 1 + (rings - 1) * segments
    faces = [np.stack([np.zeros(segments, dtype=np.int64), 1 + j, 1 + after], axis=1)]
    for ring in range(rings - 2):
        upper, lower = 1 + ring * segments, 1 + (ring + 1) * segments
        faces.append(np.stack([upper + j, lower + j, lower + after], axis=1))
        faces.append(np.stack([upper + j, lower + after, upper + after], axis=1))
    last = 1 + (rings - 2) * segments
    faces.append(np.stack([last + j, np.full(segments, south), last + after], axis=1))
    return vertices, np.concatenate(faces)


def sphere_volume(radius):
    return 4.0 / 3.0 * np.pi * radius**3
