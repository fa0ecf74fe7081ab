"""Sensors and transforms over ROS 2: /tf against /odom, /tf_static, the IMU, GNSS (with its
heading), magnetometer and depth sounder readings, dropouts and latencies.

Each test runs `boatsim run --fast` on a small scenario and reads its bag: simulation time
only, no wall-clock assumption.
"""

import math

import numpy as np
import pytest
import yaml

from boat_dynamics.physics.body.rigid_body import rotation_matrix
from boat_dynamics.physics.sensors import Datum, geodetic_to_enu

G = 9.81
DATUM = {"latitude_deg": 45.0, "longitude_deg": -4.0, "altitude": 0.0}
IMU = {"type": "imu", "name": "imu", "rate_hz": 100, "position": [0.5, 0.2, 0.3],
       "noise": {"gyroscope": {"noise_density": 1e-3},
                 "accelerometer": {"noise_density": 5e-3}}}
GNSS = {"type": "gnss", "name": "gnss", "rate_hz": 5, "position": [-1.0, 0.0, 1.0],
        "noise": {"horizontal_sigma": 1.0, "vertical_sigma": 2.0, "bias_sigma": 0.0}}


ODOMETRY = {"type": "odometry", "name": "odom_noisy", "rate_hz": 10,
            "noise": {"position_sigma": 0.3}}


def _scenario(tmp_path, seed=3, publish_tf=True, waves=False, imu=IMU):
    data = {"simulation": {"seed": seed, "datum": DATUM, "publish_tf": publish_tf},
            "boats": [{"name": "alpha", "sensors": [imu, GNSS, ODOMETRY]}]}
    if waves:
        data["ocean"] = {"components": [{"amplitude": 0.2, "wavelength": 20.0,
                                         "direction_deg": 30.0, "steepness": 0.5}]}
        data["boats"][0]["commands"] = [{"t": 0.0, "thrust": 0.6, "rudder": 0.2}]
    path = tmp_path / f"sensors_{seed}_{publish_tf}_{waves}.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


def _messages(bag, types=None):
    """{topic: [(stamp ns, message)]} of a bag (and into ``types``, {topic: type name})."""
    from rosbags.highlevel import AnyReader

    out = {}
    with AnyReader([bag]) as reader:
        for conn, stamp, raw in reader.messages():
            out.setdefault(conn.topic, []).append((stamp, reader.deserialize(raw, conn.msgtype)))
            if types is not None:
                types[conn.topic] = conn.msgtype
    return out


def _run(boatsim, tmp_path, scenario, seconds, name, types=None):
    bag = tmp_path / name
    sim = boatsim("run", str(scenario), "--fast", "--duration", str(seconds), "--record",
                  str(bag))
    assert sim.wait(timeout=180) == 0, sim.output()
    assert "Traceback" not in sim.output()
    return _messages(bag, types)


def _vec(v):
    return np.array([v.x, v.y, v.z])


def _quat(q):
    return np.array([q.x, q.y, q.z, q.w])


