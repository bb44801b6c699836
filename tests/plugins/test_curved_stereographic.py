"""The sphere's stereographic view (issue 35, design note and item 4): `--set plane=stereographic`
or `stereographic:K`, the projection from the centre of tile K, every edge the true circular arc.

Facts checked: stereographic projection is conformal, so the corner angles of the projected
regular polygons of {4,3}, {5,3} and {3,5} are the spherical ones, 2π/q (the interior angle of
{p, q}'s face: q of them close round a vertex); it maps circles on the sphere to circles or lines
(a great circle through the pole to a line), so the arc through an edge's projected ends and
midpoint holds every other projected point of that edge, and the SVG arc command drawn (its
radius and flags read back by the SVG rules, F.6.5 of SVG 1.1) sweeps through them; every face
is drawn once (the pole's tile as the outside, holding every other tile); bad planes and poles
are one-line errors, exit 2.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import shapely
from cliutil import assert_one_line_error
from family_cli import family_cli

from tilekit.errors import ParameterError
from tilekit.plugins.curved import LavesTiling, model, uniform_tiling
from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling
from tilekit.plugins.curved.render import (
    circle_through,
    stereographic_edges,
    three_point_arc_commands,
)
from tilekit.plugins.curved.tiling import RegularTiling


def _tilings() -> list:
    """Regular, uniform, Laves, and shaped (Laves and curved-isohedral) tilings of the sphere."""
    return [RegularTiling(3, 3, plane="stereographic"), RegularTiling(4, 3, plane="stereographic"),
            RegularTiling(3, 5, plane="stereographic:7"), uniform_tiling("5.6.6", plane="stereographic"),
            uniform_tiling("3.3.3.3.4", plane="stereographic:5"), LavesTiling("[3.4.3.4]", plane="stereographic"),
            LavesTiling("[3.4.3.4]", group="rotations", edges={"a": "0.3,0.15:0.6,-0.1"}, plane="stereographic:3"),
            CurvedIsohedralTiling(3, 3, pairing="a b c", edges={"a": "0.25,0.2:0.4,0.15"}, plane="stereographic:2")]


def _tangent(a: np.ndarray, m: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Unit tangents at a of the arcs from a through m to b (each (n, 2)), pointing along them."""
    c, _, straight = circle_through(a, m, b)
    radial = a - c
    t = np.stack([-radial[:, 1], radial[:, 0]], axis=1)
    t = np.where(((t * (m - a)).sum(axis=1) < 0)[:, None], -t, t)  # the arc a -> m is under half a turn
    t = np.where(straight[:, None], b - a, t)
    return t / np.linalg.norm(t, axis=1, keepdims=True)


@pytest.mark.parametrize("pq, poles", [((4, 3), (0, 3)), ((5, 3), (0, 7)), ((3, 5), (0, 11))])
def test_projection_is_conformal(pq, poles):
    """The corner angles of every projected face, the pole's too, between its edges' arcs at the
    corner, are the spherical angle 2π/q to 1e-9."""
    p, q = pq
    for pole in poles:
        t = RegularTiling(p, q, plane=f"stereographic:{pole}")
        (idx, flat, mid, _), = stereographic_edges(t.patch(), pole)
        n, k = flat.shape[:2]
        a = flat.reshape(-1, 2)
        to_next = _tangent(a, mid.reshape(-1, 2), np.roll(flat, -1, axis=1).reshape(-1, 2))
        to_prev = _tangent(a, np.roll(mid, 1, axis=1).reshape(-1, 2), np.roll(flat, 1, axis=1).reshape(-1, 2))
        angle = np.arccos(np.clip((to_next * to_prev).sum(axis=1), -1.0, 1.0))
        assert len(angle) == n * p
        assert np.abs(angle - 2 * math.pi / q).max() < 1e-9, (pq, pole)


