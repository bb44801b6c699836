"""Substitution systems as data (§6.1): prototiles, expansion constant, rules, and their checks.

A system file (TOML, one per system in ``catalogue/substitution/``) names its prototiles
(congruent ones may appear under distinct labels), the expansion constant ``scale``, and a
rule per prototile ``T_i -> [(j, M), ...]``. Following the book's convention (Figure 6.5)
each M already includes the factor 1/s, so a rule's children cover the *unscaled* parent.
A child's M is written either as a 2x3 ``matrix`` or as ``vertices``: where the child's
outline vertices 0, 1, 2 land in the parent's frame. All numbers are expressions in named
constants (phi, sqrt2, ...) evaluated once by :mod:`.expr`.

The loader checks what the book requires of a system: indices in range, every M a similarity
of scale 1/s, and — by ``kind`` — that the children of each rule cover the parent exactly
(``exact``: a composition), tile without overlap but leave indentations and protrusions
(``indented``, e.g. Gähler's shield), or cover it with consistent overlaps (``overlapping``,
e.g. Lord's tiling). Every error names the file, the rule and the problem.

Optional ``[[tile]]`` / ``[assemble]`` tables describe a final assembly (exercise 6.10):
each half-tile prototile names the whole tile it is half of and where that whole tile sits
in the half-tile's frame; generation then emits the whole tiles, each exactly once.
"""

from __future__ import annotations

import functools
import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import shapely

from tilekit.errors import GeometryError, ParseError, TilekitError
from tilekit.geometry import Affine
from tilekit.plugins.substitution.expr import constants_with, evaluate
from tilekit.plugins.substitution.formats import read_system_data
from tilekit.plugins.substitution.keypoint import keypoint_system_from_data
from tilekit.plugins.substitution.rules import MatrixFacts, Rule
from tilekit.polygon import inscribed_disc as inscribed_disc  # moved to tilekit.polygon
from tilekit.polygon import signed_area
from tilekit.polygon import symmetry_maps as outline_symmetries  # moved to tilekit.polygon
from tilekit.resources import read_toml
from tilekit.tiling import Prototile

__all__ = ["MatrixFacts", "Rule", "SubstitutionSystem", "load_data", "load_system", "system_from_data"]

KINDS = ("exact", "indented", "overlapping")

#: Relative tolerance of the loader's geometric checks (areas as a fraction of the parent).
CHECK_TOL = 1e-7


@dataclass
class SubstitutionSystem(MatrixFacts):
    """A validated substitution system (see the module docstring for the file format)."""

    name: str
    title: str
    scale: float
    kind: str
    prototiles: list[Prototile]
    rules: list[Rule]
    seed: int = 0
    output_prototiles: list[Prototile] | None = None
    assemble_tile: np.ndarray | None = None
    assemble_matrix: np.ndarray | None = None
    facts: dict[str, Any] = field(default_factory=dict)
    #: Pairing assembly (exercise 6.10 by shared edges): the half-tile's edge vertex indices,
    #: and per relation ("mirror": opposite handedness, "turn": same) the whole tile index and
    #: its placement in the frame of the reference half.
    pairing_edge: tuple[int, int] | None = None
    pairing: dict[str, tuple[int, np.ndarray]] = field(default_factory=dict)
    source: str = "<memory>"
    data: dict[str, Any] = field(default_factory=dict)
    symmetries: list[np.ndarray] = field(default_factory=list)
    output_symmetries: list[np.ndarray] = field(default_factory=list)

    # ------------------------------------------------------------------ derived facts
    @property
    def n(self) -> int:
        return len(self.prototiles)

    @property
    def tiles(self) -> list[Prototile]:
        """The prototiles a generated patch is made of (the whole tiles after assembly)."""
        return self.output_prototiles if self.output_prototiles is not None else self.prototiles

    def child_labels(self) -> list[np.ndarray]:
        return [np.asarray(rule.children, dtype=np.int64) for rule in self.rules]

    def rep_tile(self) -> int | None:
        """k if the system is a k-rep-tile (one prototile, all children congruent), else None."""
        if self.n != 1 or self.kind != "exact":
            return None
        return int(len(self.rules[0].children))


# ---------------------------------------------------------------------- loading


def load_system(path: str | Path) -> Any:
    """Read and validate a system file (TOML): a SubstitutionSystem, or a KeypointSystem
    when the file says ``engine = "keypoint"``."""
    return load_data(read_toml(path, "substitution system"), source=Path(path).name)


