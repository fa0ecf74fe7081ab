"""Sea trials (physics/experiments/trials.py): copies of a boat driven side by side."""

import math
from dataclasses import replace

import numpy as np
import pytest
from ready_scenarios import ready, seed

from boat_dynamics.physics.core.model import initial_state, reference_pose
from boat_dynamics.physics.experiments.trials import Order, orders_for, sea_trials
from ocean_sim.physics.waves import WaveComponent, WaveField

SEA = WaveField((WaveComponent(0.2, 20.0, 0.0, 0.5, 0.0),))


def _boat(**extra):
    sc = ready({"boats": [seed(extra)]})
    return sc.boats[0]


def test_copies_on_their_headings_meet_the_waves_as_ordered():
    boat = _boat()
    orders = [Order("head", math.pi, 1.0, 0.0), Order("following", 0.0, 1.0, 0.0)]
    track = sea_trials(boat, SEA, orders, 2.0, 0.01)
    assert track.t[0] == 0.0 and track.t[-1] == pytest.approx(2.0)
    # the waves travel toward +x: head seas means heading -x
    assert math.cos(track.attitude[0, 0, 2]) == pytest.approx(-1.0, abs=1e-9)
    assert math.cos(track.attitude[1, 0, 2]) == pytest.approx(1.0, abs=1e-9)
    assert track.velocity[:, -1, 0].min() > 0.1  # both driven ahead


def test_one_boat_per_order_steps_as_the_same_boat_given_once():
    # the calm-water runs of the driving suite put a heeled copy beside the others
    boat = _boat()
    orders = [Order("a", 0.0, 1.0, 0.0), Order("b", 1.0, 0.5, 0.2)]
    once = sea_trials(boat, SEA, orders, 1.0, 0.01)
    each = sea_trials([boat, boat], SEA, orders, 1.0, 0.01)
    assert np.array_equal(once.position, each.position)
    assert np.array_equal(once.velocity, each.velocity)
    heeled = replace(boat, initial=initial_state(
        boat.params, reference_pose(boat.params, boat.initial)[0], roll=math.radians(10.0)))
    mixed = sea_trials([boat, heeled], SEA, orders, 1.0, 0.01)
    assert np.array_equal(mixed.position[0], once.position[0])  # a boat ignores the others
    assert mixed.attitude[1, 0, 0] == pytest.approx(math.radians(10.0), abs=1e-9)
    with pytest.raises(ValueError, match="3 boats for 2 orders"):
        sea_trials([boat] * 3, SEA, orders, 1.0, 0.01)


def test_a_twin_screw_boat_without_a_rudder_turns_by_differential_thrust():
    twin = _boat(rudder={"model": "none"}, propulsion=[
        {"name": "left", "max_thrust": 500.0, "position": [-2.0, 0.8, -0.4]},
        {"name": "right", "max_thrust": 500.0, "position": [-2.0, -0.8, -0.4]}])
    order = orders_for(twin.params, "turn", 0.0, 0.8, 0.3)
    share = 0.3 / float(twin.params.rudder.max_angle)
    assert order.throttle == pytest.approx((0.8 * (1.0 - share), 0.8))  # port side slower
    assert order.rudder == 0.0
    track = sea_trials(twin, WaveField(), [order], 10.0, 0.01)
    assert track.attitude[0, -1, 2] > math.radians(5.0)  # turned to port (CCW)
    ruddered = _boat()
    assert orders_for(ruddered.params, "turn", 0.0, 0.8, 0.3) == Order("turn", 0.0, 0.8, 0.3)
