"""The design document's table of scenario keys is the reader's own (it cannot drift)."""

from pathlib import Path

import pytest

from boat_dynamics.physics.scenario import parse_scenario
from boat_dynamics.physics.scenario.read import keys_read, number
from boat_dynamics.tools import scenario_keys
from boat_dynamics.tools.scenario_keys import BEGIN, END, KeyTableError, key_table, render

DESIGN = Path(__file__).resolve().parents[3] / "docs" / "DESIGN.md"


def test_the_design_documents_table_is_the_one_the_reader_gives():
    text = DESIGN.read_text()
    documented = text[text.index(BEGIN):text.index(END) + len(END)]
    assert documented == render(key_table()), (
        "docs/DESIGN.md's scenario keys are stale: python -m boat_dynamics.tools.scenario_keys "
        "--write")


def test_every_key_has_a_default_and_what_is_allowed():
    table = key_table()
    paths = [k.path for k in table]
    assert len(paths) == len(set(paths)) > 150
    assert all(k.default and k.allowed for k in table)
    by_path = {k.path: k for k in table}
    assert by_path["boats[].mass"].default.startswith("half the hull's displacement")
    assert by_path["simulation.publish_rate_hz"].allowed == "number in (0, rate_hz] Hz"
    assert by_path["boats[].hull.subdivisions"].allowed == (
        "integer in [1, 64] (quads per box face edge; a cylinder's bands along its axis)")


def test_a_default_that_depends_on_the_hull_without_saying_so_is_refused(monkeypatch):
    """A reader whose default is computed from the hull must describe it (default_doc)."""
    from boat_dynamics.physics.scenario import boat as boat_module

    original = boat_module.number

    def careless(d, name, key, default, *args, default_doc=None, **kwargs):
        return original(d, name, key, default, *args, **kwargs)  # drops the description

    monkeypatch.setattr(boat_module, "number", careless)
    # the first found: the mass (half the hull's displacement) or the anchor line's damping
    # (a share of critical on that mass)
    with pytest.raises(KeyTableError, match=r"boats\[\]\.(mass|anchor_line\.damping): .*"
                                            r"(with another|give its reader default_doc)"):
        key_table()


def test_a_key_no_reader_describes_is_refused(monkeypatch):
    monkeypatch.setitem(scenario_keys.EXERCISES, "an undescribed key", {})
    from boat_dynamics.physics.scenario import read

    original = read.only

    def with_an_extra_key(d, key, allowed):
        return original(d, key, (*allowed, "undescribed") if key == "simulation" else allowed)

    monkeypatch.setattr("boat_dynamics.physics.scenario.sea.only", with_an_extra_key)
    with pytest.raises(KeyTableError, match=r"keys no reader describes: simulation\.undescribed"):
        key_table()


def test_outside_keys_read_nothing_is_kept():
    with keys_read() as seen:
        number({"x": 1.0}, "x", "k", 0.0)
    assert len(seen) == 1
    parse_scenario({})  # outside: nowhere to go, nothing kept
    assert len(seen) == 1
