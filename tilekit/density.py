"""Densities over the unit square for importance sampling (§7.4): a PNG image, a safe
expression in x and y, or a named density, all held as one grid of cell values.

A :class:`Density` is piecewise constant on an h x w grid over [0, 1]^2 (row 0 at y = 0,
x to the right). Its integral over any box is exact from the summed-area table: the
cumulative function F(x, y) is bilinear inside every cell, so interpolating the table
bilinearly gives F exactly, and a box integral is four lookups (vectorised over boxes).
Brighter pixels and larger values mean *more* samples (``invert`` turns an image round).
"""

from __future__ import annotations

import io
import math
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from tilekit import expr
from tilekit.errors import ParameterError, ParseError
from tilekit.files import read_bytes
from tilekit.limits import refuse_over

#: Largest image (width x height) read as a density; each pixel costs ~24 bytes here.
MAX_DENSITY_PIXELS = 16_777_216
#: Side of the grid an expression is evaluated on (cell centres; the midpoint rule).
EXPRESSION_GRID = 1024

#: Named densities: each an expression in x and y over the unit square.
NAMED = {
    "uniform": "1",
    "ramp": "x",
    "radial": "exp(-8*((x-0.5)**2 + (y-0.5)**2))",
    "step": "x >= 0.5",
    "rings": "0.55 + 0.45*cos(40*sqrt((x-0.5)**2 + (y-0.5)**2))",
}


