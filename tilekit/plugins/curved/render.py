"""SVG of curved tilings: the Poincaré disc with every edge the true circular arc (a geodesic
is an arc of a circle orthogonal to the unit circle, or a diameter), the Klein disc with
straight edges, and the sphere in orthographic projection, the far side faint behind the
near side, or in stereographic projection from a tile's centre, every edge the true arc
through its projected ends and midpoint (a great circle goes to a circle, or to a line
through the origin when it passes through the pole), the pole's tile drawn as the outside.

One ``<path>`` per colour; coordinates are the model plane's (the disc's radius is 1, y up),
so the picture is resolution independent and a PNG is cairosvg's rasterization of it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from tilekit.errors import GeometryError, ParameterError
from tilekit.geometry import as_region
from tilekit.plugins.curved import model

DEFAULT_PALETTE = ("#f4d35e", "#ee964b", "#f95738", "#5aa9e6", "#7fc8f8", "#c1e1c1", "#a3c4bc", "#ffd6e0")


def _fmt(a: np.ndarray) -> np.ndarray:
    return np.char.mod("%.7f", a)


def arc_commands(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """SVG commands drawing the geodesic from Poincaré points a to b, (m, 2) each, y flipped
    for SVG: 'A r r 0 0 s x y', or 'L x y' for a geodesic through the centre (a diameter)."""
    det = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    ra, rb = (a * a).sum(axis=1), (b * b).sum(axis=1)
    # through the centre (up to rounding): |det| = |a||b| sin, so a point at the centre itself
    # (a tiling centred on a vertex) is measured against the other point's length
    straight = np.abs(det) < 1e-12 * np.maximum(1e-300, np.sqrt(np.maximum(ra, rb)))
    d = np.where(straight, 1.0, det)
    # the centre c of the orthogonal circle: c . a = (|a|^2 + 1) / 2, c . b = (|b|^2 + 1) / 2
    ka, kb = (ra + 1) / 2, (rb + 1) / 2
    cx = (ka * b[:, 1] - kb * a[:, 1]) / d
    cy = (a[:, 0] * kb - b[:, 0] * ka) / d
    r = np.sqrt(np.maximum(cx * cx + cy * cy - 1.0, 0.0))
    cross = (a[:, 0] - cx) * (b[:, 1] - cy) - (a[:, 1] - cy) * (b[:, 0] - cx)
    sweep = np.where(cross > 0, "0", "1")  # y is flipped: counter-clockwise in the disc is sweep 0
    x, y = _fmt(b[:, 0]), _fmt(-b[:, 1])
    rs = _fmt(r)
    arc = np.char.add(np.char.add(np.char.add(np.char.add("A", rs), " "), rs), " 0 0 ")
    arc = np.char.add(np.char.add(np.char.add(np.char.add(arc, sweep), " "), x), " ")
    arc = np.char.add(arc, y)
    line = np.char.add(np.char.add(np.char.add("L", x), " "), y)
    return np.where(straight, line, arc)


def halfplane_arc_commands(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """SVG commands drawing the geodesic from half-plane points a to b, (m, 2) each, y flipped:
    the arc of the circle centred on the real axis through both, or 'L x y' when they lie on
    one vertical line."""
    dx = a[:, 0] - b[:, 0]
    scale = np.maximum(np.abs(a).max(axis=1), np.abs(b).max(axis=1))
    straight = np.abs(dx) < 1e-12 * np.maximum(scale, 1e-300)
    d = np.where(straight, 1.0, dx)
    cx = ((a * a).sum(axis=1) - (b * b).sum(axis=1)) / (2 * d)
    r = np.hypot(a[:, 0] - cx, a[:, 1])
    cross = (a[:, 0] - cx) * b[:, 1] - a[:, 1] * (b[:, 0] - cx)
    sweep = np.where(cross > 0, "0", "1")
    x, y, rs = _fmt(b[:, 0]), _fmt(-b[:, 1]), _fmt(r)
    arc = np.char.add(np.char.add(np.char.add(np.char.add("A", rs), " "), rs), " 0 0 ")
    arc = np.char.add(np.char.add(np.char.add(np.char.add(arc, sweep), " "), x), " ")
    arc = np.char.add(arc, y)
    line = np.char.add(np.char.add(np.char.add("L", x), " "), y)
    return np.where(straight, line, arc)


def circle_through(a: np.ndarray, m: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The circles through three points a, m, b (each (n, 2)): centres (n, 2), radii (n,) and
    a mask of the triples that are collinear (m within 1e-9 of |ab| of the line ab: drawn as a
    segment, centre and radius then meaningless)."""
    u, w = m - a, b - a
    cross = u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]
    ww = (w * w).sum(axis=1)
    straight = np.abs(cross) <= 1e-9 * ww
    d = np.where(straight, 1.0, 2.0 * cross)
    uu = (u * u).sum(axis=1)
    # the centre c = a + x with 2 x.u = |u|^2 and 2 x.w = |w|^2
    cx = (uu * w[:, 1] - ww * u[:, 1]) / d
    cy = (ww * u[:, 0] - uu * w[:, 0]) / d
    centre = a + np.stack([cx, cy], axis=1)
    return centre, np.hypot(cx, cy), straight


