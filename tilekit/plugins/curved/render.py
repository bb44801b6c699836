"""SVG of curved tilings: the Poincaré disc with every edge the true circular arc (a geodesic
is an arc of a circle orthogonal to the unit circle, or a diameter), the Klein disc with
straight edges, and the sphere in orthographic projection, the far side faint behind the
near side.

One ``<path>`` per colour; coordinates are the model plane's (the disc's radius is 1, y up),
so the picture is resolution independent and a PNG is cairosvg's rasterization of it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from tilekit.errors import ParameterError
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
    view = model.PLANE_VIEWS.get(getattr(first, "plane", "poincare"), (-1.0, -1.0, 1.0, 1.0))
    if getattr(first, "sign", -1) > 0:
        view = (-1.0, -1.0, 1.0, 1.0)
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
    proto = patch.prototiles[0] if len(patch.prototiles) else None
    hyper = proto is None or proto.sign < 0
    if hyper and getattr(proto, "plane", "poincare") == "halfplane":
        out.append(f'<rect x="{x0:.6f}" y="{-y1:.6f}" width="{w:.6f}" height="{max(y1, 0.0):.6f}" fill="#f8f8f8"/>')
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
