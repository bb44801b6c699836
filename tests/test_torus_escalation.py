"""Tori past the default bound (issue 28): the estimate of what the tori of a form cost, the
refusal of a request over the limit, escalation past ``--torus-tiles`` for the forms still
undecided, and ``--codes`` (classifying named forms only).

The published fact behind the exhaustive test: Myers' data give A075206(13) = 431 anisohedral
13-ominoes and A054359(13) = 38,669 tilers; the n = 13 run found 430 and 38,668 within 12 tiles
per unit, and the one form left, ``...x/.xxx/xxx./.xxx/.xxx``, tiles with 20 tiles per unit
(docs/benchmarks.md, the n = 13 run). Its tiling is checked from the geometry: exact by
``Patch.validate``, 5 transitivity classes by ``tilekit.symmetry``.
"""

from __future__ import annotations

import json

import pytest
import shapely
from click.testing import CliRunner

import tilekit
from tilekit import symmetry
from tilekit.errors import ParameterError
from tilekit.lattice import GRIDS, SQUARE
from tilekit.limits import LimitError
from tilekit.plugins.polyomino import classify as classify_mod
from tilekit.plugins.polyomino import torus
from tilekit.plugins.polyomino.classify import (
    DEFAULT_TORUS_TILES,
    MAX_TORUS_CLAUSES,
    check_bounds,
    check_torus_cost,
    classify,
    torus_tiling,
)
from tilekit.plugins.polyomino.classify_search import MAX_CLASSIFY, MAX_CLASSIFY_OTHER
from tilekit.plugins.polyomino.isohedral import analyse
from tilekit.plugins.polyomino.placements import Forms
from tilekit.plugins.polyomino.torus import (
    TorusSearch,
    formula_size,
    sublattice_count,
    sublattices,
    torus_cost,
)

#: The 13-omino that tiles only with 20 tiles per translational unit (docs/benchmarks.md).
TWENTY = "...x/.xxx/xxx./.xxx/.xxx"
#: Exercise 5.4's anisohedral octomino: k = 2 on a torus of 4 tiles per unit.
OCTOMINO = ".x../xx../.x../.xx./..xx"


def test_sublattice_count_is_sigma():
    """The sublattices of index N of Z^2 number sigma(N), the sum of N's divisors: one HNF basis
    per divisor a and residue b < N / a; checked against the enumeration, and sigma(12) = 28,
    sigma(260) = 588."""
    assert all(sublattice_count(N) == sum(1 for _ in sublattices(N)) for N in range(1, 200))
    assert (sublattice_count(12), sublattice_count(260)) == (28, 588)


def test_the_formula_estimate_is_the_formula_built():
    """For an asymmetric form (8 orientations) on a torus it does not wrap onto itself, the
    estimated variables and clauses are exactly those of TorusSearch's formula; where a copy
    would cover a torus cell twice it is dropped, so the estimate bounds the formula."""
    poly = tilekit.polyomino(TWENTY)
    forms = Forms(SQUARE, poly.cells)
    assert forms.J == 8
    ts = TorusSearch(forms)
    for lat, exact in (((1, 51, 260), True), ((5, 2, 52), True), ((4, 1, 65), False), ((1, 5, 26), False)):
        clauses, var, _ = ts._formula(lat)
        variables = max(abs(x) for c in clauses for x in c)
        est_v, est_c = formula_size(SQUARE, 13, lat[0] * lat[2], forms.J)
        if exact:
            assert (variables, len(clauses)) == (est_v, est_c) == (28_860, 80_341)
        else:
            assert variables <= est_v and len(clauses) <= est_c


def test_the_tori_estimate_against_the_lattices_tried():
    """torus_cost counts every sublattice exactly and the tori up to the point group as
    sublattices / (|G| / 2) (-1 fixes every lattice); the lattices TorusSearch tries (one per
    orbit) are at least that many and at most the sublattices, and within 10% for the
    13-ominoes to 12 tiles per unit."""
    forms = Forms(SQUARE, tilekit.polyomino(TWENTY).cells)
    ts = TorusSearch(forms)
    cost = torus_cost(SQUARE, 13, 12)
    tried = sum(len(ts.lattices(13 * m)) for m in range(2, 13))
    assert cost.sublattices == sum(sublattice_count(13 * m) for m in range(2, 13)) == 1764
    assert cost.tori <= tried <= cost.sublattices and tried <= 1.1 * cost.tori
    assert cost.largest_clauses == formula_size(SQUARE, 13, 13 * 12)[1]
    # the cost grows with the bound; m = 13..20 alone is what the escalation adds
    more = torus_cost(SQUARE, 13, 20)
    assert more.clauses == cost.clauses + torus_cost(SQUARE, 13, 20, least=13).clauses
    assert more.cpu_seconds == pytest.approx(more.clauses * torus.TORUS_CPU_PER_CLAUSE)


