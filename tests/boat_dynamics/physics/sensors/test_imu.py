"""The IMU model: true specific force and rate against closed forms; noise statistics."""

import math

import numpy as np
import pytest

from boat_dynamics.physics.body.rigid_body import quat_from_euler
from boat_dynamics.physics.core.model import BoatState
from boat_dynamics.physics.sensors import (
    ImuSpec,
    InertialNoise,
    imu_start,
    measure_imu,
    stream_key,
    true_motion,
)

G = 9.81
QUIET = InertialNoise(0.0, 0.0, 0.0, 1.0)


def _state(t, velocity=(0, 0, 0), omega=(0, 0, 0), yaw=0.0):
    return BoatState(t, np.zeros(3), quat_from_euler(0.0, 0.0, yaw), np.array(velocity, float),
                     np.array(omega, float))


def test_a_level_imu_at_rest_reads_plus_g_up():
    omega, force = true_motion(np.zeros(3), _state(0.0), _state(0.01), np.array([1, 2, 3.0]), G)
    np.testing.assert_array_equal(omega, np.zeros(3))
    np.testing.assert_allclose(force, [0.0, 0.0, G], atol=1e-12)


def test_a_tilted_imu_at_rest_reads_gravity_in_its_own_axes():
    roll = 0.3
    before = BoatState(0.0, np.zeros(3), quat_from_euler(roll, 0, 0), np.zeros(3), np.zeros(3))
    after = BoatState(0.01, np.zeros(3), quat_from_euler(roll, 0, 0), np.zeros(3), np.zeros(3))
    _, force = true_motion(np.zeros(3), before, after, np.zeros(3), G)
    # body z tilted by roll about x: gravity's reaction appears on +y and +z (FLU)
    np.testing.assert_allclose(force, [0.0, G * math.sin(roll), G * math.cos(roll)], atol=1e-12)


def test_specific_force_is_the_acceleration_plus_centripetal_plus_tangential():
    # the centre of mass accelerates forward at 2 m/s^2 while the hull turns at 0.5 rad/s
    # with 0.1 rad/s^2; an IMU 1 m ahead of the centre of mass and 0.5 m to port reads
    # a + alpha x r + omega x (omega x r) + g (Titterton & Weston, sec. 3.2), in body axes
    dt, w0, w1 = 0.01, 0.5, 0.5 + 0.1 * 0.01
    com = np.array([0.0, 0.0, -0.2])
    before = _state(0.0, (1.0, 0, 0), (0, 0, w0))
    # world velocity R1 v1 = R0 v0 + a dt: the body turned by w1 dt about z
    yaw = w1 * dt
    v_world = np.array([1.0 + 2.0 * dt, 0.0, 0.0])
    c, s = math.cos(yaw), math.sin(yaw)
    v_body = np.array([c * v_world[0] + s * v_world[1], -s * v_world[0] + c * v_world[1], 0])
    after = _state(dt, v_body, (0, 0, w1), yaw)
    omega, force = true_motion(com, before, after, np.array([1.0, 0.5, -0.2]), G)
    r = np.array([1.0, 0.5, 0.0])
    expected_world = (np.array([2.0, 0, 0])
                      + np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
                      @ (np.cross([0, 0, 0.1], r)
                         + np.cross([0, 0, w1], np.cross([0, 0, w1], r))))
    expected = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]]) @ (expected_world + [0, 0, G])
    np.testing.assert_allclose(omega, [0, 0, w1])
    np.testing.assert_allclose(force, expected, atol=1e-9)
    assert force[0] < 2.0 - 0.2  # the centripetal term is there: -w^2 x = -0.25 m/s^2


def _readings(spec, n, seed=7):
    key = stream_key(seed, 0, 0)
    state = imu_start(spec, key)
    q = np.array([0.0, 0.0, 0.0, 1.0])
    out = []
    for _ in range(n):
        reading, state = measure_imu(spec, key, state, q, np.zeros(3), np.array([0, 0, G]))
        out.append(np.concatenate([reading.angular_velocity, reading.linear_acceleration]))
    return np.array(out), reading


