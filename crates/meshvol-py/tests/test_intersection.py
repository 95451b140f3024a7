"""meshvol.intersection: the overlap of two bodies, each placed by an optional rigid pose,
against closed forms (boxes overlapping in a box), with the report of `meshvol intersect`."""

import warnings

import meshvol
import numpy as np
import pytest
from solids import box, box_inertia


def mesh(lo, hi):
    return meshvol.Mesh(*box(lo, hi))


def translation(t):
    pose = np.eye(4)
    pose[:3, 3] = t
    return pose


def rotation_z(quarter_turns, t=(0.0, 0.0, 0.0)):
    """A rotation about z by a multiple of 90° (entries exactly 0 and ±1), then `t`."""
    c, s = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)][quarter_turns % 4]
    pose = translation(t)
    pose[:3, :3] = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
    return pose


def rotation(axis, angle, t=(0.0, 0.0, 0.0)):
    """Rodrigues' rotation about `axis` by `angle` radians, then `t`."""
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    pose = translation(t)
    pose[:3, :3] = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K
    return pose


def assert_holds(r, exact, rel=1e-9):
    """The certified interval holds `exact` and is narrow; volume is its midpoint."""
    assert r.lower <= exact <= r.upper, (r.lower, exact, r.upper)
    assert r.upper - r.lower <= rel * max(exact, 1.0)
    assert r.volume == pytest.approx(exact, rel=rel, abs=1e-15)


# A: [0, 1] × [0, 1.5] × [0, 2] (volume 3); B: [0.25, 1.5] × [0.5, 2] × [1, 2.5]
# (1.25 × 1.5 × 1.5 = 2.8125). A∩B = [0.25, 1] × [0.5, 1.5] × [1, 2]: 0.75 × 1 × 1.
A_LO, A_HI = (0.0, 0.0, 0.0), (1.0, 1.5, 2.0)
B_LO, B_HI = (0.25, 0.5, 1.0), (1.5, 2.0, 2.5)
OVERLAP, OVERLAP_CENTROID, OVERLAP_SIZE = 0.75, [0.625, 1.0, 1.5], (0.75, 1.0, 1.0)
VOLUME_A, VOLUME_B = 3.0, 2.8125
CONTACT_VECTOR = [-1.0, -0.75, -0.75]


def assert_overlap_report(r):
    assert_holds(r, OVERLAP)
    assert r.volume_a == VOLUME_A and r.volume_b == VOLUME_B
    union = VOLUME_A + VOLUME_B - OVERLAP
    assert r.union_lower <= union <= r.union_upper
    assert r.iou_lower <= OVERLAP / union <= r.iou_upper
    assert r.iou == pytest.approx(OVERLAP / union, rel=1e-9)
    assert r.dice == pytest.approx(2 * OVERLAP / (VOLUME_A + VOLUME_B), rel=1e-9)
    assert r.a_minus_b == pytest.approx(VOLUME_A - OVERLAP, rel=1e-9)
    assert r.b_minus_a == pytest.approx(VOLUME_B - OVERLAP, rel=1e-9)
    assert not r.disjoint
    assert isinstance(r.centroid, np.ndarray) and r.centroid.shape == (3,)
    np.testing.assert_allclose(r.centroid, OVERLAP_CENTROID, rtol=1e-9)
    assert isinstance(r.inertia, np.ndarray) and r.inertia.shape == (3, 3)
    np.testing.assert_allclose(r.inertia, box_inertia(OVERLAP_SIZE), rtol=1e-9, atol=1e-12)
    # The interface: B's faces x = 0.25, y = 0.5, z = 1 inside A (areas 1, 0.75, 0.75,
    # normals −x, −y, −z), and A's faces x = 1, y = 1.5, z = 2 inside B, the same areas.
    assert r.contact_area == pytest.approx(2 * 2.5, rel=1e-9)
    np.testing.assert_allclose(r.contact_vector, CONTACT_VECTOR, rtol=1e-9)
    np.testing.assert_allclose(
        r.contact_normal, np.divide(CONTACT_VECTOR, np.linalg.norm(CONTACT_VECTOR)), rtol=1e-9
    )
    assert r.warnings == []


