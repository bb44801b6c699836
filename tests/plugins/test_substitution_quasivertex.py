"""Quasivertex parameterizations of the Penrose rhombs (book §6.3, Figures 6.13 and 6.14).

The point formulas are those of Figure 6.13; the point order around each tile and the
placement of the book's frame were derived (see quasivertex.py) and are checked here by what
they must achieve: deformed patches tile (Patch.validate), and Figure 6.14's edge labels
abcdefegabhg / afcdegabhg meet in the interlocking pairs (a,g), (b,e), (c,d), (f,h) of §6.3.
"""

from __future__ import annotations

import math
from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest
import shapely
from test_substitution import assert_valid

from tilekit.errors import ParameterError
from tilekit.geometry import Affine
from tilekit.plugins.substitution import from_spec, tiling
from tilekit.plugins.substitution import quasivertex as qv

#: Parameter sets (r1, theta1 degrees, r2, theta2 degrees) that give simple tiles; the last
#: two are large deformations whose tiles reach well outside their straight rhombs.
GOOD = [
    (0.15, 20.0, 0.25, -30.0),
    (0.1, -20.0, 0.1, 40.0),
    (0.3, 10.0, 0.2, 5.0),
    (0.0, 0.0, 0.35, 0.0),
    (0.513, 65.0, 0.526, -5.1),
    (0.27, 82.3, 0.572, 53.4),
]
REGION = (-5.0, -5.0, 5.0, 5.0)


def p3(r1: float, t1: float, r2: float, t2: float, **kw):
    return tiling("penrose-p3").configure(r1=r1, theta1=t1, r2=r2, theta2=t2, **kw)


def cyclic_equal(a: np.ndarray, b: np.ndarray) -> bool:
    return len(a) == len(b) and any(np.allclose(np.roll(a, k, axis=0), b, atol=1e-9) for k in range(len(a)))


def test_zero_parameters_give_the_straight_rhombs() -> None:
    """r1 = r2 = 0 collapses every quasivertex onto a corner (Figure 6.13): the straight P3
    tiles, and the same patch as the unparameterized tiling."""
    plain = tiling("penrose-p3")
    for theta in (0.0, 37.0):
        t = p3(0.0, theta, 0.0, -theta)
        for a, b in zip(t.prototiles, plain.prototiles):
            assert cyclic_equal(a.outline, b.outline)
        pa, pb = t.patch(REGION), plain.patch(REGION)
        assert len(pa) == len(pb)
        assert np.isclose(shapely.area(pa.geometries()).sum(), shapely.area(pb.geometries()).sum())


@pytest.mark.parametrize("params", GOOD)
def test_deformed_rhombs_tile(params) -> None:
    """Every patch of deformed rhombs is a tiling of its region: no overlaps, no gaps (the
    defining property of a quasivertex parameterization, §6.3), near the origin and far
    away where the tiles come from a deeper substitution."""
    t = p3(*params)
    assert [len(p.outline) for p in t.prototiles] == [
        len(qv._merge(*qv.book_outlines(qv.QuasivertexParams(*params))[n])[0]) for n in ("thin", "thick")
    ]
    patch = t.patch(REGION)
    assert_valid(patch, REGION)
    far = (61.0, -23.0, 67.0, -17.0)
    assert_valid(t.patch(far), far)


def test_cli_depth_patch_tiles() -> None:
    """A fixed-depth patch (as `tilekit render penrose-p3 --depth 6 --set r1=...` draws it) has
    no overlaps, and every interior edge meets its reversed copy in exactly one other tile."""
    t = tiling("penrose-p3").configure(depth=6, r1=0.15, theta1=30, r2=0.25, theta2=-15)
    patch = t.patch()
    report = patch.validate()
    assert not report.overlaps, report.summary()
    # whole-patch area is exactly the straight patch's area
    straight = tiling("penrose-p3").configure(depth=6).patch()
    assert np.isclose(shapely.area(patch.geometries()).sum(), shapely.area(straight.geometries()).sum(), rtol=1e-12)


@pytest.mark.parametrize("r1, t1, r2, t2", GOOD + [(0.05, -60.0, 0.4, -20.0), (0.4, 0.0, 0.45, 0.0)])
def test_deformed_tiles_keep_their_areas(r1, t1, r2, t2) -> None:
    """The quasivertices only trade area along a tile's own boundary: the thick rhomb keeps
    area sin(2pi/5) and the thin one sin(pi/5) (unit edges) for every parameter value.
    (Not implied by tiling alone -- only the tile-frequency-weighted sum is -- so measured.)"""
    t = p3(r1, t1, r2, t2)
    thin, thick = t.prototiles
    assert math.isclose(thick.area, math.sin(2 * math.pi / 5), rel_tol=1e-12)
    assert math.isclose(thin.area, math.sin(math.pi / 5), rel_tol=1e-12)


def _edges_by_position(patch):
    """World edges of the deformed tiles (between consecutive quasivertices) -> labels."""
    found = defaultdict(list)
    for p, tr in zip(patch.prototile, patch.transform):
        tile = patch.prototiles[p]
        corners = list(tile.corners)
        pts = Affine.apply(tr, tile.outline[corners])
        labels = [tile.edge_labels[c] for c in corners]
        for i, lab in enumerate(labels):
            a, b = pts[i], pts[(i + 1) % len(pts)]
            key = tuple(np.round(np.concatenate([a, b]) if tuple(np.round(a, 6)) < tuple(np.round(b, 6)) else np.concatenate([b, a]), 6))
            found[key].append((lab, float(np.linalg.norm(b - a))))
    return found


