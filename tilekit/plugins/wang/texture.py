"""Wang tiles made from an example image (§7.5; Cohen, Shade, Hiller and Deussen 2003, and
Lagae and Dutré 2006 for corner tiles), with minimum-error boundary cuts (Efros and Freeman 2001).

**Edge tiles.** Each edge colour is a square *source patch* of the example, T x T pixels
(T the tile side), whose centre lines are the tile edge: the tile south of a horizontal edge
of colour k shows the patch's lower half in its N triangle, the tile north of it the upper
half in its S triangle, so the pixels on both sides of every edge are neighbouring pixels of
one patch, whatever tiles are placed. A tile's four triangles meet along its diagonals, where
two patches that never met in the example touch. In each quadrant both patches cover every
pixel, so the diagonal is replaced by the path of least error between them: a boundary
column b(r) = r + s(r) per row, |s(r + 1) - s(r)| <= 1, found by dynamic programming over the
cost e(r, b - 1) + e(r, b), e = squared colour difference of the two patches (Efros and
Freeman's cut, with Kwatra et al.'s cost of a pair of pixels across it). The cut starts at the
tile corner and ends at its centre (s = 0 there), and s(r) >= 1 - r keeps the pixels of both
edges from the edge's own patch, so the straight diagonal is one of the paths searched and
the cut never costs more than it. One pixel per tile corner belongs to two edges and can come
from only one patch: Cohen et al.'s *corner problem* at pixel scale.

**Corner tiles.** Each corner colour is a square patch of (T + 2 band) pixels centred on the
lattice point; a tile's quadrant next to a corner comes from that corner's patch, and the four
tiles around a lattice point show one patch, so every edge pixel, corners included, is
continuous. The cuts run along the tile's mid-lines (the four arms of a cross), from the edge
midpoint (fixed, so neighbours agree) to the centre, within ``band`` pixels of the mid-line.

A tile's content depends only on its colours, so one cut serves every tile with the same pair
of colours at that place. Patch positions are drawn on a lattice of half-patch spacing (patches
overlap by at most half their side), ``tries`` times, and the draw with the least total cut
error is kept. The result, :class:`TextureTiles`, is saved as an atlas PNG whose tEXt chunk
holds the tile set and the construction (:meth:`TextureTiles.save`, :func:`load_texture_tiles`).
"""

from __future__ import annotations

import json
import os
import stat
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from tilekit import limits
from tilekit.errors import ParameterError, ParseError
from tilekit.plugins.wang.tileset import CORNERS, E, N, S, W, WangTileSet
from tilekit.pngstream import write_png

#: Smallest tile side in pixels (a cut needs room), and the tile side must be even.
MIN_TILE = 8
#: Largest tile side, pixels of one atlas, of an example, bytes of an image file (limits.py).
MAX_TILE = limits.MAX_TEXTURE_TILE
MAX_ATLAS_PIXELS = limits.MAX_ATLAS_PIXELS
MAX_EXAMPLE_PIXELS = limits.MAX_EXAMPLE_PIXELS
MAX_IMAGE_BYTES = limits.MAX_IMAGE_BYTES
#: The tEXt key of an atlas PNG's metadata.
ATLAS_KEY = "tilekit-wang-texture"
ATLAS_VERSION = 1
#: The extra that brings Pillow (reading images); named in the error when it is missing.
EXTRA = "texture"


# ---------------------------------------------------------------------- reading images


def _pillow() -> Any:
    try:
        from PIL import Image  # optional: the 'texture' extra
    except ImportError:
        raise ParameterError(f"reading images needs Pillow: pip install 'tilekit[{EXTRA}]'") from None
    return Image