def test_boxes_overlapping_in_a_box():
    r = meshvol.intersection(mesh(A_LO, A_HI), mesh(B_LO, B_HI))
    assert_overlap_report(r)
    d = r.to_dict()
    assert d["file"] == "mesh, mesh" and d["files"] == ["mesh", "mesh"]
    assert d["lower"] == r.lower and d["centroid"] == r.centroid.tolist()
    assert d["inertia"] == r.inertia.tolist()
    assert set(d) <= set(dir(r))
    assert repr(r).startswith("Intersection(lower=")


def test_translated_b_is_the_same_overlap():
    size = np.subtract(B_HI, B_LO)
    at_origin = mesh((0.0, 0.0, 0.0), size)
    r = meshvol.intersection(mesh(A_LO, A_HI), at_origin, pose_b=translation(B_LO))
    assert_overlap_report(r)
    # Moving both bodies together moves the overlap, and keeps its volume.
    shift = (10.0, -20.0, 5.0)
    both = meshvol.intersection(
        mesh(A_LO, A_HI),
        at_origin,
        pose_a=translation(shift),
        pose_b=translation(np.add(B_LO, shift)),
    )
    assert_holds(both, OVERLAP)
    np.testing.assert_allclose(both.centroid, np.add(OVERLAP_CENTROID, shift), rtol=1e-9)


def test_quarter_turn_about_z_is_exact():
    # B = [0, 2] × [0, 1] × [0, 1] turned 90° about z: [-1, 0] × [0, 2] × [0, 1]; moved by
    # (1.5, 0.5, 0): [0.5, 1.5] × [0.5, 2.5] × [0, 1]. With the unit cube: 0.5 × 0.5 × 1.
    cube, bar = mesh((0, 0, 0), (1, 1, 1)), mesh((0, 0, 0), (2, 1, 1))
    r = meshvol.intersection(cube, bar, pose_b=rotation_z(1, (1.5, 0.5, 0.0)))
    assert_holds(r, 0.25)
    np.testing.assert_allclose(r.centroid, [0.75, 0.75, 0.5], rtol=1e-9)
    assert r.volume_b == 2.0
    # Unturned, the bar overlaps the cube in [0.5, 1] × [0.5, 1] × [0, 1] as well ...
    assert_holds(meshvol.intersection(cube, bar, pose_b=translation((0.5, 0.5, 0))), 0.25)
    # ... and turned the other way, from x = -1.5 .. 0.5: [0, 0.5] × [0, 1] × [0, 1].
    r = meshvol.intersection(cube, bar, pose_b=rotation_z(-1, (-0.5, 2.0, 0.0)))
    assert_holds(r, 0.5)


def test_rotated_cube_inside_a_cube():
    # A unit cube centred at the origin turned about a generic axis fits inside [-1, 1]³
    # (its half-diagonal is √3/2 < 1): the overlap is the whole cube, volume 1 (up to
    # the rounding of the turned corners, far below the interval's width).
    inner = mesh((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5))
    outer = mesh((-1, -1, -1), (1, 1, 1))
    pose = rotation((1.0, 2.0, 3.0), 0.7)
    r = meshvol.intersection(outer, inner, pose_b=pose)
    assert r.lower <= 1.0 + 1e-12 and 1.0 - 1e-12 <= r.upper
    assert r.upper - r.lower <= 1e-9
    np.testing.assert_allclose(r.centroid, [0, 0, 0], atol=1e-9)
    assert r.iou == pytest.approx(1 / 8, rel=1e-9)
    # The same turn on both bodies about the shared centre keeps the overlap: box ∩ box.
    r = meshvol.intersection(mesh(A_LO, A_HI), mesh(B_LO, B_HI), pose_a=pose, pose_b=pose)
    assert r.lower - 1e-12 <= OVERLAP <= r.upper + 1e-12
    assert r.upper - r.lower <= 1e-8


