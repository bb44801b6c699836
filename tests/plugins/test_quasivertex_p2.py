"""The kite and dart quasivertex parameterization (book §6.3), derived from P2 patches.

The book gives P2's consequences only in its text: the edge labels abcdaefghd (kite) and
ghefgcdabf (dart) with the interlocking pairs (a,d), (b,h), (c,e), (f,g), "four non-congruent
edge shapes between them". The derivation (p2_derivation.derive) must find them from the
adjacencies of the family's own patches; the formulas used by the family must be the ones
it finds; deformed patches must tile and keep the labels' pairing on every shared piece.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from test_substitution import assert_valid

from tilekit.errors import ParameterError
from tilekit.geometry import Affine
from tilekit.plugins.substitution import p2_derivation, tiling
from tilekit.plugins.substitution import quasivertex as qv
from tilekit.plugins.substitution import quasivertex_p2 as p2
from tilekit.plugins.substitution.shapes import canonical_transforms, halves_mirror
from tilekit.tiling import Patch


def p2_tiling(r1: float, t1: float, r2: float, t2: float, **kw):
    return tiling("penrose-p2").configure(r1=r1, theta1=t1, r2=r2, theta2=t2, **kw)


def test_derivation_reproduces_the_books_labels() -> None:
    """Of all choices of at most one cut corner per tile, exactly two reproduce §6.3's labels
    (kite abcdaefghd, dart ghefgcdabf, pairs (a,d), (b,h), (c,e), (f,g)), mirror images of
    each other, each leaving four free parameters (P3's r1, theta1, r2, theta2 count); the
    module's data is the first of them."""
    d = p2_derivation.derive(max_cuts=1)
    assert d.edges == p2.EDGES
    book = d.book
    assert sorted(tuple(sorted(c.cuts.items())) for c in book) == [
        (("dart", (1,)), ("kite", (3,))), (("dart", (3,)), ("kite", (1,)))]
    assert all(c.dimension == 4 and c.pieces == (10, 10) and c.classes == 4 for c in book)
    ours = next(c for c in book if c.cuts == {"kite": (p2.CUT["kite"],), "dart": (p2.CUT["dart"],)})
    # ke(short) (unknown 3) from ks(long) (0), ks(short) (2) from ke(long) (1)
    assert sorted(ours.relations) == [(2, 1, p2.SHORT_FROM_LONG[0]), (3, 0, p2.SHORT_FROM_LONG[1])]
    other = next(c for c in book if c is not ours)
    assert sorted(other.relations) == [(2, 1, -p2.SHORT_FROM_LONG[0]), (3, 0, -p2.SHORT_FROM_LONG[1])]
    assert any(starts == p2.BOOK_START for _, starts in ours.book)


def test_zero_parameters_give_the_straight_kite_and_dart() -> None:
    plain = tiling("penrose-p2")
    t = p2_tiling(0.0, 30.0, 0.0, -10.0)
    for a, b in zip(t.prototiles, plain.prototiles):
        assert len(a.outline) == len(b.outline) == 4
        assert any(np.allclose(np.roll(a.outline, k, axis=0), b.outline, atol=1e-9) for k in range(4))


def test_every_quasivertex_of_a_larger_patch_is_parameterized() -> None:
    """In a patch of about 300 deformed tiles, every vertex of any tile that lies on another
    tile's boundary is one of that tile's own ten quasivertices (no tiling vertex anywhere
    falls inside a piece), and each tile keeps exactly ten."""
    t = p2_tiling(0.17, 23.0, 0.12, -31.0)
    patch = t.patch((-7.0, -7.0, 7.0, 7.0))
    assert all(len(p.outline) == 10 for p in patch.prototiles)
    outlines = [Affine.apply(m, np.asarray(patch.prototiles[p].outline)) for p, m in zip(patch.prototile, patch.transform)]
    verts = np.concatenate(outlines)
    rings = [shapely.LinearRing(o) for o in outlines]
    tree = shapely.STRtree(rings)
    pts = shapely.points(verts)
    pairs = tree.query(pts, predicate="dwithin", distance=1e-7)
    checked = 0
    for v, r in zip(*pairs):
        d = np.linalg.norm(outlines[r] - verts[v], axis=1).min()
        assert d < 1e-7, f"a vertex lies {d:.3g} from tile {r}'s quasivertices on its boundary"
        checked += 1
    assert checked > 2 * len(verts)  # each vertex on its own tile and (inside the patch) at least one other


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.floats(0.0, 0.3), st.floats(-45.0, 45.0), st.floats(0.0, 0.3), st.floats(-45.0, 45.0))
def test_deformed_kites_and_darts_tile_and_match(r1: float, t1: float, r2: float, t2: float) -> None:
    """Any admissible (r1, theta1, r2, theta2) in this range: the patch validates (no gap, no
    overlap), every shared piece pairs a label with its §6.3 partner, drawn identically, and
    the substitution family's arrangement is kept: on the same placements, tiles that share an
    edge when straight still share one, and deformed tiles only meet tiles their straight
    forms touched."""
    params = qv.QuasivertexParams(r1, t1, r2, t2)
    assume(not qv._bad_tiles(params, "penrose-p2"))
    deformed = p2_tiling(r1, t1, r2, t2)
    patch = deformed.patch((-4.0, -4.0, 4.0, 4.0))
    assert_valid(patch, (-3.0, -3.0, 3.0, 3.0))
    report = qv.matching_report(patch)
    assert report.ok, report.summary()
    straight = tiling("penrose-p2")
    proto, tr = straight.raw(shapely.box(-3.0, -3.0, 3.0, 3.0))
    tr = canonical_transforms(proto, tr, halves_mirror(straight.system))
    before = Patch(straight.prototiles, proto, tr).adjacency()
    after = Patch(deformed.prototiles, proto, tr).adjacency()
    pairs = [{tuple(p) for p in np.asarray(a).tolist()} for a in (before.edge, after.edge, before.touching)]
    assert pairs[0] <= pairs[1] <= pairs[2]


