"""The compiled rudder lift and thrust against their numpy oracles, for stacked groups."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.force_models.propulsion import Propulsion, _thrust_numpy, thrust
from boat_dynamics.physics.force_models.rudder import Rudder, _lift_numpy, rudder_wrench

_GROUP = dict(seed=st.integers(0, 2**32 - 1), boats=st.integers(1, 12))


def _close(got, want):
    for name in ("force", "torque"):
        a, b = getattr(got, name), getattr(want, name)
        assert a.shape == b.shape, name
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * (np.abs(b).max() + 1.0),
                                   err_msg=name)


@settings(max_examples=100, deadline=None)
@given(shared=st.booleans(), **_GROUP)
def test_the_compiled_rudder_lift_equals_numpys(seed, boats, shared):
    rng = np.random.default_rng(seed)
    g = (boats,)
    model = Rudder("lift", area=rng.uniform(0.01, 2.0, g), lift_coefficient=rng.uniform(1, 6, g),
                   position=rng.normal(size=(boats, 3)) * 3.0, skeg_area=rng.uniform(0, 1, g))
    if shared:  # one boat's parameters (floats and a vector) shared by the group
        model = Rudder("lift", area=0.3, lift_coefficient=2.5, position=np.array([-2, 0, -0.4]),
                       skeg_area=0.1)
    args = (rng.uniform(-0.6, 0.6, g), rng.normal(size=(boats, 3)) * 4.0,
            rng.normal(size=(boats, 3)) * 0.5, rng.uniform(1000.0, 1030.0, g),
            rng.normal(size=(boats, 3)) * 0.3)
    got = rudder_wrench(model, *args)
    _close(got, _lift_numpy(model, *args, np.zeros(boats)))


@settings(max_examples=100, deadline=None)
@given(steerable=st.booleans(), at_com=st.booleans(), **_GROUP)
def test_the_compiled_thrust_equals_numpys(seed, boats, steerable, at_com):
    rng = np.random.default_rng(seed)
    direction = rng.normal(size=(boats, 3))
    model = Propulsion(rng.uniform(10.0, 1e4, boats), rng.normal(size=(boats, 3)) * 3.0,
                       direction / np.linalg.norm(direction, axis=1, keepdims=True),
                       steerable=steerable, at_center_of_mass=at_com)
    args = (rng.uniform(-1, 1, boats), rng.uniform(-0.6, 0.6, boats),
            rng.normal(size=(boats, 3)) * 0.3)
    _close(thrust(model, *args), _thrust_numpy(model, *args))


def test_a_group_of_one_is_the_single_boat_call():
    """The compiled group path and the numpy one-boat path give one boat the same wrench."""
    rudder = Rudder("lift", position=np.array([-2.0, 0.0, -0.3]), skeg_area=0.05)
    com = np.array([0.1, 0.0, -0.2])
    one = rudder_wrench(rudder, 0.2, np.array([3.0, 0.4, 0.0]), np.array([0.0, 0.0, 0.1]),
                        1025.0, com)
    group = rudder_wrench(rudder, np.array([0.2]), np.array([[3.0, 0.4, 0.0]]),
                          np.array([[0.0, 0.0, 0.1]]), np.array([1025.0]), com[None])
    np.testing.assert_allclose(group.force[0], one.force, rtol=1e-14)
    np.testing.assert_allclose(group.torque[0], one.torque, rtol=1e-14)
    assert one.force[1] < 0.0 < one.torque[2]  # a port angle pushes the stern to starboard
