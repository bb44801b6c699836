"""Wang tile sets as data: the ``.wang`` text format, its parser, and the set's derived facts.

A Wang tile (§6.2) is a unit square with a colour on each edge, placed by translation only;
like colours must meet across every shared edge. A set is stored as (N, E, S, W) colour
indices in a ``(T, 4)`` integer array. Corner tiles (Lagae and Dutré, §7.5) colour the four
vertices instead; they are stored with their corner colours and converted to edge colours
(each edge's colour is the pair of its end-point colours), so one matching rule, one checker
and one set of solvers serve both kinds.

The file format (one set per file, reviewed in diffs; ``#`` at the start of a line or after
white space starts a comment)::

    name: jeandel-rao
    title: Jeandel-Rao aperiodic set of 11 Wang tiles
    source: E. Jeandel and M. Rao, ... (free text, one line)
    known_aperiodic: true
    palette: 0=#1b9e77 1=#d95f02
    tiles: N E S W          # or any order of N E S W; for corner tiles: corners: NE SE SW NW
    4 2 1 2  t0             # four colour tokens, then an optional tile name
    ...

Every problem is reported as ``file:line: what is wrong`` in a :class:`ParseError`.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.errors import NotFoundError, ParseError
from tilekit.files import read_text
from tilekit.limits import MAX_WANG_TILES, refuse_over_memory
from tilekit.resources import catalogue_dir
from tilekit.tiling import Prototile

#: Side indices into a tile's (N, E, S, W) row.
N, E, S, W = 0, 1, 2, 3
SIDES = ("N", "E", "S", "W")
#: Corner indices into a corner tile's (NE, SE, SW, NW) row.
CORNERS = ("NE", "SE", "SW", "NW")
#: The header keys a ``.wang`` file may set (besides the ``tiles:``/``corners:`` line).
HEADER_KEYS = ("name", "title", "source", "known_aperiodic", "notes", "palette", "aliases")

_TOKEN = re.compile(r"^[A-Za-z0-9_.+\-]+$")
_NAME = re.compile(r"^[a-z0-9][a-z0-9_.\-]*$")
#: A comment starts at '#' at the start of a line or after white space ('0=#fff' is no comment).
_COMMENT = re.compile(r"(?:^|\s)#.*$")
_HEX = re.compile(r"^#(?:[0-9a-fA-F]{3}|[0-9a-fA-F]{6})$")


@dataclass(frozen=True, eq=False)
class WangTileSet:
    """A set of Wang tiles: ``tiles[t] = (N, E, S, W)`` colour indices into ``colours``.

    ``colours`` are the colour tokens as written in the file (for corner sets, edge colours
    are 'a/b' pairs of corner tokens and ``corners[t] = (NE, SE, SW, NW)`` indexes
    ``corner_colours``). ``palette`` maps colour tokens (corner tokens for corner sets) to
    CSS colours for rendering.
    """

    name: str
    tiles: np.ndarray
    colours: tuple[str, ...]
    tile_names: tuple[str, ...] = ()
    title: str = ""
    source: str = ""
    known_aperiodic: bool = False
    notes: str = ""
    palette: Mapping[str, str] = field(default_factory=dict)
    corners: np.ndarray | None = None
    corner_colours: tuple[str, ...] = ()
    path: str = ""
    aliases: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        tiles = np.asarray(self.tiles, dtype=np.int64)
        if tiles.ndim != 2 or tiles.shape[1] != 4 or len(tiles) == 0:
            raise ParseError(f"tile set {self.name!r}: tiles must be a non-empty (T, 4) array, got {tiles.shape}")
        if tiles.min() < 0 or tiles.max() >= len(self.colours):
            raise ParseError(f"tile set {self.name!r}: a colour index is outside 0..{len(self.colours) - 1}")
        tiles.setflags(write=False)
        object.__setattr__(self, "tiles", tiles)
        names = tuple(self.tile_names) or tuple(f"t{i}" for i in range(len(tiles)))
        if len(names) != len(tiles):
            raise ParseError(f"tile set {self.name!r}: {len(names)} names for {len(tiles)} tiles")
        object.__setattr__(self, "tile_names", names)
        if self.corners is not None:
            c = np.asarray(self.corners, dtype=np.int64)
            c.setflags(write=False)
            object.__setattr__(self, "corners", c)

    # ------------------------------------------------------------------ basic facts
    def __len__(self) -> int:
        return len(self.tiles)

    def __repr__(self) -> str:
        return f"<WangTileSet {self.name}: {len(self)} tiles, {len(self.colours)} colours>"

    @property
    def kind(self) -> str:
        """'corner' for corner-coloured tiles, else 'edge'."""
        return "corner" if self.corners is not None else "edge"

    def tile_colours(self, t: int) -> dict[str, str]:
        """Tile t's colour tokens by side, e.g. {'N': '4', 'E': '2', 'S': '1', 'W': '2'}."""
        return {side: self.colours[int(c)] for side, c in zip(SIDES, self.tiles[t])}

    @cached_property
    def horizontal_colours(self) -> np.ndarray:
        """Colour indices used on N or S edges (the edges between vertically adjacent tiles)."""
        return np.unique(self.tiles[:, [N, S]])

    @cached_property
    def vertical_colours(self) -> np.ndarray:
        """Colour indices used on E or W edges."""
        return np.unique(self.tiles[:, [E, W]])

    @property
    def colour_count(self) -> int:
        """Number of distinct edge colours (horizontal and vertical counted separately)."""
        return len(self.horizontal_colours) + len(self.vertical_colours)

    def _nw_counts(self) -> np.ndarray:
        """Tiles per (n, w) over the pairs of colours that can meet at a tile's NW corner
        (pairs without a tile count 0), counted over the tiles, not over a colours x colours
        table: a set with thousands of colours costs its tiles, not colours squared.

        For edge sets every pair of a horizontal and a vertical colour can meet; for corner
        sets only pairs that agree on the colour of the shared north-west corner.
        """
        h, v = self.horizontal_colours, self.vertical_colours
        hpos = np.searchsorted(h, self.tiles[:, N])
        vpos = np.searchsorted(v, self.tiles[:, W])
        _, counts = np.unique(hpos * len(v) + vpos, return_counts=True)
        if self.corners is None:
            meeting = len(h) * len(v)
        else:
            c = len(self.colours)
            west_end = np.full(c, -1)  # corner at the west end of a horizontal edge colour
            north_end = np.full(c, -1)  # corner at the north end of a vertical edge colour
            west_end[self.tiles[:, N]] = self.corners[:, 3]
            west_end[self.tiles[:, S]] = self.corners[:, 2]
            north_end[self.tiles[:, W]] = self.corners[:, 3]
            north_end[self.tiles[:, E]] = self.corners[:, 0]
            k = len(self.corner_colours)
            meeting = int(np.bincount(west_end[h], minlength=k) @ np.bincount(north_end[v], minlength=k))
        # a tile's own N and W meet, so the pairs with tiles are among the meeting ones
        return np.concatenate([counts, np.zeros(meeting - len(counts), dtype=counts.dtype)])

    @cached_property
    def complete(self) -> bool:
        """Every (N, W) pair of colours that can meet has at least one tile, so Cohen et al.'s
        scanline fill (§7.5) never gets stuck."""
        return bool(self._nw_counts().min() >= 1)

    @cached_property
    def stochastic(self) -> bool:
        """Complete with at least two tiles for every (N, W) pair, so every step of the
        scanline fill has a random choice (the property of Figure 6.9)."""
        return bool(self._nw_counts().min() >= 2)

    @cached_property
    def corner_table(self) -> np.ndarray | None:
        """For corner sets: ``table[ne, se, sw, nw]`` = a tile with those corner colours, or -1."""
        if self.corners is None:
            return None
        k = len(self.corner_colours)
        refuse_over_memory("corner table entries", float(k) ** 4, 8, hint=f"set {self.name!r} has {k} corner colours")
        table = np.full((k, k, k, k), -1, dtype=np.int64)
        # later duplicates lose to the first tile listed (reverse assignment keeps the first)
        idx = np.arange(len(self.corners))[::-1]
        c = self.corners[::-1]
        table[c[:, 0], c[:, 1], c[:, 2], c[:, 3]] = idx
        return table

    @cached_property
    def corner_complete(self) -> bool:
        """Corner set with a tile for every assignment of corner colours (random access works)."""
        k = len(self.corner_colours)
        if self.corners is None or len(self) < k**4:  # too few tiles for every colouring
            return False
        table = self.corner_table
        return table is not None and bool((table >= 0).all())

    # ------------------------------------------------------------------ serialisation
    def to_json(self) -> dict[str, Any]:
        """A JSON description that :meth:`from_json` turns back into an equal set."""
        out: dict[str, Any] = {"name": self.name}
        if self.corners is not None:
            out["corners"] = [[self.corner_colours[int(c)] for c in row] for row in self.corners]
        else:
            out["tiles"] = [[self.colours[int(c)] for c in row] for row in self.tiles]
        out["tile_names"] = list(self.tile_names)
        for key in ("title", "source", "notes"):
            if getattr(self, key):
                out[key] = getattr(self, key)
        if self.known_aperiodic:
            out["known_aperiodic"] = True
        if self.palette:
            out["palette"] = dict(self.palette)
        if self.aliases:
            out["aliases"] = list(self.aliases)
        return out

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> WangTileSet:
        """Rebuild a set from :meth:`to_json` output (errors name the bad field)."""
        try:
            name = str(data["name"])
            meta = dict(
                title=str(data.get("title", "")),
                source=str(data.get("source", "")),
                notes=str(data.get("notes", "")),
                known_aperiodic=bool(data.get("known_aperiodic", False)),
                palette=dict(data.get("palette", {})),
                aliases=tuple(str(a) for a in data.get("aliases", ())),
            )
            names = [str(n) for n in data.get("tile_names", [])]
            if "corners" in data:
                return from_corners(name, [tuple(map(str, r)) for r in data["corners"]], names, **meta)
            return from_tuples(name, [tuple(map(str, r)) for r in data["tiles"]], names, **meta)
        except KeyError as exc:
            raise ParseError(f"Wang tile set spec lacks the field {exc.args[0]!r} (needs name and tiles or corners)") from None
        except (TypeError, ValueError) as exc:
            if isinstance(exc, ParseError):
                raise
            raise ParseError(f"Wang tile set spec is malformed: {exc}") from None

    def to_text(self) -> str:
        """The set in the ``.wang`` file format (``parse_tileset(set.to_text())`` round-trips)."""
        lines = [f"name: {self.name}"]
        for key in ("title", "source", "notes"):
            if getattr(self, key):
                lines.append(f"{key}: {getattr(self, key)}")
        if self.known_aperiodic:
            lines.append("known_aperiodic: true")
        if self.palette:
            lines.append("palette: " + " ".join(f"{k}={v}" for k, v in self.palette.items()))
        if self.aliases:
            lines.append("aliases: " + " ".join(self.aliases))
        if self.corners is not None:
            lines.append("corners: NE SE SW NW")
            rows = [[self.corner_colours[int(c)] for c in r] for r in self.corners]
        else:
            lines.append("tiles: N E S W")
            rows = [[self.colours[int(c)] for c in r] for r in self.tiles]
        for row, tname in zip(rows, self.tile_names):
            lines.append(" ".join(row) + "  " + tname)
        return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------- constructors


