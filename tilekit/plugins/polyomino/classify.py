"""The classification of one polyomino: isohedral tiler, anisohedral tiler (least k found),
non-tiler with its Heesch numbers, or undecided within stated bounds.

The order of the tests is the cheap-first order of Myers' and Kaplan's searches:

1. a hole: no tiling (a copy covering a cell of the hole would have to fit inside it);
2. the boundary-word test (:mod:`isohedral`, Langerman and Winslow): an isohedral tiling;
3. the local test of corona 1 (:func:`heesch.first_corona_rows`, one compiled call): no copy
   left for corona 1 proves a non-tiler with Hc = Hh = 0 before any solver is set up;
4. coronas by SAT (:mod:`heesch`) up to ``probe`` levels (one more when Kaplan's numbers are
   known but need the proof): a level with no patch even with holes proves a non-tiler, and
   its Hc and Hh are Kaplan's;
5. otherwise tori with 2..``torus_tiles`` tiles per translational unit (:mod:`torus`): a
   cover is a periodic tiling, and the fewest transitivity classes found is the k recorded;
6. otherwise coronas up to ``max_level``; still surrounded: ``undecided`` with the bounds.
   While coronas remain to be tried the torus search first gets :data:`TORUS_SHARE` of the
   time left; stopped there, one more corona level runs before the tori go on;
7. on request (``escalate_torus_tiles``, ``--escalate-torus-tiles``), a form still undecided
   goes on to the tori past ``torus_tiles``, up to that many tiles per unit, with the time left.
   Only the forms that every other step left open pay for the larger tori (one 13-omino needs 20
   tiles per unit); what they cost is estimated before anything runs (:func:`check_torus_cost`).

Every verdict reached on tori says up to how many tiles per unit they were searched, and so
does ``evidence["torus_tiles"]``; ``evidence["seconds"]`` is CPU seconds (the budget's: the
classifying thread's and its forked solvers').

The time limit is a :class:`tilekit.budget.Budget`: CPU seconds of the classifying thread (and
of any solver process it forks), so that a verdict does not depend on the machine's load; its
wall-clock cap (``WALL_FACTOR`` times as long) still ends a starved classification.

The ``polyomino-classify`` search that runs this over every free polyomino is
:mod:`classify_search`.

Nothing is guessed: ``tiles`` is ``true`` only with a tiling in hand, ``false`` only with a
proof (a hole, or a level at which no corona exists), and ``undecided`` otherwise.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from tilekit.budget import Budget, thread_cpu_clock
from tilekit.colouring import Colouring
from tilekit.errors import ParameterError, ParseError
from tilekit.lattice import GRIDS, Grid, outline
from tilekit.limits import SAT_BYTES_PER_CLAUSE, refuse_over, refuse_over_memory
from tilekit.plugins.polyomino.heesch import (
    MAX_LEVEL_LIMIT,
    Corona,
    HeeschResult,
    HeeschSolver,
    first_corona_rows,
    heesch,
)
from tilekit.plugins.polyomino.isohedral import analyse
from tilekit.plugins.polyomino.placements import Forms
from tilekit.plugins.polyomino.surround import SurroundResult, SurroundTest
from tilekit.plugins.polyomino.torus import TorusCost, TorusSearch, TorusTiling, torus_cost
from tilekit.schema import Field, check
from tilekit.symmetry import wallpaper_group
from tilekit.tiling import Patch, PeriodicTiling

#: The grids the classification runs on: all ten. A polyform's copies are its images under the
#: grid's symmetries (a point-group element and a grid translation, :meth:`Grid.is_translation`),
#: so on the grids with cells of several shapes a copy puts octagons on octagons and squares on
#: squares; "tiles" means tiles with such copies, the question Kaplan's heesch-sat answers.
CLASSIFIED_GRIDS = tuple(GRIDS)
#: The grids whose boundary-word test finds every isohedral tiler: the square grid (Langerman and
#: Winslow's theorem) and the hex and iamond grids (checked: the counts equal Myers' A075214 and
#: A075223, tests/test_polyform_grids.py). On the others a tile may tile isohedrally only with
#: neighbours mirrored across an edge (a single drafter: the kisrhombille tiling itself), which no
#: template describes, so a torus tiling with two or more classes does not end the search there:
#: the tori go on to ``torus_tiles`` tiles per unit looking for one class (an isohedral tiling has
#: at most as many tiles per unit as the grid's point group has elements, 8 or 12).
BOUNDARY_COMPLETE = ("square", "hex", "iamond")
#: Most tiles per translational unit an option may ask the torus search for; what a request
#: costs is estimated first (:func:`torus.torus_cost`) and refused over MAX_TORUS_CLAUSES.
MAX_TORUS_TILES = 48
#: Tiles per translational unit tried by default: 8 decides every polyomino to n = 10, but one
#: 11-omino (``..x../..xxx/xxxx./xx.x.``, pgg, k = 3) needs 12 (docs/benchmarks.md). One
#: 13-omino (``...x/.xxx/xxx./.xxx/.xxx``, pgg, k = 5) needs 20: it is reached by escalation
#: (``escalate_torus_tiles``), not by a larger default, which would cost every form that
#: survives three coronas the tori of 13..20 tiles per unit.
DEFAULT_TORUS_TILES = 12
#: Most SAT clauses the tori of one form may take in all (the estimate of :func:`torus.torus_cost`
#: for the largest form of a request, summed over every torus up to the bound): about 1.5 CPU
#: hours at :data:`torus.TORUS_CPU_PER_CLAUSE`. The 13-ominoes to 20 tiles per unit are 6.6e7.
MAX_TORUS_CLAUSES = 500_000_000
#: The share of the CPU time left that the torus search may use while coronas remain to be tried:
#: when it is stopped there, the next corona level runs (a non-tiler whose tori are slow to
#: exhaust is proved by it), then the torus search goes on with all the time left (a tiler
#: that needs a large unit still finds it), once.
TORUS_SHARE = 0.5
#: Further covers of one torus searched for fewer transitivity classes (TorusSearch.search).
ALTERNATIVES = 64
#: Largest polyomino classified on request (``Polyomino.classification``, ``--set view=``).
MAX_INTERACTIVE = 16
#: The classification's default solver: Glucose can be interrupted in this process, so a
#: per-polyomino time limit costs no fork per call, and on these small formulas it was 1.4x
#: faster than CaDiCaL for the whole n = 8 classification (docs/benchmarks.md).
CLASSIFY_SOLVER = "glucose4"


@dataclass
class Classification:
    tiles: str  # "true" / "false" / "undecided"
    isohedral: bool
    anisohedral_k: int | None = None
    heesch: int | None = None
    heesch_holes: int | None = None
    witness: dict | None = None
    verdict: str = ""
    evidence: dict = field(default_factory=dict)

    def columns(self) -> dict[str, Any]:
        """The classification columns of a polyominoes row."""
        return {"tiles": self.tiles, "isohedral": self.isohedral, "anisohedral_k": self.anisohedral_k, "heesch": self.heesch,
                "heesch_holes": self.heesch_holes,
                "witness": None if self.witness is None else json.dumps(self.witness, separators=(",", ":")),
                "verdict": self.verdict}


def check_bounds(probe: int, max_level: int, torus_tiles: int, escalate_torus_tiles: int = 0) -> None:
    if not 1 <= probe <= MAX_LEVEL_LIMIT:
        raise ParameterError(f"the corona probe must be between 1 and {MAX_LEVEL_LIMIT} levels, got {probe}")
    if not probe <= max_level <= MAX_LEVEL_LIMIT:
        raise ParameterError(f"--max-level must be between the probe ({probe}) and {MAX_LEVEL_LIMIT}, got {max_level}")
    if not 2 <= torus_tiles <= MAX_TORUS_TILES:
        raise ParameterError(f"--torus-tiles must be between 2 and {MAX_TORUS_TILES}, got {torus_tiles}")
    if escalate_torus_tiles and not torus_tiles < escalate_torus_tiles <= MAX_TORUS_TILES:
        raise ParameterError(f"--escalate-torus-tiles must be 0 (off) or between --torus-tiles + 1 ({torus_tiles + 1}) "
                             f"and {MAX_TORUS_TILES}, got {escalate_torus_tiles}")


def check_torus_cost(grid: Grid, cells: int, torus_tiles: int, escalate_torus_tiles: int = 0) -> TorusCost:
    """The estimated cost of the tori of one ``cells``-cell form up to the larger of the two
    bounds (:func:`torus.torus_cost`); over :data:`MAX_TORUS_CLAUSES` clauses, or a largest
    torus formula over the memory available, a one-line LimitError naming the estimate, the
    limit and the options that lower it, before any search starts."""
    return _checked_torus_cost(grid.name, cells, max(torus_tiles, escalate_torus_tiles or 0),
                               "--escalate-torus-tiles" if escalate_torus_tiles else "--torus-tiles")


@functools.lru_cache(maxsize=256)
def _checked_torus_cost(grid_name: str, cells: int, most: int, option: str) -> TorusCost:
    """:func:`check_torus_cost`, once per process for each size and bound that passes (it runs
    for every form classified: the memory check alone reads /proc, a quarter of a millisecond)."""
    grid = GRIDS[grid_name]
    cost = torus_cost(grid, cells, most)
    hint = (f"the tori of one {cells}-cell form on the {grid.name} grid up to {most} tiles per unit "
            f"({cost.tori:,} tori, about {cost.cpu_seconds / 3600:.2g} CPU hours); ask for fewer with {option}")
    refuse_over("SAT clauses", cost.clauses, MAX_TORUS_CLAUSES, hint=hint)
    refuse_over_memory("SAT clauses in the largest torus formula", cost.largest_clauses, SAT_BYTES_PER_CLAUSE,
                       hint=hint)
    return cost


def check_grid(grid: Grid) -> None:
    """A one-line ParameterError for a grid the classification does not know."""
    if grid.name not in CLASSIFIED_GRIDS:
        raise ParameterError(f"the classification runs on the {', '.join(CLASSIFIED_GRIDS)} grids, not {grid.name}")


def _corona_json(c: Corona | None, hc: int | None) -> dict | None:
    return None if c is None else c.to_json() | {"hole_free": not c.holes}


def classify(grid: Grid, cells: np.ndarray, analysis: dict | None, *, has_holes: bool = False,
             probe: int = 2, max_level: int = 5, torus_tiles: int = DEFAULT_TORUS_TILES,
             escalate_torus_tiles: int = 0, time_limit: Budget | float | None = 120.0,
             solver: str = CLASSIFY_SOLVER, first: np.ndarray | None = None) -> Classification:
    """Classify one polyform (``analysis`` from :func:`isohedral.analyse`, None if holey).
    ``escalate_torus_tiles``: a form still undecided once every step has run to its bound (coronas
    to ``max_level``, tori to ``torus_tiles``) goes on to the tori of up to this many tiles per
    unit (0: no further), within the same time limit.
    ``time_limit``: a :class:`Budget`, or CPU seconds of the calling thread from this call on
    (None: no limit); spent, the verdict is ``undecided`` with its bounds.
    ``first``: corona 1's rows from :func:`heesch.first_corona_rows`, when already computed."""
    check_grid(grid)
    check_bounds(probe, max_level, torus_tiles, escalate_torus_tiles)
    check_torus_cost(grid, len(cells), torus_tiles, escalate_torus_tiles)
    if has_holes:
        return Classification("false", False, verdict="does not tile: it has a hole, and no copy fits in a hole",
                              evidence={"step": "hole"})
    a = analysis or {}
    if a.get("isohedral"):
        kinds = [fam for fam in ("translation", "halfturn", "quarterturn", "reflection") if a.get(fam)]
        sigs = sorted({f["heesch"] for f in a.get("factorisations", [])})
        ih = ", ".join(f"IH{i}" for i in a.get("ih_types", []))
        return Classification("true", True,
                              verdict=f"tiles isohedrally: boundary factorisation by {'/'.join(kinds)} "
                                      f"({', '.join(sigs)}){'; ' + ih if ih else ''}",
                              evidence={"step": "boundary word", "kinds": kinds})
    budget = Budget.of(time_limit)
    t0 = _cpu_clock(budget)
    if first is None:
        first = first_corona_rows(grid, cells)  # corona 1's copies by the local test, one compiled call
    if not len(first):  # no corona even with holes: Hc = Hh = 0, proved with no solver
        kernel = Corona(np.zeros((1, 3), dtype=np.int64), np.zeros(1, dtype=np.int64), False)
        seconds = t0()
        return _non_tiler(HeeschResult(0, 0, kernel, kernel, 0, True, "no 1-corona patch exists", 0, seconds), seconds)
    hs = HeeschSolver(grid, cells, solver=solver, first=first)
    try:
        return _coronas_and_tori(grid, cells, hs, probe, max_level, torus_tiles, escalate_torus_tiles, solver, t0,
                                 budget)
    finally:
        hs.close()


