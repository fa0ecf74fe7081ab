"""The README's wake-crossing scenario over ROS 2: an FFT sea, a launch's wake, a boat in it."""

import numpy as np

from boat_dynamics.tools.bags import read_bag


def test_the_work_boat_feels_the_launchs_wake_only_once_it_is_in_it(boatsim, tmp_path):
    """scenarios/wake_crossing.yaml, run as the README says, 17 s: the crosser enters the
    launch's wake at about 13.2 s (examples/wake_crossing.py, without ROS); before, its
    wrench/made_waves is only the waves the launch scatters, 18-26 m off (newtons: under
    5 N measured), after it is kilonewtons; the launch, which neither the crosser's wake nor
    its scattered waves reach (within 8 of its hull radii, 17.6 m), feels none; the sea is
    the FFT tile."""
    bag = tmp_path / "wake"
    sim = boatsim("run", "scenarios/wake_crossing.yaml", "--fast", "--duration", "17",
                  "--record", str(bag))
    assert sim.wait(timeout=240) == 0, sim.output()
    msgs = read_bag(bag, ["/crosser/wrench/made_waves", "/launch/wrench/made_waves",
                          "/ocean/wave_field"])
    for boat, reached in (("crosser", True), ("launch", False)):
        rows = np.array([(m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec,
                          m.wrench.force.z) for _, m in msgs[f"/{boat}/wrench/made_waves"]])
        assert rows[-1, 0] >= 16.0, rows[-1]
        if not reached:
            assert not rows[:, 1].any()
            continue
        assert np.abs(rows[rows[:, 0] < 12.5, 1]).max() < 20.0
        assert np.abs(rows[rows[:, 0] > 14.0, 1]).max() > 1000.0
    (_, field), = msgs["/ocean/wave_field"][:1]
    assert len(field.components) == 24  # the 6 x 6 tile's (N - 1)^2 wavenumbers but k = 0