def test_defaults_are_never_refused_and_the_limit_is_named():
    """The default bound is within the limit for the largest form of every grid; a request
    over it is refused before anything runs, with one line naming the estimate, the limit and
    the option; a bound outside 2..MAX_TORUS_TILES or an escalation not above --torus-tiles is
    a ParameterError naming the valid range."""
    for name, grid in GRIDS.items():
        most = MAX_CLASSIFY if name == "square" else MAX_CLASSIFY_OTHER
        assert check_torus_cost(grid, most, DEFAULT_TORUS_TILES).clauses <= MAX_TORUS_CLAUSES
    assert check_torus_cost(SQUARE, 13, 12, 20).tori == torus_cost(SQUARE, 13, 20).tori
    with pytest.raises(LimitError) as e:
        check_torus_cost(SQUARE, 14, 12, 48)
    msg = str(e.value)
    assert "\n" not in msg and f"over the limit of {MAX_TORUS_CLAUSES:,}" in msg
    assert "14-cell form" in msg and "48 tiles per unit" in msg and "--escalate-torus-tiles" in msg
    with pytest.raises(LimitError, match="--torus-tiles"):
        check_torus_cost(SQUARE, 14, 48)
    with pytest.raises(ParameterError, match=r"--escalate-torus-tiles must be 0 \(off\) or between "
                                              r"--torus-tiles \+ 1 \(13\) and 48, got 12"):
        check_bounds(2, 5, 12, 12)
    with pytest.raises(ParameterError, match="--torus-tiles must be between 2 and 48, got 49"):
        check_bounds(2, 5, 49)
    # classify refuses before it looks at the form (a hole would otherwise end it at once)
    with pytest.raises(LimitError, match="over the limit"):
        classify(SQUARE, tilekit.polyomino("xxxxxx/x....x/xxxxxx").cells, None, torus_tiles=12, escalate_torus_tiles=48,
                 has_holes=True)


def test_escalation_runs_after_every_other_step(monkeypatch):
    """The octomino tiles with 4 tiles per unit. Bounded at 2, it is undecided; escalated to 4,
    the larger tori run only after the coronas to --max-level, and the verdict and evidence
    say how far the tori went."""
    cells = tilekit.polyomino(OCTOMINO).cells
    a = analyse(SQUARE, cells, construct=False)
    c = classify(SQUARE, cells, a, max_level=3, torus_tiles=2)
    assert c.tiles == "undecided" and c.verdict.startswith("undecided up to 3 coronas and 2 tiles per translational")
    assert c.evidence["torus_tiles"] == 2
    calls = []
    real_search, real_heesch = torus.TorusSearch.search, classify_mod.heesch

    def search(self, m_range, **kw):
        calls.append(("torus", m_range.start, m_range.stop - 1))
        return real_search(self, m_range, **kw)

    def heesch(*args, **kw):
        calls.append(("coronas", kw["max_level"]))
        return real_heesch(*args, **kw)

    monkeypatch.setattr(torus.TorusSearch, "search", search)
    monkeypatch.setattr(classify_mod, "heesch", heesch)
    c = classify(SQUARE, cells, a, max_level=3, torus_tiles=2, escalate_torus_tiles=4)
    assert calls == [("coronas", 2), ("torus", 2, 2), ("coronas", 3), ("torus", 3, 4)]
    assert c.tiles == "true" and c.anisohedral_k == 2 and c.evidence["m"] == 4 and c.evidence["torus_tiles"] == 4
    assert c.evidence["seconds"] >= 0
    # escalated, but the time limit ends the larger tori: undecided, with the tori searched
    calls.clear()
    c = classify(SQUARE, cells, a, max_level=3, torus_tiles=2, escalate_torus_tiles=4, time_limit=0)
    assert c.tiles == "undecided" and "torus_tiles" not in c.evidence


def test_codes_classify_the_named_forms_only(tmp_path):
    """``--codes`` classifies the forms named and stores their rows; the escalated octomino is
    stored as an anisohedral tiler; a code of another grid or size is refused in one line."""
    from tilekit.cli import cli

    db = f"sqlite:///{tmp_path / 'c.sqlite'}"

    def run(*args):
        return CliRunner().invoke(cli, ["--catalogue", db, *args])

    res = run("search", "polyomino-classify", "--codes", f"{OCTOMINO} T-tetromino", "--max-cells", "8",
              "--torus-tiles", "2", "--escalate-torus-tiles", "4", "--max-level", "3")
    assert res.exit_code == 0, res.output
    r = run("list", "--family", "polyomino", "--format", "json")
    rows = json.loads(r.output)
    assert len(rows) == 2
    r = run("list", "--family", "polyomino", "--where", "anisohedral_k=2", "--count")
    assert r.output.strip() == "1"
    res = run("show", OCTOMINO)
    assert "tiles anisohedrally: 4 tiles per translational unit" in res.output
    for args, needle in ((["--codes", OCTOMINO, "--max-cells", "7"], "has 8 cells, outside --min-cells (1) .. "
                                                                     "--max-cells (7)"),
                         (["--codes", "hex:0,0;3,0"], "a form of the hex grid, not of --grid square"),
                         (["--codes", OCTOMINO, "--max-cells", "8", "--escalate-torus-tiles", "12"], "0 (off)"),
                         (["--max-cells", "14", "--torus-tiles", "48"], "over the limit of 500,000,000")):
        res = run("search", "polyomino-classify", *args)
        assert res.exit_code == 2, res.output
        assert needle in res.stderr and res.stderr.strip().count("\n") == 0, res.stderr


@pytest.mark.exhaustive
def test_the_13_omino_with_20_tiles_per_unit():
    """The one 13-omino the default bound leaves undecided tiles with 20 tiles per unit (10-12 CPU
    minutes: 578 s here, 707 s through the CLI; marked exhaustive). Through the public API with the
    escalation: a tiler, k = 5, pgg; its tiling exact over a region and 5-isohedral by
    tilekit.symmetry (A075206(13) = 431 counts it)."""
    poly = tilekit.polyomino(TWENTY)
    c = poly.classification(escalate_torus_tiles=20, time_limit=3600)
    assert c.tiles == "true" and not c.isohedral and c.anisohedral_k == 5
    assert c.evidence["m"] == 20 and c.evidence["torus_tiles"] == 20 and c.witness["group"] == "pgg"
    til = torus_tiling(SQUARE, poly.cells, c.witness)
    region = shapely.box(-40, -40, 40, 40)  # 545 tiles: more than 27 translational units
    patch = til.patch(region)
    report = patch.validate(region)
    assert report.ok, report.summary()
    assert len(patch) > 500 and symmetry.isohedrality(til) == 5