def _cpu_clock(budget: Budget | None) -> Callable[[], float]:
    """CPU seconds since now: the budget's use (this thread's and its forked solvers'), or with
    no budget this thread's CPU clock (what the evidence's ``seconds`` record)."""
    if budget is not None:
        start = budget.used()
        return lambda: budget.used() - start
    clock = thread_cpu_clock()
    start = clock()
    return lambda: clock() - start


def _coronas_and_tori(grid: Grid, cells: np.ndarray, hs: HeeschSolver, probe: int, max_level: int, torus_tiles: int,
                      escalate: int, solver: str, t0: Callable[[], float], budget: Budget | None) -> Classification:
    """Steps 4-7 of the module docstring, on ``hs`` (its ladder holds every corona level)."""
    complete = grid.name in BOUNDARY_COMPLETE
    proved = complete  # no isohedral tiling: by the complete boundary-word test, or the direct one
    if not complete:
        # the direct isohedral test on corona 1's formula (:mod:`surround`); unsatisfiable
        # proves that no isohedral tiling exists, so the tori need look for k >= 2 only
        st = SurroundTest(hs).run(budget)
        if st.isohedral:
            return _surround_isohedral(grid, cells, st, t0)
        proved = st.isohedral is False
    r = heesch(grid, cells, max_level=probe, time_limit=budget, hs=hs)
    level = probe
    if not r.decided and hs.kaplan and r.surrounded >= probe and probe < max_level:
        # Kaplan's numbers are known but not yet a proof: one more level with holes allowed
        level = probe + 1
        r = heesch(grid, cells, max_level=level, time_limit=budget, hs=hs, start=level, best=r.hc_witness)
    if r.decided:
        return _non_tiler(r, t0())
    if r.surrounded < level:  # the time limit
        return _undecided(r.surrounded, None, t0(), r.reason, r.hc_witness)
    ts = TorusSearch(hs.forms, solver=solver)
    want_k = 2 if proved else 1  # with no isohedral tiling, k = 2 is already the least
    # cheap first: small translational units, one more corona, larger units, more coronas
    stages = [("torus", min(4, torus_tiles)), ("coronas", min(probe + 1, max_level)),
              ("torus", torus_tiles), ("coronas", max_level)]
    if escalate > torus_tiles:  # still undecided: the larger tori, once the coronas are done
        stages.append(("torus", escalate))
    best: TorusTiling | None = None
    tried_m = 1
    shared = True  # the torus search still shares the time with the coronas (once stopped: no more)
    i = 0
    while i < len(stages):
        what, bound = stages[i]
        i += 1
        if what == "torus":
            if bound <= tried_m:
                continue
            cut = None  # where the time limit stopped the search for a tiling with fewer classes
            if not proved and best is not None:
                bound = max(bound, torus_tiles)  # a tiler: look for one class on every torus now
            share = shared and budget is not None and level < max_level and best is None
            # sharing, the rest is kept for the next corona level
            torus_budget = budget.share(TORUS_SHARE) if share else budget
            stopped = 0
            for m, tt in ts.search(range(tried_m + 1, bound + 1), want_k=want_k, time_limit=torus_budget):
                if tt is None:
                    if best is not None:  # a tiling was found: the limit only ended the search for a smaller k
                        cut = m
                        break
                    if share:  # one more corona level may prove a non-tiler; then the tori go on
                        stopped = m
                        break
                    reason = f"torus search stopped by the time limit ({budget}) at {m} tiles per unit"
                    return _undecided(level, m - 1, t0(), reason, r.hc_witness)
                if best is None or tt.k < best.k:
                    best = tt
            if stopped:
                tried_m, shared = stopped - 1, False
                stages[i:i] = [("coronas", level + 1), ("torus", bound)]
                continue
            tried_m = bound
            if best is not None and best.k == 1:
                # one transitivity class: an isohedral tiling the boundary-word templates did not
                # give (a grid without a complete boundary criterion, such as the kite grid)
                witness = best.to_json()
                a_, b_, d_ = best.lattice
                witness["group"] = wallpaper_group(torus_tiling(grid, cells, witness)).iuc
                return Classification("true", True, witness=witness,
                                      verdict=f"tiles isohedrally: a torus tiling with one transitivity class "
                                              f"({best.m} tiles per translational unit, period lattice ({a_},{b_}),"
                                              f"(0,{d_}), symmetry group {witness['group']})",
                                      evidence={"step": "torus", "m": best.m, "lattice": list(best.lattice),
                                                "torus_tiles": best.m, "seconds": round(t0(), 3)})
            if best is not None and not proved and tried_m < torus_tiles and cut is None:
                continue  # one class may need a larger unit: the next torus stage goes on
            if best is not None:
                a_, b_, d_ = best.lattice
                witness = best.to_json()
                # the group's name, from the geometry (tilekit.symmetry), for the verdict
                witness["group"] = wallpaper_group(torus_tiling(grid, cells, witness)).iuc
                how = ("no boundary factorisation" if complete else
                       "no isohedral tiling (the direct test: no first corona closed under its copies' transforms)"
                       if proved else
                       f"no one-class tiling on the tori with up to {tried_m} tiles per unit (each torus searched "
                       f"for up to {ALTERNATIVES} covers; the {grid.name} grid has no complete boundary-word test)")
                # the tori searched: to the bound, or to the tiling when its k cannot be lowered
                searched = cut - 1 if cut is not None else best.m if best.k <= want_k else tried_m
                verdict = (f"tiles anisohedrally: {best.m} tiles per translational unit (torus of period lattice "
                           f"({a_},{b_}),(0,{d_})), symmetry group {witness['group']}, {best.k} transitivity "
                           f"classes; {how}"
                           + (f" (the search for fewer classes stopped by the time limit ({budget}) at {cut} tiles "
                              f"per unit)"
                              if cut is not None else
                              f" (the least k found on the tori with up to {searched} tiles per unit)"
                              if best.k > want_k else ""))
                return Classification("true", False, anisohedral_k=best.k, witness=witness, verdict=verdict,
                                      evidence={"step": "torus", "m": best.m, "lattice": list(best.lattice),
                                                "torus_tiles": searched, "sat_calls": ts.sat_calls + hs.sat_calls,
                                                "seconds": round(t0(), 3)})
        else:
            if bound <= level or best is not None:  # no coronas for a tiler
                continue
            r = heesch(grid, cells, max_level=bound, time_limit=budget, hs=hs, start=level + 1, best=r.hc_witness)
            if r.decided:
                return _non_tiler(r, t0(), torus=tried_m)
            if r.surrounded < bound:  # the time limit
                return _undecided(r.surrounded, tried_m, t0(), r.reason, r.hc_witness)
            level = bound
    return _undecided(level, tried_m, t0(), r.reason, r.hc_witness)


