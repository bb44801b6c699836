"""Dihedral Escherization (Kaplan and Salesin 2004; Kaplan 2009, §7.3): split tilings (an
isohedral tile cut in two by a path between two boundary points), recovery of a known split
tile, the metric's invariances per piece, and the one-line errors."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from cliutil import assert_one_line_error
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit.cli import cli
from tilekit.edgeshapes import EdgeShape
from tilekit.errors import GeometryError, ParameterError, ParseError
from tilekit.plugins.isohedral import dihedral, escher, heaven
from tilekit.plugins.isohedral.engine import IsohedralTiling
from tilekit.plugins.isohedral.spec import tiling_from_spec
from tilekit.plugins.isohedral.split import (
    SplitTiling,
    boundary_position,
    outline_position,
    piece_rows,
)
from tilekit.polygon import signed_area

pytest.importorskip("scipy")

#: A generic IH1 tile (three J shapes, four interior points each: inside the fitted tile space
#: at the default --edge-points) split by a two-point path from 0.4 of the way along edge 0
#: to 0.6 along edge 3 (inside the default --path-points 4's space); the benchmark uses it too.
SPEC = json.loads((Path(__file__).resolve().parent.parent / "data" / "escher" / "ih1-split.json").read_text())


def known() -> SplitTiling:
    t = tiling_from_spec(SPEC)
    assert isinstance(t, SplitTiling)
    return t


def pieces(t: SplitTiling) -> list[np.ndarray]:
    return [np.asarray(p.outline, dtype=float) for p in t.prototiles]


def similar(pts: np.ndarray, angle: float, scale: float, shift: tuple[float, float], mirror: bool = False) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    q = pts * [1, -1] if mirror else pts
    return scale * q @ np.array([[c, s], [-s, c]]) + np.asarray(shift)


# --------------------------------------------------------------------------- split tilings


def test_piece_rows_partition_the_outline():
    """Each outline vertex strictly between the ends is in exactly one piece, the ends in both,
    the path's points in both (reversed in piece 0)."""
    m, k = 30, 3
    for u, v in [(2.0, 18.0), (2.5, 17.25), (27.5, 3.0), (0.0, 29.5)]:
        p0, p1 = piece_rows(m, u, v, k)
        inner0 = {int(r[0]) for r in p0[1:-k - 1]}
        inner1 = {int(r[0]) for r in p1[1:-k - 1]}
        assert not inner0 & inner1
        on_end = {int(math.floor(w)) for w in (u, v) if w == math.floor(w)}
        assert inner0 | inner1 | on_end == set(range(m))
        assert [int(r[0]) for r in p0[-k:]] == [m + 2, m + 1, m] and [int(r[0]) for r in p1[-k:]] == [m, m + 1, m + 2]


def test_boundary_positions_round_trip():
    counts = np.array([5, 3, 7, 1])
    for s in [0.0, 0.4, 1.0, 2.75, 3.5]:
        assert boundary_position(counts, outline_position(counts, s)) == pytest.approx(s)


def test_split_tiling_is_a_valid_dihedral_tiling_whose_pieces_make_the_tile():
    t = known()
    base = t.base
    a0, a1 = (signed_area(q) for q in pieces(t))
    assert a0 > 0 and a1 > 0
    assert a0 + a1 == pytest.approx(signed_area(np.asarray(base.prototile.outline)), rel=1e-12)
    union = shapely.union(*(shapely.Polygon(q) for q in pieces(t)))
    assert union.symmetric_difference(shapely.Polygon(base.prototile.outline)).area < 1e-12
    region = t.default_region()
    patch = t.patch(region)
    assert set(patch.prototile.tolist()) == {0, 1}
    report = patch.validate(region)
    assert report.ok, report.summary()
    # every tile of the base tiling inside the region is there as its two pieces, each piece
    # inside its tile
    inside = [g for g in base.patch(region).geometries() if region.contains(g)]
    assert inside
    pieces_in = patch.geometries()
    for g in inside:
        parts = [q for q in pieces_in if q.intersection(g).area > 1e-9 * g.area]
        assert len(parts) == 2, len(parts)
        assert all(g.buffer(1e-9).contains(q) for q in parts)