def guarded_loader(fn: Callable[..., Any]) -> Callable[..., Any]:
    """Wrap a ``*_from_data(data, source)`` loader so that data of a wrong shape the explicit
    checks did not foresee is still one ParseError naming the file (never a traceback), and
    NumPy's floating-point warnings stay quiet (non-finite results are rejected instead)."""

    @functools.wraps(fn)
    def wrapper(data: Any, source: str = "<data>", *args: Any, **kwargs: Any) -> Any:
        try:
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                return fn(data, source, *args, **kwargs)
        except TilekitError:
            raise
        except (TypeError, ValueError, AttributeError, KeyError, IndexError, ArithmeticError,
                RecursionError, np.linalg.LinAlgError, shapely.errors.ShapelyError) as exc:
            raise ParseError(
                f"substitution system {source}: malformed data ({type(exc).__name__}: {str(exc)[:120]}); "
                "see docs/families/substitution.md for the file format"
            ) from None

    return wrapper


@guarded_loader
def load_data(data: Mapping[str, Any], source: str = "<data>") -> Any:
    """A system of either engine from parsed data."""
    engine = data.get("engine", "similarity") if isinstance(data, Mapping) else "similarity"
    if engine == "keypoint":
        return keypoint_system_from_data(data, source)
    if engine != "similarity":
        raise ParseError(f"substitution system {source}: engine {engine!r} is not 'similarity' or 'keypoint'")
    return system_from_data(data, source=source)


def system_from_data(data: Mapping[str, Any], source: str = "<data>") -> SubstitutionSystem:
    """Build and validate a system from parsed TOML/JSON data (``source`` names it in errors):
    the shape of every field is checked by the dialect's schema (:mod:`.formats`), then names
    are resolved and the geometry is checked."""
    where = f"substitution system {source}"
    raw = data
    _, data = read_system_data(data, source, "similarity")
    ctx = _Context(where, constants_with(data["constants"]))
    name = str(data.get("name") or Path(source).stem)
    scale = ctx.num(data["scale"], "scale")
    if not scale > 1:
        raise ctx.fail(f"expansion constant scale = {scale:g} must be greater than 1")
    protos, names = _prototiles(data["prototile"], "prototile", ctx)
    index = {nm: i for i, nm in enumerate(names)}
    rules = _rules(data["rule"], protos, names, index, ctx)
    seed = _resolve(data.get("seed", names[0]), index, "seed", ctx.fail)
    system = SubstitutionSystem(
        name=name,
        title=str(data.get("title", name)),
        scale=scale,
        kind=data["kind"],
        prototiles=protos,
        rules=rules,
        seed=seed,
        facts=dict(data.get("properties", {})),
        source=source,
        data=dict(raw),
    )
    if "pairing" in data:
        if "assemble" in data:
            raise ctx.fail("give either [assemble] or [pairing], not both")
        _pairing(system, data, ctx)
    elif "tile" in data or "assemble" in data:
        _assembly(system, data, names, ctx)
    check_system(system, names)
    system.symmetries = rule_symmetries(system)
    if system.output_prototiles is not None:
        system.output_symmetries = [outline_symmetries(t.outline) for t in system.output_prototiles]
    return system


class _Context:
    """Where errors point, and the numbers of a file: expressions in its named constants."""

    def __init__(self, where: str, env: Mapping[str, float]) -> None:
        self.where = where
        self.env = env

    def fail(self, msg: str) -> ParseError:
        return ParseError(f"{self.where}: {msg}")

    def num(self, value: Any, ctx: str) -> float:
        try:
            return evaluate(value, self.env)
        except ParseError as exc:
            raise self.fail(f"{ctx}: {exc}") from None

    def points(self, values: Sequence[Any], ctx: str) -> np.ndarray:
        return np.array([[self.num(x, ctx), self.num(y, ctx)] for x, y in values]).reshape(-1, 2)


