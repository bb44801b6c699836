"""Quasivertex parameterizations of the Penrose tiles (book §6.3): the rhombs' of Figures 6.13
and 6.14 (below), and the kite and dart's, derived in :mod:`.quasivertex_p2` and served
through the same functions (``system_outlines``, ``deformed_tiles``, ``matching_report``).

Four numbers r1, theta1, r2, theta2 move the tiling vertices of a P3 tiling off the rhombs'
corners. Figure 6.13 places the quasivertices in a frame where the thick rhomb is
A = (sin pi/5, 0), B = (0, cos pi/5), C = -A, D = -B and the thin rhomb A' = (sin pi/10, 0),
B' = (0, cos pi/10), C' = -A', D' = -B' (A, C, A', C' obtuse corners):

    thick: E = A + r1 u(7pi/10 - t1)   F = A + r2 u(7pi/10 - t2)
           G = rot(B, -2pi/5, F)        H = rot(B, -2pi/5, E)
           I = D + r2 u(pi/2 - t2)      J = D + r1 u(pi/2 - t1)
           K = rot(D, -2pi/5, J)        L = rot(D, -2pi/5, I)     M = rot(D, -2pi/5, H)
    thin:  E' = A' + r1 u(6pi/5 - t1)   F' = B' + r2 u(7pi/5 - t2)
           G' = rot(C', -4pi/5, F')     H' = D' + r1 u(3pi/5 - t1)
           I' = D' + r1 u(pi/5 - t1)    J' = rot(A', 4pi/5, F')   K' = rot(A', 4pi/5, E')

(u(a) = (cos a, sin a); rot(p, a, q) turns q by a about p.) The extracted text of the book
gives these formulas but not the figure, so the order of the points around each tile was
derived here (see docs/families/substitution.md, "Quasivertex shapes"): placing every point
of every tile of a generated P3 patch for generic parameters, the only counter-clockwise
cycles whose directed edges all meet a reversed copy in a neighbour are

    thick: A E F B G H I J D K L M   (12 edges; C is not a vertex of the deformed tile)
    thin:  A' E' F' C' G' H' D' I' J' K'   (10 edges; B' is not a vertex)

and, starting at A and A', the book's edge labels abcdefegabhg and afcdegabhg then satisfy
exactly the interlocking pairs (a, g), (b, e), (c, d), (f, h) of Figure 6.14 on every shared
edge. Each deformed tile keeps the area of its straight rhomb for every parameter value
(the quasivertex moves trade area between a tile's own edges), which the tests check.
r1 = r2 = 0 gives the straight rhombs back.

The book's frame is tied to the tiles of ``penrose-p3`` by fixed similarities (checked
against the system's tile outlines), so the deformation respects the matching rules: every
placement is direct (reflected placements re-expressed by the rhomb's mirror symmetry).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import shapely

from tilekit.errors import GeometryError, ParameterError
from tilekit.geometry import POINT_TOL, Affine
from tilekit.plugins.substitution import quasivertex_p2 as p2
from tilekit.plugins.substitution.shapes import complement
from tilekit.tiling import Prototile

#: Point order around the deformed tiles (counter-clockwise, from A / A').
THICK_ORDER = "AEFBGHIJDKLM"
THIN_ORDER = "AEFCGHDIJK"
#: Figure 6.14's edge labels, edge i running from point i to point i + 1 of the order above.
THICK_LABELS = "abcdefegabhg"
THIN_LABELS = "afcdegabhg"
#: Interlocking pairs of §6.3: an edge labelled x meets an edge labelled PARTNER[x].
PARTNER = {"a": "g", "g": "a", "b": "e", "e": "b", "c": "d", "d": "c", "f": "h", "h": "f"}
#: The label that carries a pair's shape as given (its partner carries the complement).
PRIMARY = ("a", "b", "c", "f")
#: Option names (angles in degrees).
PARAM_NAMES = ("r1", "theta1", "r2", "theta2")
#: Systems with a quasivertex parameterization: P3's of Figure 6.13 (this module) and P2's
#: derived from the family's own patches (:mod:`.quasivertex_p2`).
SUPPORTED = ("penrose-p3", "penrose-p2")
#: The same systems by the short name ``--tiling`` and the editor's ``?tiling=`` take.
BY_TILING = {name.removeprefix("penrose-"): name for name in SUPPORTED}


@dataclass(frozen=True)
class QuasivertexSpec:
    """What a system's quasivertex tiles are: tile names (system order), labels, pairs."""

    tiles: tuple[str, ...]
    labels: dict[str, str]
    partner: dict[str, str]
    primary: tuple[str, ...]


