"""One home for the size limits of everything tilekit can make, and the check that refuses.

A command that can make a large object first *estimates* its size (``Tiling.estimate_tiles``,
the grid and SAT sizes of a Wang question, the pixels of a PNG) and calls :func:`refuse_over`
before allocating anything. The refusal is a :class:`LimitError` (a ``TilekitError``, so the
CLI prints it as one line and exits 2) naming the estimate, the limit and the option that
raises it.

The defaults are sized so that a refused object would need more than a few GB: a placed tile
costs 80-90 bytes as a Patch's arrays ((3, 3) float64 map, int64 prototile, colour) and
several hundred more as SVG text. Generating it peaks higher, because the previous level of
a substitution is alive while the last one is made: 94-163 bytes per tile measured at 10^6
tiles (tracemalloc, docs/benchmarks.md), which GENERATION_BYTES_PER_TILE bounds. Whatever
the tile limits are raised to, :func:`refuse_over_memory` refuses a patch whose arrays
would not fit in the memory the machine has available; a substitution patch can instead be
streamed in chunks (``Tiling.iter_patches``, STREAM_CHUNK_TILES), which ``tilekit render``
does for the formats written from a stream (``export.STREAM_FORMATS``).
"""

from __future__ import annotations

import math
import numbers
import os

from tilekit.errors import ParameterError, TilekitError

#: Tiles in one rendered patch (``tilekit render --max-tiles``).
MAX_TILES = 2_000_000
#: Cells of one Wang grid drawn by ``wang render`` (``--max-tiles``).
MAX_GRID_CELLS = 1_000_000
#: Cells of one ``wang solve`` question (``--max-tiles``).
MAX_SOLVE_CELLS = 1_000_000
#: Boolean variables of one SAT encoding, cells x tiles (``wang solve --max-variables``);
#: a variable with its clauses costs about 200 bytes.
MAX_SAT_VARIABLES = 5_000_000
#: Colours of one periodic colouring (``--set colouring=``).
MAX_COLOURS = 1_000
#: Pixels of one PNG image (width x height).
MAX_PNG_PIXELS = 100_000_000
#: Largest |coordinate| of a region: beyond it, float spacing is too coarse to place tiles.
MAX_COORDINATE = 1e9
#: Largest substitution depth any system accepts (the tile estimate is the real bound).
MAX_DEPTH = 60
#: Peak bytes per tile while a substitution patch is generated (measured 94-163 at 10^6
#: tiles for every generator; see docs/benchmarks.md), with a margin.
GENERATION_BYTES_PER_TILE = 200
#: Peak bytes per tile while a patch is drawn as SVG (measured about 405 for Penrose
#: rhombs: the polygons, the path text and the document), with a margin.
RENDER_BYTES_PER_TILE = 500
#: Tiles a notebook draws inline (``_repr_svg_`` of a Patch, Tiling or catalogue entry);
#: over it a short line of text is shown instead of a giant SVG.
MAX_REPR_TILES = 5_000
#: Tiles of one DXF file: ezdxf builds the whole drawing in memory as Python objects, 2.0-3.5 kB
#: and 0.12-0.27 ms per tile (measured, docs/benchmarks.md), so 200,000 tiles is ~700 MB and up to
#: a minute; GeoJSON, JSON and the cut SVG are streamed and need no limit of their own.
MAX_DXF_TILES = 200_000
#: Peak bytes per tile while the adjacency of a patch is computed (measured 0.9-1.0 kB for
#: 3.4.6.4 and Penrose rhombs, 1.4 kB for the chair and 2.3 kB for pentomino-F, whose edges
#: are split at T-junctions; docs/benchmarks.md), with a margin.
ADJACENCY_BYTES_PER_TILE = 3_000
#: Tiles per chunk of a streamed substitution patch (``Tiling.iter_patches``, ``tilekit
#: render`` past what fits in memory): about GENERATION_BYTES_PER_TILE each while a chunk
#: is made, so ~200 MB, or less when less memory is available.
STREAM_CHUNK_TILES = 1 << 20
#: Fraction of the available memory one patch may take.
MEMORY_FRACTION = 0.8
#: Wang textures (§7.5): width and height of a streamed texture (``wang synth``), the tile side
#: (``wang texture --tile``), all tiles of one atlas (2^26 RGB pixels are 192 MiB), an example
#: image's pixels, and the bytes of an image file read (example or atlas).
MAX_TEXTURE_SIDE = 1 << 16
MAX_TEXTURE_TILE = 1024
MAX_ATLAS_PIXELS = 1 << 26
MAX_EXAMPLE_PIXELS = 4096 * 4096
MAX_IMAGE_BYTES = 256 << 20


