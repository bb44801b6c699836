"""The derivation of the kite and dart's quasivertex parameterization (see
:mod:`.quasivertex_p2`, whose module docstring states the method): it builds straight P2
patches with the substitution family, so it lives apart from the data module that the
family's tiling imports (no import circle); the tests and docs/families/substitution.md run it.
"""

from __future__ import annotations

import cmath
import itertools
import math
from dataclasses import dataclass

import numpy as np
import shapely

from tilekit.plugins.substitution import tiling as substitution_tiling
from tilekit.plugins.substitution.engine import _row_groups
from tilekit.plugins.substitution.quasivertex_p2 import BOOK_LABELS, SYSTEM, _outline
from tilekit.plugins.substitution.shapes import (
    EDGE_QUANTUM,
    InterlockClasses,
    canonical_transforms,
    edge_classes,
    edge_keys,
    halves_mirror,
)
from tilekit.tiling import Patch, Prototile


@dataclass
class Candidate:
    """One choice of cut corners and what its generic deformation gave."""

    cuts: dict[str, tuple[int, ...]]
    dimension: int  # real dimension of the spokes' null space
    simple: bool  # a member with simple tiles was found
    valid: bool = False  # its patch passed Patch.validate
    unpaired: int = 0  # pieces without exactly one reversed twin
    classes: int = 0  # interlocking piece classes found across the patch
    pieces: tuple[int, ...] = ()
    book: list[tuple[dict[str, str], dict[str, int]]] | None = None  # (pair renaming, start per tile)
    relations: list[tuple[int, int, float]] | None = None  # (unknown j, unknown i, degrees): z_j = turn * z_i


@dataclass
class Derivation:
    edges: dict[str, tuple[tuple[int, int], ...]]
    candidates: list[Candidate]

    @property
    def book(self) -> list[Candidate]:
        return [c for c in self.candidates if c.book]


