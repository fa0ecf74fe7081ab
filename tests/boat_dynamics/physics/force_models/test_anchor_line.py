"""The anchor line: slack within its reach, a spring beyond, pulling towards its anchor only."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from boat_dynamics.physics.body.rigid_body import quat_from_euler, rotation_matrix
from boat_dynamics.physics.force_models.anchor_line import (
    AnchorLine,
    anchor_line_wrench,
    line_tension,
)

LINE = AnchorLine(anchor=np.array([[0.0, 0.0, -10.0]]), fairlead=np.array([[0.0, 0.0, -0.5]]),
                  length=np.array([10.0]), stiffness=np.array([2e4]), damping=np.array([500.0]))
COM = np.array([[0.0, 0.0, -0.3]])


def _wrench(position, rpy=(0.0, 0.0, 0.0), velocity=(0.0, 0.0, 0.0), rate=(0.0, 0.0, 0.0)):
    rot = rotation_matrix(quat_from_euler(*rpy))[None]
    return anchor_line_wrench(LINE, np.array([position], float), rot,
                              np.array([velocity], float), np.array([rate], float), COM)


def test_a_slack_line_pulls_nothing():
    # the fairlead 9.7 m above the anchor (centre of mass 0.2 m above the fairlead)
    w = _wrench([0.0, 0.0, -0.1])
    assert np.all(w.force == 0.0) and np.all(w.torque == 0.0)
    assert line_tension(np.array([9.99]), np.array([5.0]), np.array([10.0]),
                        np.array([2e4]), np.array([500.0]))[0] == 0.0


def test_a_stretched_line_pulls_k_times_its_stretch_towards_the_anchor():
    # fairlead at (6, 0, -0.5 + 0.2 + z): distance sqrt(36 + 9.7^2) from the anchor
    com = np.array([6.0, 0.0, -0.1 + 0.0])
    fairlead = com + np.array([0.0, 0.0, -0.2])
    along = LINE.anchor[0] - fairlead
    d = np.linalg.norm(along)
    w = _wrench(com)
    np.testing.assert_allclose(w.force[0], 2e4 * (d - 10.0) * along / d, rtol=1e-12)
    # the torque about the centre of mass: lever (0, 0, -0.2) x force
    np.testing.assert_allclose(w.torque[0], np.cross([0.0, 0.0, -0.2], w.force[0]), atol=1e-9)


def test_the_line_damps_its_stretch_but_never_pushes():
    com = np.array([6.0, 0.0, -0.1])
    away, towards = _wrench(com, velocity=(1.0, 0.0, 0.0)), _wrench(com, velocity=(-200.0, 0, 0))
    still = _wrench(com)
    unit = -still.force[0] / np.linalg.norm(still.force[0])  # fairlead away from the anchor
    rate = float(unit[0])  # d' of moving +x at 1 m/s
    extra = np.linalg.norm(away.force[0]) - np.linalg.norm(still.force[0])
    assert math.isclose(extra, 500.0 * rate, rel_tol=1e-9)
    assert np.all(towards.force == 0.0)  # k (d - L) + c d' < 0: a line goes slack, not stiff


def test_the_body_frame_wrench_is_the_world_one_turned():
    com, rpy = np.array([4.0, 5.0, 0.3]), (0.2, -0.1, 1.0)
    w = _wrench(com, rpy)
    rot = rotation_matrix(quat_from_euler(*rpy))
    lever = np.array([0.0, 0.0, -0.2])
    fairlead = com + rot @ lever
    along = LINE.anchor[0] - fairlead
    d = np.linalg.norm(along)
    world = 2e4 * (d - 10.0) * along / d
    np.testing.assert_allclose(rot @ w.force[0], world, rtol=1e-12)
    np.testing.assert_allclose(w.torque[0], np.cross(lever, w.force[0]), atol=1e-9)


finite = st.floats(-30.0, 30.0)


@settings(max_examples=200, deadline=None)
@given(st.tuples(finite, finite, st.floats(-9.0, 2.0)), st.tuples(finite, finite, finite),
       st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(-3.2, 3.2)))
def test_a_line_only_ever_pulls_its_hull_towards_the_anchor(com, velocity, rpy):
    w = _wrench(com, rpy, velocity)
    rot = rotation_matrix(quat_from_euler(*rpy))
    fairlead = np.array(com) + rot @ np.array([0.0, 0.0, -0.2])
    world = rot @ w.force[0]
    assert world @ (LINE.anchor[0] - fairlead) >= -1e-9
    assert np.linalg.norm(world) == 0.0 or np.linalg.norm(LINE.anchor[0] - fairlead) > 10.0
