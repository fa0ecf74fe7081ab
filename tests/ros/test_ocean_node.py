"""The ocean node over ROS: sea state as parameters, /ocean/surface, `boatsim query`."""

import math
import subprocess
import sys
import time

import numpy as np
import pytest
import yaml
from boat_msgs.msg import WaveField
from boat_msgs.srv import SampleSurface
from nav_msgs.msg import Odometry
from rcl_interfaces.msg import Parameter as ParameterMsg
from rcl_interfaces.msg import ParameterType, ParameterValue
from rcl_interfaces.srv import GetParameters, SetParameters, SetParametersAtomically
from sensor_msgs.msg import PointCloud2

from boat_dynamics.physics.scenario import default_scenario_path
from boat_msgs_py import names
from boat_msgs_py.convert import time_to_seconds, wave_field_from_msg
from boat_msgs_py.qos import WAVE_FIELD_QOS
from ocean_sim.physics.waves import sample_surface


def _double_array(name, values):
    return ParameterMsg(name=name, value=ParameterValue(
        type=ParameterType.PARAMETER_DOUBLE_ARRAY, double_array_value=list(values)))


def _double(name, value):
    return ParameterMsg(name=name, value=ParameterValue(
        type=ParameterType.PARAMETER_DOUBLE, double_value=value))


def _fields(probe):
    fields = []
    probe.node.create_subscription(WaveField, names.WAVE_FIELD, fields.append, WAVE_FIELD_QOS)
    probe.spin_until(lambda: fields, 30.0, "/ocean/wave_field")
    return fields


def test_sea_state_parameters_change_at_run_time_and_bad_changes_are_refused(boatsim, probe):
    sim = boatsim("run", "--fast")
    fields = _fields(probe)
    assert len(fields[0].components) == 3
    get = probe.node.create_client(GetParameters, "/ocean/get_parameters")
    current = probe.call(get, GetParameters.Request(names=["components.amplitude", "depth"]))
    assert list(current.values[0].double_array_value) == [0.3, 0.15, 0.08]
    assert math.isinf(current.values[1].double_value)

    atomically = probe.node.create_client(SetParametersAtomically,
                                          "/ocean/set_parameters_atomically")
    new = [_double_array("components.amplitude", [0.5, 0.2]),
           _double_array("components.wavelength", [30.0, 10.0]),
           _double_array("components.direction", [1.0, 0.0]),
           _double_array("components.steepness", [0.6, 0.3]),
           _double_array("components.phase", [0.0, 1.0]),
           _double("depth", 40.0)]
    result = probe.call(atomically, SetParametersAtomically.Request(parameters=new)).result
    assert result.successful, result.reason
    probe.spin_until(lambda: len(fields) >= 2, 10.0, "the new wave field")
    sea = wave_field_from_msg(fields[-1])
    assert [c.amplitude for c in sea.components] == [0.5, 0.2] and sea.depth == 40.0

    # the service answers with the new sea
    client = probe.node.create_client(SampleSurface, names.SAMPLE_SURFACE)
    epoch = time_to_seconds(fields[-1].header.stamp)
    from geometry_msgs.msg import Point

    from boat_msgs_py.convert import seconds_to_time
    xy = np.array([[3.0, 4.0], [-20.0, 7.5]])
    expected = sample_surface(sea, xy, 2.0)

    def answers_the_new_sea() -> bool:  # the surface server has its own subscription to it
        answer = probe.call(client, SampleSurface.Request(
            stamp=seconds_to_time(epoch + 2.0), points=[Point(x=x, y=y) for x, y in xy]))
        return answer.success and np.abs(np.array(answer.heights)
                                          - expected.heights).max() < 1e-9

    probe.spin_until(answers_the_new_sea, 10.0, "an answer from the new sea")

    # refusals: the reason names the key and the value; the old sea stays
    single = probe.node.create_client(SetParameters, "/ocean/set_parameters")
    cases = [
        ([_double_array("components.wavelength", [30.0, -1.0])],
         "components[1].wavelength = -1.0 is not allowed: must be > 0 (m)"),
        ([_double_array("components.amplitude", [0.5, 0.2, 0.1])],
         "component arrays must have the same length"),
        ([_double_array("components.amplitude", [8.0, 0.2])], "crests loop"),  # sum Q k a 1.04
        ([_double("depth", -3.0)], "depth = -3.0 is not allowed"),
        ([_double("surface.size", 2000.0)],  # 1 m apart: 4e6 points
         "would make 4e+06 /ocean/surface points; at most 1e+06"),
    ]
    for params, reason in cases:
        res = probe.call(single, SetParameters.Request(parameters=params)).results[0]
        assert not res.successful and reason in res.reason, res.reason
    # each in range, together 1.6e9 points: before, MemoryError took every node down
    res = probe.call(atomically, SetParametersAtomically.Request(parameters=[
        _double("surface.size", 2000.0), _double("surface.resolution", 0.05)])).result
    assert not res.successful
    assert "would make 1.6e+09 /ocean/surface points; at most 1e+06" in res.reason
    probe.spin_for(0.3)
    assert wave_field_from_msg(fields[-1]) == sea  # nothing new published
    again = probe.call(get, GetParameters.Request(names=["components.amplitude"]))
    assert list(again.values[0].double_array_value) == [0.5, 0.2]
    # the dynamics node has the new sea: as an update, or as its first one when the change
    # came before it subscribed (the ocean's node is made first; seen once with both cores
    # busy). Its log line comes when its executor has served the message: with both cores
    # busy that was after the checks above once, so wait for it (sim time does not matter).
    probe.spin_until(lambda: ("updated sea state: 2 components" in sim.output()
                              or "received sea state: 2 components" in sim.output()),
                     30.0, "the dynamics node's log of the new sea state")
    assert sim.stop() == 0
    assert "new sea state: 2 components" in sim.output()


