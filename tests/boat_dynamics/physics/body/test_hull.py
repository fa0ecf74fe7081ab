"""Hull meshes: the box generator, file loading, and the checks that refuse bad meshes."""

import numpy as np
import pytest
import trimesh

from boat_dynamics.physics.body.hull import (
    BoxHull,
    HullMesh,
    HullMeshError,
    box_mesh,
    check_mesh,
    load_mesh,
    longest_edge,
    refine,
    subdivide,
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


def test_a_mesh_too_large_is_refused_before_it_is_read(tmp_path):
    """Before: a 10 M-triangle STL took 5.1 GB, then a traceback."""
    import struct
    import tracemalloc

    from boat_dynamics.physics.body.hull import MAX_MESH_FILE_BYTES, MAX_TRIANGLES

    huge = tmp_path / "huge.stl"  # 10 M triangles' size, sparse: no disk used
    with open(huge, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", 10_000_000))
        f.truncate(84 + 50 * 10_000_000)
    many = tmp_path / "many.stl"  # a whole binary STL of 120,000 (zero) triangles, 6 MB
    many.write_bytes(b"\0" * 80 + struct.pack("<I", 120_000) + bytes(50 * 120_000))
    tracemalloc.start()
    try:
        with pytest.raises(HullMeshError, match=f"at most {MAX_MESH_FILE_BYTES:,}"):
            load_mesh(str(huge))
        with pytest.raises(HullMeshError, match=f"declares 120,000 triangles.*{MAX_TRIANGLES:,}"):
            load_mesh(str(many))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 1_000_000  # neither was read


def test_inertia_tensor_of_a_turned_box_is_the_turned_diagonal():
    from boat_dynamics.physics.body.rigid_body import quat_from_euler, rotation_matrix

    hull = BoxHull(4.0, 2.0, 1.0)
    box = box_mesh(hull, 2)
    r = rotation_matrix(quat_from_euler(0.2, 0.5, -0.3))
    turned = HullMesh(box.vertices @ r.T, box.faces)
    expected = r @ np.diag(hull.solid_inertia(100.0)) @ r.T
    np.testing.assert_allclose(turned.inertia_tensor(100.0), expected, atol=1e-10)
    products = turned.inertia_products(100.0)
    assert products == pytest.approx([-expected[0, 1], -expected[0, 2], -expected[1, 2]])
    assert np.all(box.inertia_products(100.0) == pytest.approx(0.0, abs=1e-12))


def test_subdividing_keeps_the_surface_and_halves_the_edges():
    box = trimesh.creation.icosphere(subdivisions=1, radius=1.0)
    mesh = HullMesh(np.asarray(box.vertices), np.asarray(box.faces))
    finer = subdivide(mesh)
    check_mesh(finer)  # closed, outward, no degenerate triangle
    assert finer.faces.shape[0] == 4 * mesh.faces.shape[0]
    # each shared edge has one midpoint: V - E + F = 2 still holds
    assert finer.vertices.shape[0] - 3 * finer.faces.shape[0] // 2 + finer.faces.shape[0] == 2
    assert finer.volume == pytest.approx(mesh.volume, rel=1e-12)  # same planes
    assert finer.inertia_tensor(10.0) == pytest.approx(mesh.inertia_tensor(10.0), rel=1e-12)
    assert longest_edge(finer) == pytest.approx(longest_edge(mesh) / 2, rel=1e-12)


def test_refining_stops_at_the_edge_length_or_the_triangle_budget():
    mesh = box_mesh(BoxHull(4.0, 2.0, 1.0))  # longest edge: a 4 x 2 face's diagonal, 4.47 m
    assert refine(mesh, 5.0, 4096) is mesh
    fine = refine(mesh, 0.6, 4096)
    assert longest_edge(fine) <= 0.6 < 2 * longest_edge(fine)
    assert fine.faces.shape[0] == 12 * 4**3
    capped = refine(mesh, 0.01, 1000)
    assert capped.faces.shape[0] == 12 * 4**3  # 768: one more would make 3,072 > 1,000
