import math

import pytest

from boat_dynamics.physics.core.commands import CommandScript, check_command


def test_in_range_passes_unchanged():
    c = check_command(0.25, -1.0, 1.0)
    assert (c.value, c.problem) == (0.25, None)


@pytest.mark.parametrize(("raw", "clamped"), [(1.5, 1.0), (-7.0, -1.0)])
def test_out_of_range_is_clamped_with_the_reason(raw, clamped):
    c = check_command(raw, -1.0, 1.0)
    assert c.value == clamped
    assert "clamped" in c.problem and "[-1, 1]" in c.problem


@pytest.mark.parametrize("raw", [math.nan, math.inf, -math.inf])
def test_non_finite_is_refused(raw):
    c = check_command(raw, -0.6, 0.6, "rad")
    assert c.value is None
    assert "finite" in c.problem and "rad" in c.problem


def test_script_is_piecewise_constant():
    s = CommandScript((0.0, 10.0, 20.0), (1.0, 0.5, 0.0), (0.0, 0.3, -0.3))
    assert s.at(-1.0) == (0.0, 0.0)
    assert s.at(0.0) == (1.0, 0.0)
    assert s.at(9.999) == (1.0, 0.0)
    assert s.at(10.0) == (0.5, 0.3)
    assert s.at(1e6) == (0.0, -0.3)
