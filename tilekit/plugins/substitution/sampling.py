"""Importance sampling by selective substitution (§7.4): one sample per tile, tiles substituted
only where the density asks for more samples.

``penrose`` follows Ostromoukhov, Donohue and Jodoin (SIGGRAPH 2004) on the Penrose rhombs'
Robinson triangles (``penrose-p3``); ``polyomino`` follows Ostromoukhov (SIGGRAPH 2007) with
the chair, the L-tromino 4-rep-tile (``chair``). Both run the shared level loop
(:func:`levels.refine_levels`) over the shipped systems; nothing here knows Penrose geometry.

A tile t carries its density integral I(t) (its area times the mean density over its bounding
box, from exact box integrals), the least integral A(t) of its ancestors, and a rank value v(t)
in (0, 1): the mixed-radix radical inverse of its path of child digits, the last step most
significant (v(child) = (r + v(parent)) / k for the r-th of k children in a farthest-first
order of the rule, cyclically shifted by a hash of the parent when the system has several
prototiles, so that digits do not follow labels), so siblings are ranked far apart and tiles
of one level have ranks spread evenly over (0, 1) — a hierarchical ordered dither. With threshold tau (the integral one sample
stands for) a tile is substituted while I > tau, and a tile that stops keeps its sample (its
centroid) when I / tau > v: a tile wanting a fraction of a sample gets it with that frequency,
so counts change smoothly with tau instead of in steps of s^2. Hence the point of t is in the
set exactly for tau in [I(t), min(A(t), I(t) / v(t))), the interval the sampler reports.

The correction step (both papers) moves each chosen sample by a vector looked up by its
structural context and its E = I / tau, from tables fitted once by Lloyd relaxation
(:func:`tilekit.sampling.train_corrections`, benchmarks/train_corrections.py) and shipped in
catalogue/substitution/sampling/.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np

from tilekit.geometry import Affine
from tilekit.limits import GENERATION_BYTES_PER_TILE, MAX_DEPTH, refuse_over_memory
from tilekit.plugins.substitution.levels import refine_levels
from tilekit.polygon import centroid, signed_area
from tilekit.resources import catalogue_dir

#: The shipped system each method substitutes.
SYSTEMS = {"penrose": "penrose-p3", "polyomino": "chair"}
#: Child indices of the last CONTEXT_LEVELS substitutions name a tile's structural context
#: (with its prototile), the key of the correction table. With scrambled digits (systems of
#: several prototiles) the pair (child index, rank digit) of the last SCRAMBLED_CONTEXT_LEVELS
#: substitutions does: which relatives are kept then depends on the digits too.
CONTEXT_LEVELS = 4
SCRAMBLED_CONTEXT_LEVELS = 3


def context_shape(labels: int, width: int) -> tuple[int, int, int]:
    """(base per level, levels, number of keys) of the context keys of a system with ``labels``
    prototiles and at most ``width`` children a rule."""
    if labels > 1:
        base, levels = width * width, SCRAMBLED_CONTEXT_LEVELS
    else:
        base, levels = width, CONTEXT_LEVELS
    return base, levels, labels * base**levels
#: Bins of E = I / tau (the fraction of a sample a leaf wants, in (0, 1]) in the correction table.
CORRECTION_BINS = 8

#: Levels below the covering supertile a refinement may go (a peaked density needs more
#: levels than a uniform one; the tiles per level are bounded by the integral, not the depth).
MAX_REFINE_LEVELS = MAX_DEPTH + 40


@lru_cache(maxsize=4)
def _prepared(system_name: str) -> tuple:
    """The system, each prototile's area and centroid, and each rule's farthest-first child order."""
    # start-up cost: the package's systems load NumPy and shapely; a sampler calls this when it runs
    from tilekit.plugins.substitution.builtin import builtin_systems

    system = builtin_systems()[system_name]
    areas = np.array([signed_area(p.outline) for p in system.prototiles])
    cents = np.array([centroid(p.outline) for p in system.prototiles])
    ranks = []
    for rule in system.rules:
        pts = np.array([Affine.apply(m, cents[c][None])[0] for c, m in zip(rule.children, rule.matrices)])
        order = [0]
        while len(order) < len(pts):
            d = np.min(np.linalg.norm(pts[:, None] - pts[order][None], axis=2), axis=1)
            d[order] = -1.0
            order.append(int(np.argmax(d)))
        rank = np.empty(len(pts), dtype=np.int64)
        rank[order] = np.arange(len(pts))
        ranks.append(rank)
    width = max(len(r) for r in ranks)
    rank_table = np.full((len(ranks), width), -1, dtype=np.int64)
    for i, r in enumerate(ranks):
        rank_table[i, : len(r)] = r
    sizes = np.array([len(r) for r in ranks], dtype=np.int64)
    most = max(len(p.outline) for p in system.prototiles)
    corners = np.array([np.vstack([p.outline, np.repeat(p.outline[-1:], most - len(p.outline), axis=0)])
                        for p in system.prototiles])
    return system, areas, cents, rank_table, sizes, corners


def root_tile(method: str, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A supertile covering the unit square: the system's covering seed for a box twice the
    square's size, turned about the square's centre by a random angle and shifted by up to half
    the square (``seed`` fixes both)."""
    # start-up cost: as in _prepared
    from tilekit.geometry import as_region
    from tilekit.plugins.substitution.builtin import builtin_systems
    from tilekit.plugins.substitution.tiling import tiling_from_spec

    tiling = tiling_from_spec({"system": SYSTEMS[method]}, builtin_systems())
    label, t, _ = tiling.seed_placement(as_region((-0.5, -0.5, 1.5, 1.5)))
    rng = np.random.default_rng(seed)
    angle = float(rng.uniform(0, 2 * np.pi))
    shift = rng.uniform(-0.5, 0.5, size=2)
    motion = Affine.translation(0.5 + shift[0], 0.5 + shift[1]) @ Affine.rotation(angle) @ Affine.translation(-0.5, -0.5)
    return np.array([label], dtype=np.int64), (motion @ t)[None]