def test_split_spec_round_trips_and_reopens_from_a_file(tmp_path):
    t = known()
    again = tiling_from_spec(t.spec())
    assert again.spec() == t.spec()
    for p, q in zip(pieces(t), pieces(again)):
        assert np.array_equal(p, q)
    f = tmp_path / "t.isohedral.json"
    f.write_text(json.dumps({"family": "isohedral", "spec": t.spec()}))
    out = tmp_path / "t.svg"
    result = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{tmp_path / 'c.db'}", "render", "--system", str(f),
                                      "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_text().count("<path") >= 2  # one path per colour: both pieces drawn


@pytest.mark.parametrize(
    ("split", "error", "fragment"),
    [
        ({"ends": [1.0, 1.0]}, ParameterError, "the same point"),
        ({"ends": [0.5, 6.5]}, ParameterError, "must lie in [0, 6)"),
        ({"ends": [0.5]}, ParseError, "ends"),
        ({"path": "0,0:1,0"}, ParseError, "'ends' is missing"),
        ({"ends": [0.5, 3.5], "path": "0,0:0.5,3:1,0"}, GeometryError, "split"),  # the path leaves the tile
        ({"ends": [0.5, 3.5], "path": "0,0:0.6,0.2:0.6,-0.2:0.4,-0.2:0.4,0.2:1,0"}, GeometryError, "crosses itself"),
        ("half", ParseError, "not an object"),
    ],
)
def test_bad_splits_are_one_line_errors(tmp_path, split, error, fragment):
    spec = {**SPEC, "split": split}
    with pytest.raises(error) as info:
        tiling_from_spec(spec)
    assert fragment in str(info.value) and "\n" not in str(info.value)
    f = tmp_path / "bad.isohedral.json"
    f.write_text(json.dumps({"spec": spec}))
    result = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{tmp_path / 'c.db'}", "render", "--system", str(f),
                                      "-o", str(tmp_path / "x.svg")])
    assert_one_line_error(result, fragment)


# --------------------------------------------------------------------------- the metric


@settings(max_examples=25, deadline=None)
@given(
    angles=st.tuples(st.floats(-math.pi, math.pi), st.floats(-math.pi, math.pi)),
    log_scales=st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    shifts=st.tuples(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3)),
    mirror=st.tuples(st.booleans(), st.booleans()),
)
def test_piece_distances_are_invariant_under_separate_similarities_of_the_goals(angles, log_scales, shifts, mirror):
    """Each piece is compared with its own goal by its own best similarity: moving, turning,
    scaling or mirroring either goal leaves both distances (here: of a different split of the
    same tile, so they are not 0) unchanged."""
    t = known()
    other = SplitTiling(t.base, 1.5, 4.2, EdgeShape.parse("0.5,0.1"))
    a, b = pieces(t)
    base = dihedral.split_distances(other, a, b)
    assert min(base) > 0.01
    # scales within 5x of each other keep the goals' area ratio under the limit
    ls = (log_scales[0], log_scales[0] + (log_scales[1] - log_scales[0]) / 7)
    moved = [similar(g, angles[i], math.exp(ls[i]), (shifts[i], -shifts[1 - i]), mirror[i]) for i, g in enumerate((a, b))]
    got = dihedral.split_distances(other, *moved)
    assert got == pytest.approx(base, abs=2e-6)


def test_each_piece_of_the_known_split_is_at_distance_zero_from_itself():
    t = known()
    assert max(dihedral.split_distances(t, *pieces(t))) < 1e-7


# --------------------------------------------------------------------------- the search


def test_a_known_split_tile_is_recovered_and_ranked_first():
    """The two pieces of a known IH1 split tile, each moved by its own similarity (one of them
    mirrored), are recovered at distance < 1e-6 by IH1 and ranked above IH41 (a quadrilateral
    type, > 1e-3 away); the result tiles (Patch.validate) and is closer than the search's
    starting tile (default parameters, straight edges, a straight chord)."""
    a, b = pieces(known())
    a = similar(a, 0.7, 3.0, (5.0, -2.0))
    b = similar(b, -2.0, 2.5, (-1.0, 4.0), mirror=True)
    results, failed = dihedral.escherize_dihedral(a, b, [41, 1])
    assert not failed
    assert [r.ih for r in results] == [1, 41]
    best = results[0]
    assert best.distance < 1e-6 and results[1].distance > 1e-3
    tiling = best.tiling()
    # near 0 the metric resolves about 1e-8 (d = sqrt(1 - x) with x rounded to ~1e-16)
    assert max(dihedral.split_distances(tiling, a, b)) == pytest.approx(best.distance, abs=1e-7)
    region = tiling.default_region()
    assert tiling.patch(region).validate(region).ok
    start = SplitTiling(IsohedralTiling(1), 0.5, 3.5)
    assert max(dihedral.split_distances(start, a, b)) > 0.05