def _rules(raw_rules: list[Mapping[str, Any]], protos: list[Prototile], names: list[str],
           index: Mapping[str, int], ctx: _Context) -> list[Rule]:
    rules: list[Rule | None] = [None] * len(protos)
    for r, raw in enumerate(raw_rules):
        parent = _resolve(raw["parent"], index, f"rule #{r + 1} parent", ctx.fail)
        rctx = f"rule for {names[parent]!r}"
        if rules[parent] is not None:
            raise ctx.fail(f"{rctx}: given twice")
        labels, mats = [], []
        for c, kid in enumerate(raw["child"]):
            cctx = f"{rctx}, child #{c + 1}"
            j = _resolve(kid["tile"], index, cctx, ctx.fail)
            labels.append(j)
            mats.append(_child_matrix(kid, protos[j], cctx, ctx))
        rules[parent] = Rule(np.array(labels, dtype=np.int64), np.array(mats))
    missing = [names[i] for i, rl in enumerate(rules) if rl is None]
    if missing:
        raise ctx.fail(f"no rule for prototile(s) {', '.join(missing)}")
    return rules  # type: ignore[return-value]


def _pairing(system: SubstitutionSystem, data: Mapping[str, Any], ctx: _Context) -> None:
    """The [pairing] assembly: whole tiles made of two half-tiles sharing an edge."""
    output, out_names = _prototiles(data.get("tile"), "tile", ctx)
    out_index = {nm: i for i, nm in enumerate(out_names)}
    table = data["pairing"]
    if len(system.prototiles) != 1:
        raise ctx.fail("[pairing] needs exactly one (half-tile) prototile")
    k = len(system.prototiles[0].outline)
    if any(v >= k for v in table["edge"]):
        raise ctx.fail(f"[pairing] edge must be two vertex indices of the half-tile (0..{k - 1})")
    system.output_prototiles = output
    system.pairing_edge = (int(table["edge"][0]), int(table["edge"][1]))
    for relation in ("mirror", "turn"):
        if relation in table:
            actx = f"[pairing] {relation}"
            t = _resolve(table[relation]["tile"], out_index, actx, ctx.fail)
            system.pairing[relation] = (t, _child_matrix(table[relation], output[t], actx, ctx))
    if not system.pairing:
        raise ctx.fail("[pairing] needs a 'mirror' or a 'turn' entry")


def _assembly(system: SubstitutionSystem, data: Mapping[str, Any], names: list[str], ctx: _Context) -> None:
    """The [assemble] table: where each half-tile's whole tile sits in its frame."""
    output, out_names = _prototiles(data.get("tile"), "tile", ctx)
    out_index = {nm: i for i, nm in enumerate(out_names)}
    table = data.get("assemble", {})
    n = len(system.prototiles)
    system.output_prototiles = output
    system.assemble_tile = np.zeros(n, dtype=np.int64)
    system.assemble_matrix = np.zeros((n, 3, 3))
    for i, nm in enumerate(names):
        if nm not in table:
            raise ctx.fail(f"[assemble] has no entry for prototile {nm!r}")
        actx = f"[assemble] {nm!r}"
        t = _resolve(table[nm]["tile"], out_index, actx, ctx.fail)
        system.assemble_tile[i] = t
        system.assemble_matrix[i] = _child_matrix(table[nm], output[t], actx, ctx)


def _resolve(ref: Any, index: Mapping[str, int], ctx: str, fail: Any) -> int:
    if isinstance(ref, bool):
        raise fail(f"{ctx}: tile reference {ref!r} is not a name or index")
    if isinstance(ref, int):
        if not 0 <= ref < len(index):
            raise fail(f"{ctx}: tile index {ref} out of range 0..{len(index) - 1}")
        return ref
    if isinstance(ref, str) and ref in index:
        return index[ref]
    raise fail(f"{ctx}: unknown tile {ref!r}; known: {', '.join(index)}")


def _prototiles(raw: Any, key: str, ctx: _Context) -> tuple[list[Prototile], list[str]]:
    if not raw:
        raise ctx.fail(f"no [[{key}]] tables")
    protos, names = [], []
    for i, entry in enumerate(raw):
        nm = str(entry.get("name", f"T{i + 1}"))
        if nm in names:
            raise ctx.fail(f"[[{key}]] name {nm!r} used twice")
        pts = ctx.points(entry["outline"], f"{key} {nm!r} outline")
        if shapely.Polygon(pts).is_valid is False:
            raise ctx.fail(f"{key} {nm!r}: outline is self-intersecting")
        if signed_area(pts) <= 0:
            raise ctx.fail(f"{key} {nm!r}: outline must be counter-clockwise with positive area")
        marking = tuple(ctx.points(line, f"{key} {nm!r} marking") for line in entry["marking"])
        try:
            protos.append(Prototile(pts, marking=marking, name=nm))
        except GeometryError as exc:
            raise ctx.fail(f"{key} {nm!r}: {exc}") from None
        names.append(nm)
    return protos, names