def test_shaped_pieces_interlock_and_labels_are_the_books() -> None:
    """Edge shapes on the primary labels a, b, c, f put complements on d, h, e, g; the patch
    still tiles and every shared piece meets its partner."""
    t = p2_tiling(0.15, 20.0, 0.1, -25.0, edges=["a=0.5,0.15", "b=0.3,-0.1:0.7,0.1", "c=0.5,0.1", "f=0.5,-0.12"])
    tiles = {p.name: p for p in t.prototiles}
    for name in ("kite", "dart"):
        tile = tiles[name]
        seq = "".join(tile.edge_labels[i] for i in tile.corners)
        assert seq == p2.LABELS[name]
        k = p2.BOOK_START[name]
        assert seq[k:] + seq[:k] == p2.BOOK_LABELS[name]
    patch = t.patch((-4.0, -4.0, 4.0, 4.0))
    assert_valid(patch, (-3.0, -3.0, 3.0, 3.0))
    assert qv.matching_report(patch).ok


def test_spokes_are_the_named_parameters() -> None:
    """r1, theta1 is the spoke at the long edge's class start (the kite's cut side corner K1):
    the kite's quasivertex after K0's spoke sits at K1 + u(K1, K0) r1 e^(i theta1)."""
    r1, t1, r2, t2 = 0.2, math.radians(15.0), 0.1, math.radians(-40.0)
    kite = p2.outlines(r1, t1, r2, t2)["kite"][0]
    k0, k1 = p2.CORNERS["kite"][0], p2.CORNERS["kite"][1]
    u = (k0 - k1) / abs(k0 - k1)
    cut = k1 + u * r1 * complex(math.cos(t1), math.sin(t1))
    assert np.allclose(kite[2], [cut.real, cut.imag])
    spoke2 = k0 - u * r2 * complex(math.cos(t2), math.sin(t2))
    assert np.allclose(kite[1], [spoke2.real, spoke2.imag])


def test_bad_p2_options_are_one_line() -> None:
    """P2's own pairs are named; a label and its partner cannot both be given; a spoke too long
    for the tiles is refused with the admissible range."""
    with pytest.raises(ParameterError, match="pairs a/d, b/h, c/e, f/g interlock"):
        p2_tiling(0.1, 0.0, 0.1, 0.0, edges=["z=0.5,0.1"])
    with pytest.raises(ParameterError, match="interlock"):
        p2_tiling(0.1, 0.0, 0.1, 0.0, edges=["a=0.5,0.1", "d=0.5,0.1"])
    with pytest.raises(ParameterError, match=r"kite and dart tiles self-intersect.*r1 must lie in about \[0, 0.618\]"):
        p2_tiling(5.0, 0.0, 0.0, 0.0)
