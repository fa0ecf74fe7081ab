"""Hull meshes: the box generator, file loading, and the checks that refuse bad meshes."""

import numpy as np
import pytest
import trimesh

from boat_dynamics.physics.hull import (
    BoxHull,
    HullMesh,
    HullMeshError,
    box_mesh,
    check_mesh,
    load_mesh,
)


@pytest.mark.parametrize("n", [1, 2, 5])
def test_box_mesh_is_a_closed_box(n):
    hull = BoxHull(4.0, 2.0, 1.0)
    mesh = box_mesh(hull, n)
    check_mesh(mesh)
    assert mesh.faces.shape == (12 * n * n, 3)
    assert mesh.volume == pytest.approx(8.0, rel=1e-12)
    assert mesh.extents == pytest.approx([4.0, 2.0, 1.0])
    assert mesh.solid_inertia(100.0) == pytest.approx(hull.solid_inertia(100.0), rel=1e-12)


def test_stl_and_obj_round_trip_with_scale(tmp_path):
    box = trimesh.creation.box(extents=[3000.0, 1200.0, 800.0])  # millimetres
    box.apply_translation([5000.0, 0.0, 100.0])  # off-centre: the bounding box is re-centred
    for suffix in ("stl", "obj"):
        path = tmp_path / f"hull.{suffix}"
        box.export(path)
        mesh = load_mesh(str(path), scale=0.001)
        assert mesh.volume == pytest.approx(3.0 * 1.2 * 0.8, rel=1e-9)
        assert mesh.vertices.min(axis=0) == pytest.approx([-1.5, -0.6, -0.4])
        with pytest.raises(HullMeshError, match="Wrong units"):
            load_mesh(str(path))


def _box():
    return box_mesh(BoxHull(4.0, 2.0, 1.0))


def test_open_mesh_is_refused():
    m = _box()
    with pytest.raises(HullMeshError, match="not watertight"):
        check_mesh(HullMesh(m.vertices, m.faces[1:]), "hull.stl")


def test_inward_mesh_is_refused():
    m = _box()
    with pytest.raises(HullMeshError, match="face inward"):
        check_mesh(HullMesh(m.vertices, m.faces[:, ::-1]))


def test_degenerate_triangle_is_refused():
    m = _box()
    faces = np.vstack([m.faces, [[0, 0, 1]]])
    with pytest.raises(HullMeshError, match="degenerate"):
        check_mesh(HullMesh(m.vertices, faces))


def test_unreadable_file_is_refused(tmp_path):
    bad = tmp_path / "hull.stl"
    bad.write_text("this is not a mesh")
    with pytest.raises(HullMeshError, match=r"hull\.stl"):
        load_mesh(str(bad))


def test_inertia_tensor_of_a_turned_box_is_the_turned_diagonal():
    from boat_dynamics.physics.rigid_body import quat_from_euler, rotation_matrix

    hull = BoxHull(4.0, 2.0, 1.0)
    box = box_mesh(hull, 2)
    r = rotation_matrix(quat_from_euler(0.2, 0.5, -0.3))
    turned = HullMesh(box.vertices @ r.T, box.faces)
    expected = r @ np.diag(hull.solid_inertia(100.0)) @ r.T
    np.testing.assert_allclose(turned.inertia_tensor(100.0), expected, atol=1e-10)
    products = turned.inertia_products(100.0)
    assert products == pytest.approx([-expected[0, 1], -expected[0, 2], -expected[1, 2]])
    assert np.all(box.inertia_products(100.0) == pytest.approx(0.0, abs=1e-12))