def _surround_isohedral(grid: Grid, cells: np.ndarray, st: SurroundResult, t0: Callable[[], float]) -> Classification:
    """The isohedral tiler found by the direct test, with its tiling as a torus witness."""
    tt = st.tiling
    a_, b_, d_ = tt.lattice
    # (as with the boundary-word test, the verdict does not name the wallpaper group: naming it
    # by tilekit.symmetry cost twice the whole test; :func:`torus_tiling` of the witness has it)
    return Classification("true", True, witness=tt.to_json(),
                          verdict=f"tiles isohedrally: a first corona closed under its copies' transforms generates "
                                  f"a one-class tiling ({tt.m} tiles per translational unit, period lattice "
                                  f"({a_},{b_}),(0,{d_}))",
                          evidence={"step": "surround", "m": tt.m, "lattice": list(tt.lattice), "models": st.models,
                                    "seconds": round(t0(), 3)})


def classify_form(grid: Grid, cells: np.ndarray, *, has_holes: bool = False, **bounds: Any) -> Classification:
    """:func:`classify` for one polyform with no boundary-word analysis at hand: the local test
    of corona 1 runs before the boundary-word test (a form it settles cannot tile, so it has no
    isohedral tiling to look for), then :func:`isohedral.analyse`; the same verdicts as
    ``classify(grid, cells, analyse(grid, cells, construct=False), ...)``. ``bounds``: the
    keyword arguments of :func:`classify`."""
    if has_holes:
        return classify(grid, cells, None, has_holes=True, **bounds)
    check_grid(grid)
    first = first_corona_rows(grid, cells)
    if not len(first):
        return classify(grid, cells, None, first=first, **bounds)
    return classify(grid, cells, analyse(grid, cells, construct=False), first=first, **bounds)


