"""Minimal numpy readers for the peers' worker scripts: a binary STL as an indexed mesh.

manifold3d takes (vertices, triangles) with shared vertices; this welds the STL's float32
corners by exact equality (as trimesh.load does), with one np.unique over 12-byte rows.
"""
import numpy as np

STL_DTYPE = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])


def read_stl_binary_indexed(path):
    """(vertices float32 (V, 3), faces uint32 (F, 3)) of a binary STL, corners welded."""
    with open(path, "rb") as fh:
        fh.seek(80)
        n = int(np.frombuffer(fh.read(4), "<u4")[0])
        rec = np.frombuffer(fh.read(n * 50), dtype=STL_DTYPE, count=n)
    corners = np.ascontiguousarray(rec["v"].reshape(-1, 3))
    rows = corners.view(np.dtype((np.void, 12))).ravel()
    _, first, inverse = np.unique(rows, return_index=True, return_inverse=True)
    return corners[first], inverse.reshape(-1, 3).astype(np.uint32)