def _child_matrix(kid: Mapping[str, Any], child: Prototile, ctx: str, c: _Context) -> np.ndarray:
    if ("matrix" in kid) == ("vertices" in kid):
        raise c.fail(f"{ctx}: give exactly one of 'matrix' (2x3) or 'vertices' (3 points)")
    if "matrix" in kid:
        rows = kid["matrix"]
        m = np.array([[c.num(v, f"{ctx} matrix") for v in r] for r in rows[:2]] + [[0.0, 0.0, 1.0]])
        if len(rows) == 3 and [c.num(v, ctx) for v in rows[2]] != [0.0, 0.0, 1.0]:
            raise c.fail(f"{ctx}: matrix third row must be [0, 0, 1]")
        return m
    dst = c.points(kid["vertices"], f"{ctx} vertices")
    return affine_from_points(child.outline[:3], dst, ctx, c.fail)


def affine_from_points(src: np.ndarray, dst: np.ndarray, ctx: str = "", fail: Any = None) -> np.ndarray:
    """The affine map taking the three points ``src`` to ``dst``."""
    a = np.column_stack([src, np.ones(3)])
    try:
        sol = np.linalg.solve(a, dst)  # (3, 2): rows are x-coef, y-coef, constant
    except np.linalg.LinAlgError:
        msg = f"{ctx}: the child's first three vertices are collinear"
        raise (fail(msg) if fail else GeometryError(msg)) from None
    m = np.eye(3)
    m[:2, :2] = sol[:2].T
    m[:2, 2] = sol[2]
    return m


# ---------------------------------------------------------------------- checks


def check_system(system: SubstitutionSystem, names: Sequence[str]) -> None:
    """The loader's geometric checks (similarity scale and coverage by kind)."""
    where = f"substitution system {system.source}"
    polys = [p.polygon() for p in system.prototiles]
    for j, rule in enumerate(system.rules):
        rctx = f"{where}: rule for {names[j]!r}"
        _check_similarities(rule, 1.0 / system.scale, rctx)
        kids = [
            shapely.Polygon(Affine.apply(m, system.prototiles[k].outline))
            for k, m in zip(rule.children, rule.matrices)
        ]
        _COVER_CHECKS[system.kind](polys[j], kids, rctx)
    if system.output_prototiles is not None and system.assemble_tile is not None:
        _check_assembly(system, polys, names, where)


def _check_similarities(rule: Rule, inv: float, rctx: str) -> None:
    """Every child's matrix is a similarity of scale 1/s."""
    for c, m in enumerate(rule.matrices):
        s = Affine.similarity_scale(m, tol=1e-7)
        if s is None:
            raise ParseError(f"{rctx}, child #{c + 1}: matrix is not a similarity (it shears or stretches)")
        if abs(s - inv) > 1e-7 * max(1.0, inv):
            raise ParseError(f"{rctx}, child #{c + 1}: similarity has scale {s:.9g}, expected 1/scale = {inv:.9g}")


def _overlay(parent: shapely.Polygon, kids: list[shapely.Polygon]) -> tuple[shapely.Geometry, float, float, float]:
    """(union of the children, their total area, the area tolerance, the snap grid).
    Snap-rounded: GEOS's floating overlay can lose a whole piece when shared vertices differ
    in the last bit (seen with GEOS 3.14)."""
    grid = 1e-10 * math.sqrt(parent.area)
    return shapely.union_all(kids, grid_size=grid), sum(k.area for k in kids), CHECK_TOL * parent.area, grid


def _check_exact(parent: shapely.Polygon, kids: list[shapely.Polygon], rctx: str) -> None:
    union, total, tol, grid = _overlay(parent, kids)
    outside = shapely.difference(union, parent, grid_size=grid).area
    uncovered = shapely.difference(parent, union, grid_size=grid).area
    if outside > tol:
        raise ParseError(f"{rctx}: children extend outside the parent (area {outside:.3g})")
    if uncovered > tol:
        raise ParseError(f"{rctx}: children leave a gap in the parent (area {uncovered:.3g})")
    if total - parent.area > tol:
        raise ParseError(f"{rctx}: children overlap (total area {total:.6g} > parent {parent.area:.6g})")


