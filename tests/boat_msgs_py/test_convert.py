"""Conversions between the numpy core and ROS messages (no ROS graph needed)."""

import math

import pytest
from boat_msgs.msg import WaveComponent as WaveComponentMsg
from boat_msgs.msg import WaveField as WaveFieldMsg
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_msgs_py.convert import (
    diagnostic_array,
    seconds_to_time,
    time_to_seconds,
    wave_field_from_msg,
    wave_field_to_msg,
)
from ocean_sim.physics.waves import InvalidSeaStateError, WaveComponent, WaveField


@settings(max_examples=300, deadline=None)
@given(seconds=st.floats(min_value=0.0, max_value=2.0e9, allow_nan=False))
def test_time_round_trip_keeps_the_nanosecond(seconds):
    stamp = seconds_to_time(seconds)
    assert 0 <= stamp.nanosec < 1_000_000_000 and stamp.sec >= 0
    # exact to the nanosecond, or to the float's own resolution for large times
    # half a nanosecond of rounding, plus the float error of sec + nanosec * 1e-9
    assert abs(time_to_seconds(stamp) - seconds) <= 0.5e-9 + 4 * math.ulp(seconds)


def test_time_carries_into_the_second():
    stamp = seconds_to_time(1.9999999999)  # rounds to 2 s, not 1 s + 1e9 ns
    assert (stamp.sec, stamp.nanosec) == (2, 0)


components = st.builds(
    WaveComponent,
    amplitude=st.floats(0.0, 0.15),
    wavelength=st.floats(5.0, 200.0),
    direction=st.floats(-math.pi, math.pi),
    steepness=st.floats(0.0, 1.0),
    phase=st.floats(0.0, 2 * math.pi),
)


@settings(max_examples=100, deadline=None)
@given(comps=st.lists(components, max_size=5), depth=st.sampled_from([math.inf, 12.5, 300.0]),
       gravity=st.floats(9.0, 10.0))
def test_wave_field_round_trip_is_exact(comps, depth, gravity):
    # sum Q k a <= 5 x 1 x (2 pi / 5 m) x 0.15 m = 0.94: always a valid sea
    sea = WaveField(tuple(comps), gravity=gravity, depth=depth)
    msg = wave_field_to_msg(sea, seconds_to_time(12.5))
    assert msg.header.frame_id == "world" and msg.header.stamp.sec == 12
    assert wave_field_from_msg(msg) == sea


def test_an_invalid_wave_field_message_is_refused_naming_the_field():
    msg = WaveFieldMsg(gravity=9.81, depth=math.inf, components=[
        WaveComponentMsg(amplitude=0.5, wavelength=-3.0, direction=0.0, steepness=0.5,
                         phase=0.0)])
    with pytest.raises(InvalidSeaStateError, match=r"components\[0\]\.wavelength"):
        wave_field_from_msg(msg)


def test_diagnostic_array_keeps_level_name_message_and_values():
    arr = diagnostic_array(seconds_to_time(3.0), [
        ("boatsim: alpha", 1, "submerged", (("draft_m", "0.51"), ("gm_m", "0.42"))),
        ("boatsim: bravo", 0, "ok", ())])
    assert [s.name for s in arr.status] == ["boatsim: alpha", "boatsim: bravo"]
    alpha = arr.status[0]
    assert alpha.level == b"\x01" and alpha.message == "submerged"
    assert alpha.hardware_id == "boatsim: alpha"
    assert [(v.key, v.value) for v in alpha.values] == [("draft_m", "0.51"), ("gm_m", "0.42")]
    assert arr.status[1].values == []


def test_a_hostile_environment_message_is_refused_before_it_allocates():
    # any node on the domain may publish /ocean/environment: 4e9 gust components (a uint32)
    # once made the dynamics node allocate 29.8 GiB and die; the bounds are the parameters'
    from boat_msgs.msg import Environment as EnvironmentMsg

    from boat_msgs_py.convert import environment_from_msg
    from ocean_sim.physics.environment import InvalidEnvironmentError

    msg = EnvironmentMsg(wind_speed=10.0, gusts="norsok", gust_components=4_000_000_000)
    with pytest.raises(InvalidEnvironmentError, match=r"wind\.gust_components: 4000000000"):
        environment_from_msg(msg)
    msg = EnvironmentMsg(current_speed=25.0, wind_speed=1.0, gusts="none", gust_components=50)
    with pytest.raises(InvalidEnvironmentError, match=r"current.speed: 25.0 .* \[0, 20\] m/s"):
        environment_from_msg(msg)
    msg = EnvironmentMsg(wind_speed=10.0, gusts="norsok", gust_components=1000, seed=3)
    assert environment_from_msg(msg).wind.frequencies.size == 1000


def test_a_wave_field_message_of_too_many_components_is_refused_before_it_is_built():
    one = WaveComponentMsg(amplitude=0.01, wavelength=50.0, direction=0.0, steepness=0.0,
                           phase=0.0)
    msg = WaveFieldMsg(gravity=9.81, depth=math.inf, components=[one] * 20_000)
    with pytest.raises(InvalidSeaStateError, match=r"20000 components.*at most 4096"):
        wave_field_from_msg(msg)


@pytest.mark.parametrize("data", [[1.0], [math.nan, 3.0], [1.0, math.inf], [-1.0, 2.0],
                                  [1.0, -2.0], [1.0, 1e300]])
def test_a_lockstep_grant_out_of_bounds_is_refused(data):
    # an infinite command count raised OverflowError inside the node's callback
    from boat_msgs_py.convert import lockstep_grant

    with pytest.raises(ValueError, match=r"grant is|finite and >= 0"):
        lockstep_grant(data)


def test_a_lockstep_grant_is_the_time_and_the_count():
    from boat_msgs_py.convert import lockstep_grant

    assert lockstep_grant([2.5, 7.0]) == (2.5, 7)
    assert lockstep_grant([1e18, 3.0]) == (1e18, 3)  # the replayer's last grant


def test_an_fft_tiles_message_carries_its_tile_and_an_old_message_none():
    from types import SimpleNamespace

    from ocean_sim.physics.fft import TileSpec, tile_sea

    sea = tile_sea(TileSpec(size=80.0, resolution=8, seed=1))
    msg = wave_field_to_msg(sea, seconds_to_time(0.0))
    assert (msg.tile_size, msg.tile_resolution) == (80.0, 8)
    assert wave_field_from_msg(msg) == sea and wave_field_from_msg(msg).tile == sea.tile
    gerstner = wave_field_to_msg(WaveField(sea.components), seconds_to_time(0.0))
    assert (gerstner.tile_size, gerstner.tile_resolution) == (0.0, 0)
    assert wave_field_from_msg(gerstner).tile is None
    # a bag recorded before the tile fields: its messages have none
    old = SimpleNamespace(gravity=msg.gravity, depth=msg.depth, components=msg.components)
    assert wave_field_from_msg(old) == WaveField(sea.components)
    msg.tile_size = 81.0  # components off the lattice it names: refused
    with pytest.raises(InvalidSeaStateError, match="must lie on the tile's lattice"):
        wave_field_from_msg(msg)