class LimitError(TilekitError, ValueError):
    """An object would exceed a size limit; the message names estimate, limit and option."""


def _fmt(n: float) -> str:
    if not math.isfinite(n):
        return "unboundedly many"
    if n >= 1e15:
        return f"{n:.3g}"
    return f"{int(round(n)):,}"


def refuse_over(what: str, estimate: float, limit: float, option: str | None = None, hint: str = "") -> None:
    """Raise LimitError when ``estimate`` (of ``what``, e.g. 'tiles') exceeds ``limit``.

    ``option`` is the command-line option that raises the limit (``--max-tiles``).
    """
    if not math.isnan(estimate) and estimate <= limit:
        return
    msg = f"this would make about {_fmt(estimate)} {what}, over the limit of {_fmt(limit)}"
    if hint:
        msg += f"; {hint}"
    if option:
        msg += f" (raise it with {option} N, or ask for less)"
    raise LimitError(msg)


def check_chunk_tiles(chunk_tiles: object) -> int:
    """A chunk size (tiles per chunk of a stream) as a positive int, or ParameterError."""
    if isinstance(chunk_tiles, bool) or not isinstance(chunk_tiles, numbers.Integral) or chunk_tiles < 1:
        raise ParameterError(f"chunk size {chunk_tiles!r} must be a positive whole number of tiles")
    return int(chunk_tiles)


def check_coordinates(bounds: tuple[float, float, float, float], what: str = "region") -> None:
    """A region whose coordinates are not finite or beyond ±MAX_COORDINATE is an error."""
    if not all(math.isfinite(v) for v in bounds):
        raise LimitError(f"{what} {tuple(bounds)} has a non-finite coordinate")
    big = max(abs(v) for v in bounds)
    if big > MAX_COORDINATE:
        raise LimitError(
            f"{what} coordinate {big:.3g} is beyond ±{MAX_COORDINATE:.0e}, where tiles cannot be "
            "placed accurately; use a region nearer the origin"
        )


def available_memory() -> float:
    """Bytes of memory available to a new allocation (MemAvailable of /proc/meminfo, else
    the free physical pages; inf when the system says neither)."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        return float(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):
        return math.inf


def fits_in_memory(count: float, bytes_each: float) -> bool:
    """Whether ``count`` objects of ``bytes_each`` bytes take at most MEMORY_FRACTION of the
    available memory."""
    need = count * bytes_each
    return not math.isnan(need) and need <= MEMORY_FRACTION * available_memory()


def refuse_over_memory(what: str, count: float, bytes_each: float, hint: str = "") -> None:
    """Raise LimitError when ``count`` objects of ``bytes_each`` bytes would take more than
    MEMORY_FRACTION of the available memory: checked before allocating, whatever the count
    limits were raised to."""
    need = count * bytes_each
    avail = available_memory()
    if not fits_in_memory(count, bytes_each):
        msg = (f"this would make about {_fmt(count)} {what}, about {need / 2**30:.3g} GiB at "
               f"{bytes_each:g} bytes each, more than the {avail / 2**30:.3g} GiB of memory available")
        if hint:
            msg += f"; {hint}"
        raise LimitError(msg)