SPECS = {
    "penrose-p3": QuasivertexSpec(("thin", "thick"), {"thick": THICK_LABELS, "thin": THIN_LABELS}, PARTNER, PRIMARY),
    "penrose-p2": QuasivertexSpec(("kite", "dart"), dict(p2.LABELS), p2.PARTNER, p2.PRIMARY),
}


@dataclass(frozen=True)
class QuasivertexParams:
    """r1, r2 (lengths, edge length 1) and theta1, theta2 (degrees) of Figure 6.13."""

    r1: float = 0.0
    theta1: float = 0.0
    r2: float = 0.0
    theta2: float = 0.0

    def radians(self) -> tuple[float, float, float, float]:
        return self.r1, math.radians(self.theta1), self.r2, math.radians(self.theta2)

    def as_dict(self) -> dict[str, float]:
        return {"r1": self.r1, "theta1": self.theta1, "r2": self.r2, "theta2": self.theta2}

    def text(self) -> str:
        return f"r1={self.r1:g}, theta1={self.theta1:g}, r2={self.r2:g}, theta2={self.theta2:g}"

    @classmethod
    def from_options(cls, options: Mapping[str, object]) -> QuasivertexParams:
        """Parse r1/theta1/r2/theta2 (numbers or numeric strings; missing ones are 0)."""
        values: dict[str, float] = {}
        for name in PARAM_NAMES:
            raw = options.get(name, 0.0)
            try:
                v = float(raw)  # type: ignore[arg-type]
            except (TypeError, ValueError):
                raise ParameterError(f"quasivertex parameter {name}={raw!r} is not a number") from None
            if not math.isfinite(v):
                raise ParameterError(f"quasivertex parameter {name}={raw!r} is not finite")
            values[name] = v
        return cls(**values)


def _u(a: float) -> np.ndarray:
    return np.array([math.cos(a), math.sin(a)])


def _rot(p: np.ndarray, a: float, q: np.ndarray) -> np.ndarray:
    """The book's rotate(p, a, q): q rotated by a about p."""
    return Affine.apply(Affine.rotation(a, (float(p[0]), float(p[1]))), q)


def thick_points(params: QuasivertexParams) -> dict[str, np.ndarray]:
    """The 13 named points of the thick rhomb (Figure 6.13, book frame)."""
    r1, t1, r2, t2 = params.radians()
    pi = math.pi
    A = np.array([math.sin(pi / 5), 0.0])
    B = np.array([0.0, math.cos(pi / 5)])
    C, D = -A, -B
    E = A + r1 * _u(7 * pi / 10 - t1)
    F = A + r2 * _u(7 * pi / 10 - t2)
    G = _rot(B, -2 * pi / 5, F)
    H = _rot(B, -2 * pi / 5, E)
    I = D + r2 * _u(pi / 2 - t2)  # noqa: E741 - the book's name
    J = D + r1 * _u(pi / 2 - t1)
    K = _rot(D, -2 * pi / 5, J)
    L = _rot(D, -2 * pi / 5, I)
    M = _rot(D, -2 * pi / 5, H)
    return dict(A=A, B=B, C=C, D=D, E=E, F=F, G=G, H=H, I=I, J=J, K=K, L=L, M=M)


def thin_points(params: QuasivertexParams) -> dict[str, np.ndarray]:
    """The 11 named points A'..K' of the thin rhomb (Figure 6.13, book frame)."""
    r1, t1, r2, t2 = params.radians()
    pi = math.pi
    A = np.array([math.sin(pi / 10), 0.0])
    B = np.array([0.0, math.cos(pi / 10)])
    C, D = -A, -B
    E = A + r1 * _u(6 * pi / 5 - t1)
    F = B + r2 * _u(7 * pi / 5 - t2)
    G = _rot(C, -4 * pi / 5, F)
    H = D + r1 * _u(3 * pi / 5 - t1)
    I = D + r1 * _u(pi / 5 - t1)  # noqa: E741 - the book's name
    J = _rot(A, 4 * pi / 5, F)
    K = _rot(A, 4 * pi / 5, E)
    return dict(A=A, B=B, C=C, D=D, E=E, F=F, G=G, H=H, I=I, J=J, K=K)


