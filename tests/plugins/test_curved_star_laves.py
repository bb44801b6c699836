"""The duals of the non-Wythoffian uniform tilings of the hyperbolic plane (issue 35;
tilekit/plugins/curved/starlaves.py): face-transitive Laves tilings [3^3.6^2], [4^2.6^2] ...

Facts checked: the dual of the dual (the tiles' corners are the uniform tiling's face centres and
their centres its vertices; the tiles round a corner are as many as the face's sides, angles 2π);
no overlap and no gap (validate on a disc); the tile's symmetries in the group are exactly the
vertex star's symmetries that map the uniform tiling onto itself (checked on its faces, not by
the closure that finds them); the incidence symbol's own tile symmetries are those; its
Delaney symbol closes on the tile's topology and its orbifold satisfies Gauss–Bonnet (the tile's
area over |tile symmetry| is −2πχ); every record builds; one-line errors.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from cliutil import assert_one_line_error
from family_cli import family_cli
from test_uniform import vertex_table

from tilekit.errors import ParameterError
from tilekit.plugins.curved import delaney, star_laves_records
from tilekit.plugins.curved.starlaves import StarLavesTiling
from tilekit.plugins.curved.stars import StarTiling, develop, star_symmetries

SAMPLE = ["3.3.3.6.6", "4.4.6.6", "3.4.4.4.4", "4.4.4.4.5", "3.3.3.3.4.4", "3.3.3.8.8"]


@pytest.mark.parametrize("config", SAMPLE)
def test_dual_of_the_dual_and_validate(config):
    t = StarLavesTiling(config, radius=2.0)
    u = StarTiling(config, radius=2.0)
    patch, upatch = t.patch(), u.patch()
    assert patch.validate(shapely.Point(0, 0).buffer(math.tanh(1.0), 64)).ok  # the disc of radius 2
    near = math.cosh(1.5)
    corners = np.concatenate(patch.vertex_lists())
    ucentres = upatch.model_centres()
    for pts, pool in ((corners[corners[:, 2] <= near], ucentres),                      # corners: face centres
                      (patch.model_centres()[patch.model_centres()[:, 2] <= near],     # centres: vertices
                       np.concatenate(upatch.vertex_lists()))):
        gap = np.abs(pts[:, None, :] - pool[None, :, :]).max(axis=2).min(axis=1)
        assert gap.max() < 1e-7
    # round each corner near the centre: as many tiles as the face there has sides, angles 2π
    sizes = {tuple(np.round(c, 7)): n for c, n in zip(ucentres, [len(f) for f in upatch.vertex_lists()])}
    checked = 0
    for v, tiles, total in vertex_table(patch):
        if v[2] <= near:
            assert len(tiles) == sizes[tuple(np.round(v, 7))] and abs(total - 2 * math.pi) < 1e-9
            checked += 1
    assert checked >= len(t.corners)


@pytest.mark.parametrize("config", SAMPLE)
def test_tile_symmetries_are_the_tilings(config):
    """Each of the star's symmetries maps the uniform tiling's faces near the pole onto faces
    of the same size exactly when the group holds it (the closure of stars.tiling_stabiliser,
    checked here on the faces instead); the symbol's tile symmetries are as many."""
    t = StarLavesTiling(config)
    _, faces, sizes = develop(t.star, t.pairing, 3.0)
    centres = faces[:, :, 2]
    inner = centres[:, 2] <= math.cosh(1.5)
    kept = 0
    for m, _perm in star_symmetries(t.star):
        moved = centres[inner] @ m.T
        d = np.abs(moved[:, None, :] - centres[None, :, :]).max(axis=2)
        hit = d.argmin(axis=1)
        symmetry = bool((d.min(axis=1) < 1e-7).all() and (sizes[hit] == sizes[inner]).all())
        in_group = bool((np.abs(t.stabiliser - m).max(axis=(1, 2)) < 1e-9).any())
        assert symmetry == in_group
        kept += symmetry
    assert kept == len(t.stabiliser) == len(t.incidence_symbol.tile_symmetries())
    assert t.properties()["tile_symmetry"] == kept


def test_records_build_and_their_groups_satisfy_gauss_bonnet():
    """Every vertex-star record has its dual: its symbol closes on the tile's topology (the
    Delaney check), and the orbifold's area −2πχ is the tile's area over its symmetries."""
    recs = star_laves_records()
    assert len(recs) == 98 and len({r.name for r in recs}) == 98
    for r in recs:
        t = StarLavesTiling.from_spec(r.spec)
        assert t.spec() == r.spec and r.properties["orbifold"] == t.symbol_orbifold()
        chi = delaney.euler_characteristic(t.delaney_symbol, t.valences)
        assert abs(-2 * math.pi * float(chi) - t.tile_area() / r.properties["tile_symmetry"]) < 1e-9, r.name
        assert notation_sorted(r.properties["valences"]) == notation_sorted(r.properties["dual_configuration"])
    named = {r.name: r for r in recs}
    assert named["[3^3.6^2]"].properties["orbifold"] == "2*32"
    assert named["[3^3.6^2]"].properties["incidence_symbol"] == "[a+a-b+cb-; a+b-c]"
    assert "V3.3.3.6.6" in named["[3^3.6^2]"].aliases


def notation_sorted(dotted: str) -> list[int]:
    return sorted(int(x) for x in dotted.split("."))


@pytest.fixture
def cli(tmp_path, monkeypatch):
    return family_cli(tmp_path, monkeypatch, "curved")


def test_cli_names_and_errors(cli):
    r = cli("render", "[3^3.6^2]", "--set", "radius=1.5", "-o", "d.svg")
    assert r.exit_code == 0, r.output
    for name in ("V6.6.3.3.3", "[4.4.6.6]"):
        r = cli("show", name)
        assert r.exit_code == 0 and "laves" in r.output, r.output
    assert_one_line_error(cli("render", "[3^3.6^2]", "--set", "radius=40", "-o", "x.svg"), "radius")
    assert_one_line_error(cli("render", "[3^3.6^2]", "--set", "pairing=0- 1- 2- 3- 4-", "-o", "x.svg"),
                          "do not close up")


@pytest.mark.parametrize("kwargs, needle", [
    ({"configuration": "3.4.3.4.4"}, "no pairing of its star's edges closes up"),
    ({"configuration": "3.4.4.4"}, "is spherical"),
    ({"configuration": "3.3.3.6.6", "radius": -1}, "radius"),
])
def test_bad_input_is_one_line(kwargs, needle):
    with pytest.raises(ParameterError) as err:
        StarLavesTiling(**kwargs)
    assert needle in str(err.value) and "\n" not in str(err.value)