def test_command_writes_split_specs_that_reopen(tmp_path):
    a, b = pieces(known())
    fa, fb = tmp_path / "a.json", tmp_path / "b.json"
    fa.write_text(json.dumps(a.tolist()))
    fb.write_text(json.dumps(b.tolist()))
    out = tmp_path / "out"
    result = CliRunner().invoke(cli, ["escherize", str(fa), str(fb), "--types", "IH41", "--starts", "1",
                                      "--samples", "64", "-o", str(out)])
    assert result.exit_code == 0, result.output
    ranking = json.loads((out / "ranking.json").read_text())
    assert [r["name"] for r in ranking] == ["IH41"]
    spec = json.loads((out / "01-IH41-split.isohedral.json").read_text())
    assert spec["spec"] == ranking[0]["spec"] and "split" in spec["spec"]
    tiling = tiling_from_spec(spec["spec"])
    d = dihedral.split_distances(tiling, a, b, samples=64)
    assert max(d) == pytest.approx(ranking[0]["distance"], abs=1e-9)
    assert list(d) == pytest.approx(ranking[0]["distances"], abs=1e-9)
    assert (out / "01-IH41-pieces.svg").read_text().count("<path") == 4  # two pieces, two goals
    svg = tmp_path / "r.svg"
    reopened = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{tmp_path / 'c.db'}", "render", "--system",
                                        str(out / "01-IH41-split.isohedral.json"), "-o", str(svg)])
    assert reopened.exit_code == 0, reopened.output


@pytest.mark.parametrize(
    ("goal_b", "fragment"),
    [
        ([[0, 0], [1, 1], [1, 0], [0, 1]], "goal B: the polygon crosses itself"),
        ([[0, 0], [1, 1]], "at least 3"),
        ((np.array([[0, 0], [1, 0], [1, 1], [0, 1]]) * 0.01).tolist(), "give goals within 25x"),
        ((np.array([[0, 0], [1, 0], [1, 1], [0, 1]]) * 100).tolist(), "goal B's area is"),
    ],
)
def test_bad_goal_pairs_are_one_line_errors(tmp_path, goal_b, fragment):
    a = [[0, 0], [2, 0], [2, 1], [0, 1]]
    with pytest.raises(ParseError, match=None) as info:
        dihedral.check_goals(a, goal_b)
    assert fragment.replace("goal B: ", "") in str(info.value)
    fa, fb = tmp_path / "a.json", tmp_path / "b.json"
    fa.write_text(json.dumps(a))
    fb.write_text(json.dumps(goal_b))
    result = CliRunner().invoke(cli, ["escherize", str(fa), str(fb), "-o", str(tmp_path / "out")])
    assert_one_line_error(result, fragment.replace("goal B: ", ""))
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("extra", "fragment"),
    [
        (["c.json"], "one goal (monohedral) or two (dihedral), got 3"),
        (["--path-points", "0"], "out of range 1..24"),
        (["--path-points", "25"], "out of range 1..24"),
    ],
)
def test_bad_dihedral_invocations_are_one_line_errors(tmp_path, extra, fragment):
    sq = [[0, 0], [1, 0], [1, 1], [0, 1]]
    for name in ("a.json", "b.json", "c.json"):
        (tmp_path / name).write_text(json.dumps(sq))
    args = [str(tmp_path / "a.json"), str(tmp_path / "b.json")]
    args += [str(tmp_path / e) if e.endswith(".json") else e for e in extra]
    result = CliRunner().invoke(cli, ["escherize", *args, "-o", str(tmp_path / "out")])
    assert_one_line_error(result, fragment)


