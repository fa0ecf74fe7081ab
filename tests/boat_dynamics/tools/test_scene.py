"""What `boatsim view` draws (boat_dynamics.tools.scene), read back from the drawing calls."""

import math
import sys

import numpy as np
import pytest

from boat_dynamics.physics.scenario import default_scenario_path, load_scenario, parse_scenario
from boat_dynamics.tools.scene import MAX_SEA_VERTICES, Scene, hull_shape, sea_mesh
from ocean_sim.physics.fft import TileSpec, tile_sea
from ocean_sim.physics.waves import WaveComponent, WaveField, displace, sample_surface

#: rerun-sdk (the view extra; make test installs it) needs Python 3.11.
pytestmark = pytest.mark.skipif(sys.version_info < (3, 11), reason="rerun-sdk needs 3.11+")

SEA = WaveField((WaveComponent(0.4, 20.0, 0.3, 0.5, 0.0), WaveComponent(0.1, 7.0, -0.8, 0.4, 1.0)))


def _values(batch):
    return np.array(batch.as_arrow_array().to_pylist(), dtype=float)


class Drawn(Scene):
    """A scene that keeps what it draws: (time, entity, archetype, static)."""

    def __init__(self, *args, **kwargs):
        import rerun as rr

        self.drawn = []
        super().__init__(rr.RecordingStream("boatsim_test"), *args, **kwargs)

    def _log(self, entity, archetype, static=False):
        self.drawn.append((None if static else self.t, entity, archetype, static))

    def at(self, entity):
        return [(t, a) for t, e, a, _ in self.drawn if e == entity]


def test_the_sea_is_the_surface_on_world_fixed_points():
    vertices, triangles, colours = sea_mesh(SEA, 3.2, np.array([10.3, -4.6]), 20.0, 0.5)
    assert vertices.shape == (41 * 41, 3) and triangles.shape == (2 * 40 * 40, 3)
    np.testing.assert_allclose(vertices[:, :2] / 0.5, np.round(vertices[:, :2] / 0.5), atol=1e-9)
    expected = sample_surface(SEA, vertices[:, :2], 3.2).heights  # float64 reference
    np.testing.assert_allclose(vertices[:, 2], expected, atol=2e-5)  # drawn in float32
    assert colours.dtype == np.uint8 and len(np.unique(colours, axis=0)) > 50  # shaded
    moved, _, _ = sea_mesh(SEA, 3.2, np.array([10.3 + 0.2, -4.6 - 0.1]), 20.0, 0.5)
    np.testing.assert_array_equal(moved[:, :2], vertices[:, :2])  # it does not swim


def test_a_wide_sea_keeps_to_the_vertex_budget_and_its_size():
    vertices, _, _ = sea_mesh(SEA, 0.0, np.zeros(2), 2000.0, 1.0)
    assert len(vertices) <= MAX_SEA_VERTICES
    span = vertices[:, :2].max(axis=0) - vertices[:, :2].min(axis=0)
    np.testing.assert_allclose(span, 2000.0, rtol=1e-9)


TILE = tile_sea(TileSpec(size=60.0, resolution=16, seed=3, spectrum="jonswap",
                         significant_height=1.0, peak_period=5.0, choppiness=0.9))


def test_an_fft_sea_is_drawn_from_its_grid_exact_at_the_nodes_tiled_over_any_area():
    # 1 m grid (L = 60 m, M = 60) over 2.5 tiles far from the origin
    t, centre = 7.3, np.array([1000.3, -523.6])
    vertices, triangles, colours = sea_mesh(TILE, t, centre, 150.0, 1.0)
    assert vertices.shape == (151 * 151, 3) and triangles.shape == (2 * 150 * 150, 3)
    rest = np.round(centre - 75.0) + np.stack(np.meshgrid(np.arange(151.0), np.arange(151.0),
                                                          indexing="ij"), -1).reshape(-1, 2)
    np.testing.assert_allclose(vertices, displace(TILE, rest, t), rtol=0, atol=1e-9)
    assert np.abs(vertices[:, :2] - rest).max() > 0.05  # the particles, displaced
    some = vertices[::37]  # the inverted query agrees at the vertices (as it does anywhere)
    assert np.abs(sample_surface(TILE, some[:, :2], t).heights - some[:, 2]).max() < 1e-3
    assert len(np.unique(colours, axis=0)) > 50  # shaded
    moved, _, _ = sea_mesh(TILE, t, centre + [0.1, -0.1], 150.0, 1.0)
    np.testing.assert_array_equal(moved, vertices)  # it does not swim
    made, _, _ = sea_mesh(TILE, t, centre, 150.0, 1.0, made=lambda xy: 0.01 * xy[:, 0])
    np.testing.assert_array_equal(made[:, :2], vertices[:, :2])  # the boats' waves added
    np.testing.assert_allclose(made[:, 2], vertices[:, 2] + 0.01 * vertices[:, 0], atol=1e-12)