def test_tf_is_the_odometry_and_tf_static_mounts_every_sensor(boatsim, tmp_path):
    msgs = _run(boatsim, tmp_path, _scenario(tmp_path, waves=True), 4, "bag")
    odom = {stamp: m for stamp, m in msgs["/alpha/odom"]}
    assert len(msgs["/tf"]) == len(odom) == 201  # 50 Hz, t = 0..4 s
    for stamp, tf in msgs["/tf"]:
        (t,) = tf.transforms
        assert (t.header.frame_id, t.child_frame_id) == ("world", "alpha/base_link")
        pose = odom[stamp].pose.pose
        assert (t.header.stamp.sec, t.header.stamp.nanosec) == (
            odom[stamp].header.stamp.sec, odom[stamp].header.stamp.nanosec)
        np.testing.assert_array_equal(_vec(t.transform.translation), _vec(pose.position))
        np.testing.assert_array_equal(_quat(t.transform.rotation), _quat(pose.orientation))
    (_, static), = msgs["/tf_static"]
    mounts = {(t.header.frame_id, t.child_frame_id): _vec(t.transform.translation)
              for t in static.transforms}
    assert set(mounts) == {("alpha/base_link", "alpha/imu_link"),
                           ("alpha/base_link", "alpha/gnss_link")}
    np.testing.assert_array_equal(mounts["alpha/base_link", "alpha/imu_link"], [0.5, 0.2, 0.3])
    # the GNSS fixes convert back to the antenna's true position within the noise: the
    # antenna is 1 m behind and 1 m above the hull reference point
    datum = Datum(math.radians(45.0), math.radians(-4.0), 0.0)
    errors = []
    for stamp, fix in msgs["/alpha/gnss/fix"]:
        assert fix.header.frame_id == "alpha/gnss_link"
        pose = odom[stamp].pose.pose
        antenna = _vec(pose.position) + rotation_matrix(_quat(pose.orientation)) @ [-1, 0, 1.0]
        errors.append(geodetic_to_enu(datum, math.radians(fix.latitude),
                                      math.radians(fix.longitude), fix.altitude) - antenna)
        np.testing.assert_allclose(np.diag(np.reshape(fix.position_covariance, (3, 3))),
                                   [1.0, 1.0, 4.0])
    assert len(errors) == 20  # 5 Hz from the first step: t = 0.2 .. 4.0 s
    # the GNSS velocity: the antenna's, in the frame its header names (world, ENU), with a
    # covariance a filter can use: the normalised errors squared average 3 (chi-squared, 3
    # dof; 20 fixes: 60 dof, whose mean lies in 1.5-5.2 with 99.9 %: Wilson-Hilferty)
    nees = []
    for stamp, vel in msgs["/alpha/gnss/vel"]:
        assert vel.header.frame_id == "world"
        cov = np.reshape(vel.twist.covariance, (6, 6))
        assert np.linalg.eigvalsh(cov).min() >= 0.0
        pose, twist = odom[stamp].pose.pose, odom[stamp].twist.twist
        body = _vec(twist.linear) + np.cross(_vec(twist.angular), [-1.0, 0.0, 1.0])
        error = _vec(vel.twist.twist.linear) - rotation_matrix(_quat(pose.orientation)) @ body
        nees.append(error @ np.linalg.solve(cov[:3, :3], error))
    assert len(nees) == 20 and 1.5 < np.mean(nees) < 5.2, nees
    # the noisy odometry: odom's pose within its noise, the covariance from its sigma
    noisy = msgs["/alpha/odom_noisy"]
    assert len(noisy) == 40 and noisy[0][1].child_frame_id == "alpha/base_link"
    offsets = [_vec(m.pose.pose.position) - _vec(odom[stamp].pose.pose.position)
               for stamp, m in noisy]
    assert 0.0 < np.abs(offsets).max() < 4.5 * 0.3
    assert noisy[-1][1].pose.covariance[0] == pytest.approx(0.09)
    assert np.all(np.abs(errors) < 4.5 * np.array([1.0, 1.0, 2.0]))
    assert np.abs(np.array(errors)[:, :2]).max() > 0.1  # noise is there


def test_a_gnss_outage_publishes_no_fix_and_no_velocity_then_fixes_again(boatsim, tmp_path):
    gnss = {**GNSS, "outages": [[1.0, 2.0]]}
    path = tmp_path / "outage.yaml"
    path.write_text(yaml.safe_dump({"simulation": {"seed": 3, "datum": DATUM},
                                    "boats": [{"name": "alpha", "sensors": [gnss]}]}))
    msgs = _run(boatsim, tmp_path, path, 3, "bag")

    def t(msg):
        return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9

    fixes = [m for _, m in msgs["/alpha/gnss/fix"]]
    assert len(fixes) == 15  # 5 Hz, t = 0.2 .. 3.0 s
    lost = [m for m in fixes if 1.0 <= t(m) < 2.0 - 1e-9]
    assert len(lost) == 5 and all(m.status.status == -1 and math.isnan(m.latitude)
                                  for m in lost)
    kept = [m for m in fixes if m not in lost]
    assert all(m.status.status == 0 and abs(m.latitude - 45.0) < 1e-3 for m in kept)
    velocity_times = [t(m) for _, m in msgs["/alpha/gnss/vel"]]
    assert len(velocity_times) == 10 and not any(1.0 <= x < 2.0 - 1e-9 for x in velocity_times)