def test_library_checks_its_settings():
    a, b = pieces(known())
    with pytest.raises(ParameterError, match="path points"):
        dihedral.escherize_dihedral(a, b, [1], settings=dihedral.DihedralSettings(path_points=0))
    with pytest.raises(ParameterError, match="marked"):
        dihedral.escherize_dihedral(a, b, [19])


# --------------------------------------------------------------------------- Heaven and Hell


def test_two_colourings_exist_exactly_for_the_topologies_with_even_vertex_valences():
    """A plane tiling's tiles can be coloured in two colours with every pair of edge-neighbours
    different iff every tiling vertex has even valence (face 2-colourability of a plane map):
    of the 81 unmarked types, the 43 of topologies 4^4 (30), 6^3 (8), 4.8^2 (4) and 4.6.12 (1)."""
    from tilekit.plugins.isohedral.templates import get_template, topology_valences

    even = [ih for ih in range(1, 94) if not get_template(ih).marked
            and all(v % 2 == 0 for v in topology_valences(get_template(ih).topology))]
    assert heaven.heaven_hell_types() == even
    assert len(even) == 43


def test_heaven_and_hell_from_a_goal_and_its_mirror_image(tmp_path):
    """A chiral IH41 tile and its mirror image as the two goals: one IH41 tile matches both
    (distance < 1e-6; a type's tilings are closed under reflection), and its tiling, coloured
    by the found two-colouring, is valid with every pair of edge-neighbours in two colours."""
    t = IsohedralTiling("IH41", None, {"a": EdgeShape.parse("0.3,0.15:0.6,-0.1")}, check=True)
    a = np.asarray(t.prototile.outline)
    b = similar(a, 1.0, 2.0, (3.0, 1.0), mirror=True)
    results, failed = heaven.heaven_hell(a, b, [41, 44])
    assert not failed
    best = results[0]
    assert best.ih == 41 and best.distance < 1e-6 and best.mirrored[0] != best.mirrored[1]
    tiling = best.tiling()
    region = tiling.default_region()
    patch = tiling.patch(region)
    assert patch.validate(region).ok
    pairs = patch.adjacency().edge
    assert len(pairs) and np.all(patch.colour[pairs[:, 0]] != patch.colour[pairs[:, 1]])
    assert set(patch.colour.tolist()) == {0, 1}


def test_heaven_and_hell_command(tmp_path):
    t = IsohedralTiling("IH41", None, {"a": EdgeShape.parse("0.3,0.15:0.6,-0.1")}, check=True)
    a = np.asarray(t.prototile.outline)
    fa, fb = tmp_path / "a.json", tmp_path / "b.json"
    fa.write_text(json.dumps(a.tolist()))
    fb.write_text(json.dumps((a * [-1, 1]).tolist()))
    out = tmp_path / "out"
    result = CliRunner().invoke(cli, ["escherize", str(fa), str(fb), "--heaven-hell", "--types", "IH41",
                                      "--starts", "1", "-o", str(out)])
    assert result.exit_code == 0, result.output
    spec = json.loads((out / "01-IH41-hh.isohedral.json").read_text())
    assert spec["spec"]["colouring"] == "(1)(2 1)(2 1)"  # the checkerboard
    assert (out / "01-IH41-tile.svg").exists() and (out / "01-IH41-tiling.svg").exists()
    reopened = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{tmp_path / 'c.db'}", "render", "--system",
                                        str(out / "01-IH41-hh.isohedral.json"), "-o", str(tmp_path / "r.svg")])
    assert reopened.exit_code == 0, reopened.output
    bad = CliRunner().invoke(cli, ["escherize", str(fa), str(fb), "--heaven-hell", "--types", "IH1", "-o", str(out)])
    assert_one_line_error(bad, "IH1 has no two-colouring")
    one = CliRunner().invoke(cli, ["escherize", str(fa), "--heaven-hell", "-o", str(out)])
    assert_one_line_error(one, "--heaven-hell needs two goals")


# --------------------------------------------------------------------------- metamorphosis