@pytest.mark.parametrize("params", GOOD[:3])
def test_figure_6_14_labels_meet_in_interlocking_pairs(params) -> None:
    """§6.3: the thick and thin rhombs' edges, labelled abcdefegabhg and afcdegabhg from A
    and A', meet only in the pairs (a,g), (b,e), (c,d), (f,h) -- checked on every shared edge
    of a patch; paired edges have equal lengths."""
    t = p3(*params)
    assert ["".join(p.edge_labels[c] for c in p.corners) for p in t.prototiles] == [qv.THIN_LABELS, qv.THICK_LABELS]
    shared = [v for v in _edges_by_position(t.patch(REGION)).values() if len(v) == 2]
    assert len(shared) > 300
    seen = set()
    for (la, da), (lb, db) in shared:
        assert qv.PARTNER[la] == lb, (la, lb)
        assert math.isclose(da, db, rel_tol=1e-9)
        seen.add(frozenset((la, lb)))
    assert seen == {frozenset(p) for p in ("ag", "be", "cd", "fh")}


@pytest.mark.parametrize("edges", [
    ["a=0.3,0.08:0.6,-0.05", "c=0.5,0.12", "f=0.4,-0.1", "b=0.5,0.05"],
    ["g=0.25,-0.1:0.7,0.1", "d=0.5,-0.12"],
])
def test_user_edge_shapes_interlock(edges) -> None:
    """Edge shapes on the labelled edges (the partner label gets the complement) still tile."""
    t = p3(0.15, 20.0, 0.25, -30.0, edges=edges)
    plain = p3(0.15, 20.0, 0.25, -30.0)
    assert all(len(a.outline) > len(b.outline) for a, b in zip(t.prototiles, plain.prototiles))
    assert_valid(t.patch(REGION), REGION)
    back = from_spec(t.spec())
    assert all(cyclic_equal(a.outline, b.outline) for a, b in zip(back.prototiles, t.prototiles))


@pytest.mark.parametrize("options, name", [
    (dict(r1=0.9, theta1=30), "r1=0.9"),
    (dict(r1=0.2, r2=0.3, theta2=170), "theta2=170"),
    (dict(r1=0.2, theta1=-40, r2=0.1, theta2=60), "r1=0.2"),
])
def test_self_intersecting_parameters_are_rejected_by_name(options, name) -> None:
    with pytest.raises(ParameterError, match=rf"parameter {name} makes the .*self-intersect.*must lie in"):
        tiling("penrose-p3").configure(**options)


def test_named_range_is_valid() -> None:
    """The range the error message offers really gives simple tiles."""
    with pytest.raises(ParameterError) as err:
        tiling("penrose-p3").configure(r1=0.2, r2=0.3, theta2=170)
    lo, hi = (float(v) for v in str(err.value).split("[")[1].split("]")[0].split(","))
    for v in (lo, (lo + hi) / 2, hi):
        p3(0.2, 0.0, 0.3, v)


def test_bad_options_are_rejected() -> None:
    with pytest.raises(ParameterError, match="r1='x' is not a number"):
        tiling("penrose-p3").configure(r1="x")
    with pytest.raises(ParameterError, match="apply to penrose-p3, penrose-p2 only"):
        tiling("chair").configure(r1=0.1, r2=0.2)
    with pytest.raises(ParameterError, match="cannot be combined"):
        tiling("penrose-p3").configure(r1=0.1, r2=0.2, params=[0.1])
    with pytest.raises(ParameterError, match="not a quasivertex edge label"):
        p3(0.1, 0, 0.2, 0, edges=["z=0.5,0.1"])
    with pytest.raises(ParameterError, match="interlock"):
        p3(0.1, 0, 0.2, 0, edges=["a=0.5,0.1", "g=0.5,0.1"])
    with pytest.raises(ParameterError, match="edge shapes on .*self-intersect"):
        p3(0.1, 0, 0.2, 0, edges=["c=0.5,0.9:0.4,-0.9:0.6,0.2:0.3,0.2"])
    with pytest.raises(ParameterError, match="does not take option"):
        tiling("penrose-p3").configure(r3=0.1)


def test_cli_render_with_settings(tmp_path: Path) -> None:
    """`tilekit render penrose-p3 --depth 5 --set r1=... --edge a=...` writes the picture."""
    from click.testing import CliRunner

    from tilekit.cli import cli

    db = f"sqlite:///{tmp_path / 'cat.db'}"
    out = tmp_path / "qv.svg"
    args = ["--catalogue", db, "render", "penrose-p3", "--depth", "5", "--set", "r1=0.15", "--set", "theta1=30",
            "--set", "r2=0.25", "--set", "theta2=-15", "--edge", "a=0.4,0.1", "-o", str(out)]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    n = len(tiling("penrose-p3").configure(depth=5).patch())  # the straight depth-5 patch
    assert f"({n} tiles)" in res.output
    assert out.read_text().startswith("<svg")
    bad = CliRunner().invoke(cli, args[:-2] + ["--set", "r1=0.9", "-o", str(out)])
    assert bad.exit_code != 0 and "r1=0.9" in bad.output
