"""Example images for texture synthesis, made by the project's own code (nothing downloaded):
fractal noise, pebbles and bricks, each repeatable from a seed.

They are the test and documentation inputs of :mod:`tilekit.plugins.wang.texture`: a
stochastic texture (noise), one of discrete objects that cross tile edges (pebbles, the
kind Cohen et al. made Wang tiles for), and a structured one whose straight mortar lines show
where a tile set breaks structure (bricks).
"""

from __future__ import annotations

import numpy as np

from tilekit.errors import ParameterError

#: The example kinds, for ``tilekit wang example KIND``.
KINDS = ("noise", "pebbles", "bricks")
#: Sides an example may have (pixels).
MIN_SIDE, MAX_SIDE = 32, 4096


def _check(size: int) -> int:
    if isinstance(size, bool) or not isinstance(size, int | np.integer) or not MIN_SIDE <= size <= MAX_SIDE:
        raise ParameterError(f"example size {size!r} must be a whole number of pixels from {MIN_SIDE} to {MAX_SIDE}")
    return int(size)


def fractal_noise(size: int, rng: np.random.Generator, beta: float = 2.0, lowest: float = 2.0) -> np.ndarray:
    """A (size, size) field of 1/f^(beta/2)-amplitude noise by spectral synthesis, scaled to
    [0, 1]; frequencies below ``lowest`` cycles per image are left out."""
    white = rng.standard_normal((size, size))
    f = np.hypot(*np.meshgrid(np.fft.fftfreq(size) * size, np.fft.rfftfreq(size) * size, indexing="ij"))
    amp = np.where(f >= lowest, np.maximum(f, 1.0) ** (-beta / 2), 0.0)
    field = np.fft.irfft2(np.fft.rfft2(white) * amp, s=(size, size))
    lo, hi = np.percentile(field, [0.5, 99.5])
    return np.clip((field - lo) / (hi - lo), 0.0, 1.0)


def _ramp(t: np.ndarray, stops: list[tuple[float, tuple[int, int, int]]]) -> np.ndarray:
    xs = [s for s, _ in stops]
    return np.stack([np.interp(t, xs, [c[k] for _, c in stops]) for k in range(3)], axis=-1)


def _to_uint8(rgb: np.ndarray) -> np.ndarray:
    return np.clip(np.rint(rgb), 0, 255).astype(np.uint8)


def noise_example(size: int = 256, seed: int = 0) -> np.ndarray:
    """Lichen on stone: two octaves of fractal noise through a colour ramp, (size, size, 3) uint8."""
    size = _check(size)
    rng = np.random.default_rng(seed)
    coarse = fractal_noise(size, rng, beta=2.2, lowest=3.0)
    fine = fractal_noise(size, rng, beta=1.2, lowest=size / 16)
    t = np.clip(0.8 * coarse + 0.2 * fine, 0, 1)
    stops = [(0.0, (38, 44, 32)), (0.35, (86, 98, 58)), (0.55, (142, 140, 92)), (0.75, (190, 176, 128)),
             (1.0, (232, 222, 190))]
    return _to_uint8(_ramp(t, stops))