def test_disjoint_poses_give_exactly_zero():
    a, b = mesh(A_LO, A_HI), mesh(B_LO, B_HI)
    for pose in (translation((10.0, 0.0, 0.0)), rotation_z(2, (-1.5, 0.0, 0.0))):
        r = meshvol.intersection(a, b, pose_b=pose)
        assert (r.lower, r.upper, r.volume, r.iou, r.dice) == (0.0, 0.0, 0.0, 0.0, 0.0)
        assert r.disjoint and r.centroid is None and r.inertia is None
        assert r.union == VOLUME_A + VOLUME_B
    # Touching face to face (B moved to start where A ends in x) is 0 exactly too.
    r = meshvol.intersection(a, b, pose_b=translation((0.75, 0.0, 0.0)))
    assert (r.lower, r.upper, r.volume) == (0.0, 0.0, 0.0)


def test_a_body_with_itself_is_itself():
    a = mesh(A_LO, A_HI)
    for pose in (None, np.eye(4), rotation((0.3, -1.0, 0.2), 1.1, (4.0, 5.0, 6.0))):
        r = meshvol.intersection(a, a, pose_a=pose, pose_b=pose)
        assert r.lower - 1e-12 <= VOLUME_A <= r.upper + 1e-12
        assert r.iou_lower <= 1.0 + 1e-12 and r.iou_upper >= 1.0 - 1e-12
    assert_holds(meshvol.intersection(a, a), VOLUME_A)
    assert_holds(meshvol.intersection(a, a, pose_a=np.eye(4), pose_b=np.eye(4)), VOLUME_A)


def test_poses_as_lists_and_float32():
    a, b = mesh(A_LO, A_HI), mesh((0, 0, 0), np.subtract(B_HI, B_LO))
    as_list = translation(B_LO).tolist()
    assert_holds(meshvol.intersection(a, b, pose_b=as_list), OVERLAP)
    # A rotation rounded to float32 is within the rigid tolerance (1e-6).
    turned = rotation((1.0, 1.0, 0.0), 0.3).astype(np.float32)
    r = meshvol.intersection(a, a, pose_a=turned, pose_b=turned)
    assert r.volume == pytest.approx(VOLUME_A, rel=1e-5)


@pytest.mark.parametrize(
    "pose, why",
    [
        (np.diag([2.0, 2.0, 2.0, 1.0]), "not a rotation"),
        (np.diag([1.0, 1.0, 1.001, 1.0]), "not a rotation"),
        (np.array([[1, 0.5, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]]), "shear"),
        (np.diag([1.0, 1.0, -1.0, 1.0]), "mirror"),
        (np.where(np.eye(4) == 1, np.nan, 0.0), "finite"),
        (translation((np.inf, 0.0, 0.0)), "finite"),
        (np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1.0]]), "last row"),
        (np.eye(3), r"shape \(3, 3\)"),
        (np.eye(4)[:3], r"shape \(3, 4\)"),
        (np.zeros(16), r"shape \(16,\)"),
        ("not a pose", "4×4"),
    ],
)
def test_poses_that_are_not_rigid_are_refused(pose, why):
    a, b = mesh(A_LO, A_HI), mesh(B_LO, B_HI)
    with pytest.raises(ValueError, match="pose_b") as e:
        meshvol.intersection(a, b, pose_b=pose)
    assert e.match(why)
    with pytest.raises(ValueError, match="pose_a"):
        meshvol.intersection(a, b, pose_a=pose)


def test_other_arguments():
    a = mesh(A_LO, A_HI)
    with pytest.raises(ValueError, match="tolerance"):
        meshvol.intersection(a, a, tolerance=0.0)
    with pytest.raises(TypeError):
        meshvol.intersection(a, 3.0)
    # A string is a path, read as meshvol.load reads it.
    with pytest.raises(FileNotFoundError, match="not a mesh"):
        meshvol.intersection(a, "not a mesh")


def test_open_body_is_its_checked_solid_with_warnings():
    vertices, faces = box(B_LO, B_HI)
    open_b = meshvol.Mesh(vertices, faces[2:])  # two triangles short: a hole, capped
    with pytest.warns(meshvol.MeshWarning) as caught:
        r = meshvol.intersection(mesh(A_LO, A_HI), open_b)
    assert r.warnings and all(w.startswith("mesh: ") for w in r.warnings)
    assert {str(w.message) for w in caught} >= set(r.warnings)
    assert r.lower <= OVERLAP <= r.upper
    # The check is kept by the Mesh: a second pose warns again, from the same check.
    with pytest.warns(meshvol.MeshWarning):
        r2 = meshvol.intersection(mesh(A_LO, A_HI), open_b, pose_b=np.eye(4))
    assert r2.warnings == r.warnings