def read_image(path: str | Path, what: str = "example image", max_pixels: int = MAX_EXAMPLE_PIXELS,
               max_bytes: int = MAX_IMAGE_BYTES) -> tuple[np.ndarray, dict[str, str]]:
    """An image file as an (h, w, 3) uint8 RGB array and its text chunks, read through Pillow
    from a regular file of at most ``max_bytes``, refused (ParseError / LimitError, one line)
    before decoding when it is no image or has more than ``max_pixels`` pixels."""
    p = Path(path)
    name = str(path)[:200]
    try:
        st = os.stat(p)
    except OSError as exc:
        raise ParseError(f"{what} {name!r} cannot be read: {exc.strerror or exc}") from None
    if not stat.S_ISREG(st.st_mode):
        raise ParseError(f"{what} {name!r} is not a regular file; give a PNG (or other image) file")
    if st.st_size > max_bytes:
        raise limits.LimitError(f"{what} {p.name!r} has {st.st_size:,} bytes, over the limit of {max_bytes:,}")
    image = _pillow()
    try:
        with image.open(p) as im:
            w, h = im.size
            limits.refuse_over("pixels", w * h, max_pixels, hint=f"{what} {p.name!r} is {w} x {h}; scale it down")
            text = {str(k): v for k, v in getattr(im, "text", {}).items() if isinstance(v, str)}
            rgb = np.asarray(im.convert("RGB"), dtype=np.uint8)
    except limits.LimitError:
        raise
    except Exception as exc:  # Pillow raises many kinds (UnidentifiedImageError, OSError, SyntaxError, ...)
        raise ParseError(f"{what} {p.name!r} cannot be read as an image ({type(exc).__name__}: {str(exc)[:100]})") from None
    return rgb, text


# ---------------------------------------------------------------------- the cut


