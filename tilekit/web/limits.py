"""Render limits for the web server: how many tiles a render request may draw.

``check_render_size(tiling, region, depth)`` uses ``Tiling.estimate_tiles(region)`` (the
same estimate ``tilekit render`` checks against ``--max-tiles``; a depth is already part of
a configured tiling), and for objects without it a conservative estimate of its own: for a fixed substitution depth, the exact tile count of
that many substitutions of the seed tile (``M^depth e`` from the system's matrix); for
anything else the region's area over the smallest prototile's area, times four (tiles that
only touch the region are drawn too).
"""

from __future__ import annotations

import math
from typing import Any

from tilekit.errors import ParameterError, TilekitError

#: Tiles one render request may draw (``tilekit serve --max-tiles``): smaller than the
#: command line's ``tilekit.limits.MAX_TILES``, since a browser draws every tile it is sent.
DEFAULT_MAX_TILES = 20_000

# the server's connection limits (tilekit.web.server, set by tilekit serve)
#: Seconds a client has to send a whole request head (``tilekit serve --head-seconds``).
HEAD_SECONDS = 10.0
#: Seconds an idle keep-alive connection stays open after a response.
KEEP_ALIVE_SECONDS = 5
#: The largest request head (request line and headers) h11 buffers: above the app's own
#: 8 KiB query and 2 KiB path limits, so their 414 is the app's JSON.
MAX_HEAD_BYTES = 2 << 20
#: Open connections (and requests in flight) before uvicorn answers 503 itself.
MAX_CONNECTIONS = 1000
#: Seconds the server waits for requests in flight when told to stop.
GRACEFUL_SECONDS = 10


class RenderTooLarge(TilekitError):
    """A render request would draw more tiles than the limit (HTTP 413)."""

    def __init__(self, estimate: int, limit: int, what: str = "") -> None:
        self.estimate = int(estimate)
        self.limit = int(limit)
        name = f"{what}: " if what else ""
        super().__init__(
            f"{name}this render would draw about {self.estimate:,} tiles; the limit is {self.limit:,} "
            "per request (use a smaller region or depth)"
        )


def _area(region: Any) -> float:
    if region is None:
        return 0.0
    if hasattr(region, "area"):
        return float(region.area)
    x0, y0, x1, y1 = region
    return float((x1 - x0) * (y1 - y0))


def estimate_tiles(tiling: Any, region: Any, depth: int | None = None) -> int:
    """An upper estimate of the tiles ``tiling.patch(region)`` draws at ``depth``."""
    own = getattr(tiling, "estimate_tiles", None)
    if callable(own):
        if depth is not None and callable(getattr(tiling, "configure", None)):
            try:
                own = tiling.configure(depth=depth).estimate_tiles
            except TypeError:  # a family without depths: the estimate is the region's
                pass
        value = float(own(region))
        return int(value) if math.isfinite(value) and value < 2**62 else 2**62
    if depth is None:
        depth = getattr(tiling, "depth", None)
    system = getattr(tiling, "system", None)
    if depth is not None and system is not None and hasattr(system, "counts"):
        try:
            return int(sum(system.counts(int(depth))[-1]))
        except (TilekitError, ValueError, TypeError, IndexError):
            pass
    areas = []
    for proto in getattr(tiling, "prototiles", ()) or ():
        a = getattr(proto, "area", None)
        if a is not None and math.isfinite(float(a)) and float(a) > 0:
            areas.append(float(a))
    if not areas:
        return 0
    return int(math.ceil(4 * _area(region) / min(areas)))


def check_render_size(tiling: Any, region: Any, depth: int | None = None,
                      limit: int = DEFAULT_MAX_TILES) -> int:
    """The estimate, or :class:`RenderTooLarge` (naming the estimate and the limit) above ``limit``."""
    if depth is not None and (not isinstance(depth, int) or depth < 0):
        raise ParameterError(f"depth {depth!r} must be a whole number >= 0")
    estimate = estimate_tiles(tiling, region, depth)
    if estimate > limit:
        raise RenderTooLarge(estimate, limit, getattr(tiling, "name", "") or "")
    return estimate