def three_point_arc_commands(a: np.ndarray, m: np.ndarray, b: np.ndarray) -> np.ndarray:
    """SVG commands from a through m to b (each (n, 2), y flipped for SVG): the circle through
    the three points as two arcs, a to m and m to b, 'A r r 0 0 s mx my A r r 0 0 s x y' (each
    under half a turn, so the small-arc flag is right and the end points fix the centre well
    even where the whole arc is near a half circle), or 'L x y' where they are collinear."""
    _, r, straight = circle_through(a, m, b)
    u, w = m - a, b - m
    ccw = u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0] > 0
    sweep = np.where(ccw, "0", "1")  # y is flipped: counter-clockwise in the model plane is sweep 0
    rs = _fmt(r)
    head = np.char.add(np.char.add(np.char.add(np.char.add("A", rs), " "), rs), " 0 0 ")
    head = np.char.add(np.char.add(head, sweep), " ")
    x, y, mx, my = _fmt(b[:, 0]), _fmt(-b[:, 1]), _fmt(m[:, 0]), _fmt(-m[:, 1])
    arc = np.char.add(np.char.add(np.char.add(np.char.add(head, mx), " "), my), " ")
    arc = np.char.add(np.char.add(np.char.add(np.char.add(arc, head), x), " "), y)
    line = np.char.add(np.char.add(np.char.add("L", x), " "), y)
    return np.where(straight, line, arc)


def stereographic_edges(patch: Any, pole: int) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """The patch's tiles in the stereographic view from the centre of tile ``pole``: per
    prototile, (tile indices, projected corners (n, k, 2), projected edge midpoints (n, k, 2),
    corners on the turned sphere (n, k, 3)). Consecutive corners are joined by a geodesic (a
    shaped tile is the geodesic polygon through its points), and the midpoint is that
    geodesic's; a tile placed by a reflection is read backwards, so every tile runs
    counter-clockwise seen from outside the sphere."""
    n = len(patch)
    if isinstance(pole, bool) or not isinstance(pole, (int, np.integer)) or not 0 <= pole < n:
        raise ParameterError(f"plane stereographic:{pole}: the pole must be the centre of one of the {n} tiles, "
                             f"K in 0..{n - 1}")
    rot = model.pole_rotation(patch.transform[pole])
    out = []
    for _, idx, pr in patch.parts():
        corners = pr.points[list(pr.corners or range(len(pr.points)))]
        v = model.apply(rot @ patch.transform[idx], corners)                      # (n, k, 3)
        mirrored = np.linalg.det(patch.transform[idx]) < 0
        v[mirrored] = v[mirrored, ::-1]
        mid = v + np.roll(v, -1, axis=1)
        mid /= np.linalg.norm(mid, axis=-1, keepdims=True)
        out.append((idx, model.stereographic(v), model.stereographic(mid), v))
    return out


def stereographic_paths(patch: Any, pole: int) -> tuple[np.ndarray, float]:
    """One closed SVG subpath per tile of the stereographic view (edges as true arcs), the pole's
    tile's being its boundary only (it is drawn as the outside), and the half-width of a square
    about the origin holding the pole tile's boundary, hence every other tile."""
    paths = np.empty(len(patch), dtype=object)
    extent = 0.0
    for idx, flat, mid, v in stereographic_edges(patch, pole):
        n, k = flat.shape[:2]
        nxt = np.roll(flat, -1, axis=1)
        cmds = three_point_arc_commands(flat.reshape(-1, 2), mid.reshape(-1, 2), nxt.reshape(-1, 2)).reshape(n, k)
        out = np.char.add(np.char.add(np.char.add("M", _fmt(flat[:, 0, 0])), " "), _fmt(-flat[:, 0, 1]))
        for j in range(k):
            out = np.char.add(np.char.add(out, " "), cmds[:, j])
        paths[idx] = np.char.add(out, " Z")
        at = np.flatnonzero(idx == pole)
        if len(at):
            # the pole tile's edges sampled along their geodesics: its boundary's farthest point
            a, b = v[at[0]], np.roll(v[at[0]], -1, axis=0)
            s = np.linspace(0.0, 1.0, 33)[:, None, None]
            pts = (1 - s) * a[None] + s * b[None]
            pts /= np.linalg.norm(pts, axis=-1, keepdims=True)
            flat_pts = model.stereographic(pts).reshape(-1, 2)
            x, y = flat_pts[:, 0], flat_pts[:, 1]
            # it runs clockwise in the plane when its tile holds the pole (the tile is outside it)
            if 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)) >= 0:
                raise GeometryError(f"plane stereographic:{pole}: tile {pole} does not hold its own centre "
                                    "(a shaped tile bent past it); take another tile as the pole")
            extent = float(np.abs(flat_pts).max())
    return paths, extent