@pytest.mark.parametrize(
    ("ih", "params", "edges"),
    [
        (1, [0.12, 0.5, 0.15, 0.6], {"a": "0.2,0.1:0.4,0.12:0.6,-0.1:0.8,-0.05", "c": "0.3,0.1:0.7,0.1"}),
        (41, None, {"a": "0.3,0.15:0.6,-0.1"}),
        (16, None, {"b": "0.25,0.12:0.5,0:0.75,-0.12"}),  # an S edge (centrally symmetric shapes)
        (84, None, {}),  # no shapes: the strip is the tiling itself
    ],
)
def test_metamorphosis_strip_is_a_tiling_from_the_start_tile_to_the_end_tile(ih, params, edges):
    """Every edge is interpolated at its own midpoint, so neighbours agree: the strip has no
    gap and no overlap (Patch.validate), its tiles left of the strip are the start tile and
    right of it the end tile (distance 0 after a similarity, same area)."""
    from tilekit.plugins.isohedral.metamorphosis import metamorphosis

    end = IsohedralTiling(ih, params, {k: EdgeShape.parse(v) for k, v in edges.items()}, check=True)
    start = IsohedralTiling(ih, list(end.params))
    patch, box = metamorphosis(start, end, 8, 2)
    region = shapely.box(*box)
    report = patch.validate(region)
    assert report.ok, report.summary()
    seen = {0: 0, 1: 0}
    corners = np.array(end.prototile.corners)  # the same outline indices at every t (equal point counts)
    for proto, aspect in zip(patch.prototiles, patch.aspect):
        q = np.asarray(proto.outline)
        # a reflected aspect's outline was clockwise and is stored reversed
        mirrored = np.linalg.det(end.unit_transform[aspect][:2, :2]) < 0
        at = len(q) - 1 - corners if mirrored else corners
        mids = (q[at] + np.roll(q[at], -1, axis=0)) / 2
        # every edge's midpoint left of the strip (t = 0) or right of it (t = 1)
        for side, keyframe, outside in ((0, start, mids[:, 0].max() <= 1e-9), (1, end, mids[:, 0].min() >= box[2] - 1e-9)):
            if outside:
                seen[side] += 1
                assert signed_area(q) == pytest.approx(keyframe.prototile.area, rel=1e-9)
                assert escher.shape_distance(q, np.asarray(keyframe.prototile.outline)) < 1e-6
    assert seen[0] > 0 and seen[1] > 0


def test_metamorphosis_refuses_keyframes_it_cannot_interpolate():
    from tilekit.plugins.isohedral.metamorphosis import metamorphosis

    a = IsohedralTiling(1)
    with pytest.raises(ParameterError, match="two tilings of one type"):
        metamorphosis(a, IsohedralTiling(2))
    with pytest.raises(ParameterError, match="parameters .* differ"):
        metamorphosis(a, IsohedralTiling(1, [0.12, 0.5, 0.15, 0.6]))
    with pytest.raises(ParameterError, match="same number of points"):
        metamorphosis(IsohedralTiling(1, None, {"a": EdgeShape.parse("0.5,0.1")}),
                      IsohedralTiling(1, None, {"a": EdgeShape.parse("0.3,0.1:0.6,0.1")}))
    with pytest.raises(ParameterError, match="2..40 columns"):
        metamorphosis(a, a, 41)


def test_metamorphosis_command(tmp_path):
    end = IsohedralTiling(41, None, {"a": EdgeShape.parse("0.3,0.15:0.6,-0.1")}, check=True)
    f = tmp_path / "end.isohedral.json"
    f.write_text(json.dumps({"family": "isohedral", "spec": end.spec()}))
    result = CliRunner().invoke(cli, ["metamorphosis", str(f), "--columns", "6", "-o", str(tmp_path / "m.svg")])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "m.svg").read_text().startswith("<svg")
    other = tmp_path / "other.isohedral.json"
    other.write_text(json.dumps({"spec": {"ih": 1}}))
    bad = CliRunner().invoke(cli, ["metamorphosis", str(f), "--start", str(other), "-o", str(tmp_path / "x.svg")])
    assert_one_line_error(bad, "two tilings of one type")
    big = CliRunner().invoke(cli, ["metamorphosis", str(f), "--columns", "99", "-o", str(tmp_path / "x.svg")])
    assert_one_line_error(big, "out of range 2..40")