def _index(tokens: Iterable[str]) -> tuple[tuple[str, ...], dict[str, int]]:
    """Colour tokens in a stable order: numeric tokens numerically, then the rest as written."""
    seen = list(dict.fromkeys(tokens))
    numeric = sorted((t for t in seen if t.isdigit()), key=int)
    other = [t for t in seen if not t.isdigit()]
    order = tuple(numeric + other)
    return order, {t: i for i, t in enumerate(order)}


def from_tuples(
    name: str,
    tiles: Sequence[Sequence[Any]],
    tile_names: Sequence[str] = (),
    **meta: Any,
) -> WangTileSet:
    """A set from (N, E, S, W) colour tuples (any hashable tokens; converted with ``str``)."""
    _check_count(name, tiles)
    rows = [tuple(str(c) for c in t) for t in tiles]
    for i, r in enumerate(rows):
        if len(r) != 4:
            raise ParseError(f"tile set {name!r}: tile {i} has {len(r)} colours, expected 4 (N, E, S, W)")
    colours, index = _index(c for r in rows for c in r)
    arr = np.array([[index[c] for c in r] for r in rows], dtype=np.int64).reshape(-1, 4)
    _check_duplicates(name, arr, tile_names)
    return WangTileSet(name=name, tiles=arr, colours=colours, tile_names=tuple(tile_names), **meta)