def test_a_wide_fft_sea_keeps_to_the_vertex_budget_and_its_size():
    vertices, _, _ = sea_mesh(TILE, 0.0, np.zeros(2), 2000.0, 1.0)
    assert len(vertices) <= MAX_SEA_VERTICES
    span = vertices[:, :2].max(axis=0) - vertices[:, :2].min(axis=0)
    np.testing.assert_allclose(span, 2000.0, atol=12.0)  # within 11 m strides, displaced


def test_a_gerstner_sea_is_drawn_as_before_bit_for_bit():
    # the tile's own components without its tile: a Gerstner sum, drawn by the query
    for sea in (SEA, WaveField(TILE.components)):
        vertices, triangles, colours = sea_mesh(sea, 3.2, np.array([10.3, -4.6]), 20.0, 0.5)
        ticks = np.round((np.array([10.3, -4.6]) - 10.0) / 0.5) * 0.5
        gx, gy = np.meshgrid(ticks[0] + 0.5 * np.arange(41), ticks[1] + 0.5 * np.arange(41),
                             indexing="ij")
        xy = np.column_stack([gx.ravel(), gy.ravel()])
        heights = sample_surface(sea, xy, 3.2).heights
        np.testing.assert_array_equal(vertices, np.column_stack([xy, heights]))
        reach = max(sum(c.amplitude for c in sea.components), 1e-9)
        share = np.clip(0.5 + 0.5 * heights / reach, 0.0, 1.0)[:, None]
        np.testing.assert_array_equal(
            colours, (np.array([12, 44, 92]) + share * np.array([84, 124, 130])).astype(np.uint8))
        assert triangles.shape == (2 * 40 * 40, 3)


def test_a_hull_is_its_buoyancy_mesh_and_an_arrow_a_hull_length_at_full_thrust():
    spec = load_scenario(default_scenario_path()).boats[0]
    shape = hull_shape(spec.params)
    np.testing.assert_array_equal(shape.vertices, spec.params.buoyancy.mesh.vertices)
    assert shape.force_scale * 2000.0 == pytest.approx(4.0)  # max_thrust 2 kN, 4 m long
    assert shape.arrow_origin[2] > shape.vertices[:, 2].max()  # over the deck, visible
    twin = parse_scenario({"boats": [{"propulsion": [
        {"name": "l", "max_thrust": 300.0, "position": [-1, 0.5, 0]},
        {"name": "r", "max_thrust": 300.0, "position": [-1, -0.5, 0]}]}]}).boats[0]
    assert hull_shape(twin.params).force_scale * 600.0 == pytest.approx(4.0)  # both together
    assert hull_shape(None).vertices.shape[1] == 3  # a boat no scenario has: the default box


def test_poses_forces_paths_and_sea_are_drawn_in_their_frames_at_their_times():
    spec = load_scenario(default_scenario_path()).boats[0]
    scene = Drawn({"": hull_shape(spec.params)}, sources=("thrust",), sea_period=0.5)
    scene.blueprint(focus="")
    for k in range(160):  # 3.2 s at 50 Hz, moving east
        t = k * 0.02
        scene.pose(t, "", (0.5 * t, 0.0, 0.1), (0.0, 0.0, 0.0, 1.0))
        scene.sea(t, SEA)
        scene.wrench(t, "", "thrust", (1500.0, 0.0, 0.0))
        scene.wrench(t, "", "buoyancy", (0.0, 0.0, 4e4))  # not asked for: not drawn
    poses = scene.at("world/boat")  # 50 Hz in: the first at or after each 0.05 s drawn
    expected = sorted({min(t for t in 0.02 * np.arange(160) if t >= m - 1e-9)
                       for m in 0.05 * np.arange(64)})
    assert [t for t, _ in poses] == pytest.approx(expected)
    np.testing.assert_allclose(_values(poses[-1][1].translation), [[1.58, 0.0, 0.1]])
    np.testing.assert_allclose(_values(poses[-1][1].quaternion), [[0.0, 0.0, 0.0, 1.0]])
    focus = scene.at("world/focus")  # the camera's frame follows the boat (no rotation)
    np.testing.assert_allclose(_values(focus[-1][1].translation), [[1.58, 0.0, 0.1]])
    (_, hull), = scene.at("world/boat/hull")
    assert len(_values(hull.vertex_positions)) == len(spec.params.buoyancy.mesh.vertices)
    arrows = scene.at("world/boat/forces/thrust")
    np.testing.assert_allclose(_values(arrows[-1][1].vectors), [[3.0, 0.0, 0.0]])  # 1.5 kN
    assert scene.at("world/boat/forces/buoyancy") == []
    seas = [(t, a) for t, a in scene.at("world/sea") if a.vertex_positions is not None]
    assert [t for t, _ in seas] == pytest.approx([0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0])
    indices = [a for _, a in scene.at("world/sea") if a.triangle_indices is not None]
    assert len(indices) == 1  # the grid's triangles once: only its heights change
    scene.finish()
    path = _values(scene.at("world/paths/boat")[-1][1].strips)[0]
    np.testing.assert_allclose(path[:, 0], 0.5 * 0.2 * np.arange(len(path)), atol=1e-6)


