"""Textures of any size from textured Wang tiles (§7.5): a fill of the tile lattice, turned
into pixels block by block of rows and streamed to a PNG, or any window of the unbounded
texture computed alone.

The texture's pixel (X, Y) (Y down) lies in tile column X // T and tile row Y // T, which is
the lattice square (X // T, -1 - Y // T) of the fills (y up). Two fills:

- **random access** (Lagae and Dutré; sets with a tile for every corner colouring, or every
  edge colouring): the tile of a square is a hash of its lattice points or edges, so any
  window is computed without the rest and equals the same window of a full render;
- **scanline** (Cohen et al.; complete edge sets): the fill of
  :func:`~tilekit.plugins.wang.fill.scanline_rows`, one block of tile rows at a time from
  the top, each continuing from the south colours of the last.

Either way a block of pixel rows is one gather of tile pixel rows (``TextureTiles.rows``),
so the memory in use is one block (about :data:`CHUNK_BYTES`), whatever the texture's size.
"""

from __future__ import annotations

import math
import shutil
import zlib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from tilekit import limits
from tilekit.errors import ParameterError
from tilekit.plugins.wang.fill import random_access_fill, scanline_rows, supports_random_access
from tilekit.plugins.wang.quality import SeamStats, repetition
from tilekit.plugins.wang.texture import TextureTiles, load_texture_tiles
from tilekit.plugins.wang.tileset import WangTileSet
from tilekit.pngstream import IDAT_BYTES, PngWriter, filter_rows

#: Fills a texture can use (``wang synth --method``).
METHODS = ("auto", "random-access", "scanline")
#: Largest width or height of a synthesised texture (pixels; limits.py).
MAX_SIDE = limits.MAX_TEXTURE_SIDE
#: Largest |x0|, |y0| of a window of the unbounded texture (pixels): tile coordinates stay far
#: inside the lattice hash's int64 range.
MAX_ORIGIN = 1 << 48
#: Bytes of pixels in one block of rows.
CHUNK_BYTES = 8 << 20
#: Margin on the sampled compression ratio when a PNG's size is estimated, and the most bytes
#: of rows the sample compresses.
SIZE_MARGIN = 1.25
SAMPLE_BYTES = 2 << 20
#: Default zlib level and PNG filter of a texture (docs/benchmarks.md measures the choices).
LEVEL = 6
FILTER = "none"


def choose_method(tileset: WangTileSet, method: str = "auto") -> str:
    """The fill a set can use: random access when it has a tile for every corner (or edge)
    colouring, else the scanline fill of a complete set; ParameterError otherwise."""
    if method not in METHODS:
        raise ParameterError(f"texture fill {method!r} is not one of {', '.join(METHODS)}")
    ra, sc = supports_random_access(tileset), tileset.complete and tileset.corners is None
    if method == "auto":
        if ra or sc:
            return "random-access" if ra else "scanline"
    elif method == "random-access" and ra:
        return method
    elif method == "scanline" and sc:
        return method
    able = [m for m, ok in (("random-access", ra), ("scanline", sc)) if ok]
    raise ParameterError(
        f"set {tileset.name!r} cannot be filled by {'any streamed fill' if method == 'auto' else method}: "
        + (f"it can use {', '.join(able)}" if able else
           "texture synthesis needs a complete edge set (scanline, e.g. stochastic-2colour) or a set with "
           "a tile for every corner colouring (random access, e.g. corner-2colour)")
    )


def check_window(width: int, height: int, x0: int = 0, y0: int = 0) -> tuple[int, int, int, int]:
    """A texture window: 1..MAX_SIDE pixels each way, |x0|, |y0| <= MAX_ORIGIN."""
    for name, v, lo, hi in (("width", width, 1, MAX_SIDE), ("height", height, 1, MAX_SIDE),
                            ("x0", x0, -MAX_ORIGIN, MAX_ORIGIN), ("y0", y0, -MAX_ORIGIN, MAX_ORIGIN)):
        if isinstance(v, bool) or not isinstance(v, int | np.integer) or not lo <= v <= hi:
            raise ParameterError(f"texture {name} {v!r} must be a whole number from {lo} to {hi}")
    return int(width), int(height), int(x0), int(y0)


def _grid_blocks(tex: TextureTiles, method: str, seed: int, i0: int, i1: int, j0: int, cols: int,
                 block: int) -> Iterator[tuple[int, np.ndarray]]:
    """(first tile row, grid of tile rows first .. first + k - 1) for tile rows i0..i1."""
    ts = tex.tileset
    if method == "scanline":
        start = 0
        for grid in scanline_rows(ts, i1 + 1, cols, seed, block=block):
            yield start, grid
            start += len(grid)
        return
    for i in range(i0, i1 + 1, block):
        k = min(block, i1 + 1 - i)
        # tile row i is the lattice row y = -1 - i; the fill's row 0 is its northernmost
        yield i, random_access_fill(ts, k, cols, x0=j0, y0=-(i + k), seed=seed)