def _check_indented(parent: shapely.Polygon, kids: list[shapely.Polygon], rctx: str) -> None:
    union, total, tol, _ = _overlay(parent, kids)
    if abs(total - union.area) > tol:
        raise ParseError(f"{rctx}: children overlap each other (an indented system may not)")
    if abs(total - parent.area) > tol:
        raise ParseError(
            f"{rctx}: children's area {total:.6g} differs from the parent's {parent.area:.6g} "
            "(protrusions must balance indentations)"
        )


def _check_overlapping(parent: shapely.Polygon, kids: list[shapely.Polygon], rctx: str) -> None:
    union, _, tol, grid = _overlay(parent, kids)
    uncovered = shapely.difference(parent, union, grid_size=grid).area
    if uncovered > tol:
        raise ParseError(f"{rctx}: children do not cover the parent (gap area {uncovered:.3g})")


#: What the children of a rule must do to the parent, by the system's ``kind``.
_COVER_CHECKS = {"exact": _check_exact, "indented": _check_indented, "overlapping": _check_overlapping}


def _check_assembly(system: SubstitutionSystem, polys: list[shapely.Polygon], names: Sequence[str], where: str) -> None:
    """Each half-tile lies inside the whole tile it names, placed by an isometry."""
    assert system.output_prototiles is not None
    assert system.assemble_tile is not None and system.assemble_matrix is not None
    for i, (t, m) in enumerate(zip(system.assemble_tile, system.assemble_matrix)):
        actx = f"{where}: [assemble] {names[i]!r}"
        if not Affine.is_isometry(m, tol=1e-7):
            raise ParseError(f"{actx}: the whole tile's placement is not an isometry")
        whole = shapely.Polygon(Affine.apply(m, system.output_prototiles[t].outline))
        half = polys[i]
        if shapely.difference(half, whole, grid_size=1e-10 * math.sqrt(half.area)).area > CHECK_TOL * half.area:
            raise ParseError(f"{actx}: the half-tile is not inside the whole tile it names")


# ---------------------------------------------------------------------- symmetry


def rule_symmetries(system: SubstitutionSystem) -> list[np.ndarray]:
    """Per prototile, the outline symmetries that also preserve its substitution (exercise 6.7).

    Two matrices M and M @ S place the same tile of prototile i exactly when S is a symmetry
    of the outline *and* of everything the rule produces from it; a greatest fixed point:
    start from the outline symmetries and drop S whenever S maps the rule's children onto a
    set that differs from the children modulo their own surviving symmetries.
    """
    groups = [outline_symmetries(p.outline) for p in system.prototiles]
    changed = True
    while changed:
        changed = False
        for i, rule in enumerate(system.rules):
            keep = [groups[i][0]]
            base = _child_keys(rule.children, rule.matrices, groups)
            for s in groups[i][1:]:
                moved = _child_keys(rule.children, s[None] @ rule.matrices, groups)
                if moved == base:
                    keep.append(s)
            if len(keep) != len(groups[i]):
                groups[i] = np.array(keep)
                changed = True
    return groups


def _child_keys(children: np.ndarray, mats: np.ndarray, groups: list[np.ndarray]) -> set[tuple[int, ...]]:
    keys = set()
    for j, m in zip(children, mats):
        cands = [tuple(np.round((m @ g)[:2].ravel() * 1e6).astype(np.int64).tolist()) for g in groups[int(j)]]
        keys.add((int(j), *min(cands)))
    return keys


def inflation_radii(system: SubstitutionSystem) -> tuple[np.ndarray, np.ndarray]:
    """Per prototile, a centre c_i and radius R_i bounding all its descendants at every depth.

    R_i = max(radius of T_i about c_i, max over children |M c_j - c_i| + R_j / s), iterated to
    its fixed point (a contraction, since 1/s < 1). Exact systems give the outline radius.
    """
    centres = np.array([p.outline.mean(axis=0) for p in system.prototiles])
    base = np.array([np.linalg.norm(p.outline - c, axis=1).max() for p, c in zip(system.prototiles, centres)])
    radius = base.copy()
    inv = 1.0 / system.scale
    for _ in range(200):
        new = base.copy()
        for i, rule in enumerate(system.rules):
            img = np.einsum("nij,nj->ni", rule.matrices[:, :2, :2], centres[rule.children]) + rule.matrices[:, :2, 2]
            reach = np.linalg.norm(img - centres[i], axis=1) + radius[rule.children] * inv
            new[i] = max(base[i], float(reach.max()))
        if np.allclose(new, radius, rtol=1e-12, atol=1e-12):
            break
        radius = new
    return centres, radius * (1 + 1e-9) + 1e-12