def from_corners(
    name: str,
    corners: Sequence[Sequence[Any]],
    tile_names: Sequence[str] = (),
    **meta: Any,
) -> WangTileSet:
    """A corner-tile set from (NE, SE, SW, NW) corner colour tuples (Lagae and Dutré).

    Each edge gets the colour 'a/b' of its two end points read west-to-east (N and S edges)
    or north-to-south (E and W edges), so that matching edges is matching corners.
    """
    _check_count(name, corners)
    rows = [tuple(str(c) for c in t) for t in corners]
    for i, r in enumerate(rows):
        if len(r) != 4:
            raise ParseError(f"tile set {name!r}: corner tile {i} has {len(r)} colours, expected 4 (NE, SE, SW, NW)")
    for i, r in enumerate(rows):
        for c in r:
            if not _TOKEN.match(c):  # '/' joins corner colours into edge colours below
                raise ParseError(
                    f"tile set {name!r}: corner colour {c!r} of tile {i} must be letters, digits, '_', '.', '+' or '-'"
                )
    ccols, cindex = _index(c for r in rows for c in r)
    carr = np.array([[cindex[c] for c in r] for r in rows], dtype=np.int64).reshape(-1, 4)
    _check_duplicates(name, carr, tile_names, what="corner tile")
    edges = [(f"{nw}/{ne}", f"{ne}/{se}", f"{sw}/{se}", f"{nw}/{sw}") for ne, se, sw, nw in rows]
    colours, index = _index(c for r in edges for c in r)
    arr = np.array([[index[c] for c in r] for r in edges], dtype=np.int64)
    return WangTileSet(
        name=name, tiles=arr, colours=colours, tile_names=tuple(tile_names), corners=carr,
        corner_colours=ccols, **meta,
    )