def test_dropouts_lose_readings_and_leave_the_others_as_they_were(boatsim, tmp_path):
    """An IMU and a GNSS with dropouts publish some of their readings; each one published is
    the very reading of the same run without dropouts (the noise runs on)."""
    runs = {}
    for dropout in (0.0, 0.4):
        sensors = [{**IMU, "dropout": dropout}, {**GNSS, "dropout": dropout}]
        path = tmp_path / f"dropout_{dropout}.yaml"
        path.write_text(yaml.safe_dump({"simulation": {"seed": 3, "datum": DATUM},
                                        "boats": [{"name": "alpha", "sensors": sensors}]}))
        runs[dropout] = _run(boatsim, tmp_path, path, 2, f"bag_{dropout}")
    for topic, full in (("/alpha/imu/data", 200), ("/alpha/gnss/fix", 10)):
        every = {stamp: repr(m) for stamp, m in runs[0.0][topic]}
        some = {stamp: repr(m) for stamp, m in runs[0.4].get(topic, [])}
        assert len(every) == full
        assert 0 < len(some) < full  # about 60 %: 120 of 200 IMU readings, 6 of 10 fixes
        assert all(every[stamp] == msg for stamp, msg in some.items()), topic
    assert abs(len(runs[0.4]["/alpha/imu/data"]) - 120) < 3 * math.sqrt(200 * 0.24)


def test_an_imu_on_a_boat_at_rest_in_still_water_reads_g_with_its_noise(boatsim, tmp_path):
    # white noise and a slow bias (no random walk, whose drift over the run would add to the
    # spread): 2,000 readings
    steady = {**IMU, "noise": {
        "gyroscope": {"noise_density": 1e-3, "random_walk": 0.0},
        "accelerometer": {"noise_density": 5e-3, "random_walk": 0.0}}}
    msgs = _run(boatsim, tmp_path, _scenario(tmp_path, imu=steady), 20, "bag")
    imu = [m for _, m in msgs["/alpha/imu/data"]]
    assert len(imu) == 2000  # 100 Hz from the first step
    acc = np.array([_vec(m.linear_acceleration) for m in imu])
    gyro = np.array([_vec(m.angular_velocity) for m in imu])
    assert imu[0].header.frame_id == "alpha/imu_link"
    sigma_a, sigma_g = 5e-3 * 10, 1e-3 * 10  # density x sqrt(100 Hz)
    # in 20 s the biases (300 s and 1000 s correlation times) barely move: the spread is the
    # white noise's (within 5 %), the mean g plus the bias (within 3 bias sigmas)
    np.testing.assert_allclose(acc.std(axis=0), sigma_a, rtol=0.05)
    np.testing.assert_allclose(gyro.std(axis=0), sigma_g, rtol=0.05)
    assert np.all(np.abs(acc.mean(axis=0) - [0, 0, G]) < 3 * 2.45e-3 + 4 * sigma_a / 44.7)
    assert np.all(np.abs(gyro.mean(axis=0)) < 3 * 7e-5 + 4 * sigma_g / 44.7)
    cov = np.reshape(imu[-1].linear_acceleration_covariance, (3, 3))
    assert cov == pytest.approx(np.eye(3) * (sigma_a**2 + 2.45e-3**2), rel=1e-9)


def test_the_same_seed_gives_the_same_sensor_readings_and_tf_can_be_left_out(boatsim,
                                                                             tmp_path):
    topics = ("/alpha/imu/data", "/alpha/gnss/fix", "/alpha/gnss/vel")

    def readings(msgs):
        return {t: [repr(m) for _, m in msgs[t]] for t in topics}

    first = _run(boatsim, tmp_path, _scenario(tmp_path, waves=True), 2, "a")
    again = _run(boatsim, tmp_path, _scenario(tmp_path, waves=True, publish_tf=False), 2, "b")
    other = _run(boatsim, tmp_path, _scenario(tmp_path, seed=4, waves=True), 2, "c")
    assert readings(first) == readings(again)
    assert readings(first)["/alpha/imu/data"] != readings(other)["/alpha/imu/data"]
    assert "/tf" in first and "/tf" not in again