def _row_blocks(tex: TextureTiles, width: int, height: int, method: str, seed: int, x0: int, y0: int,
                chunk_bytes: int | None) -> Iterator[tuple[int, np.ndarray, int, int]]:
    """Blocks of texture rows as (first row's offset in the window, index (k, cols) into
    ``tex.rows`` flattened to (tiles * T, 3T), xoff, cols): a block's pixels are that index
    gathered, (k, cols * T, 3), cropped to columns xoff .. xoff + width."""
    width, height, x0, y0 = check_window(width, height, x0, y0)
    method = choose_method(tex.tileset, method)
    if method == "scanline" and (x0, y0) != (0, 0):
        raise ParameterError("the scanline fill starts at the texture's top-left corner; a window at "
                             f"({x0}, {y0}) needs a set with random access (e.g. corner-2colour)")
    t = tex.tile
    j0, j1 = x0 // t, (x0 + width - 1) // t
    i0, i1 = y0 // t, (y0 + height - 1) // t
    cols = j1 - j0 + 1
    rows_per_chunk = max(1, int(CHUNK_BYTES if chunk_bytes is None else chunk_bytes) // (cols * t * 3))
    tiles_per_block = max(1, rows_per_chunk // t)
    for ia, grid in _grid_blocks(tex, method, seed, i0, i1, j0, cols, tiles_per_block):
        lo = max(y0, ia * t)
        hi = min(y0 + height, (ia + len(grid)) * t)
        for ya in range(lo, hi, rows_per_chunk):
            y = np.arange(ya, min(hi, ya + rows_per_chunk))
            yield ya - y0, grid[y // t - ia] * t + (y % t)[:, None], x0 - j0 * t, cols


def texture_rows(tex: TextureTiles, width: int, height: int, method: str = "auto", seed: int = 0,
                 x0: int = 0, y0: int = 0, chunk_bytes: int | None = None) -> Iterator[np.ndarray]:
    """The texture's pixels in the window [x0, x0 + width) x [y0, y0 + height) as blocks of
    rows from the top, (k, width, 3) uint8 each, about ``chunk_bytes`` (default
    :data:`CHUNK_BYTES`) a block. The scanline fill starts at the texture's origin, so a
    window away from it needs random access."""
    t = tex.tile
    source = tex.rows.reshape(-1, 3 * t)  # tile pixel rows: row r of tile k is k * T + r
    for _, index, xoff, cols in _row_blocks(tex, width, height, method, seed, x0, y0, chunk_bytes):
        block = source[index].reshape(len(index), cols * t, 3)
        yield block if xoff == 0 and cols * t == width else block[:, xoff:xoff + width]


def texture_window(tex: TextureTiles, x0: int, y0: int, width: int, height: int, seed: int = 0) -> np.ndarray:
    """The pixels of one window of the unbounded texture, (height, width, 3) uint8, by random
    access: equal to the same window of any larger render with the same seed."""
    return render_texture(tex, width, height, method="random-access", seed=seed, x0=x0, y0=y0)


def render_texture(tex: TextureTiles, width: int, height: int, method: str = "auto", seed: int = 0,
                   x0: int = 0, y0: int = 0) -> np.ndarray:
    """A whole texture in memory, (height, width, 3) uint8 (refused when it would not fit)."""
    width, height, x0, y0 = check_window(width, height, x0, y0)
    limits.refuse_over_memory("texture pixels", float(width) * height, 3.0,
                              hint="stream it to a file instead (write_texture)")
    out = np.empty((height, width, 3), dtype=np.uint8)
    t = tex.tile
    source = tex.rows.reshape(-1, 3 * t)
    # one block: the output is in memory anyway, and one gather is the fastest
    whole = (height + 2 * t) * (width + 2 * t) * 3
    for y, index, xoff, cols in _row_blocks(tex, width, height, method, seed, x0, y0, whole):
        k = len(index)
        if xoff == 0 and cols * t == width:  # gather straight into the output
            np.take(source, index, axis=0, out=out[y:y + k].reshape(k, cols, 3 * t), mode="clip")  # unbuffered
        else:
            out[y:y + k] = source[index].reshape(k, cols * t, 3)[:, xoff:xoff + width]
    return out


def estimate_png_bytes(sample: np.ndarray, width: int, height: int, level: int = LEVEL, filter: str = FILTER) -> float:
    """Bytes of a PNG of ``width`` x ``height`` RGB pixels like ``sample`` (a block of its rows):
    the sample's compressed size per row, scaled to the height, times SIZE_MARGIN, plus the
    chunks' overhead."""
    rows = sample.reshape(len(sample), -1)
    rows = rows[:max(1, SAMPLE_BYTES // rows.shape[1])]
    filtered = filter_rows(rows, np.zeros(rows.shape[1], dtype=np.uint8), 3, filter)
    packed = zlib.compress(filtered.tobytes(), level)
    per_row = len(packed) / len(rows)
    data = per_row * height * SIZE_MARGIN
    return data + 12 * (data / IDAT_BYTES + 4) + 1024


def check_disk(path: str | Path, size: float) -> None:
    """LimitError (one line) when ``size`` bytes would not fit in the free space where ``path``
    is written (``shutil.disk_usage``)."""
    folder = Path(path).absolute().parent
    if not folder.is_dir():
        return  # (a missing folder fails when the file is opened)
    free = float(shutil.disk_usage(folder).free)
    if size > free:
        raise limits.LimitError(
            f"{Path(path).name} would take about {size / 2**30:.3g} GiB (estimated from the compression of its "
            f"first rows), more than the {free / 2**30:.3g} GiB free in {folder}; ask for a smaller --width/--height"
        )


def write_texture(tex: TextureTiles, path: str | Path, width: int, height: int, method: str = "auto",
                  seed: int = 0, x0: int = 0, y0: int = 0, level: int = LEVEL, filter: str = FILTER,
                  threads: int = 1, progress: Callable[[int], Any] | None = None,
                  measure: Any = None) -> dict[str, Any]:
    """Stream a texture to a PNG, row block by row block: first its size is estimated from
    its first block and refused (LimitError) when it exceeds the free disk space; a failure
    while writing removes the unfinished file. ``progress(rows)`` is called after each block,
    ``measure.feed(block, y)`` (e.g. a :class:`~tilekit.plugins.wang.quality.SeamStats`)
    sees every block; ``threads`` compress in parallel (:class:`~tilekit.pngstream.PngWriter`).
    Returns what was written."""
    p = Path(path)
    if p.suffix.lower() != ".png":
        raise ParameterError(f"a texture is written as .png, not {str(path)!r}")
    width, height, x0, y0 = check_window(width, height, x0, y0)
    method = choose_method(tex.tileset, method)
    blocks = texture_rows(tex, width, height, method, seed, x0, y0)
    first = next(blocks)
    estimate = estimate_png_bytes(first, width, height, level, filter)
    check_disk(p, estimate)
    text = {"Software": "tilekit wang synth",
            "Description": f"{tex.tileset.name} texture, {tex.tile} px tiles, {method} fill, seed {seed}, "
                           f"window ({x0}, {y0}) {width} x {height}"}
    y = y0
    with PngWriter(p, width, height, 3, level=level, filter=filter, text=text, threads=threads) as png:
        for block in _chain(first, blocks):
            png.write(block)
            if measure is not None:
                measure.feed(block, y, x0)
            y += len(block)
            if progress is not None:
                progress(len(block))
    return {"path": str(p), "width": width, "height": height, "method": method, "bytes": png.bytes_written,
            "estimate": int(math.ceil(estimate))}


def _chain(first: np.ndarray, rest: Iterator[np.ndarray]) -> Iterator[np.ndarray]:
    yield first
    yield from rest


def synthesize(tiles_path: str | Path, path: str | Path, width: int, height: int, *, method: str = "auto",
               seed: int = 0, x0: int = 0, y0: int = 0, level: int = LEVEL, threads: int = 1,
               progress: Callable[[int], Any] | None = None, stats: bool = False) -> dict[str, Any]:
    """``tilekit wang synth``: the tile atlas at ``tiles_path`` (:func:`load_texture_tiles`)
    assembled into a ``width`` x ``height`` texture streamed to the PNG ``path``
    (:func:`write_texture`). Returns what :func:`write_texture` does plus ``tileset`` (the set's
    name) and, with ``stats``, ``seams`` (SeamStats over every block) and ``repetition`` (the
    autocorrelation peak of a crop of at most 1024 px a side)."""
    tex = load_texture_tiles(tiles_path)
    measure = SeamStats(tex.tile) if stats else None
    done = write_texture(tex, path, width, height, method=method, seed=seed, x0=x0, y0=y0, level=level,
                         threads=threads, progress=progress, measure=measure)
    done["tileset"] = tex.tileset.name
    if measure is not None:
        side = min(width, height, 1024)
        done["seams"] = measure.result()
        done["repetition"] = repetition(render_texture(tex, side, side, done["method"], seed, x0, y0), tex.tile)
    return done