def test_white_noise_has_the_configured_density_and_a_zero_mean():
    # noise density N at rate f is a per-sample sigma N sqrt(f) (IEEE 952): 100 Hz
    spec = ImuSpec(rate_hz=100.0, gyroscope=InertialNoise(2e-3, 0.0, 0.0, 1.0),
                   accelerometer=InertialNoise(5e-3, 0.0, 0.0, 1.0), orientation_sigma=0.0)
    data, reading = _readings(spec, 20000)
    sigma = np.array([2e-3] * 3 + [5e-3] * 3) * 10.0
    truth = np.array([0, 0, 0, 0, 0, G])
    np.testing.assert_allclose(data.std(axis=0), sigma, rtol=0.05)
    assert np.all(np.abs(data.mean(axis=0) - truth) < 0.05 * sigma)
    # the covariance published with the reading is that of the noise
    np.testing.assert_allclose(np.diag(reading.angular_velocity_covariance), (2e-2) ** 2)
    np.testing.assert_allclose(np.diag(reading.linear_acceleration_covariance), (5e-2) ** 2)


def test_the_bias_is_a_gauss_markov_process_of_the_configured_sigma_and_time():
    # many independent units (streams): the bias's spread is bias_instability at any time,
    # and its correlation over one correlation time is 1/e (Gelb 1974, sec. 3.8)
    spec = ImuSpec(rate_hz=10.0, gyroscope=InertialNoise(0.0, 0.0, 1e-3, 2.0),
                   accelerometer=QUIET, orientation_sigma=0.0)
    first, later = [], []
    for unit in range(1500):
        key = stream_key(1, unit, 0)
        state = imu_start(spec, key)
        values = []
        for _ in range(21):  # 2 s = one correlation time after the first reading
            reading, state = measure_imu(spec, key, state, np.array([0, 0, 0, 1.0]),
                                         np.zeros(3), np.zeros(3))
            values.append(reading.angular_velocity[0])
        first.append(values[0])
        later.append(values[20])
    first, later = np.array(first), np.array(later)
    assert first.std() == pytest.approx(1e-3, rel=0.05)
    assert later.std() == pytest.approx(1e-3, rel=0.05)
    assert np.corrcoef(first, later)[0, 1] == pytest.approx(math.exp(-1.0), abs=0.05)


def test_the_random_walk_grows_as_its_density_times_root_time():
    spec = ImuSpec(rate_hz=10.0, gyroscope=QUIET,
                   accelerometer=InertialNoise(0.0, 2e-3, 0.0, 1.0), orientation_sigma=0.0)
    ends = []
    for unit in range(1500):
        key = stream_key(2, unit, 0)
        state = imu_start(spec, key)
        for _ in range(40):  # 4 s
            reading, state = measure_imu(spec, key, state, np.array([0, 0, 0, 1.0]),
                                         np.zeros(3), np.zeros(3))
        ends.append(reading.linear_acceleration[1])
    assert np.std(ends) == pytest.approx(2e-3 * math.sqrt(4.0), rel=0.05)


def test_the_same_key_gives_the_same_readings_and_another_seed_others():
    spec = ImuSpec()
    a, _ = _readings(spec, 50, seed=3)
    b, _ = _readings(spec, 50, seed=3)
    c, _ = _readings(spec, 50, seed=4)
    np.testing.assert_array_equal(a, b)
    assert np.all(a != c)


def test_an_imu_on_a_boat_floating_in_still_water_reads_g_within_its_noise():
    from boat_dynamics.physics.core.boat import BoatInputs, step
    from boat_dynamics.physics.core.pipeline import init_scenario
    from boat_dynamics.physics.scenario import parse_scenario
    from ocean_sim.physics.waves import WaveField

    boat = init_scenario(parse_scenario({"boats": [{"sensors": [
        {"type": "imu", "position": [1.0, 0.5, 0.3]}]}]})).boats[0]
    spec, key = boat.sensors[0], stream_key(0, 0, 0)
    state, imu = boat.initial, imu_start(boat.sensors[0], stream_key(0, 0, 0))
    z = []
    for _ in range(200):
        after = step(boat.params, state, BoatInputs(), WaveField(), 0.01)
        omega, force = true_motion(boat.params.center_of_mass, state, after, spec.position, G)
        np.testing.assert_allclose(force, [0, 0, G], atol=1e-6)  # the true motion: at rest
        reading, imu = measure_imu(spec, key, imu, after.orientation, omega, force)
        z.append(reading.linear_acceleration[2])
        state = after
    sigma = math.sqrt(reading.linear_acceleration_covariance[2, 2])
    assert np.all(np.abs(np.array(z) - G) < 4.5 * sigma)
    bias = spec.accelerometer.bias_instability
    assert abs(np.mean(z) - G) < 3 * bias + 4 * sigma / math.sqrt(200)