def _non_tiler(r, seconds: float, torus: int | None = None) -> Classification:
    if r.hh > r.hc:
        how = (f"no hole-free {r.hc + 1}-corona patch; {r.hh} corona{'s' if r.hh != 1 else ''} only with a hole "
               f"in the outermost")
    else:
        how = f"no {r.hc + 1}-corona patch exists"
    extra = f"; no torus tiling with up to {torus} tiles per unit" if torus and torus > 1 else ""
    witness = {"kind": "heesch", "hc": _corona_json(r.hc_witness, r.hc), "hh": _corona_json(r.hh_witness, r.hh)}
    return Classification("false", False, heesch=r.hc, heesch_holes=r.hh, witness=witness,
                          verdict=f"does not tile: Heesch number {r.hc} ({how}){extra}",
                          evidence={"step": "coronas", "failed_level": r.hc + 1, "sat_calls": r.sat_calls,
                                    "seconds": round(seconds, 3)} | ({"torus_tiles": torus} if torus and torus > 1 else {}))


def _undecided(levels: int, torus: int | None, seconds: float, reason: str, witness: Corona | None) -> Classification:
    bounds = f"undecided up to {levels} coronas"
    if torus and torus > 1:
        bounds += f" and {torus} tiles per translational unit"
    return Classification("undecided", False, witness={"kind": "heesch", "hc": _corona_json(witness, levels), "hh": None},
                          verdict=f"{bounds} ({reason})",
                          evidence={"step": "bounds", "seconds": round(seconds, 3)} | ({"torus_tiles": torus} if torus and torus > 1 else {}))


