"""The compiled loop of the scanline fill (numba): cell by cell in row-major order.

Row-major order is the scanline method itself (Cohen et al., §7.5): every cell's north and
west neighbours are placed before it. The draw for cell (i, j) uses ``u[i, j]``, so the
grid depends only on the seed.
"""

from __future__ import annotations

from tilekit.jit import njit


@njit(cache=True, nogil=True)
def scanline_loop(choices, counts, south, east, u, grid, north):  # pragma: no cover - compiled
    """Fill ``grid`` (rows, cols): cell (i, j) gets ``choices[n, w, k]`` with n the south
    colour above (on the first row ``north[j]``: ANY = counts.shape[0] - 1 at the top of a
    fill, the last row's south colours when a fill continues), w the east colour to the
    left (ANY in the first column) and k = floor(u[i, j] * counts[n, w])."""
    rows, cols = grid.shape
    any_ = counts.shape[0] - 1
    for i in range(rows):
        w = any_
        for j in range(cols):
            n = north[j] if i == 0 else south[grid[i - 1, j]]
            k = int(u[i, j] * counts[n, w])
            t = choices[n, w, k]
            grid[i, j] = t
            w = east[t]
