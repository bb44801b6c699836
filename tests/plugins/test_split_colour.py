"""Split (dihedral) isohedral tilings coloured by piece, by base tile, or by transitivity class
(``--set split_colour=piece|tile|class``, the spec's ``split.colour``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from cliutil import assert_one_line_error

from tilekit.cli import cli
from tilekit.errors import ParameterError
from tilekit.geometry import Affine
from tilekit.plugins.isohedral.engine import IsohedralTiling
from tilekit.plugins.isohedral.spec import tiling_from_spec
from tilekit.symmetry import symmetries

REGION = (-4.0, -4.0, 4.0, 4.0)


def split(ih: int, ends: str, colour: str):
    return IsohedralTiling(ih).configure(split=ends, split_colour=colour)


def centres(patch) -> np.ndarray:
    return np.array([Affine.apply(m, np.asarray(patch.prototiles[p].outline)).mean(axis=0)
                     for p, m in zip(patch.prototile, patch.transform)])


def test_piece_colouring_is_the_prototile() -> None:
    patch = split(4, "0.5,2.5", "piece").patch(REGION)
    assert patch.validate(REGION)
    assert np.array_equal(np.asarray(patch.colour), np.asarray(patch.prototile))


def test_tile_colouring_is_the_base_tilings_on_both_pieces() -> None:
    """Each piece takes the colour the base tiling gives the tile it was cut from (IH4's
    default colouring has 3 colours): both pieces of a tile alike, and the same colour the
    unsplit tiling gives the tile under the same transform."""
    base = IsohedralTiling(4)
    t = split(4, "0.5,2.5", "tile")
    patch = t.patch(REGION)
    assert patch.validate(REGION)
    whole = base.patch((-6.0, -6.0, 6.0, 6.0))
    key = {tuple(np.round(m[:2].ravel(), 6)): c for m, c in zip(whole.transform, whole.colour)}
    for m, c in zip(patch.transform, patch.colour):
        assert key[tuple(np.round(m[:2].ravel(), 6))] == c
    assert len(set(np.asarray(patch.colour).tolist())) == 3


@pytest.mark.parametrize("ih, ends, classes", [(1, "0.5,3.5", 1), (4, "0.5,2.5", 2)])
def test_class_colouring_counts_transitivity_classes(ih: int, ends: str, classes: int) -> None:
    """IH1's default hexagon split between the midpoints of opposite edges gives two halves that
    a half-turn of the tiling swaps (Heaven and Hell: one class, one colour); IH4 split from
    edge 0 to edge 2 gives two classes. Checked independently: every symmetry of the split
    tiling maps each piece onto a piece of the same colour, and (one class) some symmetry maps
    a piece 0 onto a piece 1."""
    t = split(ih, ends, "class")
    patch = t.patch(REGION)
    assert patch.validate(REGION)
    colour = np.asarray(patch.colour)
    assert len(set(colour.tolist())) == classes
    cen = centres(patch)
    group = symmetries(t)
    inner = np.flatnonzero(np.abs(cen).max(axis=1) < 2.0)
    swapped = False
    for op in group.operations:
        moved = Affine.apply(op.matrix, cen[inner])
        d = np.linalg.norm(cen[None, :, :] - moved[:, None, :], axis=2)
        j = d.argmin(axis=1)
        ok = d[np.arange(len(inner)), j] < 1e-6
        assert np.array_equal(colour[inner][ok], colour[j[ok]])
        swapped |= bool(np.any(np.asarray(patch.prototile)[inner][ok] != np.asarray(patch.prototile)[j[ok]]))
    assert swapped == (classes == 1)


def test_colour_reaches_the_spec_and_back(tmp_path: Path) -> None:
    t = split(4, "0.5,2.5", "tile")
    spec = t.spec()
    assert spec["split"]["colour"] == "tile"
    again = tiling_from_spec(spec)
    assert np.array_equal(again.patch(REGION).colour, t.patch(REGION).colour)
    assert t.configure(params=list(t.base.params)).spec()["split"]["colour"] == "tile"  # kept by configure
    assert "colour" not in split(4, "0.5,2.5", "piece").spec()["split"]


def test_bad_colour_is_one_line(tmp_path: Path) -> None:
    with pytest.raises(ParameterError, match="piece, tile, class"):
        split(4, "0.5,2.5", "rainbow")
    res = CliRunner().invoke(cli, ["render", "IH4", "--set", "split=0.5,2.5", "--set", "split_colour=rainbow",
                                   "-o", str(tmp_path / "x.svg")])
    assert_one_line_error(res, "split colour 'rainbow' is not one of piece, tile, class")
    res = CliRunner().invoke(cli, ["render", "IH4", "--set", "split_colour=tile", "-o", str(tmp_path / "x.svg")])
    assert_one_line_error(res, "give split=S,T too")