def book_outlines(params: QuasivertexParams) -> dict[str, tuple[np.ndarray, str]]:
    """{"thick"|"thin": (outline (k, 2) in the book's frame, edge labels)}, unmerged."""
    tk, tn = thick_points(params), thin_points(params)
    return {
        "thick": (np.array([tk[c] for c in THICK_ORDER]), THICK_LABELS),
        "thin": (np.array([tn[c] for c in THIN_ORDER]), THIN_LABELS),
    }


def book_to_system() -> dict[str, np.ndarray]:
    """Similarities from the book's frame to ``penrose-p3``'s whole-tile frames.

    The system's thick rhomb is (0,0), (c3,-s3), (2c3,0), (c3,s3) with c3 = cos 3pi/10 =
    sin pi/5: the book's rhomb shifted by (c3, 0) (book C -> vertex 0). The thin rhomb
    (0,0), (c1,-s1), (2c1,0), (c1,s1) is the book's turned by -90 degrees and shifted by
    (c1, 0) (book A' -> vertex 1). Of the rhombs' two direct self-maps (identity and the
    half-turn) these are the ones under which the named points of neighbouring tiles
    coincide (the half-turn breaks the matching), found by the derivation described above.
    """
    c1 = math.cos(math.pi / 10)
    c3 = math.cos(3 * math.pi / 10)
    return {
        "thick": Affine.translation(c3, 0.0),
        "thin": Affine.translation(c1, 0.0) @ Affine.rotation(-math.pi / 2),
    }


#: A spoke shorter than this (edge lengths) is drawn as none: quasivertices closer than it to
#: their corner would be distinct points closer than the patches' point tolerance (found by
#: the hypothesis test: r1 = 1e-7 made outlines that could not be triangulated).
MIN_SPOKE = 1e-6


def system_outlines(params: QuasivertexParams, system_name: str = "penrose-p3") -> dict[str, tuple[np.ndarray, str]]:
    """{tile name: (quasivertices (k, 2) in the system's frame, edge labels)}, unmerged; r1 or r2
    below MIN_SPOKE counts as 0."""
    if abs(params.r1) < MIN_SPOKE or abs(params.r2) < MIN_SPOKE:
        params = QuasivertexParams(params.r1 if abs(params.r1) >= MIN_SPOKE else 0.0, params.theta1,
                                   params.r2 if abs(params.r2) >= MIN_SPOKE else 0.0, params.theta2)
    if system_name == "penrose-p2":
        return p2.outlines(*params.radians())
    maps = book_to_system()
    return {name: (Affine.apply(maps[name], pts), labels) for name, (pts, labels) in book_outlines(params).items()}


def _spec(system_name: str) -> QuasivertexSpec:
    if system_name not in SPECS:
        raise ParameterError(
            f"quasivertex parameters (r1, theta1, r2, theta2) apply to {', '.join(SUPPORTED)} only, not {system_name!r}"
        )
    return SPECS[system_name]


def check_system(tiles: Sequence[Prototile], system_name: str) -> None:
    """Raise ParameterError unless ``tiles`` are the system's straight tiles in the expected frames."""
    spec = _spec(system_name)
    if tuple(t.name for t in tiles) != spec.tiles:
        raise ParameterError(f"{system_name}: tiles {[t.name for t in tiles]} are not {list(spec.tiles)}")
    straight = system_outlines(QuasivertexParams(), system_name)
    for tile in tiles:
        pts = _merge(*straight[tile.name])[0]
        ok = len(pts) == len(tile.outline) and any(
            np.allclose(np.roll(pts, k, axis=0), tile.outline, atol=1e-9) for k in range(len(pts))
        )
        if not ok:
            raise GeometryError(f"{system_name}: tile {tile.name!r} is not in the frame the quasivertex formulas expect")


