"""The surface server's inputs: the shared time, the ocean's parameter events, its sea state.

No ROS graph: the callbacks are fed directly (the end-to-end answers are checked in
tests/ros/test_end_to_end.py and test_ocean_node.py).
"""

import numpy as np
import pytest
from boat_msgs.srv import SampleSurface
from geometry_msgs.msg import Point
from rcl_interfaces.msg import Parameter, ParameterEvent, ParameterValue

from boat_msgs_py.convert import seconds_to_time, wave_field_to_msg
from boat_msgs_py.process import SharedTime
from ocean_sim.physics.waves import WaveComponent, WaveField, sample_surface
from ocean_sim.ros.surface_server import SurfaceServer

SEA = WaveField(components=(WaveComponent(amplitude=0.4, wavelength=20.0, steepness=0.5),))
XY = np.array([[1.0, 2.0], [-7.5, 3.25]])


@pytest.fixture
def server(ros_context):
    node = SurfaceServer(lambda: 42.25, context=ros_context)
    yield node
    node.destroy_node()


def _ask(server, t=None) -> SampleSurface.Response:
    stamp = seconds_to_time(0.0) if t is None else seconds_to_time(100.0 + t)
    request = SampleSurface.Request(stamp=stamp, points=[Point(x=x, y=y) for x, y in XY])
    return server._on_sample(request, SampleSurface.Response())


def test_no_service_and_no_answer_before_the_first_sea_state(server):
    assert server._service is None
    answer = _ask(server)
    assert not answer.success and "no sea state yet" in answer.message


def test_answers_from_the_published_sea_at_the_clock_time(server):
    server._on_field(wave_field_to_msg(SEA, seconds_to_time(100.0)))  # epoch 100 s
    assert server._service is not None
    now = _ask(server)  # a zero stamp: the simulation's time now, 42.25 s
    stamped = _ask(server, t=3.5)
    assert np.array(now.heights) == pytest.approx(
        sample_surface(SEA, XY, 42.25).heights, abs=1e-15)
    assert np.array(stamped.heights) == pytest.approx(
        sample_surface(SEA, XY, 3.5).heights, abs=1e-15)


def test_a_point_beyond_the_bound_is_refused_and_a_failure_answered(server, monkeypatch):
    server._on_field(wave_field_to_msg(SEA, seconds_to_time(100.0)))
    far = SampleSurface.Request(points=[Point(x=1.0, y=2.0), Point(x=1e308, y=0.0)])
    answer = server._on_sample(far, SampleSurface.Response())
    assert not answer.success and "points[1] = (1e+308, 0.0)" in answer.message
    assert "beyond +-1e+07 m" in answer.message

    def broken(*args, **kwargs):
        raise FloatingPointError("overflow")

    monkeypatch.setattr("ocean_sim.ros.node.sample", broken)
    answer = _ask(server)  # answered, and the server goes on
    assert not answer.success
    assert answer.message == "could not sample the surface: FloatingPointError: overflow"


def test_follows_the_ocean_nodes_precision_only(server):
    server._on_field(wave_field_to_msg(SEA, seconds_to_time(100.0)))

    def event(node, value):
        return ParameterEvent(node=node, changed_parameters=[Parameter(
            name="precision", value=ParameterValue(type=4, string_value=value))])

    server._on_parameters(event("/someone_else", "float32"))
    assert server._precision == "float64"
    server._on_parameters(event("/ocean", "float32"))
    answer = _ask(server, t=1.0)
    assert np.array(answer.heights) == pytest.approx(
        sample_surface(SEA, XY, 1.0, precision="float32").heights, abs=1e-15)
    server._on_parameters(event("/ocean", "not-a-precision"))
    assert server._precision == "float32"


def test_the_shared_time_is_read_in_another_process(tmp_path):
    import subprocess
    import sys

    shared = SharedTime()
    try:
        shared.write(1234.5678)
        read = subprocess.run([sys.executable, "-c", "import sys; from boat_msgs_py.process "
                               "import SharedTime; print(SharedTime(sys.argv[1]).read())",
                               str(shared.path)], capture_output=True, text=True, check=True)
        assert float(read.stdout) == 1234.5678
    finally:
        shared.close()
    assert not shared.path.exists()