def test_a_magnetometer_publishes_the_earth_field_in_its_frame(boatsim, tmp_path):
    """sensor_msgs/MagneticField on <name>/data, tesla, in <boat>/<name>_link: the datum's
    field turned into the body's axes by odom's attitude, plus its hard iron, within its
    noise; the heading of the level boat follows from it."""
    sigma, hard = 1e-7, [2e-6, 0.0, 0.0]
    mag = {"type": "magnetometer", "name": "compass", "rate_hz": 25, "position": [1.0, 0, 1.5],
           "noise": {"sigma": sigma, "hard_iron": hard}}
    path = tmp_path / "magnetometer.yaml"
    path.write_text(yaml.safe_dump({
        "simulation": {"seed": 3, "datum": DATUM, "magnetic_field": {
            "declination_deg": 4.0, "inclination_deg": 60.0, "intensity_nT": 47000}},
        "boats": [{"name": "alpha", "initial_pose": {"yaw_deg": 30.0}, "sensors": [mag]}]}))
    types = {}
    msgs = _run(boatsim, tmp_path, path, 2, "bag", types)
    assert types["/alpha/compass/data"] == "sensor_msgs/msg/MagneticField"
    readings = msgs["/alpha/compass/data"]
    assert len(readings) == 50  # 25 Hz, t = 0.04 .. 2.0 s (odom: every 0.02 s)
    odom = {stamp: m for stamp, m in msgs["/alpha/odom"]}
    d, i, f = math.radians(4.0), math.radians(60.0), 47000e-9
    world = f * np.array([math.cos(i) * math.sin(d), math.cos(i) * math.cos(d), -math.sin(i)])
    errors, headings = [], []
    for stamp, m in readings:
        assert m.header.frame_id == "alpha/compass_link"
        q = _quat(odom[stamp].pose.pose.orientation)
        field = _vec(m.magnetic_field)
        errors.append(field - (rotation_matrix(q).T @ world + hard))
        corrected = field - hard
        headings.append(math.pi / 2 - d - math.atan2(corrected[1], corrected[0]))
    assert np.abs(errors).max() < 4.5 * sigma and np.abs(errors).max() > 0.1 * sigma
    np.testing.assert_allclose(np.reshape(readings[0][1].magnetic_field_covariance, (3, 3)),
                               np.eye(3) * sigma**2)
    # the boat floats level at its initial yaw: 30 deg within the noise's angle
    # (sigma / (F cos I) = 4e-3 rad)
    assert np.abs(np.degrees(headings) - 30.0).max() < 4.5 * math.degrees(sigma / (f * 0.5))
    (_, static), = msgs["/tf_static"]
    assert [t.child_frame_id for t in static.transforms] == ["alpha/compass_link"]


def test_a_depth_sounder_ranges_to_the_sea_floor_along_its_tilted_beam(boatsim, tmp_path):
    """sensor_msgs/Range (ULTRASOUND) on <name>/data in <boat>/<name>_link: from the
    transducer along the body's -z axis to the floor at the ocean's depth, within its noise;
    a floor beyond max_range reads +inf (REP-117)."""
    sigma = 0.05
    echo = {"type": "depth_sounder", "name": "echo", "position": [0.5, 0.0, -0.4],
            "field_of_view_deg": 12, "noise": {"range_sigma": sigma}}
    short = {"type": "depth_sounder", "name": "short", "max_range": 5.0}
    path = tmp_path / "depth.yaml"
    path.write_text(yaml.safe_dump({
        "simulation": {"seed": 3}, "ocean": {"depth": 12.0},
        "boats": [{"name": "alpha", "initial_pose": {"roll_deg": 8.0, "pitch_deg": -5.0},
                   "sensors": [echo, short]}]}))
    types = {}
    msgs = _run(boatsim, tmp_path, path, 2, "bag", types)
    assert types["/alpha/echo/data"] == types["/alpha/short/data"] == "sensor_msgs/msg/Range"
    readings = msgs["/alpha/echo/data"]
    assert len(readings) == 20  # 10 Hz, t = 0.1 .. 2.0 s
    odom = {stamp: m for stamp, m in msgs["/alpha/odom"]}
    errors, tilts = [], []
    for stamp, m in readings:
        assert (m.header.frame_id, m.radiation_type) == ("alpha/echo_link", 0)
        assert (m.min_range, m.max_range) == (0.5, 200.0)
        assert m.field_of_view == pytest.approx(math.radians(12.0))
        pose = odom[stamp].pose.pose
        rot = rotation_matrix(_quat(pose.orientation))
        transducer = _vec(pose.position) + rot @ [0.5, 0.0, -0.4]
        # the floor at z = -12 m, the beam's tilt theta: cos(theta) = R_zz
        errors.append(m.range - (transducer[2] + 12.0) / rot[2, 2])
        tilts.append(math.degrees(math.acos(rot[2, 2])))
    assert np.abs(errors).max() < 4.5 * sigma and np.abs(errors).max() > 0.1 * sigma
    assert max(tilts) > 3.0  # the boat rolls and pitches: the beam is tilted
    assert readings[0][1].variance == pytest.approx(sigma**2)
    assert all(m.range == math.inf for _, m in msgs["/alpha/short/data"])
    assert len(msgs["/alpha/short/data"]) == 20


