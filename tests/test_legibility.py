"""Pictures a user can read (issue 26): the outline width follows the tiles' size in pixels (a
1.2 px outline on 3 px tiles painted README's spectre nearly black), and a periodic tiling's
default region shows a few translational units (the anisohedral octomino drew 2,433 tiles)."""

from __future__ import annotations

import io
import math
import re

import numpy as np
import pytest

from tilekit.render import STROKE_MIN_PX, STROKE_PX, patch_to_svg, stroke_px_for, tile_size
from tilekit.tiling import DEFAULT_MIN_TILES, DEFAULT_UNITS, PeriodicTiling


@pytest.fixture(scope="module")
def cat(tmp_path_factory):
    from tilekit import open_catalogue

    c = open_catalogue(f"sqlite:///{tmp_path_factory.mktemp('legible') / 'c.sqlite'}")
    yield c
    c.close()


def stroke_px(svg: str) -> float:
    """The tiles' outline width in pixels: the group's stroke-width times pixels per unit."""
    width_px = float(re.search(r'<svg[^>]* width="([0-9.]+)"', svg).group(1))
    view_w = float(re.search(r'viewBox="[^ ]+ [^ ]+ ([^ ]+) ', svg).group(1))
    sw = float(re.search(r'<g transform="scale\(1,-1\)"[^>]* stroke-width="([^"]+)"', svg).group(1))
    return sw * width_px / view_w


def test_the_width_rule():
    assert stroke_px_for(100) == STROKE_PX and stroke_px_for(STROKE_MIN_PX / 2) == 0
    widths = [stroke_px_for(x) for x in np.linspace(STROKE_MIN_PX, 30, 50)]
    assert widths == sorted(widths) and 0 < widths[0] < STROKE_PX


def test_tile_size_counts_scaled_tiles(cat):
    patch = cat.tiling("4^4").patch((0, 0, 3, 3))
    assert math.isclose(tile_size(patch), 1.0)
    patch.transform[:, :2, :2] *= 2  # every tile drawn twice as large
    assert math.isclose(tile_size(patch), 2.0)


def test_big_tiles_keep_the_full_outline_small_ones_thinner(cat):
    coarse = patch_to_svg(cat.tiling("penrose-p3").configure(depth=3).patch(None))
    fine = cat.tiling("penrose-p3").configure(depth=8)
    fine_svg = patch_to_svg(fine.patch(fine.default_region()))
    assert math.isclose(stroke_px(coarse), STROKE_PX, rel_tol=1e-3)
    assert 0 < stroke_px(fine_svg) < STROKE_PX / 2
    # an explicit width is kept as given
    assert math.isclose(stroke_px(patch_to_svg(fine.configure(depth=3).patch(None), stroke_width_px=1.2)), 1.2,
                        rel_tol=1e-3)


def dark_fraction(svg: str) -> float:
    """The share of the drawing's non-white pixels that are about the outline colour #222."""
    cairosvg = pytest.importorskip("cairosvg")
    from PIL import Image

    png = cairosvg.svg2png(bytestring=svg.encode())
    px = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=float)
    lum = px.mean(axis=2)
    drawn = lum < 250
    return float(((lum < 70) & drawn).sum() / drawn.sum())


def test_readme_spectre_is_no_longer_nearly_black(cat):
    """README's `spectre --depth 5` at 800 px: with the fixed 1.2 px outline most of the drawn
    pixels were the outline's near-black; with the width rule the tiles' colours show."""
    tiling = cat.tiling("spectre").configure(depth=5)
    patch = tiling.patch(tiling.default_region())
    old = dark_fraction(patch_to_svg(patch, stroke_width_px=1.2))
    new = dark_fraction(patch_to_svg(patch))
    assert old > 0.5 and new < 0.25, (old, new)


def test_default_regions_show_a_few_units(cat):
    """Every shipped periodic tiling's default picture holds at least DEFAULT_UNITS
    translational units' worth of tiles and at most a few times that (with the tiles the
    region's border cuts), and covers its region (Patch.validate)."""
    checked = 0
    for entry in cat.query():
        tiling = cat.tiling(entry)
        if not isinstance(tiling, PeriodicTiling):
            continue
        region = tiling.default_region()
        patch = tiling.patch(region)
        per_unit = len(tiling.unit_prototile)
        wanted = max(DEFAULT_UNITS * per_unit, DEFAULT_MIN_TILES)
        assert wanted * 0.9 <= len(patch) <= 4 * wanted + 40, (entry.name, len(patch), wanted)
        checked += 1
    assert checked >= 100


def test_the_anisohedral_octomino_is_drawn_legibly():
    """Exercise 5.4's anisohedral octomino (the one 8-omino that tiles only anisohedrally,
    A075206): its torus tiling has 4 tiles in a 32-cell unit; its default region drew 2,433
    tiles before, a few units now, and the patch covers the region."""
    from tilekit.plugins.polyomino.model import from_spec

    witness = {"kind": "torus", "lattice": [1, 3, 32], "k": 2, "group": "p2",
               "tiles": [[0, 0, 0, 0], [2, 0, 20, 0], [5, 0, 46, 1], [7, 0, 28, 1]]}
    tiling = from_spec({"code": ".x../xx../.x../.xx./..xx", "witness": witness})
    assert len(tiling.unit_prototile) == 4
    region = tiling.default_region()
    patch = tiling.patch(region)
    assert DEFAULT_UNITS * 4 <= len(patch) <= 120
    assert patch.validate(region)
    assert stroke_px(patch_to_svg(patch, region=region)) == pytest.approx(STROKE_PX, rel=1e-3)