def test_closed_bodies_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        meshvol.intersection(mesh(A_LO, A_HI), mesh(B_LO, B_HI), pose_b=rotation_z(1))


def test_the_contact_turns_with_the_bodies():
    # Both bodies turned by one rotation: the interface's area stays, its vector turns,
    # and it is the derivative of the overlap under a small motion of B (a second way).
    pose = rotation((1.0, 2.0, -0.5), 0.7, t=(0.3, -0.2, 0.1))
    a, b = mesh(A_LO, A_HI), mesh(B_LO, B_HI)
    r = meshvol.intersection(a, b, pose_a=pose, pose_b=pose)
    assert r.contact_area == pytest.approx(5.0, rel=1e-9)
    np.testing.assert_allclose(r.contact_vector, pose[:3, :3] @ CONTACT_VECTOR, atol=1e-9)
    step = 1e-4
    for axis in range(3):
        moved = pose.copy()
        moved[axis, 3] += step
        plus = meshvol.intersection(a, b, pose_a=pose, pose_b=moved).volume
        moved[axis, 3] -= 2 * step
        minus = meshvol.intersection(a, b, pose_a=pose, pose_b=moved).volume
        assert (plus - minus) / (2 * step) == pytest.approx(r.contact_vector[axis], abs=1e-6)


def test_many_poses_give_what_each_pose_gives_alone():
    a, b = mesh(A_LO, A_HI), mesh(B_LO, B_HI)
    poses = np.stack([translation((0.25 * k, 0.0, -0.5 * k)) for k in range(5)])
    many = meshvol.intersections(a, b, poses_b=poses)
    assert len(many) == 5
    for k, r in enumerate(many):
        alone = meshvol.intersection(a, b, pose_b=poses[k])
        assert (r.lower, r.upper) == (alone.lower, alone.upper)
        np.testing.assert_array_equal(r.contact_vector, alone.contact_vector)
        # B shifted by (k/4, 0, −k/2): the overlap is [0.25 + k/4, 1] × [0.5, 1.5] ×
        # [max(0, 1 − k/2), min(2, 2.5 − k/2)].
        height = min(2.0, 2.5 - 0.5 * k) - max(0.0, 1.0 - 0.5 * k)
        exact = max(0.75 - 0.25 * k, 0.0) * 1.0 * height
        assert r.lower <= exact <= r.upper, (k, exact)
    # One pose for A and many for B: A's pose is used for each.
    shift = translation((5.0, 5.0, 5.0))
    both = meshvol.intersections(a, b, poses_a=shift, poses_b=poses + shift - np.eye(4))
    assert [r.volume for r in both] == pytest.approx([r.volume for r in many], rel=1e-9)
    # No poses: the bodies where they are, once.
    (only,) = meshvol.intersections(a, b)
    assert_overlap_report(only)


def test_many_poses_refuse_what_is_not_a_pose():
    a, b = mesh(A_LO, A_HI), mesh(B_LO, B_HI)
    poses = np.stack([np.eye(4)] * 3)
    poses[2, 0, 0] = 2.0
    with pytest.raises(ValueError, match=r"poses_b\[2\] is not rigid"):
        meshvol.intersections(a, b, poses_b=poses)
    with pytest.raises(ValueError, match="2 poses and the other 3"):
        meshvol.intersections(a, b, poses_a=np.stack([np.eye(4)] * 3), poses_b=np.stack([np.eye(4)] * 2))
    with pytest.raises(ValueError, match=r"\(N, 4, 4\)"):
        meshvol.intersections(a, b, poses_b=np.zeros((2, 3, 4)))
    with pytest.raises(ValueError, match="meshvol.intersections takes many"):
        meshvol.intersection(a, b, pose_b=np.stack([np.eye(4)] * 2))