def candidates(method: str, density, tau_lo: float, tau_hi: float, seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sample points whose threshold interval meets [tau_lo, tau_hi] (see the module
    docstring): ``(points (m, 2), lo (m,), hi (m,))``."""
    system, areas, cents, rank_table, sizes, corners = _prepared(SYSTEMS[method])
    # every level holds at most total / tau_lo substituted tiles (they are disjoint, each with
    # integral > tau_lo), so a level has at most max(k) times as many tiles
    refuse_over_memory("tiles in one level of the refinement", int(sizes.max()) * density.total / tau_lo,
                       2 * GENERATION_BYTES_PER_TILE, hint="ask for fewer samples")
    label, maps = root_tile(method, seed)
    out_p: list[np.ndarray] = []
    out_lo: list[np.ndarray] = []
    out_hi: list[np.ndarray] = []
    out_key: list[np.ndarray] = []
    out_frame: list[np.ndarray] = []
    width = rank_table.shape[1]
    # with several prototiles the rule order ties digits to labels (the acute triangle's first
    # child is always the acute one), so tiles of one label share rank ranges and the kept
    # fraction drifts with E; a hashed cyclic shift of each parent's digits removes that
    scramble = system.n > 1
    base, levels, _ = context_shape(system.n, width)

    def step(label: np.ndarray, maps: np.ndarray, carry: dict[str, np.ndarray], level: int) -> np.ndarray:
        if level == 0:
            v = np.full(len(label), 0.5)
            path = np.zeros(len(label), dtype=np.int64)
        else:
            k = sizes[carry["parent_label"]]
            digit = rank_table[carry["parent_label"], carry["child"]]
            if scramble:  # a hashed cyclic shift of the parent's digits: siblings stay apart
                digit = (digit + (carry["h"] % k.astype(np.uint64)).astype(np.int64)) % k
            v = (digit + carry["v"]) / k
            carry["h"] = _mix(carry["h"] ^ (carry["child"].astype(np.uint64) + np.uint64(1)) * _GOLDEN)
            step_key = carry["child"] * width + digit if scramble else carry["child"]
            path = (carry["path"] * base + step_key) % base**levels
        det = np.abs(maps[:, 0, 0] * maps[:, 1, 1] - maps[:, 0, 1] * maps[:, 1, 0])
        c = cents[label]
        x = maps[:, 0, 0] * c[:, 0] + maps[:, 0, 1] * c[:, 1] + maps[:, 0, 2]
        y = maps[:, 1, 0] * c[:, 0] + maps[:, 1, 1] * c[:, 1] + maps[:, 1, 2]
        integral = _tile_integral(density, maps, corners[label], det * areas[label])
        ancestors = carry["A"]
        with np.errstate(divide="ignore"):
            hi = np.minimum(ancestors, np.where(v > 0, integral / v, np.inf))
        keep = ((x >= 0) & (x <= 1) & (y >= 0) & (y <= 1) & (integral < hi)
                & (integral < tau_hi) & (hi > tau_lo))
        if keep.any():
            out_p.append(np.column_stack([x[keep], y[keep]]))
            out_lo.append(integral[keep])
            out_hi.append(hi[keep])
            out_key.append(label[keep] * base**levels + path[keep])
            out_frame.append(maps[keep, :2, :2])
        carry["v"] = v
        carry["path"] = path
        carry["A"] = np.minimum(ancestors, integral)
        return integral > tau_lo

    refine_levels(label, maps, [r.children for r in system.rules], [r.matrices for r in system.rules], step,
                  MAX_REFINE_LEVELS, carry={"A": np.full(1, np.inf), "v": np.full(1, 0.5),
                                            "path": np.zeros(1, dtype=np.int64),
                                            "h": _mix(np.full(1, seed, dtype=np.uint64) + _GOLDEN)})
    if not out_p:
        empty = {"key": np.zeros(0, dtype=np.int64), "frame": np.zeros((0, 2, 2)), "integral": np.zeros(0)}
        return np.zeros((0, 2)), np.zeros(0), np.zeros(0), empty
    lo = np.concatenate(out_lo)
    extra = {"key": np.concatenate(out_key), "frame": np.concatenate(out_frame), "integral": lo}
    return np.concatenate(out_p), lo, np.concatenate(out_hi), extra


_GOLDEN = np.uint64(0x9E3779B97F4A7C15)


def _mix(z: np.ndarray) -> np.ndarray:
    """The splitmix64 finaliser, vectorised (a bijection of 64-bit integers)."""
    with np.errstate(over="ignore"):
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        return z ^ (z >> np.uint64(31))


def _tile_integral(density, maps: np.ndarray, outline: np.ndarray, area: np.ndarray) -> np.ndarray:
    """The tile's area times the mean density over its bounding box (exact integrals of the
    box): close to the tile's integral for tiles small against the density's variation, and
    positive for every tile that meets the square where the density is, since the box holds
    the tile and, for an exact system, all its descendants."""
    px = maps[:, 0, 0, None] * outline[:, :, 0] + maps[:, 0, 1, None] * outline[:, :, 1] + maps[:, 0, 2, None]
    py = maps[:, 1, 0, None] * outline[:, :, 0] + maps[:, 1, 1, None] * outline[:, :, 1] + maps[:, 1, 2, None]
    x0, x1, y0, y1 = px.min(axis=1), px.max(axis=1), py.min(axis=1), py.max(axis=1)
    box = (x1 - x0) * (y1 - y0)
    return density.box_integral(x0, y0, x1, y1) * (area / box)


def correction_path(method: str) -> Path:
    """Where the shipped correction table of ``method`` is (catalogue/substitution/sampling/)."""
    return catalogue_dir() / "substitution" / "sampling" / f"{method}-corrections.csv"


@lru_cache(maxsize=4)
def correction_table(method: str) -> np.ndarray | None:
    """The shipped correction vectors of ``method``, (keys, CORRECTION_BINS, 2) in the prototile
    frame, or None when there is no table."""
    path = correction_path(method)
    if not path.is_file():
        return None
    _, _, _, rank_table, _, _ = _prepared(SYSTEMS[method])
    _, _, keys = context_shape(rank_table.shape[0], rank_table.shape[1])
    table = np.zeros((keys, CORRECTION_BINS, 2))
    rows = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    if len(rows):
        k, b = rows[:, 0].astype(np.int64), rows[:, 1].astype(np.int64)
        table[k, b] = rows[:, 2:4]
    return table


def energy_bin(integral: np.ndarray, tau: float) -> np.ndarray:
    """The bin of E = integral / tau in (0, 1] (leaves want at most one sample)."""
    e = np.clip(integral / tau, 0.0, 1.0)
    return np.minimum((e * CORRECTION_BINS).astype(np.int64), CORRECTION_BINS - 1)


def apply_corrections(method: str, points: np.ndarray, extra: dict, tau: float) -> np.ndarray:
    """Ostromoukhov et al.'s correction step: move each sample by the vector stored for its
    structural context (prototile and last child indices) and its bin of E, mapped from the
    prototile frame by the tile's linear map. Points are kept inside the unit square."""
    table = correction_table(method)
    if table is None or not len(points):
        return points
    delta = table[extra["key"], energy_bin(extra["integral"], tau)]
    moved = points + np.einsum("nij,nj->ni", extra["frame"], delta)
    return np.clip(moved, 0.0, 1.0)


def penrose_candidates(density, tau_lo: float, tau_hi: float, seed: int = 0):
    """:func:`candidates` on the Penrose rhombs' Robinson triangles (Ostromoukhov et al. 2004)."""
    return candidates("penrose", density, tau_lo, tau_hi, seed)


def polyomino_candidates(density, tau_lo: float, tau_hi: float, seed: int = 0):
    """:func:`candidates` on the chair, the L-tromino rep-tile (after Ostromoukhov 2007)."""
    return candidates("polyomino", density, tau_lo, tau_hi, seed)