def _polygon_paths(vertices: np.ndarray, arcs: bool | str) -> np.ndarray:
    """One closed SVG subpath per polygon (n, k, 2): arcs between vertices (``arcs`` True or
    'poincare': the disc's; 'halfplane': the half-plane's), or straight lines."""
    n, k = vertices.shape[:2]
    start = np.char.add(np.char.add(np.char.add("M", _fmt(vertices[:, 0, 0])), " "), _fmt(-vertices[:, 0, 1]))
    nxt = np.roll(vertices, -1, axis=1)
    if arcs == "halfplane":
        cmds = halfplane_arc_commands(vertices.reshape(-1, 2), nxt.reshape(-1, 2)).reshape(n, k)
    elif arcs:
        cmds = arc_commands(vertices.reshape(-1, 2), nxt.reshape(-1, 2)).reshape(n, k)
    else:
        pts = nxt.reshape(-1, 2)
        cmds = np.char.add(np.char.add(np.char.add("L", _fmt(pts[:, 0])), " "), _fmt(-pts[:, 1])).reshape(n, k)
    out = start
    for j in range(k):
        out = np.char.add(np.char.add(out, cmds[:, j]), " ")
    return np.char.add(out, "Z")


def _open_svg(view: tuple[float, float, float, float], region: Any, width: int | None, height: int | None,
              size: int, stroke_width: float | None, stroke_width_px: float | None,
              background: str | None) -> tuple[list[str], float, tuple[float, float, float, float]]:
    """The SVG's opening lines (the element and the background) for ``view`` (x0, y0, x1, y1)
    or ``region``'s bounds, padded by 1 %; the stroke width in model units; the padded box."""
    x0, y0, x1, y1 = as_region(region).bounds if region is not None else view
    pad = 0.01 * max(x1 - x0, y1 - y0)
    x0, y0, x1, y1 = x0 - pad, y0 - pad, x1 + pad, y1 + pad
    w, h = x1 - x0, y1 - y0
    if width is not None:
        px_w, px_h = int(width), max(1, round(width * h / w))
    elif height is not None:
        px_w, px_h = max(1, round(height * w / h)), int(height)
    else:
        s = size / max(w, h)
        px_w, px_h = max(1, round(w * s)), max(1, round(h * s))
    unit = w / px_w  # model units per pixel
    sw = stroke_width if stroke_width is not None else (stroke_width_px or 1.0) * unit
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{px_w}" height="{px_h}" '
           f'viewBox="{x0:.6f} {-y1:.6f} {w:.6f} {h:.6f}">']
    if background:
        out.append(f'<rect x="{x0:.6f}" y="{-y1:.6f}" width="{w:.6f}" height="{h:.6f}" fill="{background}"/>')
    return out, sw, (x0, y0, x1, y1)


def stereographic_svg(patch: Any, pole: int, palette: list[str], stroke: str = "#222",
                      stroke_width: float | None = None, region: Any = None, width: int | None = None,
                      height: int | None = None, stroke_width_px: float | None = None, size: int = 800,
                      background: str | None = "#ffffff") -> str:
    """SVG of a spherical patch in stereographic projection from the centre of tile ``pole``
    (:func:`stereographic_edges`): the antipode of that centre at the origin, every edge the
    true circular arc (a line through its ends where the great circle passes through the pole).
    The pole's tile, which holds the projection's centre, is the outside: the picture's square
    (just holding its boundary, or ``region``) less that boundary, filled even-odd, its own
    ``<path data-tile="outside">``; every other tile is one closed subpath of its colour's path."""
    paths, extent = stereographic_paths(patch, pole)
    e = extent
    out, sw, (x0, y0, x1, y1) = _open_svg((-e, -e, e, e), region, width, height, size, stroke_width,
                                          stroke_width_px, background)
    frame = f"M{x0:.7f} {-y0:.7f} L{x1:.7f} {-y0:.7f} L{x1:.7f} {-y1:.7f} L{x0:.7f} {-y1:.7f} Z"
    colour = patch.colour
    out.append(f'<path data-tile="outside" fill="{palette[int(colour[pole]) % len(palette)]}" fill-rule="evenodd" '
               f'stroke="{stroke}" stroke-width="{sw:.6g}" stroke-linejoin="round" d="{frame} {paths[pole]}"/>')
    rest = np.arange(len(patch)) != pole
    for c in np.unique(colour[rest]):
        sel = rest & (colour == c)
        out.append(f'<path fill="{palette[int(c) % len(palette)]}" stroke="{stroke}" stroke-width="{sw:.6g}" '
                   f'stroke-linejoin="round" d="{" ".join(paths[sel].tolist())}"/>')
    out.append("</svg>")
    return "\n".join(out)