def _merge(outline: np.ndarray, labels: str, tol: float = 1e-12) -> tuple[np.ndarray, list[str], list[int]]:
    """Drop zero-length edges (r = 0 collapses points): (points, labels, source edge indices)."""
    nxt = np.roll(outline, -1, axis=0)
    keep = np.flatnonzero(np.linalg.norm(nxt - outline, axis=1) > tol)
    return outline[keep], [labels[i] for i in keep], [int(i) for i in keep]


def _simple(outline: np.ndarray) -> bool:
    if len(outline) < 3:
        return False
    poly = shapely.Polygon(outline)
    area = 0.5 * float(np.sum(outline[:, 0] * np.roll(outline[:, 1], -1) - np.roll(outline[:, 0], -1) * outline[:, 1]))
    if not (poly.is_valid and shapely.LinearRing(outline).is_simple and area > 0):
        return False
    # an outline that doubles back along itself (a slit) is not a tile boundary
    a = outline - np.roll(outline, 1, axis=0)
    b = np.roll(outline, -1, axis=0) - outline
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    dot = np.einsum("ij,ij->i", a, b)
    scale = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)
    return not bool(np.any((np.abs(cross) <= 1e-9 * scale) & (dot < 0)))


def _bad_tiles(params: QuasivertexParams, system_name: str = "penrose-p3") -> list[str]:
    return [name for name, (pts, labels) in system_outlines(params, system_name).items()
            if not _simple(_merge(pts, labels)[0])]


def _valid_run(params: QuasivertexParams, name: str, system_name: str = "penrose-p3") -> tuple[float, float, float] | None:
    """With the other three parameters fixed: (distance to the nearest valid value of ``name``,
    low end, high end of the run of valid sampled values holding it), or None if none is valid."""
    values = np.linspace(0.0, 1.0, 401) if name.startswith("r") else np.arange(-180.0, 180.5, 1.0)
    given = getattr(params, name)
    ok = np.array([not _bad_tiles(QuasivertexParams(**{**params.as_dict(), name: float(v)}), system_name)
                   for v in values])
    if not ok.any():
        return None
    idx = np.flatnonzero(ok)
    near = int(idx[np.argmin(np.abs(values[idx] - given))])
    lo = hi = near
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    while hi < len(values) - 1 and ok[hi + 1]:
        hi += 1
    scale = 1.0 if name.startswith("r") else 180.0
    return abs(float(values[near]) - given) / scale, float(values[lo]), float(values[hi])


def admissible_range(params: QuasivertexParams, name: str, lo: float, hi: float, samples: int = 64,
                     tol: float = 1e-4, system_name: str = "penrose-p3") -> tuple[float, float] | None:
    """The values of parameter ``name`` in [lo, hi] that keep both rhombs simple with the other
    three fixed: the run of such values around the given one (or the nearest run), its ends
    found by bisection to ``tol`` and given on their valid side; None if no sampled value is
    valid. What the Penrose editor's r sliders are limited to."""
    if name not in PARAM_NAMES:
        raise ParameterError(f"quasivertex parameter {name!r} is not one of {', '.join(PARAM_NAMES)}")

    def valid(v: float) -> bool:
        return not _bad_tiles(QuasivertexParams(**{**params.as_dict(), name: float(v)}), system_name)

    values = np.linspace(lo, hi, samples + 1)
    ok = np.array([valid(v) for v in values])
    if not ok.any():
        return None
    idx = np.flatnonzero(ok)
    near = int(idx[np.argmin(np.abs(values[idx] - getattr(params, name)))])
    a = b = near
    while a > 0 and ok[a - 1]:
        a -= 1
    while b < len(values) - 1 and ok[b + 1]:
        b += 1

    def edge(good: float, bad: float) -> float:
        while abs(bad - good) > tol:
            mid = 0.5 * (good + bad)
            good, bad = (mid, bad) if valid(mid) else (good, mid)
        return good

    low = float(values[a]) if a == 0 else edge(float(values[a]), float(values[a - 1]))
    high = float(values[b]) if b == len(values) - 1 else edge(float(values[b]), float(values[b + 1]))
    return low, high


