"""Penrose Escherization on P2: the kite and dart of the derived quasivertex parameterization
(quasivertex_p2.py) fitted to goals with the same metric and optimiser as P3; every result
checked as a Penrose tiling (Patch.validate and the §6.3 pairs on every shared piece)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from click.testing import CliRunner
from test_penrose_escher import DATA, check_penrose, recover_known

from tilekit.cli import cli
from tilekit.plugins.substitution import penrose_escher as pe


def test_known_kite_and_dart_are_recovered_from_moved_goals() -> None:
    """The synthetic pair on P2: a kite and a dart of known quasivertex parameters and edge
    shapes, moved (the dart mirrored), are recovered at distance < 1e-6 with the parameters,
    and the result is a Penrose tiling (test_penrose_escher.recover_known)."""
    recover_known("p2")


def test_cli_p2_writes_a_validated_result_that_reopens(tmp_path: Path) -> None:
    """`escherize-penrose --tiling p2 GOAL_A GOAL_B` writes penrose.json, whose spec reopens
    with `render --system` (the same kite and dart) and as the printed render command."""
    runner = CliRunner()
    out = tmp_path / "out"
    res = runner.invoke(cli, ["escherize-penrose", "--tiling", "p2", str(DATA / "fish.json"), str(DATA / "bird.json"),
                              "--starts", "1", "--samples", "48", "--edge-points", "2", "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert "kite" in res.output and "dart" in res.output
    data = json.loads((out / "penrose.json").read_text())
    assert data["spec"]["system"] == "penrose-p2"
    assert data["escherize"]["distance"] == max(data["escherize"]["distances"])
    fitted = pe.PenroseResult("penrose-p2", data["escherize"]["params"], data["escherize"]["edges"], 0.0, [], [])
    check_penrose(fitted)
    res2 = runner.invoke(cli, ["render", "--system", str(out / "penrose.json"), "--region", "-3,-3,3,3",
                               "-o", str(tmp_path / "again.svg")])
    assert res2.exit_code == 0, res2.output
    from tilekit.plugins.substitution import from_file

    for p, q in zip(from_file(str(out / "penrose.json")).prototiles, fitted.tiling().prototiles):
        assert np.allclose(p.outline, q.outline)


def test_a_file_that_is_not_a_spec_is_one_line(tmp_path: Path) -> None:
    from cliutil import assert_one_line_error

    bad = tmp_path / "bad.json"
    bad.write_text('{"family": "substitution", "spec": [1, 2]}')
    res = CliRunner().invoke(cli, ["render", "--system", str(bad), "-o", str(tmp_path / "x.svg")])
    assert_one_line_error(res, "not a substitution spec")