# --------------------------------------------------------------------------- witnesses as tilings

#: A stored witness's placements: (form, x, y, class) integer rows.
_WITNESS_ROWS = Field("list", required=True, length=(1, 1 << 20),
                      items=Field("list", items=Field("int", range=(-(1 << 18), 1 << 18)), length=(4, 4)))
#: A torus witness's lattice (a, b, d): v1 = (a, b), v2 = (0, d) in cells.
_LATTICE = Field("list", required=True, items=Field("int", range=(-(1 << 18), 1 << 18)), length=(3, 3))


def _witness_rows(witness: Any, forms: Forms, what: str, lattice: bool = False) -> np.ndarray:
    """A witness's ``tiles`` as an (n, 4) array, checked (types, sizes, form indices in range,
    classes 0..n), or a one-line ParseError naming ``what``."""
    fields = {"tiles": _WITNESS_ROWS, **({"lattice": _LATTICE} if lattice else {})}
    checked = check(Field("table", fields=fields), witness, what)
    t = np.asarray(checked["tiles"], dtype=np.int64).reshape(-1, 4)
    if (t[:, 0] >= forms.J).any() or (t[:, 0] < 0).any():
        raise ParseError(f"{what}: a placement's form index is outside 0..{forms.J - 1}")
    if (t[:, 3] < 0).any() or (t[:, 3] > len(t)).any():
        raise ParseError(f"{what}: a placement's class is outside 0..{len(t)}")
    return t