def curved_svg(tiling: Any, patch: Any, palette: Any = None, stroke: str = "#222", stroke_width: float | None = None,
               region: Any = None, width: int | None = None, height: int | None = None,
               stroke_width_px: float | None = None, labels: bool = False, vectors: Any = None, size: int = 800,
               background: str | None = "#ffffff", **_ignored: Any) -> str:
    """SVG text for a patch of a :class:`RegularTiling` (see the module)."""
    if labels:
        raise ParameterError("--labels: regular tilings carry no edge labels")
    if vectors:
        raise ParameterError("--vectors: a curved tiling has no translation vectors to draw")
    pal = list(palette) if palette else list(DEFAULT_PALETTE)
    first = patch.prototiles[0] if len(patch.prototiles) else None
    pole = getattr(tiling, "pole", None)
    if getattr(first, "sign", -1) > 0 and pole is not None:
        return stereographic_svg(patch, pole, pal, stroke, stroke_width, region, width, height, stroke_width_px,
                                 size, background)
    view = model.PLANE_VIEWS.get(getattr(first, "plane", "poincare"), (-1.0, -1.0, 1.0, 1.0))
    if getattr(first, "sign", -1) > 0:
        view = (-1.0, -1.0, 1.0, 1.0)
    out, sw, (x0, y0, x1, y1) = _open_svg(view, region, width, height, size, stroke_width, stroke_width_px,
                                          background)
    proto = patch.prototiles[0] if len(patch.prototiles) else None
    hyper = proto is None or proto.sign < 0
    if hyper and getattr(proto, "plane", "poincare") == "halfplane":
        out.append(f'<rect x="{x0:.6f}" y="{-y1:.6f}" width="{x1 - x0:.6f}" height="{max(y1, 0.0):.6f}" fill="#f8f8f8"/>')
        out.append(f'<line x1="{x0:.6f}" y1="0" x2="{x1:.6f}" y2="0" stroke="{stroke}" stroke-width="{sw:.6g}"/>')
    elif hyper:
        out.append(f'<circle cx="0" cy="0" r="1" fill="#f8f8f8" stroke="{stroke}" stroke-width="{sw:.6g}"/>')
    else:
        out.append(f'<circle cx="0" cy="0" r="1" fill="#eef2f6" stroke="{stroke}" stroke-width="{sw:.6g}"/>')
    if len(patch):
        if hyper:
            paths = np.empty(len(patch), dtype=object)
            for _, idx, pr in patch.parts():
                verts = patch.projected(idx, corners=True)
                paths[idx] = _polygon_paths(verts, arcs=pr.plane if pr.plane != "klein" else False)
            for c in np.unique(patch.colour):
                sel = patch.colour == c
                out.append(f'<path fill="{pal[int(c) % len(pal)]}" stroke="{stroke}" stroke-width="{sw:.6g}" '
                           f'stroke-linejoin="round" d="{" ".join(paths[sel].tolist())}"/>')
        else:
            parts = patch.parts()
            for front in (False, True):
                # each face's part on this side of the sphere: points on the other side are
                # pushed out radially onto the rim, so the outline follows the rim there
                paths = np.empty(len(patch), dtype=object)
                sel_side = np.zeros(len(patch), dtype=bool)
                for _, idx, pr in parts:
                    pts = patch.model_points(idx) @ pr.view.T            # (n, k, 3) in view space
                    side = pts[..., 2] >= 0 if front else pts[..., 2] <= 0
                    sel_side[idx] = side.any(axis=1)
                    flat = pts[..., :2].copy()
                    rim = flat / np.maximum(np.hypot(flat[..., :1], flat[..., 1:]), 1e-12)
                    flat = np.where(side[..., None], flat, rim)
                    paths[idx] = _polygon_paths(flat, arcs=False)
                opacity = "1" if front else "0.2"
                for c in np.unique(patch.colour[sel_side]):
                    sel = sel_side & (patch.colour == c)
                    out.append(f'<path fill="{pal[int(c) % len(pal)]}" fill-opacity="{opacity}" stroke="{stroke}" '
                               f'stroke-opacity="{opacity}" stroke-width="{sw:.6g}" stroke-linejoin="round" '
                               f'd="{" ".join(paths[sel].tolist())}"/>')
    out.append("</svg>")
    return "\n".join(out)
