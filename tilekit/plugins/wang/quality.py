"""Measures of a synthesised texture (§7.5): are the tile edges and the cuts visible, and does
the texture repeat?

- **Seam error** (:class:`SeamStats`): the mean squared colour difference of horizontally or
  vertically adjacent pixels, over the pairs that straddle a tile edge against the pairs
  inside tiles. Tile edges run through the middle of a source patch, so a good tile set has a
  ratio near 1; it is fed block by block, so it measures a streamed texture of any size.
- **Cut error** (:func:`cut_error`): the same difference over the pairs of pixels inside a tile
  that came from two different source patches (across a cut), against the pairs from one.
- **Repetition** (:func:`repetition`): the largest normalised autocorrelation (Pearson's r of
  the luminance with its shifted self over the overlap) at lags of at least half a tile. A
  periodic tiling of one tile scores 1 at the lag of one tile; a texture from several tiles
  scores less, the less the more patches a tile can show.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from tilekit.errors import ParameterError

#: The largest side of the crop the autocorrelation is computed on.
MAX_CORRELATION_SIDE = 1024


def _lum(image: np.ndarray) -> np.ndarray:
    a = np.asarray(image, dtype=np.float64)
    return a if a.ndim == 2 else a[..., :3] @ np.array([0.299, 0.587, 0.114])


@dataclass
class SeamStats:
    """Sums of squared differences of adjacent pixels (mean over channels), split into pairs
    across a tile edge and pairs inside tiles, for a texture fed block by block
    (:meth:`feed`; blocks in order from the top). Tiles are ``tile`` pixels square and the
    lattice's lines are at multiples of ``tile`` in texture coordinates."""

    tile: int
    edge_sum: float = 0.0
    edge_pairs: int = 0
    inside_sum: float = 0.0
    inside_pairs: int = 0
    _last: np.ndarray | None = None
    _last_y: int | None = None

    def feed(self, block: np.ndarray, y: int, x0: int = 0) -> None:
        """Add a block of rows whose first row is texture row ``y`` and first column ``x0``."""
        b = np.asarray(block, dtype=np.float32)
        if b.ndim == 2:
            b = b[..., None]
        t = self.tile
        rows = b
        if self._last is not None and self._last_y == y - 1:
            rows = np.concatenate([self._last[None], b])
            first = y - 1
        else:
            first = y
        # horizontal pairs (x, x + 1): across an edge when x + 1 is a multiple of t
        dh = ((b[:, 1:] - b[:, :-1]) ** 2).mean(axis=2)
        edge_col = ((x0 + np.arange(1, b.shape[1])) % t) == 0
        self._add(dh[:, edge_col], dh[:, ~edge_col])
        # vertical pairs (y, y + 1)
        if len(rows) > 1:
            dv = ((rows[1:] - rows[:-1]) ** 2).mean(axis=2)
            edge_row = ((first + np.arange(1, len(rows))) % t) == 0
            self._add(dv[edge_row], dv[~edge_row])
        self._last, self._last_y = b[-1].copy(), y + len(b) - 1

    def _add(self, edge: np.ndarray, inside: np.ndarray) -> None:
        self.edge_sum += float(edge.sum(dtype=np.float64))
        self.edge_pairs += int(edge.size)
        self.inside_sum += float(inside.sum(dtype=np.float64))
        self.inside_pairs += int(inside.size)

    def result(self) -> dict[str, float]:
        """``edge``, ``inside`` (mean squared differences) and ``ratio`` = edge / inside."""
        edge = self.edge_sum / self.edge_pairs if self.edge_pairs else float("nan")
        inside = self.inside_sum / self.inside_pairs if self.inside_pairs else float("nan")
        return {"edge": edge, "inside": inside, "ratio": edge / inside if inside else float("nan"),
                "edge_pairs": self.edge_pairs, "inside_pairs": self.inside_pairs}


def seam_error(image: np.ndarray, tile: int, x0: int = 0, y0: int = 0) -> dict[str, float]:
    """:class:`SeamStats` of one image whose top-left pixel is texture pixel (x0, y0)."""
    stats = SeamStats(tile)
    stats.feed(image, y0, x0)
    return stats.result()