def test_scale_factors_and_misalignments_are_drawn_once_per_unit_with_their_sigmas():
    """Over 400 units (keys), each triad's turn-on transform I + S + M has diagonal errors
    of sigma scale_factor and off-diagonal terms of sigma misalignment (within 15 %: 1,200
    and 2,400 draws), and a unit reads (I + S + M) x: the same matrix at every reading."""
    gyro = InertialNoise(0.0, 0.0, 0.0, 1.0, scale_factor=0.01, misalignment=math.radians(0.5))
    accel = InertialNoise(0.0, 0.0, 0.0, 1.0, scale_factor=0.002, misalignment=0.0)
    spec = ImuSpec(gyroscope=gyro, accelerometer=accel, orientation_sigma=0.0)
    diagonal, off = [], []
    for unit in range(400):
        key = stream_key(7, "boat", f"imu{unit}")
        state = imu_start(spec, key)
        t = state.transform
        diagonal.append(np.diagonal(t, axis1=1, axis2=2) - 1.0)
        off.append(t[:, ~np.eye(3, dtype=bool)])
        rate, force = np.array([0.3, -0.2, 0.5]), np.array([0.1, 0.2, G])
        for _ in range(3):  # the same unit, reading after reading
            reading, state = measure_imu(spec, key, state, np.array([0, 0, 0, 1.0]), rate,
                                         force)
            np.testing.assert_allclose(reading.angular_velocity, t[0] @ rate, rtol=1e-15)
            np.testing.assert_allclose(reading.linear_acceleration, t[1] @ force, rtol=1e-15)
    diagonal, off = np.array(diagonal), np.array(off)
    assert diagonal[:, 0].std() == pytest.approx(0.01, rel=0.15)
    assert diagonal[:, 1].std() == pytest.approx(0.002, rel=0.15)
    assert off[:, 0].std() == pytest.approx(math.radians(0.5), rel=0.15)
    assert np.all(off[:, 1] == 0.0)  # no accelerometer misalignment asked
    assert abs(diagonal.mean()) < 3 * 0.01 / math.sqrt(1200)


def test_an_ideal_imu_has_no_turn_on_transform_and_readings_saturate_at_the_range():
    spec = ImuSpec(gyroscope=InertialNoise(0.0, 0.0, 0.0, 1.0, range=math.radians(300.0)),
                   accelerometer=InertialNoise(0.0, 0.0, 0.0, 1.0, range=2.0 * G),
                   orientation_sigma=0.0)
    key = stream_key(1, "a", "imu")
    state = imu_start(spec, key)
    assert state.transform is None  # no scale factor, no misalignment: read as it is
    spin = np.array([0.0, -9.0, 2.0])  # rad/s: 516 deg/s about y, beyond the 300 deg/s range
    slam = np.array([0.0, 0.0, 5.0 * G])  # a 5 g slam against a 2 g range
    reading, _ = measure_imu(spec, key, state, np.array([0, 0, 0, 1.0]), spin, slam)
    np.testing.assert_allclose(reading.angular_velocity, [0.0, -math.radians(300.0), 2.0])
    np.testing.assert_allclose(reading.linear_acceleration, [0.0, 0.0, 2.0 * G])
    # the default unit (ADIS16448-class) saturates at +-1000 deg/s and +-18 g
    assert ImuSpec().gyroscope.range == pytest.approx(math.radians(1000.0))
    assert ImuSpec().accelerometer.range == pytest.approx(18 * 9.80665)