def _svg_arc(x1, y1, x2, y2, r, large, sweep):
    """The centre and start/sweep angles of an SVG arc (SVG 1.1 F.6.5, no rotation, the radius
    as given: the three-point arcs never need scaling up beyond rounding)."""
    mx, my = (x1 - x2) / 2, (y1 - y2) / 2
    lam = (mx * mx + my * my) / (r * r)
    r = r * max(1.0, math.sqrt(lam))
    num = max(0.0, r * r * r * r - r * r * (mx * mx + my * my))
    coef = math.sqrt(num / (r * r * (mx * mx + my * my)))
    if large == sweep:
        coef = -coef
    cx = coef * r * my / r + (x1 + x2) / 2
    cy = -coef * r * mx / r + (y1 + y2) / 2
    start = math.atan2(y1 - cy, x1 - cx)
    delta = (math.atan2(y2 - cy, x2 - cx) - start) % (2 * math.pi)
    if not sweep:
        delta -= 2 * math.pi
    return cx, cy, r, start, delta


@pytest.mark.parametrize("i", range(8))
def test_arcs_hold_the_projected_great_circle(i):
    """Six more points of every edge's geodesic, projected, lie on the circle through its
    projected ends and midpoint (1e-9 of its radius) or on their line (1e-9); and on the SVG
    commands drawn (two arcs, end to midpoint to end): read back by the SVG rules, each arc
    sweeps through the points of its half (the 7-decimal coordinates: 1e-6)."""
    t = _tilings()[i]
    patch = t.patch()
    s = np.array([0.1, 0.3, 0.45, 0.55, 0.7, 0.9])
    arcs = lines = 0
    for _, flat, mid, v in stereographic_edges(patch, int(t.plane.partition(":")[2] or 0)):
        a, m, b = flat.reshape(-1, 2), mid.reshape(-1, 2), np.roll(flat, -1, axis=1).reshape(-1, 2)
        va, vb = v.reshape(-1, 3), np.roll(v, -1, axis=1).reshape(-1, 3)
        pts = (1 - s)[None, :, None] * va[:, None] + s[None, :, None] * vb[:, None]
        more = model.stereographic(pts / np.linalg.norm(pts, axis=-1, keepdims=True))   # (e, 5, 2)
        c, r, straight = circle_through(a, m, b)
        off_circle = np.abs(np.linalg.norm(more - c[:, None], axis=-1) - r[:, None]) / r[:, None]
        assert off_circle[~straight].max(initial=0.0) < 1e-9
        w = b - a
        off_line = np.abs(w[:, None, 0] * (more[..., 1] - a[:, None, 1]) - w[:, None, 1] * (more[..., 0] - a[:, None, 0]))
        assert (off_line[straight] / np.linalg.norm(w[straight], axis=1)[:, None]).max(initial=0.0) < 1e-9
        cmds = three_point_arc_commands(a, m, b)
        for e, cmd in enumerate(cmds):
            if cmd.startswith("L"):
                lines += 1
                continue
            arcs += 1
            first, second = (tuple(float(x) for x in part.split()) for part in cmd[1:].split("A"))
            (rr, _, _, large, sweep, xm, ym), (_, _, _, large2, sweep2, x2, y2) = first, second
            assert (large, large2) == (0, 0) and sweep == sweep2
            for (x0, y0, x1, y1), part in (((a[e, 0], -a[e, 1], xm, ym), more[e, :3]),
                                           ((xm, ym, x2, y2), more[e, 3:])):
                cx, cy, rad, start, delta = _svg_arc(x0, y0, x1, y1, rr, 0, int(sweep))
                for x, y in part:
                    y = -y  # SVG's y points down
                    assert abs(math.hypot(x - cx, y - cy) - rad) < 1e-6 * max(1.0, rad)
                    turn = (math.atan2(y - cy, x - cx) - start) % (2 * math.pi)
                    turn = turn if delta > 0 else turn - 2 * math.pi
                    assert 0 < turn / delta < 1
    assert arcs > 0
    if isinstance(t, RegularTiling) and (t.p, t.q) == (4, 3):
        # the cube's 4 edges on the two great circles through the pole (the edges parallel to the
        # pole face's axis), each drawn by both its faces
        assert lines == 8