def _check_count(name: str, tiles: Sequence[Any]) -> None:
    """At most MAX_WANG_TILES tiles, checked before anything is made of them."""
    if len(tiles) > MAX_WANG_TILES:
        raise ParseError(f"tile set {name!r} has {len(tiles):,} tiles; a set holds at most {MAX_WANG_TILES:,}")


def _check_duplicates(name: str, arr: np.ndarray, tile_names: Sequence[str], what: str = "tile") -> None:
    _, first, counts = np.unique(arr, axis=0, return_index=True, return_counts=True)
    if (counts > 1).any():
        row = arr[first[np.flatnonzero(counts > 1)[0]]]
        dup = np.flatnonzero((arr == row).all(axis=1))
        raise ParseError(f"tile set {name!r}: {what}s {dup.tolist()} are the same tile (each tile once)")
    if tile_names and len(set(tile_names)) != len(tile_names):
        raise ParseError(f"tile set {name!r}: tile names repeat; give each tile its own name")


# ---------------------------------------------------------------------- the file format


def parse_tileset(text: str, filename: str = "<text>") -> WangTileSet:
    """Parse a ``.wang`` file's text; every error is ``filename:line: problem``."""

    def fail(lineno: int, msg: str) -> ParseError:
        return ParseError(f"{filename}:{lineno}: {msg}")

    header: dict[str, Any] = {}
    order: tuple[int, ...] | None = None
    corner_mode = False
    rows: list[tuple[str, ...]] = []
    names: list[str] = []
    row_lines: list[int] = []
    line_of_row: dict[tuple[str, ...], int] = {}
    line_of_name: dict[str, int] = {}
    header_line = 0
    for lineno, raw in enumerate(text.splitlines(), start=1):
        line = _COMMENT.sub("", raw).strip()
        if not line:
            continue
        if order is None:
            key, sep, value = line.partition(":")
            key, value = key.strip(), value.strip()
            if not sep:
                raise fail(lineno, f"expected 'key: value' or the 'tiles: N E S W' line, got {line!r}")
            if key in ("tiles", "corners"):
                labels = value.split()
                expect = SIDES if key == "tiles" else CORNERS
                if sorted(labels) != sorted(expect):
                    raise fail(
                        lineno,
                        f"'{key}:' must list {' '.join(expect)} once each in some order, got {value!r}",
                    )
                order = tuple(labels.index(s) for s in expect)
                corner_mode = key == "corners"
                header_line = lineno
                continue
            if key not in HEADER_KEYS:
                raise fail(lineno, f"unknown key {key!r}; valid keys: {', '.join(HEADER_KEYS)}, tiles, corners")
            if key in header:
                raise fail(lineno, f"key {key!r} given twice")
            header[key] = _header_value(key, value, lambda m, ln=lineno: fail(ln, m))
            continue
        parts = line.split()
        if len(parts) not in (4, 5):
            what = "NE SE SW NW" if corner_mode else "N E S W"
            raise fail(lineno, f"a tile line needs 4 colours ({what}) and an optional name, got {len(parts)} fields: {line!r}")
        for tok in parts[:4]:
            if not _TOKEN.match(tok):
                raise fail(lineno, f"colour {tok!r} must be letters, digits, '_', '.', '+' or '-'")
        colours = tuple(parts[i] for i in order)
        if colours in line_of_row:
            raise fail(lineno, f"tile {' '.join(parts[:4])} repeats the tile on line {line_of_row[colours]}")
        tname = parts[4] if len(parts) == 5 else f"t{len(rows)}"
        if tname in line_of_name:
            raise fail(lineno, f"tile name {tname!r} repeats the one on line {line_of_name[tname]}")
        if len(rows) == MAX_WANG_TILES:
            raise fail(lineno, f"more than {MAX_WANG_TILES:,} tiles; a set holds at most {MAX_WANG_TILES:,}")
        line_of_row[colours] = line_of_name[tname] = lineno
        rows.append(colours)
        names.append(tname)
        row_lines.append(lineno)
    if order is None:
        raise fail(len(text.splitlines()) or 1, "no 'tiles: N E S W' (or 'corners: NE SE SW NW') line; a set needs tiles")
    if not rows:
        raise fail(header_line, "the tile list is empty; give one tile per line after this line")
    if "name" not in header:
        raise fail(1, "no 'name:' line; every set needs a name (lower case, digits, '-', '_', '.')")
    palette = header.get("palette", {})
    used = {c for r in rows for c in r}
    unknown = sorted(set(palette) - used)
    if unknown:
        raise fail(_line_of(text, "palette"), f"palette names colour(s) {unknown} that no tile uses; tile colours: {sorted(used)}")
    meta = dict(
        title=header.get("title", ""),
        source=header.get("source", ""),
        notes=header.get("notes", ""),
        known_aperiodic=header.get("known_aperiodic", False),
        palette=palette,
        path=filename,
        aliases=header.get("aliases", ()),
    )
    build = from_corners if corner_mode else from_tuples
    return build(header["name"], rows, names, **meta)


