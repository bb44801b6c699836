"""One home for the size limits of everything tilekit can make, and the check that refuses.

A command that can make a large object first *estimates* its size (``Tiling.estimate_tiles``,
the grid and SAT sizes of a Wang question, the pixels of a PNG) and calls :func:`refuse_over`
before allocating anything. The refusal is a :class:`LimitError` (a ``TilekitError``, so the
CLI prints it as one line and exits 2) naming the estimate, the limit and the option that
raises it.

The defaults are sized so that a refused object would need more than a few GB: a placed tile
costs 80-90 bytes as a Patch's arrays ((3, 3) float64 map, int64 prototile, colour) and
several hundred more as SVG text. Making it peaks higher, because the previous level of a
substitution is alive while the last one is made (GENERATION_BYTES_PER_TILE) and a periodic
patch's lattice points are filtered in blocks (PERIODIC_BYTES_PER_TILE). Every per-unit cost
here is a measured peak (benchmarks/bench_limits.py, docs/benchmarks.md "Limits, measured"),
and tests/test_limits_measured.py fails when an estimate is off by more than 2x. Whatever
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
#: Boolean variables of one SAT encoding (``wang solve --max-variables``); what a question
#: costs in memory is SAT_BYTES_PER_VARIABLE and SAT_BYTES_PER_CLAUSE, checked as well.
MAX_SAT_VARIABLES = 5_000_000
#: Peak bytes of one SAT question (clause blocks, python-sat's CaDiCaL 1.9.5, the model) per
#: variable and per clause, fitted to 7 Wang encodings of 0.1-0.9 M variables and 0.5-2.1 M
#: clauses (each within 0.83-1.21x; docs/benchmarks.md "Limits, measured";
#: tests/test_limits_measured.py keeps them within 2x of what a solve takes).
SAT_BYTES_PER_VARIABLE = 70
SAT_BYTES_PER_CLAUSE = 230
#: Colours of one periodic colouring (``--set colouring=``).
MAX_COLOURS = 1_000
#: Pixels of one PNG image (width x height).
MAX_PNG_PIXELS = 100_000_000
#: Largest |coordinate| of a region: beyond it, float spacing is too coarse to place tiles.
MAX_COORDINATE = 1e9
#: Largest substitution depth any system accepts (the tile estimate is the real bound).
MAX_DEPTH = 60
#: Peak bytes per tile while a substitution patch is made through the API (generation,
#: culling to the region, assembly, colours): peak resident growth measured 269-648 on
#: Penrose P3, chair, spectre, hat and Ammann-Beenker patches of 35,000-4,200,000 tiles
#: (the engine alone, by tracemalloc, 94-163); docs/benchmarks.md "Limits, measured".
GENERATION_BYTES_PER_TILE = 450
#: Peak bytes per tile of a periodic patch (PeriodicTiling.patch): measured 120-290 on
#: 3.4.6.4, 4^4 and IH41 patches of 335,000-4,000,000 tiles.
PERIODIC_BYTES_PER_TILE = 200
#: Peak bytes per tile while a patch is drawn as SVG (measured about 405 for Penrose
#: rhombs: the polygons, the path text and the document), with a margin.
RENDER_BYTES_PER_TILE = 500
#: Peak bytes per outline vertex of a tile written as each format (SVG text and its polygons,
#: GeoJSON coordinates, JSON / cut SVG / DXF: the adjacency, ADJACENCY_BYTES_PER_VERTEX): a
#: tile with shaped edges of hundreds of vertices costs them. Measured on IH16 with 6, 106 and
#: 406 vertices a tile (100-163 / 138-200 / 245-296 bytes a vertex; docs/benchmarks.md
#: "Limits, measured"), rounded up.
EXPORT_BYTES_PER_VERTEX = {".svg": 125, ".png": 125, ".geojson": 220, ".json": 300, ".cut.svg": 300, ".dxf": 300}
#: Points of one edge shape (``--edge``, after a Bézier is flattened): checking a tile for
#: overlaps (Patch.validate of its 3 x 3 units) grows with its outline vertices squared:
#: IH16 with 106 / 206 / 406 / 1,606 vertices peaked at 26 / 78 / 179 / 1,800 MB (0.2-10 s),
#: so 100 points an edge keep a tile near 400-600 vertices and 0.2-0.4 GB.
MAX_EDGE_POINTS = 100
#: Tiles a notebook draws inline (``_repr_svg_`` of a Patch, Tiling or catalogue entry);
#: over it a short line of text is shown instead of a giant SVG.
MAX_REPR_TILES = 5_000
#: Tiles of one DXF file: ezdxf builds the whole drawing in memory as Python objects, 2.0-3.5 kB
#: and 0.12-0.27 ms per tile (measured, docs/benchmarks.md), so 200,000 tiles is ~700 MB and up to
#: a minute; GeoJSON, JSON and the cut SVG are streamed and need no limit of their own.
MAX_DXF_TILES = 200_000
#: Peak bytes per outline vertex of a tile while the adjacency of a patch is computed (welded
#: vertices, edges split at T-junctions, pairs): measured 203 (Penrose P3, 4 vertices), 218
#: (chair, 6), 195 (3.4.6.4, 6) and 282 (pentomino-F, 10: its edges are split) bytes a vertex
#: of the largest prototile; docs/benchmarks.md "Limits, measured".
ADJACENCY_BYTES_PER_VERTEX = 300
#: Tiles per chunk of a streamed substitution patch (``Tiling.iter_patches``, ``tilekit
#: render`` past what fits in memory): about GENERATION_BYTES_PER_TILE each while a chunk
#: is made, so ~450 MB, or less when less memory is available.
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

#: Seconds one solver or builder call runs when its caller gives no budget of its own
#: (``wang solve --time-limit``, ``wang render --time-limit``, PatchBuilder.build's
#: max_seconds): CPU seconds (tilekit.budget) for a SAT solver, the builder and the Wang
#: backtracking search alike; it ends with a one-line SolverLimit naming the option that raises it.
DEFAULT_SOLVER_SECONDS = 60.0
#: The largest time budget an option accepts (seconds; a finite number, about 115 days).
MAX_SOLVER_SECONDS = 1e7

#: Peak bytes per tile the patch builder places (tilekit.builder: vertex stars, the frontier,
#: the grid index; measured on Wang rectangles of 1,600-6,400 cells, 5.8-6.5 kB) and per tile
#: of a torus (each tile's lattice images are placed too: 42.6-43.3 kB on 900-3,600 cells).
BUILDER_BYTES_PER_TILE = 6_500
BUILDER_BYTES_PER_TORUS_TILE = 45_000

#: Tiles of one Wang tile set (a .wang file or a spec): the solvers' sizes grow with it.
MAX_WANG_TILES = 10_000

# ---- users' files (issue 27): tilekit.files reads only regular files, bounded in size
#: Bytes of one data file a user gives (a TOML system or texture, a .wang set, a JSON spec,
#: a PNG density): the largest shipped file is under 100 kB, a 40,000-tile .wang set 0.6 MB.
MAX_FILE_BYTES = 16 << 20
#: Depth of nested lists and tables in a JSON or TOML document (tilekit.schema.parse_json /
#: parse_toml): the deepest shipped data nests 5 levels; Python's parsers recurse per level.
MAX_NESTING = 32

# ---- Escherization goals and the shape metric (tilekit.escher; every family's fits)
#: Goal polygons have at least 3 and at most this many vertices (after dropping repeats).
MAX_GOAL_POINTS = 20_000
#: A goal file larger than this is refused before it is read (bytes).
MAX_GOAL_BYTES = 5_000_000
#: Resampled points per outline (``--samples``): default and bounds; one evaluation costs
#: O(n log n) for the alignment and O(n k^2) for the projection of k control coordinates.
DEFAULT_SAMPLES = 128
MIN_SAMPLES, MAX_SAMPLES = 16, 2048
#: Worker processes of an Escherization run (``--workers``) at most.
MAX_FIT_WORKERS = 64


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


def sat_bytes(variables: float, clauses: float) -> float:
    """Peak bytes of a SAT question of this size (SAT_BYTES_PER_VARIABLE, SAT_BYTES_PER_CLAUSE)."""
    return SAT_BYTES_PER_VARIABLE * variables + SAT_BYTES_PER_CLAUSE * clauses


def available_memory() -> float:
    """Bytes of memory available to a new allocation: MemAvailable of /proc/meminfo (else the
    free physical pages), and no more than what this process's address-space limit
    (RLIMIT_AS, e.g. ``ulimit -v``) or its cgroup's memory.max leaves; inf when nothing says."""
    avail = math.inf
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    avail = float(line.split()[1]) * 1024
                    break
    except OSError:
        pass
    if math.isinf(avail):
        try:
            avail = float(os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
        except (ValueError, OSError, AttributeError):
            pass
    return min(avail, _address_space_left(), _cgroup_left())


def _status_bytes(key: str) -> float | None:
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith(key):
                    return float(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def _address_space_left() -> float:
    """RLIMIT_AS minus the address space in use (VmSize), or inf without a limit."""
    try:
        import resource

        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    except (ImportError, OSError, ValueError):
        return math.inf
    if soft == resource.RLIM_INFINITY:
        return math.inf
    used = _status_bytes("VmSize:")
    return max(0.0, soft - (used or 0.0))


def _cgroup_left() -> float:
    """The cgroup v2 memory.max minus memory.current, or inf without one."""
    try:
        with open("/sys/fs/cgroup/memory.max", encoding="ascii") as fh:
            text = fh.read().strip()
        if text == "max":
            return math.inf
        with open("/sys/fs/cgroup/memory.current", encoding="ascii") as fh:
            return max(0.0, float(text) - float(fh.read().strip()))
    except (OSError, ValueError):
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
