"""The isohedral test of a polyform from its boundary word, after Langerman and Winslow.

S. Langerman and A. Winslow, "A quasilinear-time algorithm for tiling the plane isohedrally
with a polyomino", SoCG 2016 (LIPIcs 51, 50:1-50:15; arXiv:1507.02762). A polyomino tiles
the plane isohedrally exactly when its boundary word has one of seven factorisations:
translation (Beauquier-Nivat), half-turn (Conway's criterion), quarter-turn, and type-1 /
type-2 reflection and half-turn-reflection forms. Each is a *template* here (data): a cyclic
sequence of factors, each paired with a partner factor (or itself) by a kind of isometry
(T translation, C half-turn, Q quarter-turn, G glide reflection). One generic matcher
(numba, depth-first over factor lengths with pruning, O(1) factor comparisons from
precomputed extension tables) finds every factorisation of every template.

A factorisation found is then *built*: each factor's isometry maps the tile onto its
neighbour across that factor; the group they generate gives placements, its translations a
lattice (Hermite normal form), and the placements modulo the lattice the translational unit.
The tiling is accepted only if the unit's cells are distinct modulo the lattice and fill it
exactly (|unit cells| = lattice index), an exact integer proof that it tiles. The isohedral
type is read from the Heesch type of the nonempty factors, matched against the isohedral
family's table (``catalogue/isohedral/properties.tsv``).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from tilekit.jit import njit
from tilekit.lattice import SQUARE, Grid, _edge_tables, _trace, boundary_word, outline
from tilekit.resources import catalogue_dir
from tilekit.tiling import PeriodicTiling

# kinds of factor pairing: translation, half-turn, quarter-turn, glide reflection, and the
# third- and sixth-turns of the hexagonal and triangular grids (R3, R6)
T, C, Q, G, R3, R6 = 0, 1, 2, 3, 4, 5
KIND_LETTER = {T: "T", C: "C", Q: "C4", G: "G", R3: "C3", R6: "C6"}
#: The turn of each rotation kind as a fraction of a whole turn (its candidates are the grid's
#: rotations by plus or minus that angle; a grid without them cannot use the kind's templates).
KIND_TURN = {C: 2, Q: 4, R3: 3, R6: 6}

#: (name, factorisation family, partner of each factor, kind of each factor, glide rule):
#: glide rule 1 = all glide pairs share one reflection (parallel axes, pg), 2 = the second
#: pair's reflection is the first's turned by a half-turn (perpendicular axes, pgg).
TEMPLATES: tuple[tuple[str, str, tuple[int, ...], tuple[int, ...], int], ...] = (
    ("translation", "translation", (3, 4, 5, 0, 1, 2), (T, T, T, T, T, T), 0),
    ("halfturn", "halfturn", (3, 1, 2, 0, 4, 5), (T, C, C, T, C, C), 0),
    ("quarterturn", "quarterturn", (0, 2, 1, 4, 3), (C, Q, Q, Q, Q), 0),
    ("reflection-1", "reflection", (3, 2, 1, 0, 5, 4), (T, G, G, T, G, G), 1),
    ("reflection-2", "reflection", (3, 5, 4, 0, 2, 1), (T, G, G, T, G, G), 1),
    ("halfturn-reflection-1", "reflection", (3, 1, 2, 0, 5, 4), (T, C, C, T, G, G), 0),
    ("halfturn-reflection-2", "reflection", (0, 4, 2, 5, 1, 3), (C, G, C, G, G, G), 2),
    # the rotational types of the hexagonal point group (Heesch types C3C3C3C3C3C3 and
    # CC3C3C6C6, with their degenerate forms C3C3C3C3, CC3C3, CC6C6, C3C3C6C6): each pair of
    # adjacent factors is related by a turn about their common vertex. The boundary is read
    # counter-clockwise only, so CC3C3C6C6 needs both cyclic orders (a tile and its mirror image)
    ("threefold", "threefold", (1, 0, 3, 2, 5, 4), (R3, R3, R3, R3, R3, R3), 0),
    ("sixfold-1", "sixfold", (0, 2, 1, 4, 3), (C, R3, R3, R6, R6), 0),
    ("sixfold-2", "sixfold", (0, 2, 1, 4, 3), (C, R6, R6, R3, R3), 0),
)


@njit(cache=True)
def _tables(W, perm, neg, det):
    """Extension tables, one dynamic-programming pass per diagonal (O(G L^2)).

    ext[g, a, b]: consecutive k with perm[g][W[a+k]] == neg[W[b-k]] (g a rotation: the
    neighbour walks the factor backwards); fwd[g, a, b]: consecutive k with
    perm[g][W[a+k]] == W[b+k] (g a reflection: walked forwards). The matcher reads ext only
    for rotations and fwd only for reflections, so only those are filled. Both are capped
    at L (a whole diagonal that matches). mx[g, a]: the largest ext[g, a, .] (rotations) or
    fwd[g, a, .] (reflections): no factor at a longer than mx has a partner under g.
    """
    Gn = perm.shape[0]
    L = W.shape[0]
    # one array: the rotations' rows hold ext, the reflections' rows fwd (returned as both)
    ext = np.empty((Gn, L, L), np.int64)
    fwd = ext
    mx = np.zeros((Gn, L), np.int64)
    for g in range(Gn):
        rot = det[g] > 0
        for d in range(L):
            # the diagonal: a = 0..L-1 and b = d - a (ext) or b = a + d (fwd), cyclically
            a0 = -1
            for a in range(L):
                b = (d - a) % L if rot else (a + d) % L
                if perm[g, W[a]] != (neg[W[b]] if rot else W[b]):
                    a0 = a
                    break
            if a0 < 0:
                for a in range(L):
                    b = (d - a) % L if rot else (a + d) % L
                    if rot:
                        ext[g, a, b] = L
                    else:
                        fwd[g, a, b] = L
                continue
            run = 0
            for i in range(L):
                a = (a0 - i) % L
                b = (d - a) % L if rot else (a + d) % L
                if perm[g, W[a]] == (neg[W[b]] if rot else W[b]):
                    run += 1
                else:
                    run = 0
                if rot:
                    ext[g, a, b] = run
                else:
                    fwd[g, a, b] = run
        for a in range(L):
            m = 0
            for b in range(L):
                v = ext[g, a, b] if rot else fwd[g, a, b]
                if v > m:
                    m = v
            mx[g, a] = m
    return ext, fwd, mx


@njit(cache=True)
def _palindromes(ext, half, L):
    """pal[a, l]: W[a:a+l] (cyclic) is fixed by the half-turn; pl[a, :npal[a]]: those l, ascending."""
    pal = np.zeros((L, L + 1), np.bool_)
    pl = np.zeros((L, L + 1), np.int64)
    npal = np.zeros(L, np.int64)
    for a in range(L):
        for ln in range(L + 1):
            if ln == 0 or ext[half, a, (a + ln - 1) % L] >= ln:
                pal[a, ln] = True
                pl[a, npal[a]] = ln
                npal[a] += 1
    return pal, pl, npal


@njit(cache=True)
def _splits(pal, pl, npal, L):
    """sp[a, l]: a split point of W[a:a+l] (cyclic) into two palindromes, -1 if none.

    A split with an empty part is preferred (the simpler Heesch type), else the first; only
    the palindromic prefixes of W[a:] are tried.
    """
    sp = np.full((L, L + 1), -1, np.int64)
    for a in range(L):
        for ln in range(L + 1):
            if pal[a, ln]:
                sp[a, ln] = 0
                continue
            for j in range(1, npal[a]):
                m = pl[a, j]
                if m >= ln:
                    break
                if pal[(a + m) % L, ln - m]:
                    sp[a, ln] = m
                    break
    return sp


@njit(cache=True)
def _match(W, ext, fwd, sp, bound, pl, npal, det, partner, kind, cands, ncand, glide, mul, half, out, maxout, smax):
    """Every factorisation of the cyclic word W into the template (partner, kind).

    Depth-first over the factors' lengths with every comparison O(1) from the extension
    tables; two consecutive palindromes are one step through the split table ``sp``.
    ``bound[kind, a]``: the longest factor at a that any candidate isometry of the kind maps
    onto some factor (its partner's existence only gets harder with length), so the first
    factor of a pair stops growing there.
    out rows: [start, len_0..len_{k-1}, g_0..g_{k-1}]; returns the number found.
    """
    L = W.shape[0]
    k = partner.shape[0]
    lens = np.zeros(k, np.int64)
    gs = np.zeros(k, np.int64)
    pos = np.zeros(k + 1, np.int64)
    trial = np.zeros(k + 1, np.int64)
    # combined[f]: factor f and f+1 are both palindromes, taken together
    combined = np.zeros(k, np.int64)
    prevf = np.zeros(k + 1, np.int64)
    f = 0
    while f < k:
        if f + 1 < k and kind[f] == 1 and partner[f] == f and kind[f + 1] == 1 and partner[f + 1] == f + 1:
            combined[f] = 1
            prevf[f + 2] = f
            f += 2
        else:
            prevf[f + 1] = f
            f += 1
    # freeafter[f]: free (not forced) steps after factor f; when 0, f's length is forced by the total
    freeafter = np.zeros(k + 1, np.int64)
    for f in range(k):
        cnt = 0
        j = f + 2 if combined[f] == 1 else f + 1
        while j < k:
            if partner[j] >= j:
                cnt += 1
            j += 2 if combined[j] == 1 else 1
        freeafter[f] = cnt
    found = 0
    hg = cands[1, 0]
    for s in range(min(L, smax)):
        f = 0
        pos[0] = 0
        trial[0] = 0
        while f >= 0:
            if f == k:
                if pos[k] == L:
                    if found < maxout:
                        out[found, 0] = s
                        for i in range(k):
                            out[found, 1 + i] = lens[i]
                            out[found, 1 + k + i] = gs[i]
                    found += 1
                f = prevf[f] if f > 0 else -1
                continue
            p = partner[f]
            ok = False
            nf = f + 1
            target = -1
            if freeafter[f] == 0:
                known = 0
                mult = 1
                for j in range(f + 1, k):
                    if partner[j] < f:
                        known += lens[partner[j]]
                    elif partner[j] == f and j != f:
                        mult = 2
                rest = L - pos[f] - known
                if rest < 0 or rest % mult != 0:
                    target = -2
                else:
                    target = rest // mult
            if combined[f] == 1:
                nf = f + 2
                while target != -2:
                    ln = trial[f]
                    if target >= 0:
                        if ln > 0:
                            break
                        ln = target
                    if pos[f] + ln > L:
                        break
                    trial[f] += 1
                    a = (s + pos[f]) % L
                    m = sp[a, ln]
                    if m < 0:
                        continue
                    lens[f] = m
                    lens[f + 1] = ln - m
                    gs[f] = hg
                    gs[f + 1] = hg
                    pos[f + 1] = pos[f] + m
                    ok = True
                    break
            elif p < f:
                # forced length: check the relation once
                if trial[f] == 0:
                    trial[f] = 1
                    ln = lens[p]
                    if pos[f] + ln <= L:
                        a = (s + pos[p]) % L
                        bstart = (s + pos[f]) % L
                        g0 = -1
                        if kind[f] == 3 and glide > 0:
                            for i in range(f):
                                if kind[i] == 3 and partner[i] < i and lens[i] > 0:
                                    g0 = gs[i] if glide == 1 else mul[half, gs[i]]
                                    break
                        for ci in range(ncand[kind[f]]):
                            g = cands[kind[f], ci]
                            if g0 >= 0 and ln > 0 and g != g0:
                                continue
                            if ln == 0:
                                good = True
                            elif det[g] > 0:
                                good = ext[g, a, (bstart + ln - 1) % L] >= ln
                            else:
                                good = fwd[g, a, bstart] >= ln
                            if good:
                                lens[f] = ln
                                gs[f] = g
                                ok = True
                                break
            elif p == f and f == k - 1:
                if trial[f] == 0:
                    trial[f] = 1
                    ln = L - pos[f]
                    a = (s + pos[f]) % L
                    g = cands[kind[f], 0]
                    if ln == 0 or ext[g, a, (a + ln - 1) % L] >= ln:
                        lens[f] = ln
                        gs[f] = g
                        ok = True
            else:
                while target != -2:
                    if p == f and target < 0 and kind[f] == 1:
                        # a free palindrome: only the palindromic lengths at its start
                        a = (s + pos[f]) % L
                        j = trial[f]
                        if j >= npal[a] or pos[f] + pl[a, j] > L:
                            break
                        trial[f] = j + 1
                        lens[f] = pl[a, j]
                        gs[f] = cands[1, 0]
                        ok = True
                        break
                    ln = trial[f]
                    if target >= 0:
                        if ln > 0:
                            break
                        ln = target
                    need = ln if p == f else 2 * ln
                    if pos[f] + need > L:
                        break
                    trial[f] = ln + 1 if target < 0 else 1
                    if p > f and ln > bound[kind[f], (s + pos[f]) % L]:
                        break
                    if p == f:
                        a = (s + pos[f]) % L
                        g = cands[kind[f], 0]
                        if ln > 0 and ext[g, a, (a + ln - 1) % L] < ln:
                            continue
                        gs[f] = g
                    else:
                        gs[f] = -1
                    lens[f] = ln
                    ok = True
                    break
            if ok:
                pos[nf] = pos[f] + lens[f] + (lens[f + 1] if nf == f + 2 else 0)
                if pos[nf] > L:
                    continue
                f = nf
                if f < k:
                    trial[f] = 0
            else:
                f = prevf[f] if f > 0 else -1
    return found


@njit(cache=True)
def _word_tables(W, perm, neg, det, cands, ncand, half):
    """ext, fwd, the palindrome splits and the per-kind length bounds of one word."""
    L = W.shape[0]
    ext, fwd, mx = _tables(W, perm, neg, det)
    pal, pl, npal = _palindromes(ext, half, L)
    sp = _splits(pal, pl, npal, L)
    bound = np.zeros((cands.shape[0], L), np.int64)
    for kd in range(cands.shape[0]):
        for a in range(L):
            m = 0
            for ci in range(ncand[kd]):
                v = mx[cands[kd, ci], a]
                if v > m:
                    m = v
            bound[kd, a] = m
    return ext, fwd, sp, bound, pl, npal


@njit(cache=True)
def _match_all(W, perm, neg, det, cands, ncand, mul, half, partners, kinds, ks, glides, smaxdiv, out, maxout, found):
    """Every template at once: tables and splits computed once, one compiled call per word."""
    ext, fwd, sp, bound, pl, npal = _word_tables(W, perm, neg, det, cands, ncand, half)
    for t in range(partners.shape[0]):
        k = ks[t]
        smax = W.shape[0] // smaxdiv[t]
        found[t] = _match(W, ext, fwd, sp, bound, pl, npal, det, partners[t, :k], kinds[t, :k], cands, ncand, glides[t],
                          mul, half, out[t], maxout, smax)


@njit(cache=True)
def _match_batch(cells, offs, types, ea, eb, en, el, period, perm, neg, det, cands, ncand, mul, half,
                 partners, kinds, ks, glides, smaxdiv, maxout, words, wlen, rows):
    """Boundary words and deduplicated matches of many hole-free polyforms in one compiled call.

    Polyform i is cells[offs[i]:offs[i+1]]; its word goes to words[i, :wlen[i]] (wlen -1: not
    one simple cycle). For every template, of all its matches (``maxout`` is the first
    buffer's size; a template with more is matched again into a larger one) those with at
    least three nonempty factors are kept,
    the first of each pattern of nonempty factors: rows [i, template, mask, start, len_0..].
    Returns the number of rows (which may exceed the buffer: then call again, larger).
    """
    npoly = offs.shape[0] - 1
    cap = rows.shape[0]
    out = np.zeros((maxout, 13), np.int64)
    seen = np.zeros(1 << partners.shape[1], np.int64)
    stamp = 0
    nr = 0
    for i in range(npoly):
        c = cells[offs[i]:offs[i + 1]]
        n = c.shape[0]
        out_v = np.zeros((8 * n + 8, 2), np.int64)
        out_l = np.zeros(8 * n + 8, np.int64)
        m = _trace(c, types[offs[i]:offs[i + 1]], ea, eb, en, el, period, out_v, out_l)
        wlen[i] = m
        if m <= 0:
            continue
        W = out_l[:m].copy()
        words[i, :m] = W
        ext, fwd, sp, bound, pl, npal = _word_tables(W, perm, neg, det, cands, ncand, half)
        for t in range(partners.shape[0]):
            k = ks[t]
            found = _match(W, ext, fwd, sp, bound, pl, npal, det, partners[t, :k], kinds[t, :k], cands, ncand, glides[t],
                           mul, half, out, out.shape[0], m // smaxdiv[t])
            if found > out.shape[0]:
                # more matches than the buffer holds: again with room for all (none is dropped)
                out = np.zeros((found, 13), np.int64)
                found = _match(W, ext, fwd, sp, bound, pl, npal, det, partners[t, :k], kinds[t, :k], cands, ncand,
                               glides[t], mul, half, out, found, m // smaxdiv[t])
            stamp += 1
            for r in range(found):
                mask = 0
                cnt = 0
                for j in range(k):
                    if out[r, 1 + j] > 0:
                        mask |= 1 << j
                        cnt += 1
                if cnt < 3 or seen[mask] == stamp:
                    continue
                seen[mask] = stamp
                if nr < cap:
                    rows[nr, 0] = i
                    rows[nr, 1] = t
                    rows[nr, 2] = mask
                    rows[nr, 3] = out[r, 0]
                    for j in range(k):
                        rows[nr, 4 + j] = out[r, 1 + j]
                nr += 1
    return nr


@dataclass
class Factorisation:
    template: str
    family: str
    start: int
    lengths: tuple[int, ...]
    maps: tuple[int, ...]  # group element of each factor (for the second of a pair / self)
    partner: tuple[int, ...]
    kind: tuple[int, ...]

    def signature(self) -> list[str]:
        labels: dict[int, str] = {}
        out = []
        gn = 0
        for i, (ln, kd) in enumerate(zip(self.lengths, self.kind)):
            if ln == 0:
                continue
            if kd == G:
                root = min(i, self.partner[i])
                if root not in labels:
                    gn += 1
                    labels[root] = str(gn)
                out.append("G" + labels[root])
            else:
                out.append(KIND_LETTER[kd])
        return out

    def to_json(self) -> dict:
        return {"template": self.template, "start": self.start, "lengths": list(self.lengths),
                "heesch": "".join(self.signature())}


@lru_cache(maxsize=8)
def _cands(grid: Grid) -> tuple[np.ndarray, np.ndarray]:
    """Per kind, the point-group elements a factor pair of that kind may use (the rotations
    by the kind's turn either way, every reflection for a glide), from the grid's own group:
    a grid's turn set decides which templates apply to it."""
    r = grid.rotation_order
    kinds: dict[int, list[int]] = {T: [0], G: list(range(r, 2 * r))}
    for kd, q in KIND_TURN.items():
        kinds[kd] = sorted({r // q, r - r // q}) if r % q == 0 else []
    cands = np.zeros((len(KIND_LETTER), 2 * r), np.int64)
    ncand = np.zeros(len(KIND_LETTER), np.int64)
    for kd, lst in kinds.items():
        cands[kd, :len(lst)] = lst
        ncand[kd] = len(lst)
    return cands, ncand


def _matches(grid: Grid, letters: np.ndarray, maxout: int = 256) -> tuple[np.ndarray, np.ndarray]:
    """Every match of every usable template (:func:`_match_all`): ``out[t, :found[t]]`` rows
    [start, len_0..len_{k-1}, g_0..g_{k-1}] of template t."""
    W = np.asarray(letters, dtype=np.int64)
    partners, kinds, ks, glides, smaxdiv, usable = _template_arrays(grid)
    cands, ncand = _cands(grid)
    mul = _mul_array(grid)
    half = grid.rotation_order // 2
    out = np.zeros((len(ks), maxout, 13), np.int64)
    found = np.zeros(len(ks), np.int64)
    _match_all(W, grid.letter_perm, grid.neg, grid.det, cands, ncand, mul, half, partners, kinds, ks,
               glides, smaxdiv, out, maxout, found)
    if found.max() > maxout:
        # more matches than the buffer holds: again with room for all (none is dropped)
        maxout = int(found.max())
        out = np.zeros((len(ks), maxout, 13), np.int64)
        found[:] = 0
        _match_all(W, grid.letter_perm, grid.neg, grid.det, cands, ncand, mul, half, partners, kinds, ks,
                   glides, smaxdiv, out, maxout, found)
    return out, found


def factorisations(grid: Grid, letters: np.ndarray, maxout: int = 256, dedupe: bool = False) -> list[Factorisation]:
    """Every match of every template (``dedupe``: one per pattern of nonempty factors)."""
    tabs = _template_arrays(grid)
    if tabs is None:
        return []
    usable = tabs[5]
    out, found = _matches(grid, letters, maxout)
    maxout = out.shape[1]
    res: list[Factorisation] = []
    for t, (name, fam, partner, kind, _glide) in enumerate(usable):
        k = len(partner)
        rows = out[t, :min(int(found[t]), maxout), :1 + 2 * k]
        if not len(rows):
            continue
        nonempty = rows[:, 1:1 + k] > 0
        keep = nonempty.sum(axis=1) >= 3
        rows, nonempty = rows[keep], nonempty[keep]
        if dedupe and len(rows):
            # one factorisation per pattern of nonempty factors (the Heesch type depends on nothing else)
            masks = (nonempty * (1 << np.arange(k))).sum(axis=1).tolist()
            first: dict[int, int] = {}
            for i, mk in enumerate(masks):
                first.setdefault(mk, i)
            rows = rows[sorted(first.values())]
        for row in rows.tolist():
            res.append(Factorisation(name, fam, row[0], tuple(row[1:1 + k]), tuple(row[1 + k:]), partner, kind))
    return res


@lru_cache(maxsize=8)
def _mul_array(grid: Grid) -> np.ndarray:
    return np.array(_group_mul(grid), dtype=np.int64)


_BY_NAME = {t[0]: t for t in TEMPLATES}


@lru_cache(maxsize=4096)
def _pattern(name: str, mask: int) -> tuple[tuple[str, ...], str, int | None]:
    """(canonical Heesch type, its letters, IH number) of a match of a template whose nonempty
    factors are ``mask``: the Heesch type depends on nothing else."""
    _, fam, partner, kind, _ = _BY_NAME[name]
    k = len(partner)
    f = Factorisation(name, fam, 0, tuple(mask >> i & 1 for i in range(k)), (0,) * k, partner, kind)
    sig = tuple(f.signature())
    return _canon_sig_cached(sig), "".join(sig), ih_type(f)


def _verdict(fams: dict, found: list[dict], tilings: list, boundary: np.ndarray) -> dict:
    """The result of :func:`analyse` (and of :func:`analyse_many`, each form) from its family
    flags, the factorisations kept and the tilings built."""
    return {**fams, "isohedral": bool(found), "ih_types": sorted({d["ih"] for d in found if d["ih"] is not None}),
            "factorisations": found, "tilings": tilings, "boundary": boundary}


def analyse_many(grid: Grid, polys: list[np.ndarray], maxout: int = 256) -> list[dict]:
    """``analyse(grid, cells, construct=False)`` of many hole-free polyforms, equal result by result.

    The boundary words and the matches of every template are one compiled call for the whole
    list (:func:`_match_batch`, which keeps only the first match of each pattern of nonempty
    factors, as ``factorisations(..., dedupe=True)`` does); Python then only turns the few
    kept matches per polyform into the verdict and its JSON-ready factorisations.
    """
    tabs = _template_arrays(grid)
    if tabs is None or not polys or any(t[0] not in sound(grid) for t in tabs[5]):
        return [analyse(grid, p, construct=False) for p in polys]
    partners, kinds, ks, glides, smaxdiv, usable = tabs
    cands, ncand = _cands(grid)
    sizes = np.array([len(p) for p in polys], dtype=np.int64)
    offs = np.zeros(len(polys) + 1, np.int64)
    np.cumsum(sizes, out=offs[1:])
    cells = np.ascontiguousarray(np.concatenate(polys).astype(np.int64))
    ea, eb, en, el = _edge_tables(grid)
    words = np.zeros((len(polys), 8 * int(sizes.max()) + 8), np.int64)
    wlen = np.zeros(len(polys), np.int64)
    width = 4 + partners.shape[1]
    rows = np.zeros((8 * len(polys) + 64, width), np.int64)
    args = (cells, offs, grid.cell_type(cells), ea, eb, en, el, np.int64(grid.period), grid.letter_perm, grid.neg,
            grid.det, cands, ncand, _mul_array(grid), grid.rotation_order // 2, partners, kinds, ks, glides, smaxdiv,
            maxout, words, wlen)
    nr = _match_batch(*args, rows)
    if nr > len(rows):
        rows = np.zeros((nr, width), np.int64)
        nr = _match_batch(*args, rows)
    rows = rows[:nr]
    starts = np.searchsorted(rows[:, 0], np.arange(len(polys) + 1)).tolist()
    rl = rows.tolist()
    names = [t[0] for t in usable]
    fams_of = [t[1] for t in usable]
    klen = ks.tolist()
    out: list[dict] = []
    for i, p in enumerate(polys):
        m = int(wlen[i])
        if m <= 0:
            out.append(analyse(grid, p, construct=False))
            continue
        fams = dict.fromkeys(FAMILIES, False)
        found: list[dict] = []
        done: set[tuple] = set()
        for r in rl[starts[i]:starts[i + 1]]:
            t = r[1]
            sig, letters, ih = _pattern(names[t], r[2])
            if sig in done:
                continue
            done.add(sig)
            fams[_family(fams_of[t], letters)] = True
            found.append({"template": names[t], "start": r[3], "lengths": r[4:4 + klen[t]], "heesch": letters,
                          "ih": ih})
        out.append(_verdict(fams, found, [], words[i, :m].copy()))
    return out


@lru_cache(maxsize=8)
def _template_arrays(grid: Grid):
    """The templates usable on a grid, packed into arrays for the compiled matcher."""
    _, ncand = _cands(grid)
    usable = [t for t in TEMPLATES if all(ncand[kd] > 0 for kd in t[3])]
    if not usable:
        return None
    n = len(usable)
    partners = np.zeros((n, 6), np.int64)
    kinds = np.zeros((n, 6), np.int64)
    ks = np.zeros(n, np.int64)
    glides = np.zeros(n, np.int64)
    smaxdiv = np.ones(n, np.int64)
    for i, (name, _fam, partner, kind, glide) in enumerate(usable):
        k = len(partner)
        partners[i, :k] = partner
        kinds[i, :k] = kind
        ks[i] = k
        glides[i] = glide
        # A B C Â B̂ Ĉ read from Â is the same factorisation: starts in the first half suffice
        smaxdiv[i] = 2 if name == "translation" else 1
    return partners, kinds, ks, glides, smaxdiv, tuple(usable)


# --------------------------------------------------------------------------- IH types

@lru_cache(maxsize=1)
def heesch_table() -> dict[tuple[str, ...], int]:
    """Canonical Heesch-type letter sequences -> IH number (from the isohedral family's data)."""

    out: dict[tuple[str, ...], int] = {}
    path = catalogue_dir() / "isohedral" / "properties.tsv"
    for line in path.read_text().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        parts = line.split("\t")
        ih, heesch = int(parts[0]), parts[4].strip()
        if heesch in ("-", ""):
            continue
        out.setdefault(_canon_sig(_split(heesch)), ih)
    return out


def ih_groups() -> dict[int, str]:
    out = {}
    for line in (catalogue_dir() / "isohedral" / "properties.tsv").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            parts = line.split("\t")
            out[int(parts[0])] = parts[2]
    return out


def _split(heesch: str) -> list[str]:
    out, i = [], 0
    while i < len(heesch):
        j = i + 1
        while j < len(heesch) and heesch[j].isdigit():
            j += 1
        out.append(heesch[i:j])
        i = j
    return out


def _relabel(seq: list[str]) -> tuple[str, ...]:
    names: dict[str, str] = {}
    out = []
    for s in seq:
        if s.startswith("G"):
            if s not in names:
                names[s] = "G" + str(len(names) + 1)
            out.append(names[s])
        else:
            out.append(s)
    # a single glide pair is written plain G
    if len(names) == 1:
        out = ["G" if s.startswith("G") else s for s in out]
    return tuple(out)


@lru_cache(maxsize=4096)
def _canon_sig_cached(seq: tuple[str, ...]) -> tuple[str, ...]:
    return _canon_sig(list(seq))


def _canon_sig(seq: list[str]) -> tuple[str, ...]:
    n = len(seq)
    cands = []
    for s in (seq, seq[::-1]):
        for i in range(n):
            cands.append(_relabel(s[i:] + s[:i]))
    return min(cands)


def ih_type(f: Factorisation) -> int | None:
    return heesch_table().get(_canon_sig_cached(tuple(f.signature())))


# --------------------------------------------------------------------------- construction

def _hnf_add(basis: tuple[int, int, int] | None, v: tuple[int, int]) -> tuple[int, int, int]:
    """Insert integer vector v into a 2D lattice basis in Hermite normal form (a, b, d):
    rows (a, b) and (0, d), a >= 0, d >= 0, 0 <= b < d when d > 0 (:func:`_hnf_step`)."""
    a, b, d = basis or (0, 0, 0)
    return _hnf_step(a, b, d, int(v[0]), int(v[1]))


@njit(cache=True)
def _gcd(x, y):
    x, y = abs(x), abs(y)
    while y:
        x, y = y, x % y
    return x


@njit(cache=True)
def _hnf_step(a, b, d, vx, vy):
    """The basis (a, b), (0, d) in Hermite normal form with the vector (vx, vy) added: the x
    components combined by the extended gcd, the combination with x component 0 folded into d."""
    if vx != 0 or a != 0:
        g, q0, x0, y0, x1, y1 = a, vx, 1, 0, 0, 1  # the extended gcd of a and vx
        while q0:
            k = g // q0
            g, q0 = q0, g - k * q0
            x0, x1 = x1, x0 - k * x1
            y0, y1 = y1, y0 - k * y1
        if g < 0:
            g, x0, y0 = -g, -x0, -y0
        wy = (vx // g) * b - (a // g) * vy  # the combination with x component 0
        a, b = x0 * a + y0 * vx, x0 * b + y0 * vy
        d = _gcd(d, wy)
    else:
        d = _gcd(d, vy)
    if a < 0:
        a, b = -a, -b
    if d:
        b %= d
    return a, b, d


@dataclass
class BuiltTiling:
    factorisation: Factorisation
    ih: int | None
    unit: list[tuple[np.ndarray, np.ndarray]]  # (M 2x2, t) fine-coordinate placements
    lattice: np.ndarray  # (2, 2) rows: fine-coordinate translation vectors


@njit(cache=True)
def _group_closure(gens, group, mul, depth_first):
    """The group generated by the grid symmetries ``gens`` (rows (element, tx, ty): x -> G x + t)
    modulo its translations: ``reps`` (one row (element, tx, ty) per linear part, in the order
    found; the identity first) and the translation lattice (a, b, d) in Hermite normal form, from
    Schreier's generators r e rep(r e)^-1. Coset enumeration: each representative found is
    multiplied by every generator, the representatives taken first in first out (breadth first)
    or, with ``depth_first``, last in first out; a = 0 or d = 0: no lattice of rank 2."""
    G = group.shape[0]
    ng = gens.shape[0]
    reps = np.zeros((G, 3), np.int64)  # the identity first
    at = np.full(G, -1, np.int64)
    at[0] = 0
    nr = 1
    todo = np.zeros(G, np.int64)
    head, top = 0, 1
    while head < top:
        if depth_first:
            top -= 1
            r = todo[top]
        else:
            r = todo[head]
            head += 1
        m, tx, ty = reps[r, 0], reps[r, 1], reps[r, 2]
        for i in range(ng):
            m2 = mul[m, gens[i, 0]]
            if at[m2] < 0:
                at[m2] = nr
                reps[nr, 0] = m2
                reps[nr, 1] = group[m, 0, 0] * gens[i, 1] + group[m, 0, 1] * gens[i, 2] + tx
                reps[nr, 2] = group[m, 1, 0] * gens[i, 1] + group[m, 1, 1] * gens[i, 2] + ty
                todo[top] = nr
                top += 1
                nr += 1
    a = b = d = 0
    for r in range(nr):
        m = reps[r, 0]
        for i in range(ng):
            w = at[mul[m, gens[i, 0]]]
            x = group[m, 0, 0] * gens[i, 1] + group[m, 0, 1] * gens[i, 2] + reps[r, 1] - reps[w, 1]
            y = group[m, 1, 0] * gens[i, 1] + group[m, 1, 1] * gens[i, 2] + reps[r, 2] - reps[w, 2]
            if x or y:
                a, b, d = _hnf_step(a, b, d, x, y)
    return reps[:nr].copy(), a, b, d


@njit(cache=True)
def _build(cells, verts, start, lengths, maps, partner, group, det, mul, inv, period, nroots):
    """:func:`build` in integers, one compiled call: (a, b, d, unit) with the lattice rows (a, b),
    (0, d) and ``unit`` the indices into ``reps`` of the unit's placements, ``reps`` rows
    (group element, tx, ty) in the order found; a = 0 when the factorisation gives no tiling.

    The generators: the isometry (group element, translation) taking the tile to its neighbour
    across each factor (both ways for a pair). Then the group they generate (:func:`_group_closure`,
    breadth first) and the proof: the representatives' images
    of the tile modulo the lattice are equal or disjoint, and as many cells as the lattice's
    fundamental domain holds."""
    L = verts.shape[0]
    k = lengths.shape[0]
    none = (0, 0, 0, np.zeros(0, np.int64), np.zeros((0, 3), np.int64))
    gens = np.zeros((2 * k, 3), np.int64)
    ng = 0
    pos = start
    starts = np.zeros(k, np.int64)
    for i in range(k):
        starts[i] = pos
        pos += lengths[i]
    for i in range(k):
        ln = lengths[i]
        j = partner[i]
        if ln == 0 or j > i:
            continue
        g = maps[i]
        sj = starts[j] % L
        e = (starts[i] + ln) % L if det[g] > 0 else starts[i] % L
        tx = verts[e, 0] - (group[g, 0, 0] * verts[sj, 0] + group[g, 0, 1] * verts[sj, 1])
        ty = verts[e, 1] - (group[g, 1, 0] * verts[sj, 0] + group[g, 1, 1] * verts[sj, 1])
        gens[ng, 0], gens[ng, 1], gens[ng, 2] = g, tx, ty
        ng += 1
        if j != i:
            gi = inv[g]
            gens[ng, 0] = gi
            gens[ng, 1] = -(group[gi, 0, 0] * tx + group[gi, 0, 1] * ty)
            gens[ng, 2] = -(group[gi, 1, 0] * tx + group[gi, 1, 1] * ty)
            ng += 1
    for i in range(ng):
        # a copy off the grid (e.g. a half-Cairo triangle turned about an edge's midpoint):
        # not a tiling by copies on the grid, the question the coronas and tori answer
        if gens[i, 1] % period or gens[i, 2] % period:
            return none
    reps, a, b, d = _group_closure(gens[:ng], group, mul, False)
    if a == 0 or d == 0:
        return none
    n = cells.shape[0]
    nr = reps.shape[0]
    keys = np.zeros((nr, n), np.int64)
    unit = np.zeros(nr, np.int64)
    nu = 0
    for r in range(nr):
        m = reps[r, 0]
        for c in range(n):
            x = group[m, 0, 0] * cells[c, 0] + group[m, 0, 1] * cells[c, 1] + reps[r, 1]
            y = group[m, 1, 0] * cells[c, 0] + group[m, 1, 1] * cells[c, 1] + reps[r, 2]
            # modulo the lattice rows (a, b), (0, d): first x into [0, a), then y into [0, d)
            q = x // a
            keys[nu, c] = (x - q * a) * d + (y - q * b) % d
        keys[nu].sort()
        same = False
        for u in range(nu):
            if (keys[u] == keys[nu]).all():
                same = True  # the same tile again: an element of the tile's own stabiliser
                break
        if not same:
            unit[nu] = r
            nu += 1
    flat = np.sort(keys[:nu].ravel())
    for i in range(1, flat.shape[0]):
        if flat[i] == flat[i - 1]:
            return none  # two copies (or one copy and itself) overlap modulo the lattice
    # a fundamental domain of the grid's translations (area period^2) holds one cell per type
    if nu * n * period * period != a * d * nroots:
        return none
    return a, b, d, unit[:nu].copy(), reps


@lru_cache(maxsize=8)
def _group_inverse(grid: Grid) -> tuple[int, ...]:
    out = []
    for m in grid.group:
        mi = np.round(np.linalg.inv(m)).astype(np.int64)
        out.append(int(np.nonzero((grid.group == mi).all(axis=(1, 2)))[0][0]))
    return tuple(out)


@lru_cache(maxsize=8)
def _group_mul(grid: Grid) -> tuple[tuple[int, ...], ...]:
    G = grid.group
    return tuple(tuple(int(np.nonzero((G == G[a] @ G[b]).all(axis=(1, 2)))[0][0]) for b in range(len(G)))
                 for a in range(len(G)))


def build(grid: Grid, cells: np.ndarray, verts: np.ndarray, f: Factorisation,
          ih: int | None | bool = False) -> BuiltTiling | None:
    """The tiling of a factorisation, proved exact in integers, or None if it does not tile
    with copies on the grid (every generator a symmetry of the grid, :meth:`Grid.is_translation`):
    :func:`_build`. ``ih``: the factorisation's IH type when the caller has it (False: look it up)."""
    a, b, d, unit, reps = _build(np.asarray(cells, dtype=np.int64), np.asarray(verts, dtype=np.int64), f.start,
                                 np.asarray(f.lengths, dtype=np.int64), np.asarray(f.maps, dtype=np.int64),
                                 np.asarray(f.partner, dtype=np.int64), grid.group, grid.det, _mul_array(grid),
                                 _inv_array(grid), grid.period, len(grid.roots))
    if a == 0:
        return None
    G = grid.group
    placed = [(G[m].copy(), np.array([tx, ty], dtype=np.int64)) for m, tx, ty in reps[unit].tolist()]
    return BuiltTiling(f, ih_type(f) if ih is False else ih, placed, np.array([[a, b], [0, d]], dtype=np.int64))


@lru_cache(maxsize=8)
def _inv_array(grid: Grid) -> np.ndarray:
    return np.array(_group_inverse(grid), dtype=np.int64)


#: The family flags of an analysis (``quarterturn`` on the square grid; ``threefold`` and
#: ``sixfold`` on the hexagonal and triangular ones).
FAMILIES = ("translation", "halfturn", "quarterturn", "reflection", "threefold", "sixfold")


def _family(template_family: str, letters: str) -> str:
    """The family flag a match sets. A halfturn-reflection-1 match whose glide factors are
    both empty has Heesch letters without G: it is a half-turn tiling (the same Heesch type as
    a match of the half-turn template), not one with reflections, so it sets ``halfturn``; a
    sixfold match without C6 letters has only three-fold centres (CC3C3), so ``threefold``."""
    if template_family == "reflection" and "G" not in letters:
        return "halfturn"
    if template_family == "sixfold" and "C6" not in letters:
        return "threefold"
    return template_family


#: Templates whose every match tiles on the square grid: Langerman-Winslow's theorem for
#: their forms, and the tests build every match of every polyomino up to 8 cells and prove each
#: tiling exact.
SOUND = frozenset(t[0] for t in TEMPLATES if t[1] not in ("threefold", "sixfold"))


def sound(grid: Grid) -> frozenset[str]:
    """The templates whose matches are taken as tilings without building them: Langerman and
    Winslow's theorem is for polyominoes, so on every other grid each match is built and proved
    exact (:func:`build`) before it counts."""
    return SOUND if grid.name == SQUARE.name else frozenset()


def analyse(grid: Grid, cells: np.ndarray, *, construct: bool = True, build_all: bool = False) -> dict:
    """Factorisations, verdict, IH types and (with ``construct``) built tilings of a hole-free polyform.

    Without ``construct`` (the bulk enumeration), matches of the sound templates are taken
    as proved by the theorem and only the others are built; with it, one tiling per Heesch
    type is built and proved exact (``build_all``: every match).
    """
    verts, letters = boundary_word(grid, cells)
    trusted = sound(grid)
    if not trusted and _template_arrays(grid) is not None:
        return _analyse_built(grid, cells, verts, letters, build_all)
    # where matches are built, a match that fails to build must not hide another of its pattern
    facts = factorisations(grid, letters, dedupe=not build_all and bool(trusted))
    fams = dict.fromkeys(FAMILIES, False)
    tilings: list[BuiltTiling] = []
    found: list[dict] = []
    sigs_done: set[tuple] = set()
    for f in facts:
        # the Heesch type depends only on which factors are nonempty (:func:`_pattern`)
        sig, heesch, ih = _pattern(f.template, sum(1 << i for i, ln in enumerate(f.lengths) if ln))
        if sig in sigs_done and not build_all:
            continue
        if construct or f.template not in trusted:
            bt = build(grid, cells, verts, f, ih)
            if bt is None:
                continue
            tilings.append(bt)
        sigs_done.add(sig)
        fams[_family(f.family, heesch)] = True
        found.append({"template": f.template, "start": f.start, "lengths": list(f.lengths), "heesch": heesch, "ih": ih})
    return _verdict(fams, found, tilings, letters)



@lru_cache(maxsize=16)
def _sig_ids(grid: Grid) -> np.ndarray:
    """Per usable template t and mask of nonempty factors, a number of its canonical Heesch
    type (:func:`_pattern`), the same for the same type (-1: fewer than three nonempty factors)."""
    usable = _template_arrays(grid)[5]
    ids = np.full((len(usable), 64), -1, np.int64)
    types: dict[tuple[str, ...], int] = {}
    for t, (name, _fam, partner, _kind, _glide) in enumerate(usable):
        for mask in range(1 << len(partner)):
            if bin(mask).count("1") >= 3:
                ids[t, mask] = types.setdefault(_pattern(name, mask)[0], len(types))
    return ids


@njit(cache=True)
def _build_matches(out, found, ks, partners, sig, build_all, cells, verts, group, det, mul, inv, period,
                   nroots):  # pragma: no cover - compiled
    """:func:`build` of the matches ``out``/``found`` of :func:`_matches` in their order, each
    with at least three nonempty factors, skipping (unless ``build_all``) those of a Heesch
    type ``sig[t, mask]`` already built: rows (t, r, a, b, d, first, end) of the matches that
    built, their unit's placements ``place[first:end]`` (element, tx, ty)."""
    total = 0
    for t in range(ks.shape[0]):
        total += found[t]
    kept = np.zeros((total, 7), np.int64)
    place = np.zeros((total * group.shape[0], 3), np.int64)
    done = np.zeros(64 * ks.shape[0], np.bool_)
    nk = 0
    npl = 0
    for t in range(ks.shape[0]):
        k = ks[t]
        for r in range(found[t]):
            mask = 0
            for j in range(k):
                if out[t, r, 1 + j] > 0:
                    mask |= 1 << j
            sid = sig[t, mask]
            if sid < 0 or (done[sid] and not build_all):
                continue
            a, b, d, unit, reps = _build(cells, verts, out[t, r, 0], out[t, r, 1:1 + k], out[t, r, 1 + k:1 + 2 * k],
                                         partners[t, :k], group, det, mul, inv, period, nroots)
            if a == 0:
                continue
            done[sid] = True
            kept[nk, 0], kept[nk, 1], kept[nk, 2], kept[nk, 3], kept[nk, 4] = t, r, a, b, d
            kept[nk, 5] = npl
            for u in range(unit.shape[0]):
                place[npl] = reps[unit[u]]
                npl += 1
            kept[nk, 6] = npl
            nk += 1
    return kept[:nk], place[:npl]


def _analyse_built(grid: Grid, cells: np.ndarray, verts: np.ndarray, letters: np.ndarray, build_all: bool) -> dict:
    """:func:`analyse` on a grid whose every match is built (no template is sound there, so
    ``construct`` changes nothing): the matches and their builds in two compiled calls, the
    same result as the loop over :func:`factorisations`."""
    out, found = _matches(grid, letters)
    partners, _kinds, ks, _glides, _smaxdiv, usable = _template_arrays(grid)
    kept, place = _build_matches(out, np.minimum(found, out.shape[1]), ks, partners, _sig_ids(grid), build_all,
                                 np.asarray(cells, dtype=np.int64), np.asarray(verts, dtype=np.int64), grid.group,
                                 grid.det, _mul_array(grid), _inv_array(grid), grid.period, len(grid.roots))
    fams = dict.fromkeys(FAMILIES, False)
    tilings: list[BuiltTiling] = []
    found_: list[dict] = []
    G = grid.group
    pl = place.tolist()
    for t, r, a, b, d, first, end in kept.tolist():
        name, fam, partner, kind, _glide = usable[t]
        k = len(partner)
        row = out[t, r, :1 + 2 * k].tolist()
        _sig, heesch, ih = _pattern(name, sum(1 << j for j in range(k) if row[1 + j]))
        f = Factorisation(name, fam, row[0], tuple(row[1:1 + k]), tuple(row[1 + k:]), partner, kind)
        unit = [(G[m].copy(), np.array([tx, ty], dtype=np.int64)) for m, tx, ty in pl[first:end]]
        tilings.append(BuiltTiling(f, ih, unit, np.array([[a, b], [0, d]], dtype=np.int64)))
        fams[_family(fam, heesch)] = True
        found_.append({"template": name, "start": f.start, "lengths": list(f.lengths), "heesch": heesch, "ih": ih})
    return _verdict(fams, found_, tilings, letters)


def periodic_tiling(grid: Grid, cells: np.ndarray, bt: BuiltTiling, name: str = "", family: str = "polyomino"):
    """A built tiling as a PeriodicTiling in Cartesian coordinates."""

    S = grid.to_xy
    Si = np.linalg.inv(S)
    proto = outline(grid, cells, name=name)
    transforms = []
    for M, t in bt.unit:
        A = np.eye(3)
        A[:2, :2] = S @ M @ Si
        A[:2, 2] = S @ t
        transforms.append(A)
    v1 = S @ bt.lattice[0]
    v2 = S @ bt.lattice[1]
    return PeriodicTiling([proto], [0] * len(transforms), np.array(transforms), v1, v2,
                          family=family, name=name)


__all__ = ["SQUARE", "TEMPLATES", "analyse", "analyse_many", "build", "factorisations", "ih_type", "periodic_tiling"]