def test_a_live_view_logs_a_bounded_amount_per_simulated_second_over_twenty_minutes():
    """Live, the view draws at its live periods and redraws a boat's whole path only every
    30 s (its tail every second): what it logs per simulated second stays bounded.

    Before, it logged about 83 rows a simulated second and the whole path (up to 5000 points)
    every second: a software-drawn browser fell behind by 0.7 s every second and stopped
    drawing after ten minutes of a real-time run, while the Rerun server and the view process
    held the backlog (measured: docs/performance.md).
    """
    from boat_dynamics.tools import scene as scene_module
    from boat_dynamics.tools.view import _LIVE_POSE_PERIOD, _LIVE_SEA_PERIOD, _LIVE_WRENCH_PERIOD

    spec = load_scenario(default_scenario_path()).boats[0]
    scene = Drawn({"": hull_shape(spec.params)}, sea_size=20.0, sea_resolution=2.0,
                  sea_period=_LIVE_SEA_PERIOD, pose_period=_LIVE_POSE_PERIOD,
                  wrench_period=_LIVE_WRENCH_PERIOD)
    scene.blueprint(focus="")
    duration = 1200.0  # s of simulation time: the path reaches its 5000 points at 1000 s
    for k in range(int(duration * 50) + 1):  # odometry at 50 Hz, wrenches at 10 Hz
        t = k * 0.02
        scene.pose(t, "", (2.0 * t, 5.0 * np.sin(0.01 * t), 0.1), (0.0, 0.0, 0.0, 1.0))
        scene.sea(t, SEA)
        if k % 5 == 0:
            for source in scene_module.DEFAULT_SOURCES:
                scene.wrench(t, "", source, (1500.0, 0.0, 0.0))
    timed = [(t, e, a) for t, e, a, static in scene.drawn if not static and t is not None]

    def per_second(start: float) -> tuple[float, float]:
        """Rows a simulated second, and path points a simulated second, over a minute."""
        rows = [(e, a) for t, e, a in timed if start <= t < start + 60.0]
        points = sum(len(a.strips.as_arrow_array().to_pylist()[0]) for e, a in rows
                     if e.startswith("world/paths/"))
        return len(rows) / 60.0, points / 60.0

    (rows_early, _), (rows_late, points_late) = per_second(60.0), per_second(1140.0)
    assert rows_late <= rows_early + 0.1 and rows_late < 35.0  # was about 83 rows a second
    # the whole path (<= 5000 points) twice a minute, and each second the tail since then
    # (<= 30 s of points): at most about 320 points a second however long the run (measured
    # 240; before: the whole path every second, 5000)
    whole = 60.0 / scene_module._PATH_WHOLE_PERIOD * scene_module._PATH_POINTS / 60.0
    tail = scene_module._PATH_WHOLE_PERIOD / scene_module._PATH_STEP + 1
    assert points_late <= whole + tail < 0.1 * scene_module._PATH_POINTS
    poses = scene.at("world/boat")
    assert poses[-1][0] == pytest.approx(duration)  # still drawing at the end