def validate_params(params: QuasivertexParams, system_name: str = "penrose-p3") -> None:
    """Raise ParameterError naming a parameter when a deformed rhomb self-intersects.

    The named parameter is the one whose smallest change (others fixed, r measured in edge
    lengths and theta in half-turns) makes both rhombs simple again, with its valid range.
    """
    bad = _bad_tiles(params, system_name)
    if not bad:
        return
    noun = "rhomb" if system_name == "penrose-p3" else "tile"
    what = f"the {' and '.join(bad)} {noun}{'s' if len(bad) > 1 else ''}"
    runs = {name: _valid_run(params, name, system_name) for name in PARAM_NAMES}
    fixable = sorted((run[0], name, run[1], run[2]) for name, run in runs.items() if run is not None)
    if not fixable:
        raise ParameterError(
            f"quasivertex parameters {params.text()} make {what} self-intersect and no single "
            "parameter can fix it; start from e.g. r1=0.1, r2=0.2, theta1=theta2=0"
        )
    _, name, lo, hi = fixable[0]
    unit = "" if name.startswith("r") else " degrees"
    others = ", ".join(f"{n}={getattr(params, n):g}" for n in PARAM_NAMES if n != name)
    extra = ""
    if len(fixable) > 1:
        _, n2, lo2, hi2 = fixable[1]
        extra = f" (or keep {name} and set {n2} in [{lo2:.3g}, {hi2:.3g}])"
    raise ParameterError(
        f"quasivertex parameter {name}={getattr(params, name):g} makes {what} self-intersect: with "
        f"{others}, {name} must lie in about [{lo:.3g}, {hi:.3g}]{unit}{extra}"
    )


def resolve_shapes(shapes: Mapping[str, np.ndarray], system_name: str = "penrose-p3") -> dict[str, np.ndarray]:
    """Edge shapes per label a..h: a shape given on a label puts its complement on the partner."""
    pairs = _spec(system_name).partner
    out: dict[str, np.ndarray] = {}
    for name, pts in shapes.items():
        if name not in pairs:
            text = ", ".join(f"{a}/{pairs[a]}" for a in _spec(system_name).primary)
            raise ParameterError(
                f"edge shape {name!r} is not a quasivertex edge label; valid: {', '.join(sorted(pairs))} "
                f"(pairs {text} interlock)"
            )
        partner = pairs[name]
        if partner in shapes:
            raise ParameterError(
                f"edge shapes {name!r} and {partner!r} interlock (one is the other's complement); give only one"
            )
        out[name] = np.asarray(pts, dtype=float).reshape(-1, 2)
        out[partner] = complement(out[name])
    return out


def deformed_tiles(
    tiles: Sequence[Prototile],
    system_name: str,
    params: QuasivertexParams,
    shapes: Mapping[str, np.ndarray] | None = None,
) -> list[Prototile]:
    """The system's whole tiles replaced by the quasivertex tiles (in the system's frames).

    ``shapes`` maps edge labels (a..h) to polylines from (0,0) to (1,0) (interior points); a
    label's partner gets the complement. Raises ParameterError when the parameters or the
    shapes make a tile self-intersect.
    """
    check_system(tiles, system_name)
    validate_params(params, system_name)
    per_label = resolve_shapes(shapes or {}, system_name)
    outlines = system_outlines(params, system_name)
    noun = "rhomb" if system_name == "penrose-p3" else "tile"
    out = []
    for tile in tiles:
        pts, labels, _ = _merge(*outlines[tile.name])
        k = len(pts)
        outline: list[np.ndarray] = []
        corners: list[int] = []
        seg_labels: list[str] = []
        for i in range(k):
            corners.append(len(outline))
            outline.append(pts[i])
            seg_labels.append(labels[i])
            shape = per_label.get(labels[i])
            if shape is not None and len(shape):
                outline.extend(Affine.apply(Affine.segment_map(pts[i], pts[(i + 1) % k]), shape))
                seg_labels.extend([labels[i]] * len(shape))
        arr = np.array(outline)
        if not _simple(arr):
            culprits = sorted({lab for lab in labels if lab in per_label and len(per_label[lab])})
            raise ParameterError(
                f"edge shapes on {', '.join(culprits)} make the {tile.name} {noun} self-intersect "
                f"at {params.text()}; use smaller or different shapes"
            )
        out.append(Prototile(arr, edge_labels=tuple(seg_labels), name=tile.name, corners=tuple(corners)))
    return out


