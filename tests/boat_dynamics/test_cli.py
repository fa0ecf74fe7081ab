"""The `boatsim` command line: what `--help` shows (the verbs themselves run in tests/ros)."""

from pathlib import Path

import pytest

from boat_dynamics.cli import main

VERBS = ("run", "query", "record", "compare", "reindex", "plot", "replay", "rao", "hydro",
         "topic", "node", "param", "view", "teleop")


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
    assert "the following arguments are required: scenario" in capsys.readouterr().err


@pytest.mark.parametrize("extra", [[], ["--processes"], ["--fast", "--record", "BAG"]])
def test_a_hull_that_sinks_is_refused_before_anything_starts(tmp_path, capsys, extra):
    # The reader only parses; pipeline.init finds the hull sinks, and every path of `run`
    # refuses it with exit status 2, naming the boat's key as the reader would.
    path = tmp_path / "lead.yaml"
    path.write_text("boats:\n  - {name: a}\n  - {name: lead, density: 2000.0}\n")
    extra = [str(tmp_path / "bag") if a == "BAG" else a for a in extra]
    assert main(["run", str(path), *extra]) == 2
    err = capsys.readouterr().err
    assert "boats[1].mass: 16000.0 is not allowed: the hull sinks" in err
    assert not (tmp_path / "bag").exists()  # refused before the bag was created


@pytest.mark.parametrize("verb", [["run"], ["rao"], ["hydro"]])
def test_a_hostile_scenario_file_exits_2_with_one_short_line(tmp_path, capsys, verb):
    rows = ["a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol]"]
    rows += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 9)]
    path = tmp_path / "bomb.yaml"
    path.write_text("boats:\n  - name: x\n    mass:\n" + "".join(f"      {r}\n" for r in rows))
    assert main([*verb, str(path)]) == 2
    err = capsys.readouterr().err
    assert "aliases expanded" in err and len(err) < 600 and "Traceback" not in err


def test_reindex_of_a_missing_bag_exits_2_with_one_line(tmp_path, capsys):
    assert main(["reindex", str(tmp_path / "nothing")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("boatsim reindex: error:") and "nothing" in err and "\n" not in err


def test_replay_rate_is_a_speed_factor_not_seconds(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["replay", "bag", "--rate", "0"])
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert "--rate: '0': must be a finite speed factor" in err and "seconds" not in err


def test_a_users_error_escaping_a_verb_is_one_line_and_exit_2(monkeypatch, capsys):
    """cli.main is the one place: any refused value that a verb does not catch itself."""
    from boat_dynamics import cli
    from ocean_sim.physics.errors import InvalidValueError

    def refuse(args):
        raise InvalidValueError("boats[0].mass", -3.0, "must be in (0, inf] kg")

    monkeypatch.setitem(cli._HANDLERS, "query", refuse)
    assert cli.main(["query", "1", "2"]) == 2
    err = capsys.readouterr().err
    assert err == ("boatsim query: error: boats[0].mass: -3.0 is not allowed: "
                   "must be in (0, inf] kg\n")

    def crash(args):
        raise ZeroDivisionError("a bug, not the user's")

    monkeypatch.setitem(cli._HANDLERS, "query", crash)
    with pytest.raises(ZeroDivisionError):  # a bug still shows its traceback
        cli.main(["query", "1", "2"])


@pytest.mark.parametrize(("argv", "line", "status"), [
    (["query", "1", "2", "3"],
     "boatsim query: error: coordinates come in X Y pairs; got 3 numbers", 2),
    (["compare", "a", "b", "--tol", "x=-1"],
     "boatsim compare: error: --tol 'x=-1': expected FIELD=VALUE with a number >= 0", 2),
    (["run", "--lockstep"],
     "boatsim: error: --lockstep needs --fast (a real-time run follows the wall clock)", 2),
    (["run", "--fast", "--only", "shard", "3/2"], "boatsim: error: --only shard 3/2: ", 2),
    (["run", "missing.yaml"], "boatsim: error: invalid scenario missing.yaml: ", 2),
    (["view", "--scenario", "missing.yaml"],
     "boatsim view: error: invalid scenario missing.yaml: ", 2),
    (["reindex", "not-a-bag"], "boatsim reindex: error: ", 2),
])
def test_each_verbs_refusal_is_one_line_from_main_with_its_status(argv, line, status, capsys,
                                                                  tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == status
    err = capsys.readouterr().err
    assert err.startswith(line) and err.count("\n") == 1, err


def test_only_main_prints_errors():
    """The verbs raise CommandLineError (or a user error); main alone prints `error:` lines."""
    import ast

    from boat_dynamics import cli

    tree = ast.parse(Path(cli.__file__).read_text())
    printing = [node for node in ast.walk(tree) if isinstance(node, ast.FunctionDef)
                and any(isinstance(c, ast.Call) and getattr(c.func, "id", None) == "print"
                        and "error:" in ast.unparse(c) for c in ast.walk(node))]
    assert [f.name for f in printing] == ["main"]
