"""`boatsim topic hz`'s figures, from arrival times given by the test (no wall clock)."""

from boat_dynamics.tools.introspection import TopicRate


def test_the_rate_and_its_spread_over_the_window():
    rate = TopicRate(window=4)
    assert rate.report() is None
    for t in (0.0, 0.02, 0.04, 0.06, 0.10, 0.12):  # the first two fall out of the window
        rate.arrived(t)
    # intervals kept: 0.02, 0.02, 0.04, 0.02 -> mean 0.025 s, 40 Hz
    assert rate.report() == ("average rate: 40.000\n\tmin: 0.020s max: 0.040s "
                             "std dev: 0.00866s window: 5")