def _nearest_two(size: int, cell: float, sites: np.ndarray, rows: slice) -> tuple[np.ndarray, ...]:
    """For the pixels of ``rows``: the nearest and second-nearest of ``sites`` (one site per
    grid cell of side ``cell``, ``sites[i, j]`` in cell (i - 3, j - 3), so both lie in the 7 x 7
    cells around the pixel's own); returns their indices (flat cell numbers) and squared distances."""
    n = sites.shape[0]
    yy, xx = np.mgrid[rows, 0:size].astype(np.float64) + 0.5
    ci = (yy // cell).astype(np.int64) + 3  # the grid has 3 cells of margin on every side
    cj = (xx // cell).astype(np.int64) + 3
    offsets = np.arange(-3, 4)
    ni = ci[..., None, None] + offsets[:, None]
    nj = cj[..., None, None] + offsets[None, :]
    flat = (ni * n + nj).reshape(*yy.shape, -1)  # (h, w, 49)
    s = sites.reshape(-1, 2)[flat]
    d2 = (s[..., 0] - yy[..., None]) ** 2 + (s[..., 1] - xx[..., None]) ** 2
    two = np.argpartition(d2, 1, axis=-1)[..., :2]
    d = np.take_along_axis(d2, two, axis=-1)
    swap = d[..., 0] > d[..., 1]
    two[swap] = two[swap][:, ::-1]
    d[swap] = d[swap][:, ::-1]
    return np.take_along_axis(flat, two, axis=-1), d


def pebble_example(size: int = 256, seed: int = 0, spacing: float = 30.0) -> np.ndarray:
    """Pebbles in sand: cells of the Voronoi diagram of jittered-grid sites, each shrunk from
    its boundary by a mortar gap and shaded like a rounded stone, (size, size, 3) uint8."""
    size = _check(size)
    rng = np.random.default_rng(seed)
    cells = max(1, int(round(size / spacing)))
    cell = size / cells
    n = cells + 7  # 3 cells of margin on each side, so every pixel has its 7 x 7 neighbourhood
    # one site per cell, jittered within the middle 70 % of it
    sites = (np.stack(np.mgrid[0:n, 0:n], axis=-1) - 3 + 0.15 + 0.7 * rng.random((n, n, 2))) * cell
    palette = np.array([(132, 120, 108), (160, 150, 138), (110, 98, 90), (176, 160, 130),
                        (98, 104, 112), (150, 128, 104), (186, 178, 168)], dtype=np.float64)
    stone_of = palette[rng.integers(len(palette), size=n * n)] * rng.uniform(0.9, 1.1, (n * n, 1))
    gap_field = fractal_noise(size, rng, beta=1.5, lowest=4.0)
    grain = fractal_noise(size, rng, beta=0.8, lowest=size / 8)
    sand = _ramp(fractal_noise(size, rng, beta=1.4, lowest=size / 32),
                 [(0.0, (92, 78, 58)), (0.5, (128, 110, 80)), (1.0, (158, 138, 104))])
    out = np.empty((size, size, 3))
    flat_sites = sites.reshape(-1, 2)
    step = max(1, 2_000_000 // (49 * size))
    for r0 in range(0, size, step):
        rows = slice(r0, min(size, r0 + step))
        idx, d2 = _nearest_two(size, cell, sites, rows)
        a, b = flat_sites[idx[..., 0]], flat_sites[idx[..., 1]]
        # distance to the bisector of the two nearest sites: the distance to the cell's boundary
        edge = (d2[..., 1] - d2[..., 0]) / (2.0 * np.linalg.norm(b - a, axis=-1))
        gap = 2.5 + 1.5 * gap_field[rows]
        height = np.sqrt(np.clip((edge - gap) / (0.3 * spacing), 0, 1))  # a rounded profile
        yy, xx = np.mgrid[rows, 0:size].astype(np.float64) + 0.5
        # light from the upper left: brighter where the stone faces it
        facing = ((a[..., 0] - yy) * 0.7 + (a[..., 1] - xx) * 0.7) / spacing
        light = (0.55 + 0.45 * height) * (1.0 + 0.25 * np.clip(facing, -1, 1))
        rgb = stone_of[idx[..., 0]] * (light * (0.92 + 0.16 * grain[rows]))[..., None]
        out[rows] = np.where((edge > gap)[..., None], rgb, sand[rows])
    return _to_uint8(out)


def brick_example(size: int = 256, seed: int = 0, brick: tuple[int, int] = (48, 20), mortar: int = 3) -> np.ndarray:
    """Running-bond brickwork: bricks of ``brick`` = (width, height) pixels in courses shifted by
    half a brick, each its own shade of red, with mortar joints and grain, (size, size, 3) uint8."""
    size = _check(size)
    bw, bh = brick
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:size, 0:size]
    course = yy // bh
    shifted = xx + (course % 2) * (bw // 2)
    index = course * (size // bw + 2) + shifted // bw
    in_mortar = ((yy % bh) < mortar) | ((shifted % bw) < mortar)
    base = np.array([(150, 62, 44), (168, 76, 52), (132, 56, 42), (178, 92, 64), (120, 50, 40), (158, 84, 70)],
                    dtype=np.float64)
    colour = base[rng.integers(len(base), size=int(index.max()) + 1)] * rng.uniform(0.85, 1.1, (int(index.max()) + 1, 1))
    grain = fractal_noise(size, rng, beta=1.0, lowest=size / 16)
    rgb = colour[index] * (0.85 + 0.3 * grain)[..., None]
    joint = np.array([196, 190, 176], dtype=np.float64) * (0.9 + 0.15 * grain)[..., None]
    rgb = np.where(in_mortar[..., None], joint, rgb)
    return _to_uint8(rgb)


def example(kind: str, size: int = 256, seed: int = 0) -> np.ndarray:
    """The example image of ``kind`` (one of :data:`KINDS`)."""
    makers = {"noise": noise_example, "pebbles": pebble_example, "bricks": brick_example}
    if kind not in makers:
        raise ParameterError(f"example kind {kind!r} is not one of {', '.join(KINDS)}")
    return makers[kind](size, seed)