def derive(radius: float = 6.0, max_cuts: int = 2, seed: int = 1) -> Derivation:
    """Search the cut choices (module docstring) on a P2 patch of about ``radius`` around the
    origin; every candidate is reported, those reproducing the book's labels with the renaming."""
    straight = substitution_tiling(SYSTEM)
    system = straight.system
    names = [t.name for t in system.tiles]
    classes = edge_classes(system)
    edges = {name: tuple(classes.label[p]) for p, name in enumerate(names)}
    corners = {name: tuple(complex(x, y) for x, y in np.asarray(system.tiles[p].outline, dtype=float))
               for p, name in enumerate(names)}
    nz = 2 * classes.count
    proto, tr = straight.raw(shapely.box(-radius, -radius, radius, radius))
    tr = canonical_transforms(proto, tr, halves_mirror(system))
    inner = shapely.box(-radius + 2, -radius + 2, radius - 2, radius - 2)
    rng = np.random.default_rng(seed)

    def unit_row(name: str, corner: int) -> np.ndarray:
        """The cut equation at ``corner``: incoming edge's last spoke point = outgoing's first."""
        row = np.zeros(nz, dtype=complex)
        k = len(corners[name])
        for i, end in (((corner - 1) % k, "last"), (corner, "first")):
            cls, sign = edges[name][i]
            a, b = corners[name][i], corners[name][(i + 1) % k]
            p, q = (a, b) if sign > 0 else (b, a)
            d = (q - p) / abs(q - p)
            # the first point of a +1 edge is P + d ks, of a -1 edge Q - d ke (and reversed for last)
            use_ks = (sign > 0) == (end == "first")
            coef = d if use_ks else -d
            var = 2 * cls + (0 if use_ks else 1)
            row[var] += coef if end == "first" else -coef
        return row

    def pieces_check(z: np.ndarray, cuts: dict[str, tuple[int, ...]]) -> tuple[bool, int, list[list[tuple[int, int]]]]:
        outs = [_outline(corners[n], edges[n], set(cuts[n]), tuple(z)) for n in names]
        protos = [Prototile(np.column_stack([o.real, o.imag]), name=n) for o, n in zip(outs, names)]
        patch = Patch(protos, proto, tr)
        valid = bool(patch.validate(inner))
        offsets = np.cumsum([0] + [len(o.outline) for o in protos])
        rows, runs, nodes = [], [], []
        for p, o in enumerate(protos):
            idx = np.flatnonzero(proto == p)
            if not len(idx):
                continue
            key, forward = edge_keys(o.outline, tr[idx])
            rows.append(key)
            runs.append(forward)
            nodes.append(offsets[p] + np.tile(np.arange(len(o.outline)), len(idx)))
        keys, forward, node = np.concatenate(rows), np.concatenate(runs), np.concatenate(nodes)
        _, (order, starts, sizes) = _row_groups(keys)
        classes = InterlockClasses(int(offsets[-1]))
        inside = (radius - 2) / EDGE_QUANTUM
        unpaired = 0
        for start, size in zip(starts, sizes):
            i = order[start]
            if size != 2 or forward[i] == forward[order[start + 1]]:
                # a piece on the patch's rim has no twin; inside, none may lack one
                unpaired += bool(np.all(np.abs(keys[i]) < inside))
                continue
            unpaired += not classes.union(int(node[i]), int(node[order[start + 1]]))
        numbered = classes.numbered()
        labels = [numbered[offsets[p] : offsets[p + 1]] for p in range(len(protos))]
        return valid, unpaired, labels

    def book_match(labels: list[list[tuple[int, int]]]) -> list[tuple[dict[str, str], dict[str, int]]]:
        ncls = 1 + max(c for row in labels for c, _ in row)
        pairs = [("a", "d"), ("b", "h"), ("c", "e"), ("f", "g")]
        if ncls != len(pairs):
            return []
        found = []
        for perm in itertools.permutations(range(ncls)):
            for flips in itertools.product((0, 1), repeat=ncls):
                starts = {}
                for name, row in zip(names, labels):
                    s = "".join(pairs[perm[c]][q ^ flips[c]] for c, q in row)
                    target = BOOK_LABELS[name]
                    hit = [k for k in range(len(s)) if len(s) == len(target) and s[k:] + s[:k] == target]
                    if not hit:
                        break
                    starts[name] = hit[0]
                else:
                    renaming = {f"class {c}" + ("" if q == 0 else "*"): pairs[perm[c]][q ^ flips[c]]
                                for c in range(ncls) for q in (0, 1)}
                    found.append((renaming, starts))
        return found

    per_tile = [()] + [tuple(c) for n in range(1, max_cuts + 1) for c in itertools.combinations(range(4), n)]
    out = []
    for ck, cd in itertools.product(per_tile, per_tile):
        cuts = {"kite": ck, "dart": cd}
        rows = [unit_row(n, c) for n in names for c in cuts[n]]
        if rows:
            _, sv, vh = np.linalg.svd(np.array(rows))
            null = vh[int(np.sum(sv > 1e-9)):].conj().T
        else:
            null = np.eye(nz, dtype=complex)
        cand = Candidate(cuts, 2 * null.shape[1], False)
        out.append(cand)
        if not null.shape[1]:
            continue
        for _ in range(30):  # a generic member with spokes of 0.03..0.4 roughly along their edges
            target = 0.15 * rng.uniform(0.5, 1.5, nz) * np.exp(1j * rng.normal(0, 0.4, nz))
            z = null @ np.linalg.lstsq(null, target, rcond=None)[0]
            if np.abs(z).max() > 0.4 or np.abs(z).min() < 0.02:
                continue
            try:
                valid, unpaired, labels = pieces_check(z, cuts)
            except Exception:  # noqa: BLE001 - a self-intersecting tile: try another member
                continue
            cand.simple, cand.valid, cand.unpaired = True, valid, unpaired
            cand.classes = 1 + max(c for row in labels for c, _ in row)
            cand.pieces = tuple(len(r) for r in labels)
            if valid and not unpaired:
                cand.book = book_match(labels) or None
            if cand.book:
                cand.relations = []
                for row in rows:
                    i, j = np.flatnonzero(np.abs(row) > 1e-9)
                    cand.relations.append((int(j), int(i), round(math.degrees(cmath.phase(-row[i] / row[j])), 6)))
            break
    return Derivation(edges, out)


def describe(derivation: Derivation) -> str:
    """A few lines: the candidates that reproduce the book and their spoke relations."""
    names = ("ks(long)", "ke(long)", "ks(short)", "ke(short)")
    lines = [f"edge classes (class, sign) per edge: {derivation.edges}"]
    for c in derivation.book:
        rel = "; ".join(f"{names[j]} = rot({d:g} deg) {names[i]}" for j, i, d in c.relations or [])
        lines.append(f"cuts {c.cuts}: null space of dimension {c.dimension}, pieces {c.pieces}, {rel}")
    return "\n".join(lines)