def cut_error(pixels: np.ndarray, labels: np.ndarray) -> dict[str, float]:
    """Mean squared colour difference of adjacent pixels inside tiles ``pixels`` (n, T, T, C)
    across a cut (``labels`` (n, T, T) differ) and within one patch (labels equal)."""
    p = np.asarray(pixels, dtype=np.float32)
    lab = np.asarray(labels)
    if p.shape[:3] != lab.shape:
        raise ParameterError(f"labels {lab.shape} do not match the tiles {p.shape[:3]}")
    sums = {True: 0.0, False: 0.0}
    counts = {True: 0, False: 0}
    for axis in (1, 2):
        a, b = np.moveaxis(p, axis, 0), np.moveaxis(lab, axis, 0)
        d = ((a[1:] - a[:-1]) ** 2).mean(axis=-1)
        cut = b[1:] != b[:-1]
        for flag in (True, False):
            sums[flag] += float(d[cut == flag].sum(dtype=np.float64))
            counts[flag] += int((cut == flag).sum())
    across = sums[True] / counts[True] if counts[True] else float("nan")
    within = sums[False] / counts[False] if counts[False] else float("nan")
    return {"across": across, "within": within, "ratio": across / within if within else float("nan"),
            "cut_pairs": counts[True]}


def autocorrelation(image: np.ndarray, max_lag: int | None = None) -> np.ndarray:
    """Pearson's r of an image's luminance (mean removed) with itself shifted by (dy, dx), over
    the overlap, for |dy|, |dx| <= max_lag (default: half the smaller side): a
    (2 max_lag + 1)^2 array, lag (0, 0) in the middle. Sums over overlaps by FFT, zero-padded."""
    x = _lum(image)
    h, w = x.shape
    if min(h, w) < 4:
        raise ParameterError(f"an image of {w} x {h} pixels is too small for an autocorrelation")
    lag = min(h, w) // 2 if max_lag is None else int(max_lag)
    if not 1 <= lag <= min(h, w) - 1:
        raise ParameterError(f"max_lag {max_lag!r} must be from 1 to {min(h, w) - 1}")
    x = x - x.mean()
    shape = (2 * h, 2 * w)
    fx = np.fft.rfft2(x, shape)
    ones = np.fft.rfft2(np.ones_like(x), shape)
    sq = np.fft.rfft2(x * x, shape)
    xy = np.fft.irfft2(fx * np.conj(fx), shape)  # sum over p of x(p) x(p + lag)
    # sum of x(p)^2 over p whose partner p + lag lies inside, and of x(p + lag)^2
    a2 = np.fft.irfft2(sq * np.conj(ones), shape)
    b2 = np.fft.irfft2(ones * np.conj(sq), shape)
    idx_y = np.arange(-lag, lag + 1) % shape[0]
    idx_x = np.arange(-lag, lag + 1) % shape[1]
    pick = np.ix_(idx_y, idx_x)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = xy[pick] / np.sqrt(np.maximum(a2[pick], 0) * np.maximum(b2[pick], 0))
    return np.nan_to_num(np.clip(r, -1.0, 1.0))


def repetition(image: np.ndarray, tile: int, max_side: int = MAX_CORRELATION_SIDE) -> dict[str, Any]:
    """The autocorrelation peak at lags of at least ``tile`` / 2 (Chebyshev) and at most a
    quarter of the crop (so every overlap holds most of it), on the top-left crop of at most
    ``max_side`` pixels a side: ``peak`` (Pearson's r) and its ``lag`` (dy, dx)."""
    a = np.asarray(image)[:max_side, :max_side]
    if min(a.shape[:2]) // 4 < max(1, tile // 2):
        raise ParameterError(f"a crop of {min(a.shape[:2])} px is too small to see repetition of {tile} px tiles; "
                             f"give at least {4 * max(1, tile // 2)} px")
    r = autocorrelation(a, max_lag=min(a.shape[:2]) // 4)
    lag = (r.shape[0] - 1) // 2
    dy, dx = np.meshgrid(np.arange(-lag, lag + 1), np.arange(-lag, lag + 1), indexing="ij")
    far = np.maximum(np.abs(dy), np.abs(dx)) >= max(1, tile // 2)
    masked = np.where(far, r, -np.inf)
    peak = float(masked.max())
    # of the lags within rounding of the peak (a periodic image has many), the shortest
    ties = np.flatnonzero(masked.ravel() >= peak - 1e-9)
    k = ties[np.argmin(np.maximum(np.abs(dy.ravel()[ties]), np.abs(dx.ravel()[ties])) * 4 * lag
                       + np.abs(dy.ravel()[ties]) + np.abs(dx.ravel()[ties]))]
    return {"peak": peak, "lag": (int(dy.ravel()[k]), int(dx.ravel()[k])), "side": int(min(a.shape[:2]))}


def periodic_texture(tile_pixels: np.ndarray, width: int, height: int) -> np.ndarray:
    """One tile repeated: the periodic texture (height, width, C) a single tile makes."""
    t = np.asarray(tile_pixels)
    reps = (-(-height // t.shape[0]), -(-width // t.shape[1])) + (1,) * (t.ndim - 2)
    return np.tile(t, reps)[:height, :width]
