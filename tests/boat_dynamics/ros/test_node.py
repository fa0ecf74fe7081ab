"""The dynamics node's policies that need no running node."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.ros.node import SimClock, advertises_wrenches, ready_topics
from boat_msgs_py.cdr import stamp_parts


def test_wrench_topics_are_advertised_up_to_a_hundred_boats_or_when_asked():
    assert advertises_wrenches("auto", 100, False)
    assert not advertises_wrenches("auto", 101, False)
    assert advertises_wrenches("advertised", 1000, False)
    assert not advertises_wrenches("on_subscription", 2, False)
    # a recorder process records what it finds on the graph: everything is advertised
    assert advertises_wrenches("on_subscription", 1000, True)


@settings(max_examples=200, deadline=None)
@given(epoch=st.floats(1.6e9, 2.1e9), rate_hz=st.sampled_from([10.0, 50.0, 100.0, 200.0, 400.0]),
       start=st.integers(0, 10**7))
def test_stamps_are_integer_nanoseconds_a_step_apart_whatever_the_wall_clock_epoch(
        epoch, rate_hz, start):
    """A wall-clock epoch (1.7e9 s) plus the simulation time in one float rounds to 238 ns:
    the stamps of steps 10 ms apart then differed by 10 ms +-238 ns (issue 30). In integer
    ns they are exactly a step apart, and the epoch's own ns stay what they were."""
    clock = SimClock(rate_hz=rate_hz, epoch=epoch, steps=start)
    stamps = []
    for _ in range(5):
        stamps.append(clock.stamp_ns())
        clock.steps += 1
    assert set(np.diff(stamps)) == {round(1e9 / rate_hz)}
    assert stamps[0] == round(epoch * 1e9) + round(start / rate_hz * 1e9)
    sec, nanosec = clock.stamp()
    assert sec * 10**9 + nanosec == clock.stamp_ns() and 0 <= nanosec < 10**9
    assert stamp_parts(start / rate_hz, epoch) == divmod(stamps[0], 10**9)


def test_a_topic_is_ready_once_every_lockstep_client_publishing_it_was_seen_twice():
    a, b = ("harness", "/"), ("boatsim_replay", "/")
    first = {(*a, "/cmd_thrust")}
    assert ready_topics(first, set()) == set()  # seen once: DDS may not have matched yet
    second = first | {(*a, "/cmd_rudder"), (*b, "/cmd_thrust")}
    # /cmd_thrust: a second client publishes it now, seen once; /cmd_rudder: new
    assert ready_topics(second, first) == set()
    assert ready_topics(second, second) == {"/cmd_thrust", "/cmd_rudder"}
    # a client gone from the graph: what the others publish stays ready
    assert ready_topics({(*a, "/cmd_rudder")}, second) == {"/cmd_rudder"}