def test_a_dual_antenna_gnss_publishes_the_boat_s_yaw_but_not_in_an_outage(boatsim, tmp_path):
    """sensor_msgs/Imu on <gnss>/heading: odom's yaw within the heading noise, with each fix
    that has one (none in an outage)."""
    sigma_deg = 0.5
    gnss = {**GNSS, "heading_baseline": [1.2, 0.0, 0.0], "outages": [[1.0, 1.5]],
            "noise": {**GNSS["noise"], "heading_sigma_deg": sigma_deg}}
    path = tmp_path / "heading.yaml"
    path.write_text(yaml.safe_dump({
        "simulation": {"seed": 3, "datum": DATUM},
        "boats": [{"name": "alpha", "initial_pose": {"yaw_deg": 40.0}, "sensors": [gnss]}]}))
    types = {}
    msgs = _run(boatsim, tmp_path, path, 2, "bag", types)
    assert types["/alpha/gnss/heading"] == "sensor_msgs/msg/Imu"
    headings = msgs["/alpha/gnss/heading"]
    stamps = [t for t, _ in headings]
    # 5 Hz, t = 0.2 .. 2.0 s, less the fixes at 1.0, 1.2, 1.4 s (the outage)
    assert len(headings) == 7 and not any(1.0e9 <= t < 1.5e9 for t in stamps)
    odom = {stamp: m for stamp, m in msgs["/alpha/odom"]}
    errors = []
    for stamp, m in headings:
        assert m.header.frame_id == "alpha/gnss_link"
        q = _quat(odom[stamp].pose.pose.orientation)
        x_axis = rotation_matrix(q)[:, 0]  # the baseline's direction: the body's x axis
        truth = math.atan2(x_axis[1], x_axis[0])
        yaw = 2 * math.atan2(m.orientation.z, m.orientation.w)
        errors.append(math.degrees(math.remainder(yaw - truth, 2 * math.pi)))
        assert abs(math.degrees(truth) - 40.0) < 1.0  # the boat keeps its initial yaw
    assert 0.0 < np.abs(errors).max() < 4.5 * sigma_deg
    assert np.reshape(headings[0][1].orientation_covariance, (3, 3))[2, 2] == pytest.approx(
        math.radians(sigma_deg) ** 2)


def test_a_sensor_s_latency_publishes_its_readings_that_much_later_stamped_when_taken(
        boatsim, tmp_path):
    """The bag's time of a message is the simulation time it was published at: with a
    latency L a reading stamped t is published at t + L (in simulation time), the same
    reading a run without latency publishes at t."""
    runs = {}
    for latency in (0.0, 0.05):
        sensors = [{**IMU, "latency": latency}, {**GNSS, "latency": 6 * latency},
                   {**ODOMETRY, "latency": latency}]
        path = tmp_path / f"latency_{latency}.yaml"
        path.write_text(yaml.safe_dump({"simulation": {"seed": 3, "datum": DATUM},
                                        "boats": [{"name": "alpha", "sensors": sensors}]}))
        runs[latency] = _run(boatsim, tmp_path, path, 2, f"bag_{latency}")

    def stamp_ns(msg):
        return msg.header.stamp.sec * 10**9 + msg.header.stamp.nanosec

    # odom (no latency): the bag's time is the header's stamp
    assert all(t == stamp_ns(m) for t, m in runs[0.05]["/alpha/odom"])
    for topic, latency, full in (("/alpha/imu/data", 0.05, 200), ("/alpha/gnss/fix", 0.3, 10),
                                 ("/alpha/gnss/vel", 0.3, 10), ("/alpha/odom_noisy", 0.05, 20)):
        now = runs[0.0][topic]
        late = runs[0.05][topic]
        assert len(now) == full and all(t == stamp_ns(m) for t, m in now)
        # published latency s after their stamps; those due after the run's end never are
        assert {t - stamp_ns(m) for t, m in late} == {round(latency * 1e9)}, topic
        rate = full / 2.0  # readings taken in (2 - latency, 2] s are due after the end
        assert len(late) == full - math.ceil(latency * rate - 1e-9)
        assert [repr(m) for _, m in late] == [repr(m) for _, m in now[:len(late)]]