def test_the_worlds_obstacles_are_drawn_once_from_their_markers():
    from boat_dynamics.ros.world import world_markers

    world = parse_scenario({"world": {"obstacles": [
        {"name": "pier", "points": [[8, -2], [9, -2], [9, 2], [8, 2]], "top": 1.5},
        {"name": "pile", "type": "cylinder", "center": [3, 4], "radius": 0.3}]}}).world
    scene = Drawn({})
    scene.markers(world_markers(world))
    drawn = {e: (t, a) for t, e, a, _ in scene.drawn if e.startswith("world/obstacles")}
    assert sorted(drawn) == ["world/obstacles/obstacles/0", "world/obstacles/obstacles/1",
                             "world/obstacles/obstacles/100000"]
    assert all(t is None for t, _ in drawn.values())  # static
    walls = drawn["world/obstacles/obstacles/0"][1]
    vertices = _values(walls.vertex_positions)
    assert vertices.shape == (24, 3) and vertices[:, 2].max() == 1.5  # 4 walls, 2 triangles
    assert _values(walls.triangle_indices).shape == (8, 3)
    pile = drawn["world/obstacles/obstacles/1"][1]
    np.testing.assert_allclose(_values(pile.centers), [[3.0, 4.0, 0.0]])  # from -2 to 2 m
    np.testing.assert_allclose(_values(pile.radii), [0.3], rtol=1e-6)


@pytest.mark.parametrize("made", ["all", "none"])
def test_the_sea_drawn_carries_the_wake_of_a_boat_at_speed(made):
    """A default box at 3 m/s along +x on calm water: the sea drawn behind it is its Kelvin
    wake (kelvin_wake.wake_elevation, from the poses' velocity) inside the 19.47 deg wedge,
    flat ahead of it and outside the wedge; flat everywhere for a boat that makes no waves."""
    from boat_dynamics.physics.wave_making.kelvin_wake import wake_elevation

    spec = parse_scenario({"boats": [{"hydrodynamics": {"made_waves": made}}]}).boats[0]
    shape = hull_shape(spec.params)
    assert (shape.ship is None) == (made == "none")
    scene = Drawn({"": shape}, sea_size=80.0, sea_resolution=1.0, sea_period=1.0)
    for k in range(51):  # 5 s at 10 Hz
        t = 0.1 * k
        scene.pose(t, "", (3.0 * t, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    scene.sea(5.0, WaveField())
    vertices = _values(scene.at("world/sea")[-1][1].vertex_positions)
    x, y, z = vertices[:, 0] - 15.0, vertices[:, 1], vertices[:, 2]
    inside = (x < -10.0) & (np.abs(y) < -x / np.sqrt(8.0) - 1.0)
    outside = (x > 0.0) | (np.abs(y) > -x / np.sqrt(8.0) + 1.0)
    assert not z[outside].any()
    if made == "none":
        assert not z.any()
        return
    expected = wake_elevation(shape.ship, 3.0, np.array([15.0, 0.0]), 0.0, vertices[:, :2])
    np.testing.assert_allclose(z, expected, atol=1e-5)  # drawn in float32
    assert np.abs(z[inside]).max() > 0.1  # decimetres behind a 4 m box at Fn 0.48


def test_the_sea_drawn_carries_the_waves_a_boat_scatters():
    """A default box at rest in SEA: the sea drawn is the sea's surface plus the waves the box
    radiates and scatters (scattered_waves.outgoing_elevation: millimetres to centimetres
    a few metres off), and only the sea's for a box that makes none."""
    from boat_dynamics.physics.wave_making.scattered_waves import outgoing_elevation

    drawn = {}
    for made in ("scattered", "none"):
        spec = parse_scenario({"boats": [{"hydrodynamics": {"made_waves": made}}]}).boats[0]
        scene = Drawn({"": hull_shape(spec.params)}, sea_size=30.0, sea_resolution=1.0,
                      sea_period=1.0)
        scene.pose(2.0, "", (0.0, 0.0, 0.0), (0.0, 0.0, math.sin(0.3), math.cos(0.3)))
        scene.sea(2.0, SEA)
        drawn[made] = _values(scene.at("world/sea")[-1][1].vertex_positions)
    xy = drawn["none"][:, :2]
    made = drawn["scattered"][:, 2] - drawn["none"][:, 2]
    hydro = hull_shape(parse_scenario({"boats": [{}]}).boats[0].params).hydro
    expected = outgoing_elevation(hydro, SEA, np.zeros(2), 0.6, xy, 2.0)
    np.testing.assert_allclose(made, expected, atol=1e-5)
    assert np.abs(made).max() > 0.005
