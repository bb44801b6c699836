"""Edge shapes of isohedral prototiles (§5.3.1, §5.4.4): the three-level model, shared by the
planar isohedral family and the curved family's isohedral tiles (an edge's curve lives on the
unit segment; each family maps the segment onto its tiling edges).

Level 1: a *fundamental edge shape* is a path from (0, 0) to (1, 0) (a polyline, or a chain
of cubic Bézier segments flattened for output). A U or S edge uses it for its first half and
completes the second half by the mirror or half-turn symmetry; a J edge uses it whole; I edges
are straight and take no shape.
Level 2: labels adjacent to each other in the incidence symbol share one fundamental shape
(the curve of one is the image of the other under the hop between them).
Level 3: each tiling edge maps its label's curve onto the edge of the tiling polygon.
Editing one fundamental shape therefore changes every tiling edge that depends on it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from tilekit.errors import ParameterError, ParseError
from tilekit.limits import MAX_EDGE_POINTS

#: Points per cubic Bézier segment when a smooth shape is flattened.
BEZIER_SAMPLES = 12

# The four orientation maps of the unit segment (as 2x3 affine rows).
IDENTITY = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
#: Half-turn about (1/2, 0): (x, y) -> (1 - x, -y).
ROT = np.array([[-1.0, 0.0, 1.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]])
#: Mirror in the perpendicular bisector: (x, y) -> (1 - x, y).
FLIP = np.array([[-1.0, 0.0, 1.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
#: Mirror in the segment's line: (x, y) -> (x, -y).
ROFL = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]])


def apply_unit(m: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Apply a unit-segment map to a path, keeping it directed from (0, 0) to (1, 0)."""
    out = pts @ m[:2, :2].T + m[:2, 2]
    if abs(out[0, 0]) > 0.5:  # the map swapped the endpoints: walk the path the other way
        out = out[::-1]
    return out


