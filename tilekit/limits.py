"""One home for the size limits of everything tilekit can make, and the check that refuses.

A command that can make a large object first *estimates* its size (``Tiling.estimate_tiles``,
the grid and SAT sizes of a Wang question, the pixels of a PNG) and calls :func:`refuse_over`
before allocating anything. The refusal is a :class:`LimitError` (a ``TilekitError``, so the
CLI prints it as one line and exits 2) naming the estimate, the limit and the option that
raises it.

The defaults are sized so that a refused object would need more than a few GB: a placed tile
costs about 100 bytes as arrays and several hundred more as SVG text.
"""

from __future__ import annotations

import math

from tilekit.errors import TilekitError

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