def corona_patch(grid: Grid, cells: np.ndarray, corona: dict, name: str = "") -> Patch:
    """A stored corona witness as a Patch, colour and aspect = corona number."""
    forms = Forms(grid, cells)
    t = _witness_rows(corona, forms, "polyomino corona witness")
    proto = outline(grid, forms.cells, name=name)
    return Patch([proto], np.zeros(len(t), dtype=np.int64), forms.affine(t[:, :3]), colour=t[:, 3], aspect=t[:, 3])


def torus_tiling(grid: Grid, cells: np.ndarray, witness: dict, name: str = "", family: str = "polyomino") -> PeriodicTiling:
    """A stored torus witness as a PeriodicTiling whose aspects are the transitivity classes."""
    forms = Forms(grid, cells)
    t = _witness_rows(witness, forms, "polyomino torus witness", lattice=True)
    a, b, d = (int(x) for x in witness["lattice"])
    if a == 0 or d == 0:
        raise ParseError(f"polyomino torus witness: lattice {[a, b, d]} is degenerate (a and d must not be 0)")
    p = grid.period
    v1, v2 = grid.xy(np.array([a * p, b * p])), grid.xy(np.array([0, d * p]))
    proto = outline(grid, forms.cells, name=name)
    k = int(t[:, 3].max()) + 1
    return PeriodicTiling([proto], np.zeros(len(t), dtype=np.int64), forms.affine(t[:, :3]), v1, v2,
                          Colouring.by_aspect(list(range(k))), unit_aspect=t[:, 3], family=family, name=name)