@dataclass(frozen=True, eq=False)
class EdgeShape:
    """A fundamental edge shape: a path from (0, 0) to (1, 0).

    ``points`` are polyline vertices, or with ``smooth=True`` the control points of a chain
    of cubic Bézier segments (3k + 1 points), flattened by :meth:`path`.
    """

    points: np.ndarray
    smooth: bool = False

    def __post_init__(self) -> None:
        pts = np.asarray(self.points, dtype=float).reshape(-1, 2)
        if len(pts) < 2 or not np.all(np.isfinite(pts)):
            raise ParameterError(f"edge shape needs at least two finite points, got {pts.tolist()}")
        if not (np.allclose(pts[0], (0.0, 0.0), atol=1e-9) and np.allclose(pts[-1], (1.0, 0.0), atol=1e-9)):
            raise ParameterError(
                f"edge shape must run from (0, 0) to (1, 0); got ({pts[0, 0]:g}, {pts[0, 1]:g}) "
                f"to ({pts[-1, 0]:g}, {pts[-1, 1]:g})"
            )
        if self.smooth and (len(pts) - 1) % 3:
            raise ParameterError(
                f"a smooth (cubic Bézier) edge shape needs 3k+1 control points, got {len(pts)}"
            )
        drawn = BEZIER_SAMPLES * ((len(pts) - 1) // 3) + 1 if self.smooth else len(pts)
        if drawn > MAX_EDGE_POINTS + 2:
            raise ParameterError(
                f"edge shape of {drawn - 2:,} interior points{' once flattened' if self.smooth else ''} is over the "
                f"limit of {MAX_EDGE_POINTS} (limits.MAX_EDGE_POINTS: a tile's overlap check grows with its "
                "vertices squared)"
            )
        pts = pts.copy()
        pts[0] = (0.0, 0.0)
        pts[-1] = (1.0, 0.0)
        pts.setflags(write=False)
        object.__setattr__(self, "points", pts)

    @classmethod
    def straight(cls) -> EdgeShape:
        return cls(np.array([[0.0, 0.0], [1.0, 0.0]]))

    @property
    def is_straight(self) -> bool:
        return bool(np.allclose(self.points[:, 1], 0.0) and np.all(np.diff(self.points[:, 0]) > 0))

    def path(self) -> np.ndarray:
        """The flattened path (polyline points from (0, 0) to (1, 0))."""
        if not self.smooth:
            return np.array(self.points)
        t = np.linspace(0.0, 1.0, BEZIER_SAMPLES + 1)[:-1]
        b = np.stack([(1 - t) ** 3, 3 * (1 - t) ** 2 * t, 3 * (1 - t) * t**2, t**3], axis=1)
        segs = [b @ self.points[i : i + 4] for i in range(0, len(self.points) - 1, 3)]
        return np.vstack(segs + [self.points[-1:]])

    def to_text(self, exact: bool = False) -> str:
        """The text :meth:`parse` reads: 12 significant digits, or with ``exact`` the shortest
        text that reads back as the same doubles (links that must reopen a shape exactly)."""
        def num(v: float) -> str:
            return repr(v).removesuffix(".0") if exact else f"{v:.12g}"

        body = ":".join(f"{num(x)},{num(y)}" for x, y in self.points.tolist())
        return ("bezier:" if self.smooth else "") + body

    @classmethod
    def parse(cls, text: str) -> EdgeShape:
        """'0,0:0.3,0.2:1,0' (polyline) or 'bezier:0,0:0.3,0.4:0.7,-0.4:1,0'."""
        s = text.strip()
        smooth = False
        if s.lower().startswith("bezier:"):
            smooth, s = True, s[len("bezier:") :]
        if s.count(":") > 4 * MAX_EDGE_POINTS:  # refused before thousands of numbers are read
            raise ParameterError(f"edge shape of {s.count(':') + 1:,} points is over the limit of {MAX_EDGE_POINTS}")
        try:
            pts = [tuple(float(v) for v in p.split(",")) for p in s.split(":") if p.strip()]
        except ValueError:
            raise ParseError(f"edge shape {text[:60]!r} is not points 'x,y:x,y:...' (numbers)") from None
        if any(len(p) != 2 for p in pts):
            raise ParseError(f"edge shape {text!r}: every point must be 'x,y'")
        if not all(math.isfinite(v) for p in pts for v in p):
            raise ParseError(f"edge shape {text!r}: points must be finite numbers")
        # one --edge syntax for every family: the end points (0,0) and (1,0) may be left out
        if not smooth and (not pts or not np.allclose(pts[0], (0.0, 0.0), atol=1e-9)):
            pts = [(0.0, 0.0), *pts, (1.0, 0.0)]  # interior points only, as for substitution edges
        return cls(np.array(pts), smooth)


_EDGE_OPTION = re.compile(r"^\s*([a-zA-Z])\s*=\s*(.+)$")


def parse_edge_option(text: str) -> tuple[str, EdgeShape]:
    """'b=0,0:0.3,0.2:1,0' -> ('b', EdgeShape) as the CLI's --edge passes it (a label a-z, or A-Z
    as the curved family's incidence symbols use past 26 edges)."""
    m = _EDGE_OPTION.match(text)
    if not m:
        raise ParseError(f"edge option {text!r} is not 'LABEL=x,y:x,y:...' (e.g. b=0,0:0.3,0.2:1,0)")
    return m.group(1), EdgeShape.parse(m.group(2))


def complete(kind: str, shape: EdgeShape | None) -> np.ndarray:
    """Level 1: the whole edge curve (from (0,0) to (1,0)) of a J, U, S or I edge."""
    if kind == "I" or shape is None:
        return np.array([[0.0, 0.0], [1.0, 0.0]])
    f = shape.path()
    if kind == "J":
        return f
    half = 0.5 * f
    if kind == "U":
        second = half @ FLIP[:2, :2].T + FLIP[:2, 2]
    elif kind == "S":
        second = half @ ROT[:2, :2].T + ROT[:2, 2]
    else:
        raise ParameterError(f"edge kind {kind!r} is not J, U, S or I")
    return np.vstack([half, second[::-1][1:]])
