"""The `boatsim` command line: what `--help` shows (the verbs themselves run in tests/ros)."""

import pytest

from boat_dynamics.cli import main

VERBS = ("run", "query", "record", "compare", "plot", "replay", "teleop")


def test_help_lists_the_public_verbs_and_hides_the_internal_one(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["--help"])
    assert exit_.value.code == 0
    out = capsys.readouterr().out
    listed = [line.split()[0] for line in out.splitlines() if line.startswith("    ")]
    assert listed == list(VERBS)
    assert "_node" not in out and "SUPPRESS" not in out


def test_the_internal_verb_still_parses(capsys):
    # `_node` starts the --processes children: hidden from the help, not removed
    with pytest.raises(SystemExit) as exit_:
        main(["_node", "ocean"])
    assert exit_.value.code == 2
    assert "the following arguments are required: scenario, --epoch" in capsys.readouterr().err