def _line_of(text: str, key: str) -> int:
    for lineno, raw in enumerate(text.splitlines(), start=1):
        if raw.strip().startswith(key):
            return lineno
    return 1


def _header_value(key: str, value: str, fail: Any) -> Any:
    if key == "name":
        if not _NAME.match(value):
            raise fail(f"name {value!r} must be lower case letters, digits, '-', '_' or '.'")
        return value
    if key == "known_aperiodic":
        low = value.lower()
        if low not in ("true", "false"):
            raise fail(f"known_aperiodic must be true or false, got {value!r}")
        return low == "true"
    if key == "aliases":
        names = tuple(value.split())
        for a in names:
            if not _NAME.match(a):
                raise fail(f"alias {a!r} must be lower case letters, digits, '-', '_' or '.'")
        return names
    if key == "palette":
        out: dict[str, str] = {}
        for item in value.split():
            colour, sep, css = item.partition("=")
            if not sep or not colour or not (_HEX.match(css) or (css.isalpha() and css.isascii())):
                raise fail(f"palette entry {item!r} must be COLOUR=#rrggbb or COLOUR=cssname")
            out[colour] = css
        return out
    if not value:
        raise fail(f"{key!r} is empty")
    return value


def load_tileset(path: str | Path) -> WangTileSet:
    """Read a ``.wang`` file (errors name the file and line): a regular file of at most
    ``limits.MAX_FILE_BYTES``, read through :func:`tilekit.files.read_text`."""
    return parse_tileset(read_text(path, "tile set file"), filename=str(path))