@dataclass(frozen=True)
class Density:
    """Cell values ``values[i, j]`` on [j/w, (j+1)/w] x [i/h, (i+1)/h] (row 0 at the bottom)."""

    values: np.ndarray
    name: str = "density"
    table: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        v = np.asarray(self.values, dtype=np.float64)
        if v.ndim != 2 or v.size == 0:
            raise ParameterError(f"density {self.name}: values must be a non-empty 2-D grid")
        bad = ~np.isfinite(v)
        if bad.any():
            i, j = np.argwhere(bad)[0]
            raise ParameterError(f"density {self.name} is not finite at x={(j + 0.5) / v.shape[1]:.4g}, "
                                 f"y={(i + 0.5) / v.shape[0]:.4g}; a density must be a finite number >= 0")
        if (v < 0).any():
            i, j = np.argwhere(v < 0)[0]
            raise ParameterError(f"density {self.name} is negative ({v[i, j]:.4g}) at x={(j + 0.5) / v.shape[1]:.4g}, "
                                 f"y={(i + 0.5) / v.shape[0]:.4g}; a density must be >= 0")
        h, w = v.shape
        table = np.zeros((h + 1, w + 1))
        table[1:, 1:] = np.cumsum(np.cumsum(v, axis=0), axis=1) / (h * w)
        if not table[-1, -1] > 0:
            raise ParameterError(f"density {self.name} is zero everywhere; give a density with some positive part")
        v.setflags(write=False)
        object.__setattr__(self, "values", v)
        object.__setattr__(self, "table", table)

    @property
    def total(self) -> float:
        """The integral over the unit square."""
        return float(self.table[-1, -1])

    def cumulative(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """F(x, y) = integral over [0, x] x [0, y] (coordinates clipped to the square), exact."""
        h, w = self.values.shape
        gx = np.clip(np.asarray(x, dtype=np.float64), 0.0, 1.0) * w
        gy = np.clip(np.asarray(y, dtype=np.float64), 0.0, 1.0) * h
        j = np.minimum(gx.astype(np.int64), w - 1)
        i = np.minimum(gy.astype(np.int64), h - 1)
        fx, fy = gx - j, gy - i
        t = self.table
        a, b, c, d = t[i, j], t[i, j + 1], t[i + 1, j], t[i + 1, j + 1]
        return a + fx * (b - a) + fy * (c - a) + fx * fy * (d - b - c + a)

    def box_integral(self, x0: np.ndarray, y0: np.ndarray, x1: np.ndarray, y1: np.ndarray) -> np.ndarray:
        """The integral over each box [x0, x1] x [y0, y1] (the part outside the square is 0)."""
        f = self.cumulative
        return np.maximum(f(x1, y1) - f(x0, y1) - f(x1, y0) + f(x0, y0), 0.0)

    def at(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """The value at points (that of the cell holding each; 0 outside the square)."""
        h, w = self.values.shape
        x = np.asarray(x, dtype=np.float64)
        y = np.asarray(y, dtype=np.float64)
        inside = (x >= 0) & (x <= 1) & (y >= 0) & (y <= 1)
        j = np.clip((x * w).astype(np.int64), 0, w - 1)
        i = np.clip((y * h).astype(np.int64), 0, h - 1)
        return np.where(inside, self.values[i, j], 0.0)

    def random_points(self, m: int, rng: np.random.Generator) -> np.ndarray:
        """``m`` independent points distributed by the density (cell by the CDF, uniform inside)."""
        h, w = self.values.shape
        cdf = np.cumsum(self.values.ravel())
        cell = np.searchsorted(cdf, rng.random(m) * cdf[-1], side="right")
        cell = np.minimum(cell, h * w - 1)
        i, j = np.divmod(cell, w)
        return np.column_stack([(j + rng.random(m)) / w, (i + rng.random(m)) / h])


# ---------------------------------------------------------------------- sources


def from_image(path: str | Path, invert: bool = False) -> Density:
    """A density from a PNG image's luminance (0..1; bright = more samples unless ``invert``)."""
    p = Path(path)
    data = read_bytes(p, "density image")
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ParseError(f"density image {p.name!r} is not a PNG file (its first bytes are not the PNG signature)")
    if len(data) < 24 or data[12:16] != b"IHDR":
        raise ParseError(f"density image {p.name!r} is not a PNG file (no IHDR header after the signature)")
    # the size the header claims, refused before any decoder allocates for it (PIL's own
    # bomb check would raise from Image.open, outside tilekit's errors)
    w, h = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
    refuse_over("density pixels", w * h, MAX_DENSITY_PIXELS, hint=f"{p.name} is {w} x {h}; scale it down")
    try:
        from PIL import Image, UnidentifiedImageError  # optional: the 'sampling' extra
    except ImportError:
        raise ParameterError("reading a PNG density needs Pillow: pip install 'tilekit[sampling]'") from None
    try:
        with Image.open(io.BytesIO(data), formats=["PNG"]) as im:
            if im.size != (w, h):
                raise ParseError(f"density image {p.name!r}: the header's size {w} x {h} is not the image's {im.size}")
            grey = np.asarray(im.convert("L"), dtype=np.float64) / 255.0
    except (UnidentifiedImageError, Image.DecompressionBombError, OSError, SyntaxError, ValueError,
            EOFError, MemoryError) as exc:
        if isinstance(exc, ParseError):
            raise
        raise ParseError(f"density image {p.name!r} cannot be read as a PNG ({str(exc)[:120]})") from None
    if invert:
        grey = 1.0 - grey
    return Density(grey[::-1].copy(), name=p.name)


def from_expression(text: str, size: int = EXPRESSION_GRID) -> Density:
    """A density from an expression in x and y (or a name of :data:`NAMED`), evaluated at the
    centres of a ``size`` x ``size`` grid."""
    source = NAMED.get(text, text)
    fn = compile_expression(source)
    c = (np.arange(size) + 0.5) / size
    x, y = np.meshgrid(c, c)
    with np.errstate(all="ignore"):
        values = np.broadcast_to(np.asarray(fn(x, y), dtype=np.float64), x.shape).copy()
    return Density(values, name=text if text in NAMED else f"expression {text[:60]!r}")


def density_from(spec: str, invert: bool = False, size: int = EXPRESSION_GRID) -> Density:
    """``spec`` as a density: a PNG path (ending .png, or an existing file), a name, or an expression."""
    spec = spec.strip()
    # a path when it says so (.png) or names something that exists; never an expression
    # tried as a path first (os.path.lexists answers False, not OSError, for a text too long
    # to be a file name)
    if spec.lower().endswith(".png") or (spec not in NAMED and os.path.lexists(spec)):
        return from_image(spec, invert=invert)
    d = from_expression(spec, size)
    if invert:
        v = d.values.max() - d.values
        return Density(v, name=f"inverted {d.name}")
    return d


# ---------------------------------------------------------------------- expressions

_FUNCTIONS: dict[str, Callable[..., np.ndarray]] = {
    "sqrt": np.sqrt, "exp": np.exp, "log": np.log, "sin": np.sin, "cos": np.cos, "tan": np.tan,
    "abs": np.abs, "floor": np.floor, "min": np.minimum, "max": np.maximum,
}
_CONSTANTS = {"pi": math.pi, "e": math.e}
GRAMMAR = expr.Grammar(names=("x", "y", *_CONSTANTS), functions={k: 2 if k in ("min", "max") else 1 for k in _FUNCTIONS},
                       modulo=True, compare=True, what="density expression")


def compile_expression(text: str) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """A vectorised function of arrays x, y from ``text`` (:mod:`tilekit.expr`, never ``eval``):
    numbers, x, y, pi, e, + - * / % **, one comparison (1 where true, else 0), and sqrt exp log
    sin cos tan abs floor min max. The syntax is checked here, once; values are checked by
    :class:`Density`."""
    tree = expr.parse(text, GRAMMAR, syntax_hint=f"; a density is a PNG file, a named density "
                                                 f"({', '.join(NAMED)}) or an expression in x and y")

    def fn(x: np.ndarray, y: np.ndarray) -> np.ndarray:
        env = {"x": np.asarray(x, dtype=np.float64), "y": np.asarray(y, dtype=np.float64), **_CONSTANTS}
        try:
            return np.asarray(expr.run(tree, env, _FUNCTIONS), dtype=np.float64)
        except (OverflowError, ZeroDivisionError, ValueError, TypeError) as exc:
            raise ParseError(f"density expression {expr.show(text)} cannot be evaluated: {exc}") from None

    return fn
