"""Penrose Escherization (Kaplan 2009, §7.3 with the quasivertex parameterization of §6.3):
the P3 rhombs' quasivertex parameters and interlocking edge shapes fitted to goals with the
core's Escherization metric (tilekit.escher), every result checked as a Penrose tiling."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from cliutil import assert_one_line_error

from tilekit import escher
from tilekit.cli import cli
from tilekit.errors import ParameterError
from tilekit.geometry import Affine
from tilekit.plugins.isohedral import escher as isohedral_escher
from tilekit.plugins.substitution import penrose_escher as pe
from tilekit.plugins.substitution import penrose_limits, tiling
from tilekit.plugins.substitution import quasivertex as qv
from tilekit.tiling import Patch, Prototile

DATA = Path(__file__).resolve().parent.parent / "data" / "escher"
REGION = (-4.0, -4.0, 4.0, 4.0)
#: A known deformation: quasivertex parameters (degrees) and shapes on all four primary labels.
KNOWN = dict(r1=0.12, theta1=25.0, r2=0.2, theta2=-15.0)
KNOWN_EDGES = ["a=0.25,0.06:0.5,0.1:0.75,0.04", "b=0.3,-0.05:0.5,-0.08:0.7,-0.03", "c=0.5,0.07", "f=0.4,-0.06"]
#: Shared corner-to-corner edges a patch of REGION must show at least (P3's rhombs are smaller
#: than P2's kites and darts, so its patch has about twice as many).
MIN_SHARED = {"penrose-p3": 300, "penrose-p2": 150}


def similar(points: np.ndarray, angle: float, scale: float, shift: tuple[float, float], mirror: bool) -> np.ndarray:
    m = Affine.translation(*shift) @ Affine.rotation(angle) @ np.diag([scale, scale, 1.0])
    if mirror:
        m = m @ Affine.reflection(0.0)
    return Affine.apply(m, points)


def check_penrose(result: pe.PenroseResult) -> None:
    """The independent check of a result: a patch of its tiling has no gap and no overlap, and
    Figure 6.14's pairs meet on every shared edge (checked here tile by tile)."""
    t = result.tiling()
    region = shapely.box(*REGION)
    patch = t.patch(region)
    report = patch.validate(region)
    assert report, report.summary()
    assert qv.matching_report(patch).ok
    # tile by tile: every corner-to-corner edge found twice has partner labels
    seen: dict[tuple, list[str]] = {}
    for p, tr in zip(patch.prototile, patch.transform):
        proto = patch.prototiles[p]
        pts = Affine.apply(tr, proto.outline[list(proto.corners)])
        for i, c in enumerate(proto.corners):
            a, b = np.round(pts[i], 6), np.round(pts[(i + 1) % len(pts)], 6)
            key = tuple(sorted([tuple(a), tuple(b)]))
            seen.setdefault(key, []).append(proto.edge_labels[c])
    pairs = [v for v in seen.values() if len(v) == 2]
    assert len(pairs) > MIN_SHARED[result.system]
    partner = qv.SPECS[result.system].partner
    assert all(partner[a] == b for a, b in pairs)


def test_the_metric_is_one_copy_in_the_core() -> None:
    """The isohedral family's Escherization names are the core module's objects (one copy)."""
    for name in ("shape_distance", "GoalBank", "resample", "similarity_residual", "run_guarded", "read_goal",
                 "check_goal", "align_onto", "framed_path"):
        assert getattr(isohedral_escher, name) is getattr(escher, name)


def recover_known(which: str) -> pe.PenroseResult:
    """Goal A's and goal B's tiles of KNOWN (thick and thin rhombs, or kite and dart), each
    moved by its own similarity (B mirrored), fitted: recovered at distance < 1e-6 with the
    parameters, a Penrose tiling, and a spec that rebuilds goal A's tile."""
    system = pe.SYSTEMS[which]
    first, second = pe.GOAL_TILES[system]
    t = tiling(system).configure(**KNOWN, edges=KNOWN_EDGES)
    tiles = {p.name: np.asarray(p.outline) for p in t.prototiles}
    a = similar(tiles[first], 0.7, 3.0, (5.0, -2.0), False)
    b = similar(tiles[second], -1.9, 0.4, (-1.0, 8.0), True)
    result = pe.escherize_penrose(a, b, tiling=which, settings=pe.PenroseSettings(starts=2))
    assert result.system == system
    assert result.distance < 1e-6
    assert result.mirrored == [False, True]
    assert result.shrink == 1.0
    for k, v in KNOWN.items():
        assert result.params[k] == pytest.approx(v, abs=1e-4)
    check_penrose(result)
    again = tiling(system).configure(**{k: v for k, v in result.spec().items() if k in KNOWN},
                                     edges=result.spec()["edges"])
    rebuilt = next(p for p in again.prototiles if p.name == first)
    assert escher.shape_distance(rebuilt.outline, tiles[first]) < 1e-6
    return result


def test_known_rhombs_are_recovered_from_moved_goals() -> None:
    """The synthetic pair on P3: the thick and thin rhombs of known quasivertex parameters and
    edge shapes, moved (the thin one mirrored), are recovered (:func:`recover_known`)."""
    recover_known("p3")


