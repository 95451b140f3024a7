"""meshvol.load: files written here with NumPy and the standard library."""

import zipfile

import numpy as np
import pytest

import meshvol
from solids import BOX_QUADS, box


def write_binary_stl(path, vertices, faces):
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    triangles = np.zeros(len(faces), dtype=record)
    triangles["corners"] = vertices[faces]
    with open(path, "wb") as out:
        out.write(b"binary STL written by the meshvol tests".ljust(80, b" "))
        out.write(np.uint32(len(faces)).tobytes())
        out.write(triangles.tobytes())


def test_binary_stl(tmp_path):
    vertices, faces = box((0.5, 1.0, 2.0), (2.0, 3.0, 7.0))
    path = tmp_path / "box.stl"
    write_binary_stl(path, vertices, faces)
    mesh = meshvol.load(path)
    assert (mesh.format, mesh.unit, mesh.warnings, mesh.objects) == ("stl-binary", None, [], [])
    # Three unshared vertices per triangle, in file order.
    assert (mesh.vertex_count, mesh.face_count) == (36, 12)
    assert np.array_equal(mesh.vertices, vertices[faces].reshape(-1, 3))
    assert np.array_equal(mesh.faces, np.arange(36).reshape(12, 3))
    assert mesh.mass_properties().volume == 1.5 * 2.0 * 5.0
    check = mesh.check()
    assert check.closed and check.welded_vertices == 8
    assert repr(mesh) == "Mesh(vertices=36, faces=12, triangles=12, format='stl-binary')"


def test_obj_with_quads_and_objects(tmp_path):
    vertices, _ = box((0, 0, 0), (2, 3, 4))
    lines = [f"v {x} {y} {z}" for x, y, z in vertices.tolist()]
    lines.append("o bottom_and_top")
    lines += ["f " + " ".join(str(i + 1) for i in quad) for quad in BOX_QUADS[:2].tolist()]
    lines.append("o sides")
    lines += ["f " + " ".join(str(i + 1) for i in quad) for quad in BOX_QUADS[2:].tolist()]
    path = tmp_path / "box.obj"
    path.write_text("\n".join(lines) + "\n")
    mesh = meshvol.load(str(path))
    assert mesh.format == "obj" and not mesh.is_triangle_mesh
    assert mesh.objects == [("bottom_and_top", 0, 2), ("sides", 2, 6)]
    assert mesh.faces == BOX_QUADS.tolist()
    assert mesh.mass_properties().volume == 24.0


def test_off(tmp_path):
    vertices, faces = box((0, 0, 0), (1, 2, 3))
    text = ["OFF", f"{len(vertices)} {len(faces)} 0"]
    text += [" ".join(map(str, p)) for p in vertices.tolist()]
    text += ["3 " + " ".join(map(str, f)) for f in faces.tolist()]
    path = tmp_path / "box.off"
    path.write_text("\n".join(text) + "\n")
    mesh = meshvol.load(path)
    assert mesh.format == "off" and mesh.mass_properties().volume == 6.0


def block_mesh_xml():
    """A 10 × 20 × 30 block as a 3MF <mesh> element."""
    vertices, faces = box((0, 0, 0), (10, 20, 30))
    xml_vertices = "".join(f'<vertex x="{x}" y="{y}" z="{z}"/>' for x, y, z in vertices.tolist())
    xml_triangles = "".join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in faces.tolist())
    return f"<mesh><vertices>{xml_vertices}</vertices><triangles>{xml_triangles}</triangles></mesh>"


def test_3mf_declares_its_unit(tmp_path):
    model = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">'
        f'<resources><object id="1" name="block" type="model">{block_mesh_xml()}</object></resources>'
        '<build><item objectid="1"/></build></model>'
    )
    path = tmp_path / "block.3mf"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("3D/3dmodel.model", model)
    mesh = meshvol.load(path)
    assert (mesh.format, mesh.unit) == ("3mf", "mm")
    assert mesh.mass_properties().volume == 6000.0


def test_3mf_copies_are_checked_from_their_part(tmp_path):
    # A block placed 100 × 100 times by components, 20 apart: every copy a closed shell,
    # the volume exactly 10⁴ × 6000, as for the same copies given as arrays.
    row = "".join(
        f'<component objectid="1" transform="1 0 0 0 1 0 0 0 1 {20 * i} 0 0"/>' for i in range(100)
    )
    grid = "".join(
        f'<component objectid="2" transform="1 0 0 0 1 0 0 0 1 0 {40 * j} 0"/>' for j in range(100)
    )
    model = (
        '<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">'
        f'<resources><object id="1" type="model">{block_mesh_xml()}</object>'
        f'<object id="2" type="model"><components>{row}</components></object>'
        f'<object id="3" type="model"><components>{grid}</components></object></resources>'
        '<build><item objectid="3"/></build></model>'
    )
    path = tmp_path / "blocks.3mf"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("3D/3dmodel.model", model)
    mesh = meshvol.load(path)
    check = mesh.check()
    assert (check.shells, check.closed, check.solid_volume) == (10_000, True, 6000.0 * 10_000)
    assert mesh.mass_properties().volume == 6000.0 * 10_000
    arrays = meshvol.Mesh(mesh.vertices, mesh.faces).check()
    assert (arrays.shells, arrays.edges, arrays.euler_characteristic) == (
        check.shells,
        check.edges,
        check.euler_characteristic,
    )


def test_loaded_and_built_meshes_measure_alike(tmp_path):
    vertices, faces = box((0.25, 0.5, 0.75), (1.25, 2.5, 3.75))
    path = tmp_path / "box.stl"
    write_binary_stl(path, vertices, faces)
    loaded = meshvol.load(path).mass_properties().to_dict()
    built = meshvol.Mesh(vertices.astype(np.float32), faces).mass_properties().to_dict()
    # Only where they came from differs: the file, its format, STL's unshared vertices.
    source = {"file", "format", "format_source", "vertices"}
    assert (loaded["file"], loaded["format"], loaded["vertices"]) == (str(path), "stl-binary", 36)
    assert {k: v for k, v in loaded.items() if k not in source} == {
        k: v for k, v in built.items() if k not in source
    }


def test_trimesh_reads_the_same_volume(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    vertices, faces = box((0, 0, 0), (2, 3, 4))
    path = tmp_path / "box.stl"
    write_binary_stl(path, vertices, faces)
    assert meshvol.load(path).mass_properties().volume == trimesh.load(path).volume == 24.0
