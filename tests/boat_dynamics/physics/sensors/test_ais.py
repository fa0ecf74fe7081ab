"""The AIS receiver: who reports when (ITU-R M.1371 class A intervals), range, noise."""

import math

import numpy as np
import pytest

from boat_dynamics.physics.sensors.ais import (
    KNOT,
    AisSpec,
    AisState,
    ais_reports,
    report_interval,
)
from boat_dynamics.physics.sensors.noise import stream_key

KEY = stream_key(0, "own", "ais")


def test_the_reporting_interval_follows_the_speed():
    assert report_interval(0.0) == 180.0
    assert report_interval(10 * KNOT) == 10.0
    assert report_interval(14 * KNOT) == 6.0 and report_interval(23 * KNOT) == 6.0
    assert report_interval(30 * KNOT) == 2.0


def _fleet():
    # own boat at the origin; b1 at 5 knots 1 km east heading north; b2 at 25 knots; b3 at
    # anchor; b4 50 km away (out of range)
    positions = np.array([[0.0, 0, 0], [1000, 0, 0], [0, 2000, 0], [-500, 0, 0],
                          [50_000, 0, 0]])
    velocities = np.array([[0.0, 0, 0], [0, 5 * KNOT, 0], [25 * KNOT, 0, 0], [0, 0, 0],
                           [0, 5 * KNOT, 0]])
    return positions, velocities, np.array([0.0, math.pi / 2, 0.0, 1.0, 0.0])


def test_each_boat_reports_at_its_interval_within_range_and_not_the_receiver_itself():
    spec = AisSpec(position_sigma=0.0)
    positions, velocities, headings = _fleet()
    state, heard = AisState(), {b: [] for b in range(5)}
    for k in range(400):  # 1 Hz looks over 400 s
        reports, state = ais_reports(spec, KEY, state, float(k), 0, positions, velocities,
                                     headings)
        for r in reports:
            heard[r.boat].append(k)
    assert heard[0] == [] and heard[4] == []  # itself; beyond 37 km
    assert heard[1] == list(range(0, 400, 10))
    assert heard[2] == list(range(0, 400, 2))
    assert heard[3] == [0, 180, 360]


def test_a_buoy_has_no_transponder_and_is_never_reported():
    positions, velocities, headings = _fleet()
    transmits = np.array([True, True, False, True, True])  # boat 2: a buoy
    heard = set()
    state = AisState()
    for k in range(200):
        reports, state = ais_reports(AisSpec(position_sigma=0.0), KEY, state, float(k), 0,
                                     positions, velocities, headings, transmits)
        heard |= {r.boat for r in reports}
    assert heard == {1, 3}


def test_a_report_says_where_and_how_the_boat_goes():
    positions, velocities, headings = _fleet()
    reports, _ = ais_reports(AisSpec(position_sigma=0.0), KEY, AisState(), 0.0, 0, positions,
                             velocities, headings)
    r = next(r for r in reports if r.boat == 1)
    np.testing.assert_array_equal(r.position, positions[1])
    assert r.course == pytest.approx(math.pi / 2) and r.speed == pytest.approx(5 * KNOT)
    assert r.heading == pytest.approx(math.pi / 2)


def test_the_position_noise_is_white_of_its_sigma():
    positions, velocities, headings = _fleet()
    spec, state, errors = AisSpec(position_sigma=5.0), AisState(), []
    for k in range(0, 4000, 2):
        reports, state = ais_reports(spec, KEY, state, float(k), 0, positions, velocities,
                                     headings)
        errors += [r.position[:2] - positions[r.boat, :2] for r in reports if r.boat == 2]
    errors = np.array(errors)  # 2,000 reports, 4,000 draws
    assert np.abs(errors.mean(axis=0)).max() < 4 * 5.0 / math.sqrt(len(errors))
    assert errors.std() == pytest.approx(5.0, rel=0.05)
