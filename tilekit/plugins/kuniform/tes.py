"""Read a ``.tes`` file (HyperRogue's tessellation format, used by Čtrnáct and Kopczyński's
tessellation catalogue, zenorogue/tes-catalog) describing a Euclidean tiling by regular
polygons, and turn it into the tiling's minimal D-symbol.

The part of the format read here (format: hyperrogue/tessellations/sample/README.md): a
``## name`` line, the geometry ``e2.``, ``angleunit(deg)``, tiles ``unittile(a0, a1, ...)``
(unit edges, clockwise, a_i the corner after edge i; a trailing ``*q`` or a line
``repeat(t, q)`` says the tile's edge labels repeat q times round it), and the connections in
Conway's (Doily) notation ``conway("(0 1')(2)[3 0'']")``: ``i``, ``i'``, ``i''``, ``i@n`` is
edge label i of tile 0, 1, 2, n; a pair ``(a b)`` glues edge a to edge b, ``(a)`` glues a to
itself, and square brackets make the gluing a mirror image. ``c(i1, t1, i2, t2, m)`` is the
same gluing written out. Values must be plain numbers (the format allows formulas; k-uniform
files do not use them).

The tiles are the tiling's polygons up to the symmetries the file describes, so the flags of
the tiles with their edge labels are the chambers of a D-symbol of the tiling (Delgado-
Friedrichs, *Theor. Comp. Sci.* 303, 2003): a flag (tile, label, end) changes its vertex along
the edge (σ0), its edge round the corner (σ1), and its tile across the edge by the gluing (σ2:
the other end of the partner edge, or the same end when mirrored). Face sizes are the tiles'
sides; vertex degrees come from walking round a vertex until its corners' angles sum to 360°.
Divided by its coarsest partition (:meth:`DSymbol.minimal_image`), it is the symbol the
k-uniform records store.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass

from tilekit.errors import ParseError
from tilekit.files import read_text
from tilekit.plugins.kuniform.dsymbol import DSymbol

#: The largest .tes file read (bytes) and the most tiles and edge labels it may declare.
MAX_BYTES = 1 << 20
MAX_TILES = 200
MAX_LABELS = 2000


@dataclass
class TesFile:
    """A parsed .tes file: its name, each tile's corner angles (degrees) and repeat count,
    and the gluings ((tile, label), (tile, label), mirrored)."""

    name: str
    angles: list[list[float]]
    repeat: list[int]
    gluings: list[tuple[tuple[int, int], tuple[int, int], bool]]


_CALL = re.compile(r"([A-Za-z_]\w*)\s*\((.*)\)\s*$")
_EDGE = re.compile(r"(\d+)(?:@(\d+)|('*))")


def _number(text: str, where: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise ParseError(f"{where}: {text.strip()!r} is not a plain number (formulas are not read here)") from None


def parse_tes(text: str, source: str = ".tes file") -> TesFile:
    """Parse the text of a .tes file; a one-line ParseError naming the line for anything
    outside the subset read here or malformed."""
    name = ""
    geometry = None
    unit = None
    angles: list[list[float]] = []
    repeat: list[int] = []
    gluings: list[tuple[tuple[int, int], tuple[int, int], bool]] = []
    for lineno, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        where = f"{source}, line {lineno}"
        if not line:
            continue
        if line.startswith("##"):
            name = name or line[2:].strip()
            continue
        if line.startswith("#"):
            continue
        if line in ("e2.", "h2.", "s2.") or re.fullmatch(r"[a-z]\w*\.", line):
            geometry = line[:-1]
            continue
        m = _CALL.match(line)
        if not m:
            raise ParseError(f"{where}: expected a statement such as unittile(...) or conway(\"...\"), got {line[:40]!r}")
        fn, args = m.group(1), m.group(2)
        if fn == "angleunit":
            if args.strip() != "deg":
                raise ParseError(f"{where}: only angleunit(deg) is read here, got angleunit({args.strip()})")
            unit = "deg"
        elif fn == "distunit":
            continue  # unit edges are assumed; a Euclidean arcmedge(...) is 1
        elif fn == "unittile":
            parts = [p.strip() for p in args.split(",")]
            q = 1
            if parts and parts[-1].startswith("*"):
                q = int(_number(parts.pop()[1:], where))
            tile = [_number(p, where) for p in parts]
            if not tile or q < 1:
                raise ParseError(f"{where}: a unittile needs its corner angles, got unittile({args.strip()})")
            angles.append(tile * q)
            repeat.append(q)
        elif fn == "repeat":
            parts = [p.strip() for p in args.split(",")]
            if len(parts) != 2:
                raise ParseError(f"{where}: repeat takes (tile, count), got repeat({args.strip()})")
            t, q = int(_number(parts[0], where)), int(_number(parts[1], where))
            if not 0 <= t < len(angles) or q < 1 or len(angles[t]) % q or repeat[t] != 1:
                raise ParseError(f"{where}: repeat({t}, {q}) needs a declared tile whose sides ({len(angles[t]) if 0 <= t < len(angles) else '?'}) "
                                 "the count divides")
            repeat[t] = q
        elif fn == "conway":
            body = args.strip()
            if len(body) < 2 or body[0] != '"' or body[-1] != '"':
                raise ParseError(f"{where}: conway takes a quoted text, got conway({body[:40]})")
            gluings += _conway(body[1:-1], where)
        elif fn == "c":
            parts = [p.strip() for p in args.split(",")]
            if len(parts) != 5:
                raise ParseError(f"{where}: c takes (edge, tile, edge, tile, mirrored), got c({args.strip()})")
            e1, t1, e2, t2, mir = (int(_number(p, where)) for p in parts)
            gluings.append(((t1, e1), (t2, e2), bool(mir)))
        elif fn == "tile":
            raise ParseError(f"{where}: tile(...) with edge lengths is not read here; k-uniform files use unittile(...)")
        else:
            raise ParseError(f"{where}: {fn}(...) is not read here (read: angleunit, unittile, repeat, conway, c)")
        if len(angles) > MAX_TILES or sum(len(a) for a in angles) > MAX_LABELS or len(gluings) > MAX_LABELS:
            raise ParseError(f"{where}: more than {MAX_TILES} tiles or {MAX_LABELS} edges or gluings")
    if geometry != "e2":
        raise ParseError(f"{source}: only Euclidean tessellations (e2.) are read here, got {geometry or 'no geometry line'}")
    if unit != "deg":
        raise ParseError(f"{source}: needs angleunit(deg) (angles in radians are not read here)")
    if not angles:
        raise ParseError(f"{source}: declares no unittile")
    return TesFile(name, angles, repeat, gluings)


def _conway(text: str, where: str) -> list[tuple[tuple[int, int], tuple[int, int], bool]]:
    out = []
    i = 0
    text = text.strip()
    while i < len(text):
        if text[i].isspace():
            i += 1
            continue
        if text[i] not in "([":
            raise ParseError(f"{where}: in the conway text, position {i + 1}: expected '(' or '[', got {text[i]!r}")
        close = ")" if text[i] == "(" else "]"
        j = text.find(close, i)
        if j < 0:
            raise ParseError(f"{where}: in the conway text, position {i + 1}: {text[i]!r} is not closed by {close!r}")
        items = text[i + 1:j].split()
        if not 1 <= len(items) <= 2:
            raise ParseError(f"{where}: in the conway text, position {i + 1}: a group holds one or two edges, "
                             f"got {len(items)}")
        edges = []
        for item in items:
            m = _EDGE.fullmatch(item)
            if not m:
                raise ParseError(f"{where}: in the conway text, {item!r} is not an edge (i, i', i'', i@n)")
            edges.append((int(m.group(2)) if m.group(2) else len(m.group(3) or ""), int(m.group(1))))
        out.append((edges[0], edges[-1], close == "]"))
        i = j + 1
    return out


def symbol_of_tes(tes: TesFile, source: str = ".tes file") -> DSymbol:
    """The minimal D-symbol of the tiling a parsed .tes file describes (see the module text)."""
    labels = []
    for t, (a, q) in enumerate(zip(tes.angles, tes.repeat)):
        n = len(a)
        want = 180.0 * (n - 2) / n
        if any(abs(x - want) > 1e-6 for x in a):
            raise ParseError(f"{source}: tile {t} is not a regular {n}-gon (its corners are {a[:n // q]}, not {want:g}°); "
                             "only tilings by regular polygons are read here")
        labels.append(n // q)
    base = [0]
    for m in labels:
        base.append(base[-1] + 2 * m)
    size = base[-1]

    def chamber(t: int, e: int, s: int) -> int:
        return base[t] + 2 * e + s

    s0 = [chamber(t, e, 1 - s) for t, m in enumerate(labels) for e in range(m) for s in (0, 1)]
    s1 = [chamber(t, (e + 1) % m, 0) if s == 1 else chamber(t, (e - 1) % m, 1)
          for t, m in enumerate(labels) for e in range(m) for s in (0, 1)]
    s2 = [-1] * size
    for (ta, ea), (tb, eb), mirrored in tes.gluings:
        for t, e in ((ta, ea), (tb, eb)):
            if not 0 <= t < len(labels) or not 0 <= e < labels[t]:
                raise ParseError(f"{source}: a gluing names edge {e} of tile {t}, which has no such edge label")
        for s in (0, 1):
            a, b = chamber(ta, ea, s), chamber(tb, eb, s if mirrored else 1 - s)
            for x, y in ((a, b), (b, a)):
                if s2[x] not in (-1, y):
                    raise ParseError(f"{source}: edge {ea if x == a else eb} of tile {ta if x == a else tb} is glued twice")
                s2[x] = y
    missing = [(t, e) for t, m in enumerate(labels) for e in range(m) if s2[chamber(t, e, 0)] < 0]
    if missing:
        raise ParseError(f"{source}: edge {missing[0][1]} of tile {missing[0][0]} is glued to nothing")
    face = [len(tes.angles[t]) for t, m in enumerate(labels) for _ in range(2 * m)]
    corner = [tes.angles[t][e if s == 1 else (e - 1) % m] for t, m in enumerate(labels) for e in range(m) for s in (0, 1)]
    degree = []
    for c in range(size):
        total, steps, x = 0.0, 0, c
        while total < 360 - 1e-6:
            total += corner[x]
            steps += 1
            x = s2[s1[x]]
            if steps > 42:
                break
        if abs(total - 360) > 1e-6:
            raise ParseError(f"{source}: the corners round a vertex sum to {total:g}°, not 360°: not a Euclidean tiling")
        degree.append(steps)
    enc = "/".join(",".join(map(str, col)) for col in (face, degree, s0, s1, s2))
    try:
        # the file's tiles are a translational unit or more: its symbol is not minimal yet
        return DSymbol.decode(enc, max_chambers=4 * MAX_LABELS).minimal_image()
    except ValueError as exc:
        raise ParseError(f"{source}: {exc}") from None


def read_tes(path: str | os.PathLike[str]) -> tuple[str, DSymbol]:
    """(name, minimal D-symbol) of a .tes file, read through the bounded reader."""
    text = read_text(path, ".tes file", limit=MAX_BYTES)
    tes = parse_tes(text, os.fspath(path))
    return tes.name, symbol_of_tes(tes, os.fspath(path))
