"""A sensor's latency: the delay line releases each reading latency s of simulation time on."""

import pytest

from boat_dynamics.physics.sensors import DelayLine


def _steps(dt, n):
    """The times of n steps as a run sums them (float rounding included)."""
    t, out = 0.0, []
    for _ in range(n):
        t += dt
        out.append(t)
    return out


@pytest.mark.parametrize("rate, latency, steps_later", [(100.0, 0.05, 5), (100.0, 0.01, 1),
                                                        (100.0, 0.015, 2), (1000.0, 0.3, 300),
                                                        (50.0, 0.0, 0)])
def test_each_item_is_released_at_the_first_step_at_or_after_its_time_plus_latency(
        rate, latency, steps_later):
    line, released = DelayLine(latency), {}
    times = _steps(1.0 / rate, 2000)
    for k, t in enumerate(times):
        for item in line.pop_due(t):  # as the publisher does: what is due, then new readings
            released[item] = k
        line.push(t, k)
        for item in line.pop_due(t):  # a zero latency releases at once
            released[item] = k
    assert len(released) + len(line) == len(times)
    assert all(released[k] - k == steps_later for k in released), set(
        released[k] - k for k in released)


def test_items_come_out_in_order_and_clear_drops_them():
    line = DelayLine(0.1)
    for k in range(5):
        line.push(0.02 * k, k)
    assert line.pop_due(0.15) == [0, 1, 2]
    assert len(line) == 2
    line.clear()
    assert len(line) == 0 and line.pop_due(10.0) == []


def test_a_negative_or_nan_latency_is_refused():
    for bad in (-0.1, float("nan")):
        with pytest.raises(ValueError, match="latency"):
            DelayLine(bad)
