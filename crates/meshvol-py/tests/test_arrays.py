"""How arrays go in and out: dtypes, layouts, lists, copies and zero-copy views."""

import numpy as np
import pytest

import meshvol
from solids import BOX_QUADS, OPENSCAD_CUBE_FACES, OPENSCAD_CUBE_POINTS, box


def test_float32_vertices_are_widened_exactly():
    rng = np.random.default_rng(1)
    vertices, faces = box((0.1, 0.2, 0.3), (1.7, 2.9, 3.3))
    vertices32 = (vertices + rng.normal(scale=1e-3, size=vertices.shape)).astype(np.float32)
    mesh = meshvol.Mesh(vertices32, faces)
    assert mesh.vertices.dtype == np.float64
    assert np.array_equal(mesh.vertices, vertices32.astype(np.float64))
    widened = meshvol.Mesh(vertices32.astype(np.float64), faces).mass_properties()
    assert mesh.mass_properties().signed_volume == widened.signed_volume


@pytest.mark.parametrize(
    "dtype", [np.int8, np.uint8, np.int16, np.uint16, np.int32, np.uint32, np.int64, np.uint64]
)
def test_faces_of_any_integer_dtype(dtype):
    vertices, faces = box((0, 0, 0), (2, 3, 4))
    mesh = meshvol.Mesh(vertices, faces.astype(dtype))
    assert mesh.faces.dtype == np.uint32
    assert np.array_equal(mesh.faces, faces)
    assert mesh.mass_properties().volume == 24.0


def test_big_endian_and_integer_arrays_are_converted():
    vertices, faces = box((0, 0, 0), (2, 3, 4))
    mesh = meshvol.Mesh(vertices.astype(">f8"), faces.astype(">i4"))
    assert mesh.mass_properties().volume == 24.0
    # Integer coordinates, as an OpenSCAD cube is usually written.
    cube = meshvol.Mesh(OPENSCAD_CUBE_POINTS.astype(np.int64), OPENSCAD_CUBE_FACES)
    assert cube.mass_properties().signed_volume == -1.0


def test_non_contiguous_arrays_are_read_as_laid_out():
    vertices, faces = box((0, 0, 0), (2, 3, 4))
    fortran = meshvol.Mesh(np.asfortranarray(vertices), np.asfortranarray(faces))
    # Every other row of a doubled array, and reversed rows (negative strides).
    doubled = np.repeat(vertices, 2, axis=0)[::2]
    reversed_rows = vertices[::-1]
    strided_faces = np.repeat(faces, 2, axis=0)[::2]
    assert not doubled.flags.c_contiguous and not strided_faces.flags.c_contiguous
    strided = meshvol.Mesh(doubled, strided_faces)
    flipped_rows = meshvol.Mesh(reversed_rows, 7 - faces)
    for mesh in (fortran, strided, flipped_rows):
        assert mesh.mass_properties().volume == 24.0
    assert np.array_equal(fortran.vertices, vertices)
    assert np.array_equal(flipped_rows.vertices, vertices[::-1])


def test_lists_and_tuples_are_accepted():
    vertices, faces = box((0, 0, 0), (2, 3, 4))
    mesh = meshvol.Mesh([tuple(p) for p in vertices.tolist()], faces.tolist())
    assert mesh.mass_properties().volume == 24.0
    assert mesh.is_triangle_mesh


def test_polygons_of_mixed_sizes():
    vertices, triangles = box((0, 0, 0), (2, 3, 4))
    # The bottom quad as one face, the other five as triangle pairs.
    polygons = [BOX_QUADS[0].tolist()] + triangles[[1, 2, 3, 4, 5, 7, 8, 9, 10, 11]].tolist()
    mesh = meshvol.Mesh(vertices, polygons)
    assert (mesh.face_count, mesh.triangle_count) == (11, 12)
    assert mesh.faces == polygons
    assert mesh.mass_properties().volume == 24.0
    # A NumPy object array of index arrays works too.
    ragged = np.empty(len(polygons), dtype=object)
    ragged[:] = [np.array(p) for p in polygons]
    assert meshvol.Mesh(vertices, ragged).faces == polygons


def test_vertices_and_faces_are_read_only_views_of_the_mesh():
    mesh = meshvol.Mesh(*box())
    v, f = mesh.vertices, mesh.faces
    assert v.base is mesh and f.base is mesh
    assert not v.flags.writeable and not f.flags.writeable
    assert np.shares_memory(v, mesh.vertices)
    with pytest.raises(ValueError):
        v[0, 0] = 5.0
    del mesh  # the views keep the mesh alive
    assert v.sum() == 12.0 and f.shape == (12, 3)


def test_the_mesh_owns_a_copy_of_its_input():
    vertices, faces = box()
    mesh = meshvol.Mesh(vertices, faces)
    vertices[:] = 0.0
    faces[:] = 0
    assert mesh.mass_properties().volume == 1.0


class MeshLike:
    """Anything with .vertices and .faces, as trimesh.Trimesh has."""

    def __init__(self, vertices, faces):
        self.vertices, self.faces = vertices, faces


def test_objects_with_vertices_and_faces_are_meshes():
    source = MeshLike(*box((0, 0, 0), (2, 3, 4)))
    mesh = meshvol.Mesh(source)
    assert mesh.mass_properties().volume == 24.0
    copy = meshvol.Mesh(mesh)
    assert np.array_equal(copy.vertices, mesh.vertices) and copy.vertices.base is copy


def test_a_single_argument_must_be_mesh_like():
    with pytest.raises(TypeError, match="give the faces too"):
        meshvol.Mesh(np.zeros((3, 3)))


def test_meshes_from_arrays_have_no_file_facts():
    mesh = meshvol.Mesh(*box())
    assert (mesh.format, mesh.unit, mesh.warnings, mesh.objects) == (None, None, [], [])
    assert repr(mesh) == "Mesh(vertices=8, faces=12, triangles=12)"


def test_unaligned_arrays_are_copied_not_refused():
    # Pickle protocol 5 buffers (how Dask sends arrays) and frombuffer at an odd offset
    # give arrays whose data is not aligned to their dtype.
    vertices, faces = box((0, 0, 0), (2, 1, 1))
    raw = b"\0" + vertices.astype("<f8").tobytes()
    odd_vertices = np.frombuffer(raw, dtype="<f8", offset=1).reshape(-1, 3)
    raw = b"\0" + faces.astype("<u4").tobytes()
    odd_faces = np.frombuffer(raw, dtype="<u4", offset=1).reshape(-1, 3)
    assert not odd_vertices.flags.aligned and not odd_faces.flags.aligned
    assert meshvol.Mesh(odd_vertices, odd_faces).mass_properties().volume == 2.0


def test_faces_as_two_arrays_for_any_mesh():
    # A square pyramid: a quad base and four triangles (a mesh of polygons), and the
    # same pyramid fanned into triangles: both give the faces as index and offset arrays.
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 1]], float)
    faces = [[3, 2, 1, 0], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    polygons = meshvol.Mesh(v, faces)
    assert polygons.face_indices.dtype == np.uint32 and polygons.face_offsets.dtype == np.uint64
    np.testing.assert_array_equal(polygons.face_offsets, [0, 4, 7, 10, 13, 16])
    o, i = polygons.face_offsets, polygons.face_indices
    assert [i[o[f]:o[f + 1]].tolist() for f in range(polygons.face_count)] == faces
    triangles = polygons.triangulated()
    np.testing.assert_array_equal(triangles.face_indices, np.asarray(triangles.faces).ravel())
    np.testing.assert_array_equal(triangles.face_offsets, 3 * np.arange(triangles.face_count + 1))