def wedge(length: int, band: int, start: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Allowed offsets s(r) of a cut of ``length`` rows from a fixed start (s = 0) to a fixed end
    (s = 0): |s(r)| <= min(band, r, length - 1 - r), and s(r) >= start - r (``start`` = 1 keeps
    the second edge's pixels off the first patch)."""
    r = np.arange(length)
    hi = np.minimum(np.minimum(band, r), length - 1 - r)
    lo = np.maximum(-hi, np.where(r > 0, start - r, 0))
    return lo, hi


def min_error_paths(cost: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Dynamic programming for many cuts at once: ``cost[m, r, k]`` is the error of cut m having
    offset s = k - band in row r (band = (cost.shape[2] - 1) / 2); a path has s(r) in
    [lo[r], hi[r]] and moves by at most 1 a row. Returns the offsets (m, rows) of the least
    total cost and those totals (m,)."""
    m, rows, width = cost.shape
    band = (width - 1) // 2
    k = np.arange(width) - band
    allowed = (k[None, :] >= lo[:, None]) & (k[None, :] <= hi[:, None])  # (rows, width)
    c = np.where(allowed[None], cost, np.inf)
    total = c[:, 0].copy()
    back = np.empty((m, rows, width), dtype=np.int8)
    back[:, 0] = 0
    pad = np.full((m, width + 2), np.inf)
    for r in range(1, rows):
        pad[:, 1:-1] = total
        choices = np.stack([pad[:, :-2], pad[:, 1:-1], pad[:, 2:]])  # from s-1, s, s+1
        step = np.argmin(choices, axis=0)
        total = c[:, r] + np.take_along_axis(choices, step[None], axis=0)[0]
        back[:, r] = step - 1
    path = np.empty((m, rows), dtype=np.int64)
    last = np.argmin(total, axis=1)
    best = total[np.arange(m), last]
    path[:, -1] = last
    for r in range(rows - 1, 0, -1):
        path[:, r - 1] = path[:, r] + back[np.arange(m), r, path[:, r]]
    return path - band, best


def seam_cost_table(e: np.ndarray, base: np.ndarray, first: np.ndarray, last: np.ndarray, band: int) -> np.ndarray:
    """Per-row costs of the cut positions: ``e`` (m, rows, cols) squared differences of the two
    patches in the cut's frame, a boundary b = base[r] + s before column b; the cost is
    e[b - 1] + e[b], counting only columns first[r] <= c <= last[r] (the cut's region).
    Returns (m, rows, 2 band + 1)."""
    m, rows, cols = e.shape
    s = np.arange(-band, band + 1)
    b = base[:, None] + s[None, :]  # (rows, width)
    out = np.zeros((m, rows, len(s)))
    for side in (b - 1, b):
        ok = (side >= first[:, None]) & (side <= last[:, None]) & (side >= 0) & (side < cols)
        val = np.take_along_axis(e, np.clip(side, 0, cols - 1)[None].repeat(m, axis=0), axis=2)
        out += np.where(ok[None], val, 0.0)
    return out


# ---------------------------------------------------------------------- geometry of the seams

# Frames: a seam is solved in a frame where its rows run from the tile's boundary (row 0)
# towards the centre. _FRAMES[name](a) is a view of a (k, T, T, ...) array in that frame (axes
# 1 and 2 are the tile's rows and columns), so writing to it writes to ``a``.
_FRAMES = {
    "id": lambda a: a,
    "flip_rows": lambda a: a[:, ::-1],
    "flip_cols": lambda a: a[:, :, ::-1],
    "flip_both": lambda a: a[:, ::-1, ::-1],
    "transpose": lambda a: np.swapaxes(a, 1, 2),
    "transpose_flip": lambda a: np.swapaxes(a[:, :, ::-1], 1, 2),
}

#: Edge tiles: the four diagonal seams, each (frame, right label, left label): in the frame the
#: seam runs from the corner (0, 0) to the centre; columns >= b(r) take the right label.
EDGE_SEAMS = (("id", N, W), ("flip_cols", N, E), ("flip_rows", S, W), ("flip_both", S, E))
#: Corner tiles (labels index CORNERS: NE 0, SE 1, SW 2, NW 3): the four arms of the cross
#: (frame, right label, left label, the region's columns are inclusive of the diagonals).
CORNER_SEAMS = (("id", 0, 3, True), ("flip_rows", 1, 2, True), ("transpose", 2, 3, False),
                ("transpose_flip", 1, 0, False))


def _seam_region(tile: int, kind: str, inclusive: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For a seam in its frame (rows 0 .. T/2 - 1): (base column of the straight seam, first
    and last column of the seam's region) per row."""
    h = tile // 2
    r = np.arange(h)
    if kind == "edge":  # the quadrant, diagonal seam
        return r, np.zeros(h, dtype=np.int64), np.full(h, h - 1)
    if inclusive:  # the N or S triangle (it owns the diagonals)
        return np.full(h, h), r, tile - 1 - r
    return np.full(h, h), r + 1, tile - 2 - r


@dataclass
class SeamResult:
    """Cuts solved for one kind of seam: one path per distinct pair of patches."""

    frame: str
    right: int
    left: int
    pairs: np.ndarray  # (m, 2): the (right source, left source) of each distinct pair
    offsets: np.ndarray  # (m, T/2) offsets s(r)
    cost: np.ndarray  # (m,) error of the cut
    straight: np.ndarray  # (m,) error of the straight seam (s = 0)
    inclusive: bool = True


# ---------------------------------------------------------------------- patches


def tile_sources(tileset: WangTileSet) -> tuple[list[tuple[str, int]], np.ndarray]:
    """The source patches a set needs and which one each tile label uses: ``(keys, use)`` with
    keys like ('h', colour) for horizontal edge colours, ('v', colour) for vertical ones and
    ('c', corner colour) for corner sets; ``use[t, label]`` indexes keys (labels N, E, S, W, or
    NE, SE, SW, NW for corner sets)."""
    if tileset.corners is not None:
        keys = [("c", k) for k in range(len(tileset.corner_colours))]
        return keys, tileset.corners.astype(np.int64).copy()
    h = sorted(set(tileset.tiles[:, N].tolist()) | set(tileset.tiles[:, S].tolist()))
    v = sorted(set(tileset.tiles[:, E].tolist()) | set(tileset.tiles[:, W].tolist()))
    keys = [("h", k) for k in h] + [("v", k) for k in v]
    index = {key: i for i, key in enumerate(keys)}
    use = np.empty((len(tileset), 4), dtype=np.int64)
    for side, orient in ((N, "h"), (S, "h"), (E, "v"), (W, "v")):
        use[:, side] = [index[(orient, int(c))] for c in tileset.tiles[:, side]]
    return keys, use


def window_side(tileset: WangTileSet, tile: int, band: int) -> int:
    """Side of a source patch: T for edge colours, T + 2 band for corner colours."""
    return tile if tileset.corners is None else tile + 2 * band


def label_offsets(tileset: WangTileSet, tile: int, band: int, positions: np.ndarray) -> np.ndarray:
    """(sources, 4, 2) offsets (dy, dx): label L of a tile whose source for L is k shows pixel
    (r, c) as example[r + dy, c + dx] with (dy, dx) = offsets[k, L]; ``positions`` (sources, 2)
    are the patches' top-left corners in the example."""
    h = tile // 2
    wy, wx = positions[:, 0], positions[:, 1]
    out = np.empty((len(positions), 4, 2), dtype=np.int64)
    if tileset.corners is None:
        out[:, N] = np.column_stack([wy + h, wx])
        out[:, S] = np.column_stack([wy - h, wx])
        out[:, W] = np.column_stack([wy, wx + h])
        out[:, E] = np.column_stack([wy, wx - h])
        return out
    y, x = wy + h + band, wx + h + band  # the lattice point: between pixel rows y - 1 and y
    out[:, CORNERS.index("NW")] = np.column_stack([y, x])
    out[:, CORNERS.index("NE")] = np.column_stack([y, x - tile])
    out[:, CORNERS.index("SW")] = np.column_stack([y - tile, x])
    out[:, CORNERS.index("SE")] = np.column_stack([y - tile, x - tile])
    return out


def _label_image(example: np.ndarray, offsets: np.ndarray, tile: int) -> np.ndarray:
    """(k, T, T, C) pixels of k (dy, dx) offsets, indices clipped to the example (pixels a label
    does not use may fall outside its patch)."""
    r = np.arange(tile)
    ys = np.clip(r[None, :] + offsets[:, 0:1], 0, example.shape[0] - 1)
    xs = np.clip(r[None, :] + offsets[:, 1:2], 0, example.shape[1] - 1)
    return example[ys[:, :, None], xs[:, None, :]]


def candidate_positions(shape: tuple[int, int], count: int, side: int, rng: np.random.Generator) -> np.ndarray:
    """``count`` distinct top-left corners of ``side``-pixel patches in an image of ``shape``, on
    a lattice of spacing ceil(side / 2) shifted by a random offset (so two patches overlap by
    at most half their side). ParameterError when the image holds fewer lattice positions."""
    h, w = shape
    q = max(1, (side + 1) // 2)
    ny, nx = (h - side) // q + 1, (w - side) // q + 1
    if h < side or w < side or ny * nx < count:
        need = side + q * (int(np.ceil(np.sqrt(count))) - 1)
        raise ParameterError(
            f"the example ({w} x {h} pixels) is too small for {count} patches of {side} x {side} pixels "
            f"at least {q} apart; give an example of at least {need} x {need} pixels or a smaller --tile"
        )
    oy = int(rng.integers(0, h - side - q * (ny - 1) + 1))
    ox = int(rng.integers(0, w - side - q * (nx - 1) + 1))
    cells = rng.choice(ny * nx, size=count, replace=False)
    iy, ix = np.divmod(cells, nx)
    return np.column_stack([oy + q * iy, ox + q * ix]).astype(np.int64)


# ---------------------------------------------------------------------- the tiles


@dataclass
class TextureTiles:
    """A Wang tile set with pixels: ``pixels[t]`` is tile t, (T, T, 3) uint8, in the set's tile
    order. ``labels[t]`` (when built here, not when loaded) says which patch each pixel came
    from (0..3: N, E, S, W, or NE, SE, SW, NW for corner sets); ``meta`` records the
    construction (example, positions, band, seed, cut errors)."""

    tileset: WangTileSet
    pixels: np.ndarray
    meta: dict[str, Any] = field(default_factory=dict)
    labels: np.ndarray | None = None
    seams: list[SeamResult] | None = None

    def __post_init__(self) -> None:
        p = np.asarray(self.pixels)
        if p.dtype != np.uint8 or p.ndim != 4 or p.shape[0] != len(self.tileset) or p.shape[1] != p.shape[2] \
                or p.shape[3] != 3:
            raise ParameterError(f"tile pixels must be ({len(self.tileset)}, T, T, 3) uint8, got {p.dtype} {p.shape}")
        self.pixels = np.ascontiguousarray(p)

    @property
    def tile(self) -> int:
        """The tile side in pixels."""
        return int(self.pixels.shape[1])

    @property
    def rows(self) -> np.ndarray:
        """The pixels as (tiles, T, 3T): tile t's pixel row r is ``rows[t, r]``, the unit a
        synthesis gathers."""
        n, t = self.pixels.shape[:2]
        return self.pixels.reshape(n, t, t * 3)

    def atlas(self) -> np.ndarray:
        """All tiles in one image, tile t at grid cell (t // columns, t % columns)."""
        n, t = len(self.tileset), self.tile
        cols = int(np.ceil(np.sqrt(n)))
        rows = -(-n // cols)
        out = np.zeros((rows * t, cols * t, 3), dtype=np.uint8)
        for k in range(n):
            i, j = divmod(k, cols)
            out[i * t:(i + 1) * t, j * t:(j + 1) * t] = self.pixels[k]
        return out

    def save(self, path: str | Path, level: int = 6) -> Path:
        """Write the atlas PNG with the tile set and :attr:`meta` in its tEXt chunk."""
        p = Path(path)
        if p.suffix.lower() != ".png":
            raise ParameterError(f"a tile atlas is a .png file, not {str(path)!r}")
        cols = int(np.ceil(np.sqrt(len(self.tileset))))
        info = {"version": ATLAS_VERSION, "tile": self.tile, "columns": cols, "set": self.tileset.to_json(),
                "construction": self.meta}
        write_png(p, self.atlas(), level=level, text={ATLAS_KEY: json.dumps(info, ensure_ascii=True)})
        return p


def load_texture_tiles(path: str | Path) -> TextureTiles:
    """Read an atlas written by :meth:`TextureTiles.save` (one-line errors name the file and
    what is missing)."""
    image, text = read_image(path, what="tile atlas", max_pixels=MAX_ATLAS_PIXELS)
    name = Path(path).name
    raw = text.get(ATLAS_KEY)
    if raw is None:
        raise ParseError(f"tile atlas {name!r} has no {ATLAS_KEY!r} text chunk; make one with 'tilekit wang texture'")
    try:
        info = json.loads(raw)
        version, tile, cols = int(info["version"]), int(info["tile"]), int(info["columns"])
        tileset = WangTileSet.from_json(info["set"])
        meta = dict(info.get("construction", {}))
    except (ValueError, KeyError, TypeError) as exc:
        raise ParseError(f"tile atlas {name!r}: its {ATLAS_KEY!r} chunk is malformed ({str(exc)[:80]})") from None
    if version != ATLAS_VERSION:
        raise ParseError(f"tile atlas {name!r} has format version {version}; this tilekit reads version {ATLAS_VERSION}")
    n = len(tileset)
    if not (MIN_TILE <= tile <= MAX_TILE) or cols < 1 or cols * tile > image.shape[1] or -(-n // cols) * tile > image.shape[0]:
        raise ParseError(f"tile atlas {name!r}: {n} tiles of {tile} px in {cols} columns do not fit its "
                         f"{image.shape[1]} x {image.shape[0]} pixels")
    i, j = np.divmod(np.arange(n), cols)
    r = np.arange(tile)
    pixels = image[(i[:, None] * tile + r)[:, :, None], (j[:, None] * tile + r)[:, None, :]]
    return TextureTiles(tileset, pixels, meta)


def check_tile_size(tile: int, tileset: WangTileSet) -> int:
    """A tile side in pixels: even, MIN_TILE..MAX_TILE, and the atlas within MAX_ATLAS_PIXELS."""
    if isinstance(tile, bool) or not isinstance(tile, int | np.integer) or not MIN_TILE <= tile <= MAX_TILE or tile % 2:
        raise ParameterError(f"tile size {tile!r} must be an even number of pixels from {MIN_TILE} to {MAX_TILE}")
    limits.refuse_over("atlas pixels", len(tileset) * tile * tile, MAX_ATLAS_PIXELS,
                       hint=f"{len(tileset)} tiles of {tile} x {tile}; give a smaller --tile")
    return int(tile)


def _solve_seams(tileset: WangTileSet, tile: int, band: int, example: np.ndarray, offsets: np.ndarray,
                 use: np.ndarray, straight: bool) -> list[SeamResult]:
    kind = tileset.kind
    seams = EDGE_SEAMS if kind == "edge" else CORNER_SEAMS
    h = tile // 2
    ex = example.astype(np.float32)
    out = []
    for spec in seams:
        frame, right, left = spec[0], spec[1], spec[2]
        inclusive = spec[3] if len(spec) > 3 else True
        pairs = np.unique(use[:, [right, left]], axis=0)
        to_frame = _FRAMES[frame]
        a = to_frame(_label_image(ex, offsets[pairs[:, 0], right], tile))  # (m, T, T, C) in the frame
        b = to_frame(_label_image(ex, offsets[pairs[:, 1], left], tile))
        e = ((a[:, :h] - b[:, :h]) ** 2).sum(axis=-1).astype(np.float64)  # (m, h, T)
        base, first, last = _seam_region(tile, kind, inclusive)
        costs = seam_cost_table(e, base, first, last, band)
        lo, hi = wedge(h, 0 if straight else band, start=1 if kind == "edge" else 0)
        path, best = min_error_paths(costs, lo, hi)
        flat = costs[:, np.arange(h), band].sum(axis=1)
        out.append(SeamResult(frame, right, left, pairs, path, best, flat, inclusive))
    return out


def _labels(tileset: WangTileSet, tile: int, seams: list[SeamResult], use: np.ndarray) -> np.ndarray:
    """(tiles, T, T) int8 label maps from the solved seams."""
    n, h = len(tileset), tile // 2
    labels = np.full((n, tile, tile), -1, dtype=np.int8)
    cc = np.arange(tile)
    for seam in seams:
        base, first, last = _seam_region(tile, tileset.kind, seam.inclusive)
        width = h if tileset.kind == "edge" else tile
        region = (cc[None, :width] >= first[:, None]) & (cc[None, :width] <= last[:, None])  # (h, width)
        row_of = {tuple(p): k for k, p in enumerate(seam.pairs.tolist())}
        which = np.array([row_of[(int(a), int(b))] for a, b in use[:, [seam.right, seam.left]]])
        bnd = base[None, :] + seam.offsets[which]  # (n, h)
        framed = np.where(cc[None, None, :width] >= bnd[:, :, None], seam.right, seam.left).astype(np.int8)
        sub = _FRAMES[seam.frame](labels)[:, :h, :width]  # a view of labels in the seam's frame
        sub[:, region] = framed[:, region]
    if (labels < 0).any():  # pragma: no cover - the regions partition the tile
        raise AssertionError("a pixel was left without a patch")
    return labels


def make_texture_tiles(example: np.ndarray, tileset: WangTileSet, tile: int = 128, band: int | None = None,
                       seed: int = 0, tries: int = 8, straight: bool = False, name: str = "",
                       positions: Any = None) -> TextureTiles:
    """The tiles of ``tileset`` made from ``example`` ((h, w, 3) uint8): source patches at
    the best of ``tries`` random draws of positions (or at ``positions``, the top-left
    corners of the patches in the order of ``meta["sources"]``, as a made set records them),
    joined by minimum-error cuts within ``band`` pixels of the straight seams (default T/4;
    ``straight`` keeps the straight seams, for comparison)."""
    tile = check_tile_size(tile, tileset)
    ex = np.asarray(example)
    if ex.dtype != np.uint8 or ex.ndim != 3 or ex.shape[2] != 3:
        raise ParameterError(f"an example is an (h, w, 3) uint8 image, got {ex.dtype} {ex.shape}")
    h = tile // 2
    band = tile // 4 if band is None else band
    if isinstance(band, bool) or not isinstance(band, int | np.integer) or not 0 <= band <= h:
        raise ParameterError(f"band {band!r} must be a whole number of pixels from 0 to {h} (half the tile)")
    if isinstance(tries, bool) or not isinstance(tries, int | np.integer) or not 1 <= tries <= 1000:
        raise ParameterError(f"tries {tries!r} must be a whole number from 1 to 1000")
    keys, use = tile_sources(tileset)
    side = window_side(tileset, tile, band)
    rng = np.random.default_rng(seed)
    draws = None
    if positions is not None:
        fixed = np.asarray(positions, dtype=np.int64)
        if fixed.shape != (len(keys), 2) or (fixed < 0).any() or (fixed[:, 0] + side > ex.shape[0]).any() \
                or (fixed[:, 1] + side > ex.shape[1]).any():
            raise ParameterError(f"positions must be {len(keys)} (row, column) corners of {side} px patches "
                                 f"inside the {ex.shape[1]} x {ex.shape[0]} example")
        draws = [fixed]
    best: tuple[float, np.ndarray, list[SeamResult]] | None = None
    for k in range(1 if draws else tries):
        positions = draws[k] if draws else candidate_positions(ex.shape[:2], len(keys), side, rng)
        offsets = label_offsets(tileset, tile, band, positions)
        seams = _solve_seams(tileset, tile, band, ex, offsets, use, straight)
        total = float(sum(s.cost.sum() for s in seams))
        if best is None or total < best[0]:
            best = (total, positions, seams)
    assert best is not None
    total, positions, seams = best
    offsets = label_offsets(tileset, tile, band, positions)
    labels = _labels(tileset, tile, seams, use)
    # pixel (r, c) of tile t: example[r + dy, c + dx] for the offsets of its label's source
    src = use[np.arange(len(tileset))[:, None, None], labels]  # (n, T, T) source index
    off = offsets[src, labels]  # (n, T, T, 2)
    r = np.arange(tile)
    ys, xs = r[None, :, None] + off[..., 0], r[None, None, :] + off[..., 1]
    if ys.min() < 0 or xs.min() < 0 or ys.max() >= ex.shape[0] or xs.max() >= ex.shape[1]:  # pragma: no cover
        raise AssertionError("a tile pixel falls outside its source patch")
    pixels = ex[ys, xs]
    meta = {
        "example": name, "example_size": [int(ex.shape[1]), int(ex.shape[0])], "tile": tile, "band": int(band),
        "seed": int(seed), "tries": int(tries), "straight": bool(straight), "kind": tileset.kind,
        "sources": [f"{o}:{k}" for o, k in keys], "positions": positions.tolist(), "window": side,
        "cut_error": total, "straight_error": float(sum(s.straight.sum() for s in seams)),
    }
    return TextureTiles(tileset, pixels, meta, labels, seams)