def test_rep105_frames_chain_map_odom_base_link_and_odom_drifts_with_the_odometry(
        boatsim, tmp_path):
    # simulation.frames: rep105 and a drifting odometry (10 Hz, 0.2 m/s velocity noise): /tf
    # holds map -> alpha/odom and alpha/odom -> alpha/base_link; together they are the true
    # pose (/alpha/odom, to 1e-9 m), odom -> base_link is the odometry's last reading, and
    # map -> odom moves off the identity as the odometry drifts; world -> map on /tf_static.
    data = {"simulation": {"seed": 3, "frames": "rep105"},
            "boats": [{"name": "alpha", "commands": [{"t": 0.0, "thrust": 0.6, "rudder": 0.2}],
                       "sensors": [{"type": "odometry", "name": "reckoning", "rate_hz": 10,
                                    "drift": True, "noise": {"velocity_sigma": 0.2}}]}]}
    path = tmp_path / "rep105.yaml"
    path.write_text(yaml.safe_dump(data))
    msgs = _run(boatsim, tmp_path, path, 4, "bag")
    truth = {stamp: m.pose.pose for stamp, m in msgs["/alpha/odom"]}
    links: dict = {}
    for stamp, tf in msgs["/tf"]:
        (t,) = tf.transforms
        links.setdefault(stamp, {})[(t.header.frame_id, t.child_frame_id)] = t.transform
    assert all(set(v) == {("map", "alpha/odom"), ("alpha/odom", "alpha/base_link")}
               for v in links.values())
    drift = []
    for stamp, pair in links.items():
        a, b = pair["map", "alpha/odom"], pair["alpha/odom", "alpha/base_link"]
        ra = rotation_matrix(_quat(a.rotation))
        position = _vec(a.translation) + ra @ _vec(b.translation)
        np.testing.assert_allclose(position, _vec(truth[stamp].position), atol=1e-9)
        np.testing.assert_allclose(ra @ rotation_matrix(_quat(b.rotation)),
                                   rotation_matrix(_quat(truth[stamp].orientation)), atol=1e-9)
        drift.append(np.linalg.norm(_vec(a.translation)))
    assert drift[0] < 1e-9 < drift[-1]  # the same at the start, drifted by the end
    readings = msgs["/alpha/reckoning"]
    assert {m.header.frame_id for _, m in readings} == {"alpha/odom"}
    (_, static), = msgs["/tf_static"]
    assert ("world", "map") in {(t.header.frame_id, t.child_frame_id) for t in static.transforms}


def test_an_ais_receiver_hears_the_other_boat_every_ten_seconds_where_it_is(boatsim, tmp_path):
    # bravo runs at about 1.5 m/s (under 14 knots: a report every 10 s); alpha's receiver,
    # looking at 1 Hz, publishes its reports: at its first look, then 10 s and 20 s later,
    # each its position (no noise here) at that step, its course and speed over ground.
    data = {"simulation": {"seed": 3, "datum": DATUM},
            "boats": [{"name": "alpha", "sensors": [
                          {"type": "ais", "noise": {"position_sigma": 0.0}}]},
                      {"name": "bravo", "initial_pose": {"position": [30.0, 0.0, 0.0],
                                                         "yaw_deg": 90.0},
                       "commands": [{"t": 0.0, "thrust": 0.5, "rudder": 0.0}]}]}
    path = tmp_path / "ais.yaml"
    path.write_text(yaml.safe_dump(data))
    msgs = _run(boatsim, tmp_path, path, 25, "bag")
    reports = msgs["/alpha/ais/reports"]
    stamps = [s for s, _ in reports]
    assert len(reports) == 3 and all(m.name == "bravo" for _, m in reports)
    assert np.diff(stamps).tolist() == [10_000_000_000, 10_000_000_000]
    assert {m.mmsi for _, m in reports} == {200_000_001}
    odom = {s: m.pose.pose for s, m in msgs["/bravo/odom"]}
    datum = Datum(math.radians(45.0), math.radians(-4.0), 0.0)
    for stamp, m in reports:
        truth = _vec(odom[stamp].position)
        heard = geodetic_to_enu(datum, math.radians(m.latitude_deg),
                                math.radians(m.longitude_deg), truth[2])
        np.testing.assert_allclose(heard[:2], truth[:2], atol=1e-6)
    last = reports[-1][1]
    assert 0.5 < last.speed_over_ground < 3.0
    assert min(abs(last.course_over_ground_deg), abs(last.course_over_ground_deg - 360)) < 20
    assert min(abs(last.true_heading_deg), abs(last.true_heading_deg - 360)) < 20  # north