# ---------------------------------------------------------------------- the built-in sets


def catalogue_folder() -> Path:
    """Where the shipped ``.wang`` files live (catalogue/wang/)."""
    return catalogue_dir() / "wang"


_BUILTIN: dict[str, WangTileSet] | None = None


def builtin_sets() -> dict[str, WangTileSet]:
    """Every shipped tile set by name, parsed once from catalogue/wang/*.wang."""
    global _BUILTIN
    if _BUILTIN is None:
        found: dict[str, WangTileSet] = {}
        for path in sorted(catalogue_folder().glob("*.wang")):
            ts = load_tileset(path)
            if ts.name in found:
                raise ParseError(f"{path}: set name {ts.name!r} is also used by {found[ts.name].path}")
            found[ts.name] = ts
        _BUILTIN = found
    return _BUILTIN


def get_tileset(name: str) -> WangTileSet:
    """A shipped tile set by name (NotFoundError suggests the close ones)."""
    sets = builtin_sets()
    if name in sets:
        return sets[name]
    for ts in sets.values():
        if name in ts.aliases:
            return ts
    raise NotFoundError("Wang tile set", name, sets)


# ---------------------------------------------------------------------- geometry


def _unit_square() -> np.ndarray:
    return np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


def tile_prototiles(tileset: WangTileSet) -> list:
    """One unit-square :class:`~tilekit.Prototile` per tile, cached on the set.

    The outline runs counter-clockwise from the south-west corner, so its edges are S, E,
    N, W and ``edge_labels`` holds those sides' colour tokens; the two diagonals are drawn
    as the marking, splitting the square into the four triangles of the usual picture.
    """
    cached = tileset.__dict__.get("_prototiles")
    if cached is not None:
        return cached
    diagonals = (np.array([[0.0, 0.0], [1.0, 1.0]]), np.array([[1.0, 0.0], [0.0, 1.0]]))
    protos = [
        Prototile(
            _unit_square(),
            edge_labels=tuple(tileset.colours[int(row[k])] for k in (S, E, N, W)),
            marking=diagonals,
            name=tname,
        )
        for row, tname in zip(tileset.tiles, tileset.tile_names)
    ]
    object.__setattr__(tileset, "_prototiles", protos)  # frozen dataclass: cache by hand
    return protos