@pytest.mark.parametrize("i", range(8))
def test_every_face_is_drawn_once(i):
    """One subpath per face and the pole's face as the outside (the frame less its boundary,
    even-odd), the patch's faces all drawn, every other face inside that boundary."""
    t = _tilings()[i]
    patch = t.patch()
    assert patch.validate().ok
    svg = t.render_svg(patch)
    d_outside = re.findall(r'<path data-tile="outside"[^>]*fill-rule="evenodd"[^>]* d="([^"]*)"', svg)
    assert len(d_outside) == 1 and d_outside[0].count("M") == 2
    rest = re.findall(r'<path fill="[^"]*" stroke[^>]* d="([^"]*)"', svg)
    assert sum(d.count("M") for d in rest) + 1 == len(patch)
    pole = int(t.plane.partition(":")[2] or 0)
    hole = None
    others = []
    for idx, flat, _, _ in stereographic_edges(patch, pole):
        for j, tile in enumerate(idx):
            if tile == pole:
                hole = shapely.Polygon(flat[j])
            else:
                others.append(flat[j])
    assert hole is not None and len(others) == len(patch) - 1
    # the corners of every other face lie within the pole face's corners' polygon, padded by the
    # arcs' bulge (a corner on it is shared with the pole face)
    assert all(hole.buffer(0.5 * hole.length / len(hole.exterior.coords)).covers(shapely.MultiPoint(o))
               for o in others)


def test_plane_options_and_specs():
    t = RegularTiling(4, 3, plane="stereographic:2")
    assert t.spec()["plane"] == "stereographic:2" and RegularTiling.from_spec(t.spec()).plane == "stereographic:2"
    assert RegularTiling(4, 3, plane="stereographic:0").plane == "stereographic"
    assert "plane" not in RegularTiling(4, 3, plane="orthographic").spec()
    assert t.configure(plane="orthographic").plane == "poincare"
    u = uniform_tiling("5.6.6").configure(plane="stereographic:4")
    assert u.plane == "stereographic:4" and len(re.findall("<path", u.render_svg(u.patch()))) >= 2
    with pytest.raises(ParameterError, match="K in 0..5"):
        t.configure(plane="stereographic:6").render_svg(t.patch())
    with pytest.raises(ParameterError, match="applies to tilings of the sphere"):
        RegularTiling(7, 3, plane="stereographic")
    with pytest.raises(ParameterError, match="plane applies to hyperbolic tilings"):
        CurvedIsohedralTiling(3, 3, pairing="a b c", plane="klein")


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "curved")


def test_cli_renders_the_view(cli):
    r = cli("render", "truncated-icosahedron", "--set", "plane=stereographic:12", "-o", "ball.svg")
    assert r.exit_code == 0 and "(32 tiles)" in r.output, r.output


@pytest.mark.parametrize("args, needle", [
    (["cube", "--set", "plane=stereographic:6"], "the pole must be the centre of one of the 6 tiles, K in 0..5"),
    (["cube", "--set", "plane=stereographic:-1"], "the stereographic pole's tile K must be an integer 0.."),
    (["cube", "--set", "plane=stereographic:x"], "the stereographic pole's tile K must be a number"),
    (["cube", "--set", "plane=stereographic:"], "needs a tile number K"),
    (["cube", "--set", "plane=stereo"], "plane must be one of poincare, klein, halfplane (hyperbolic) or orthographic"),
    (["cube", "--set", "plane=klein:2"], "plane must be one of"),
    (["{7,3}", "--set", "plane=stereographic"], "plane stereographic applies to tilings of the sphere"),
    (["3.14.14", "--set", "plane=orthographic"], "plane orthographic applies to tilings of the sphere"),
    (["curved-ih-4-3-3", "--set", "plane=halfplane"], "plane applies to hyperbolic tilings"),
])
def test_cli_bad_plane_is_one_line(cli, args, needle):
    assert_one_line_error(cli("render", *args, "-o", "x.svg"), needle)