def test_one_goal_fits_both_rhombs_and_tiles() -> None:
    """One goal (the fish): both rhombs are compared with it, the score is the larger distance,
    and the fitted rhombs still tile as P3 with the matching rules."""
    goal = escher.read_goal(DATA / "fish.json")
    result = pe.escherize_penrose(goal, settings=pe.PenroseSettings(starts=1, samples=64))
    assert result.distance == max(result.distances)
    for proto, d in zip(sorted(result.tiling().prototiles, key=lambda p: p.name != "thick"), result.distances):
        assert escher.shape_distance(proto.outline, goal, samples=64) == pytest.approx(d, abs=1e-9)
    # better than the straight rhombs
    straight = {p.name: p.outline for p in tiling("penrose-p3").prototiles}
    assert result.distance < max(escher.shape_distance(straight[n], goal, samples=64) for n in pe.TILES)
    check_penrose(result)


def test_matching_report_finds_broken_rules() -> None:
    """The matching check fails on a patch whose labels or edge shapes do not interlock."""
    t = tiling("penrose-p3").configure(**KNOWN, edges=KNOWN_EDGES)
    region = shapely.box(*REGION)
    patch = t.patch(region)
    assert qv.matching_report(patch).ok
    thin, thick = patch.prototiles
    # relabel the thick rhomb's edges a <-> b: shared a/g edges become b/g
    swap = {"a": "b", "b": "a"}
    relabelled = Prototile(thick.outline, edge_labels=tuple(swap.get(x, x) for x in thick.edge_labels),
                           name="thick", corners=thick.corners)
    report = qv.matching_report(Patch([thin, relabelled], patch.prototile, patch.transform))
    assert not report.ok and report.mislabelled
    assert "non-partner labels" in report.summary()
    # a bump on one thick edge that its neighbour does not have
    out = thick.outline.copy()
    i = thick.corners[0] + 1
    out[i] = out[i] + 0.05 * np.array([0.0, 1.0])
    bumped = Prototile(out, edge_labels=thick.edge_labels, name="thick", corners=thick.corners)
    report = qv.matching_report(Patch([thin, bumped], patch.prototile, patch.transform))
    assert report.misfit > 0.01 and not report.ok


def test_cli_writes_a_validated_result_and_its_render_command(tmp_path: Path) -> None:
    """`tilekit escherize-penrose` writes the spec, the tile picture and the patch; the printed
    render command draws the same rhombs."""
    runner = CliRunner()
    res = runner.invoke(cli, ["escherize-penrose", str(DATA / "fish.json"), "--starts", "1", "--samples", "48",
                              "--edge-points", "2", "-o", str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "out" / "tiles.svg").read_text().startswith("<svg")
    assert "<path" in (tmp_path / "out" / "patch.svg").read_text()
    data = json.loads((tmp_path / "out" / "penrose.json").read_text())
    assert data["spec"]["system"] == "penrose-p3" and data["escherize"]["distance"] == max(data["escherize"]["distances"])
    line = next(x for x in res.output.splitlines() if x.startswith("render: tilekit render "))
    args = line.removeprefix("render: tilekit render ").split()
    args[args.index("-o") + 1] = str(tmp_path / "again.svg")
    res2 = runner.invoke(cli, ["render", *args])
    assert res2.exit_code == 0, res2.output
    from tilekit.plugins.substitution import from_spec

    rebuilt = from_spec(data["spec"])
    fitted = pe.PenroseResult(data["spec"]["system"], data["escherize"]["params"], data["escherize"]["edges"], 0.0,
                              [], []).tiling()
    for p, q in zip(rebuilt.prototiles, fitted.prototiles):
        assert np.allclose(p.outline, q.outline)


def test_help_states_the_budget() -> None:
    res = CliRunner().invoke(cli, ["escherize-penrose", "--help"])
    assert res.exit_code == 0
    text = " ".join(res.output.split())
    assert f"at most {penrose_limits.START_EVALUATIONS} evaluations" in text
    assert f"at most {penrose_limits.POLISH_ROUNDS} rounds of a least-squares polish of at most " \
           f"{penrose_limits.POLISH_EVALUATIONS} evaluations each" in text


@pytest.mark.parametrize("args, expect", [
    (["--tiling", "p4"], "--tiling 'p4'"),
    (["--tiling", "hat"], "valid: p3, p2"),
    (["--starts", "0"], "--starts"),
    (["--samples", "8"], "--samples"),
    (["--edge-points", "99"], "--edge-points"),
])
def test_bad_options_are_one_line(tmp_path: Path, args: list[str], expect: str) -> None:
    res = CliRunner().invoke(cli, ["escherize-penrose", str(DATA / "fish.json"), *args, "-o", str(tmp_path / "o")])
    assert_one_line_error(res, expect)
    assert not (tmp_path / "o").exists()


def test_bad_goals_are_one_line(tmp_path: Path) -> None:
    cross = tmp_path / "cross.json"
    cross.write_text("[[0,0],[1,1],[1,0],[0,1]]")
    few = tmp_path / "few.json"
    few.write_text("[[0,0],[1,1]]")
    fish = str(DATA / "fish.json")
    for goals, expect in [([str(cross)], "crosses itself"), ([str(few)], "at least 3"),
                          ([fish, fish, fish], "one goal or two"), ([str(tmp_path / "none.json")], "none.json")]:
        res = CliRunner().invoke(cli, ["escherize-penrose", *goals, "-o", str(tmp_path / "o")])
        assert_one_line_error(res, expect)
    assert not (tmp_path / "o").exists()


def test_library_refuses_bad_settings() -> None:
    goal = escher.read_goal(DATA / "fish.json")
    with pytest.raises(ParameterError, match="starts"):
        pe.escherize_penrose(goal, settings=pe.PenroseSettings(starts=0))
    with pytest.raises(ParameterError, match="valid: p3, p2"):
        pe.escherize_penrose(goal, tiling="p1")
    assert math.isfinite(pe.PenroseModel(2).c0.sum())