def test_surface_cloud_is_the_surface_around_the_boat(boatsim, probe):
    sim = boatsim("run", "--fast")
    fields = _fields(probe)
    sea = wave_field_from_msg(fields[0])
    clouds, odoms = [], []
    probe.node.create_subscription(PointCloud2, names.SURFACE_CLOUD, clouds.append, 10)
    probe.node.create_subscription(Odometry, "/odom", odoms.append, 1000)

    def stamp(msg):
        return msg.header.stamp.sec, msg.header.stamp.nanosec

    def pair():
        """A cloud received and the /odom received with its stamp, or None."""
        at = {stamp(o): o for o in odoms}
        return next(((c, at[stamp(c)]) for c in clouds if stamp(c) in at), None)

    # The boat drifts meanwhile, and a --fast run may be tens of seconds in before the probe's
    # subscriptions match: the cloud is compared with where the boat was at its stamp.
    probe.spin_until(lambda: pair() is not None, 30.0, "/ocean/surface and /odom of one stamp")
    cloud, odom = pair()
    assert cloud.header.frame_id == "world"
    assert [f.name for f in cloud.fields] == ["x", "y", "z", "normal_x", "normal_y", "normal_z"]
    pts = np.frombuffer(bytes(cloud.data), dtype=np.float32).reshape(-1, 6)
    assert pts.shape[0] == cloud.width == 41 * 41  # 40 m at 1 m, around the one boat
    at = odom.pose.pose.position  # the grid's centre: the boat's position on the 1 m grid
    assert abs(pts[:, 0].mean() - at.x) <= 0.5 + 1e-5 and abs(pts[:, 1].mean() - at.y) <= 0.5 + 1e-5
    t = time_to_seconds(cloud.header.stamp) - time_to_seconds(fields[0].header.stamp)
    expected = sample_surface(sea, pts[:, :2].astype(float), t)
    assert np.abs(pts[:, 2] - expected.heights).max() < 1e-4
    assert np.abs(pts[:, 3:] - expected.normals).max() < 1e-4
    assert sim.stop() == 0