@dataclass
class MatchingReport:
    """Figure 6.14's matching rules on a patch of deformed rhombs: every edge between two
    consecutive quasivertices that two tiles share carries partner labels (a/g, b/e, c/d, f/h)
    and the same drawn polyline (one tile's edge is the other's reversed)."""

    edges: int  # tile edges (quasivertex to quasivertex) in the patch
    shared: int  # edges found in two tiles
    mislabelled: list[tuple[str, str]]  # label pairs of shared edges that are not partners
    misfit: float  # largest gap between the two drawn copies of a shared edge
    crowded: int  # edges drawn by more than two tiles
    tolerance: float

    @property
    def ok(self) -> bool:
        return not self.mislabelled and self.misfit <= self.tolerance and self.crowded == 0 and self.shared > 0

    def summary(self) -> str:
        if self.ok:
            return f"matching rules hold on {self.shared} shared edges of {self.edges}"
        parts = []
        if self.mislabelled:
            parts.append(f"{len(self.mislabelled)} shared edges with non-partner labels (e.g. {self.mislabelled[0]})")
        if self.misfit > self.tolerance:
            parts.append(f"shared edges drawn differently by up to {self.misfit:.3g}")
        if self.crowded:
            parts.append(f"{self.crowded} edges in more than two tiles")
        if not self.shared:
            parts.append("no shared edges")
        return "matching rules broken: " + "; ".join(parts)


def matching_report(patch: Any, decimals: int = 6) -> MatchingReport:
    """Check Figure 6.14's interlocking pairs on every shared edge of a patch of quasivertex
    tiles (prototiles with ``corners`` and per-segment ``edge_labels``, as
    :func:`deformed_tiles` makes them). Edges are matched by their end points (rounded to
    ``decimals``); each prototile's edges are placed for all its tiles in one batched map."""
    names = {p.name for p in patch.prototiles}
    pairs = next((s.partner for s in SPECS.values() if names <= set(s.tiles)), PARTNER)
    keys: list[np.ndarray] = []
    labels: list[np.ndarray] = []
    lines: list[np.ndarray] = []
    for p, proto in enumerate(patch.prototiles):
        maps = patch.transform[patch.prototile == p]
        if not len(maps) or not proto.corners:
            continue
        corners = list(proto.corners) + [len(proto.outline)]
        closed = np.vstack([proto.outline, proto.outline[:1]])
        for i in range(len(corners) - 1):
            seg = closed[corners[i] : corners[i + 1] + 1]
            world = Affine.apply(maps, seg) if maps.ndim == 3 else Affine.apply(maps[None], seg)
            ends = np.round(np.concatenate([world[:, 0], world[:, -1]], axis=1), decimals)
            forward = (ends[:, 0] < ends[:, 2]) | ((ends[:, 0] == ends[:, 2]) & (ends[:, 1] <= ends[:, 3]))
            key = np.where(forward[:, None], ends, ends[:, [2, 3, 0, 1]])
            keys.append(key)
            labels.append(np.full(len(maps), proto.edge_labels[corners[i]]))
            # every copy walked from its key's first end, so shared copies compare point by point
            lines.extend(w if f else w[::-1] for w, f in zip(world, forward))
    if not keys:
        return MatchingReport(0, 0, [], 0.0, 0, POINT_TOL)
    allkeys = np.concatenate(keys)
    alllabels = np.concatenate(labels)
    _, inverse, counts = np.unique(allkeys, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    order = np.argsort(inverse, kind="stable")
    starts = np.concatenate([[0], np.cumsum(counts)])
    mislabelled: list[tuple[str, str]] = []
    misfit = 0.0
    for g in np.flatnonzero(counts == 2):
        i, j = order[starts[g]], order[starts[g] + 1]
        la, lb = str(alllabels[i]), str(alllabels[j])
        if pairs.get(la) != lb:
            mislabelled.append((la, lb))
        a, b = lines[i], lines[j]
        misfit = max(misfit, float(np.abs(a - b).max()) if a.shape == b.shape else math.inf)
    return MatchingReport(len(allkeys), int(np.sum(counts == 2)), mislabelled, misfit, int(np.sum(counts > 2)),
                          POINT_TOL)