def test_boatsim_query_prints_the_library_numbers(boatsim, probe):
    sim = boatsim("run")
    fields = _fields(probe)
    sea = wave_field_from_msg(fields[0])
    out = subprocess.run([sys.executable, "-m", "boat_dynamics", "query", "3", "-4", "12.5",
                          "8", "--time", "7.5"], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    rows = [line.split() for line in out.stdout.splitlines() if not line.startswith("#")]
    assert len(rows) == 2
    expected = sample_surface(sea, np.array([[3.0, -4.0], [12.5, 8.0]]), 7.5)
    for row, h in zip(rows, expected.heights, strict=True):
        assert float(row[2]) == round(float(h), 4) or abs(float(row[2]) - h) <= 6e-5
    assert sim.stop() == 0


def test_boatsim_query_without_an_ocean_exits_1():
    out = subprocess.run([sys.executable, "-m", "boat_dynamics", "query", "1", "2",
                          "--timeout", "1"], capture_output=True, text=True, timeout=60)
    assert out.returncode == 1
    assert "did not answer within 1 s" in out.stderr and "Traceback" not in out.stderr


def test_diagnostics_and_control_mode_switch_at_run_time(boatsim, probe, tmp_path):
    from diagnostic_msgs.msg import DiagnosticArray
    from rcl_interfaces.msg import ParameterType, ParameterValue

    # The default scenario's boat in calm water: it floats at its equilibrium, so every
    # /diagnostics array, whichever the probe receives, reports its displacement. (In the
    # default waves the mean over the first 20 arrays received depended on which ones
    # arrived: 4.61 m^3 once with both cores busy.)
    scenario = yaml.safe_load(default_scenario_path().read_text())
    scenario["ocean"]["components"] = []
    calm = tmp_path / "calm.yaml"
    calm.write_text(yaml.safe_dump(scenario))
    sim = boatsim("run", str(calm), "--fast")
    arrays = []
    probe.node.create_subscription(DiagnosticArray, "/diagnostics", arrays.append, 10)
    probe.spin_until(lambda: len(arrays) >= 20, 30.0, "/diagnostics")
    status = arrays[-1].status[0]
    values = {kv.key: kv.value for kv in status.values}
    assert status.name == "boatsim: boat" and values["control_mode"] == "dynamic"
    volumes = [float({kv.key: kv.value for kv in a.status[0].values}["submerged_volume_m3"])
               for a in arrays]
    # 4100 kg / 1025 kg/m^3: half of the 4 x 2 x 1 m box
    assert volumes == pytest.approx([4.0] * len(volumes), abs=1e-3)

    set_params = probe.node.create_client(SetParameters, "/boat_dynamics/set_parameters")

    def mode(value):
        p = ParameterMsg(name="control_mode", value=ParameterValue(
            type=ParameterType.PARAMETER_STRING, string_value=value))
        return probe.call(set_params, SetParameters.Request(parameters=[p])).results[0]

    bad = mode("hovercraft")
    assert not bad.successful and "control_mode = 'hovercraft' is not allowed" in bad.reason
    assert mode("kinematic").successful
    # (waited for: up to 9 older arrays may still be queued when the reply is served)
    probe.spin_until(lambda: {kv.key: kv.value for kv in arrays[-1].status[0].values}[
        "control_mode"] == "kinematic", 10.0, "a /diagnostics array in kinematic mode")
    assert sim.stop() == 0
    assert "control_mode: now kinematic" in sim.output()


def test_surface_cloud_is_sampled_only_while_someone_subscribes_or_records():
    import rclpy

    from boat_msgs_py.qos import SURFACE_QOS
    from ocean_sim.physics.waves import WaveComponent
    from ocean_sim.physics.waves import WaveField as Sea
    from ocean_sim.ros.node import OceanNode

    sea = Sea((WaveComponent(0.3, 20.0, 0.3, 0.6, 0.0),))
    rclpy.init()
    try:
        node = OceanNode(sea, now=lambda: 0.0)
        sampled = []
        node.surface_cloud = lambda t: sampled.append(t) or PointCloud2()
        try:
            node.advance(0.0)  # nobody on /ocean/surface: nothing sampled
            assert sampled == []
            listener = rclpy.create_node("cloud_listener")
            listener.create_subscription(PointCloud2, names.SURFACE_CLOUD, lambda m: None,
                                         SURFACE_QOS)
            t, deadline = 1.0, time.monotonic() + 20.0
            while not sampled and time.monotonic() < deadline:  # matched within the DDS
                node.advance(t)  # discovery, then asked at the next 1 s check
                t += 1.0
                time.sleep(0.2)
            assert sampled, "a subscriber did not make the cloud published"
            listener.destroy_node()
        finally:
            node.destroy_node()
    finally:
        rclpy.try_shutdown()


def test_surface_cloud_of_overlapping_boats_is_one_grid_without_duplicates():
    import rclpy

    from ocean_sim.physics.waves import WaveComponent
    from ocean_sim.physics.waves import WaveField as Sea
    from ocean_sim.ros.node import OceanNode

    centers = np.array([[0.0, 0.0], [10.3, 0.2], [0.4, -25.0]])
    sea = Sea((WaveComponent(0.3, 20.0, 0.3, 0.6, 0.0),))
    rclpy.init()
    try:
        from rclpy.parameter import Parameter

        from boat_msgs_py.tap import Tap

        published = []
        node = OceanNode(sea, now=lambda: 0.0, surface_centers=lambda: centers,
                         tap=Tap(lambda topic, _type, _data: published.append(topic)))
        try:
            cloud = node.surface_cloud(2.0)
            node.advance(0.0)
            assert published.count(names.SURFACE_CLOUD) == 1
            node.advance(0.5)  # 1 Hz: not due yet
            node.advance(1.0)
            assert published.count(names.SURFACE_CLOUD) == 2
            assert node.set_parameters([Parameter("surface.rate_hz", value=0.0)])[0].successful
            node.advance(5.0)  # off
            assert published.count(names.SURFACE_CLOUD) == 2
        finally:
            node.destroy_node()
    finally:
        rclpy.try_shutdown()
    pts = np.frombuffer(bytes(cloud.data), dtype=np.float32).reshape(-1, 6)
    cells = np.round(pts[:, :2].astype(float)).astype(int)
    assert len({tuple(c) for c in cells}) == len(cells) == cloud.width  # each point once
    assert np.allclose(pts[:, :2], cells, atol=1e-4)  # on the world's 1 m grid
    # the union of three 41 x 41 squares: [-20, 30] x [-20, 20] with [-20, 20] x [-45, -5]
    expected = {(x, y) for c in np.round(centers).astype(int)
                for x in range(c[0] - 20, c[0] + 21) for y in range(c[1] - 20, c[1] + 21)}
    assert {tuple(c) for c in cells} == expected
    np.testing.assert_allclose(pts[:, 2], sample_surface(sea, pts[:, :2].astype(float),
                                                         2.0).heights, atol=1e-4)
    # a Gerstner sea's cloud is the inverted query at the grid's points, bit for bit as before
    # the FFT tile's grid (the float32 of sample_surface's answer there)
    xy = cells.astype(float)
    s = sample_surface(sea, xy, 2.0)
    np.testing.assert_array_equal(
        pts, np.column_stack([xy, s.heights, s.normals]).astype(np.float32))


def test_surface_cloud_of_an_fft_sea_is_its_grid_particles_exact_at_the_nodes():
    import rclpy

    from ocean_sim.physics.fft import TileSpec, tile_sea
    from ocean_sim.physics.waves import displace
    from ocean_sim.ros.node import OceanNode

    # rest points on the tile's 1 m grid (L = 150 m, M = 150) around boats 180 m apart: the
    # periodic tile over more than one period
    centers = np.array([[0.0, 0.0], [180.3, -20.2]])
    sea = tile_sea(TileSpec(size=150.0, resolution=16, seed=2, spectrum="jonswap",
                            significant_height=1.5, peak_period=7.0, choppiness=0.9))
    rclpy.init()
    try:
        node = OceanNode(sea, now=lambda: 0.0, surface_centers=lambda: centers)
        try:
            cloud = node.surface_cloud(31.5)
        finally:
            node.destroy_node()
    finally:
        rclpy.try_shutdown()
    pts = np.frombuffer(bytes(cloud.data), dtype=np.float32).reshape(-1, 6).astype(float)
    rest = np.array(sorted({(x, y) for c in np.round(centers).astype(int)
                            for x in range(c[0] - 20, c[0] + 21)
                            for y in range(c[1] - 20, c[1] + 21)}), dtype=float)
    assert cloud.width == len(rest)
    np.testing.assert_allclose(pts[:, :3], displace(sea, rest, 31.5), rtol=0, atol=2e-5)
    assert np.abs(pts[:, :2] - rest).max() > 0.05  # x, y displaced (Q a ~ 0.1 m)
    s = sample_surface(sea, pts[:, :2], 31.5)  # the inverted query agrees at those points
    assert np.abs(s.heights - pts[:, 2]).max() < 1e-3
    np.testing.assert_allclose(pts[:, 3:], s.normals, rtol=0, atol=1e-4)
