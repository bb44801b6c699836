"""Render patches as SVG (and PNG through cairosvg, the ``png`` extra).

Tiles are drawn as one ``<path>`` per colour whose subpaths are all the tiles of that colour,
so a 100,000-tile patch is a few elements; coordinates are formatted per prototile in batches.
The y axis points up, as in the book's figures.
"""

from __future__ import annotations

import html
import itertools
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from tilekit.errors import ParameterError, ParseError, TilekitError
from tilekit.geometry import Affine, as_region
from tilekit.limits import MAX_PNG_PIXELS, refuse_over
from tilekit.polygon import signed_area

#: The default palette: soft, distinguishable fills (colour 0 first).
PALETTE: tuple[str, ...] = (
    "#f4c27a",
    "#7fb3d5",
    "#e88a8a",
    "#9ccc8f",
    "#c3a6e0",
    "#f2e394",
    "#8fd1c8",
    "#d9a37b",
    "#b0b7c6",
    "#f5a3c7",
    "#a4c66b",
    "#e6c36a",
)


#: The CSS named colours (CSS Color Module Level 4), accepted by --colours and palettes.
CSS_COLOURS: frozenset[str] = frozenset(
    """
    aliceblue antiquewhite aqua aquamarine azure beige bisque black blanchedalmond blue
    blueviolet brown burlywood cadetblue chartreuse chocolate coral cornflowerblue cornsilk
    crimson cyan darkblue darkcyan darkgoldenrod darkgray darkgreen darkgrey darkkhaki
    darkmagenta darkolivegreen darkorange darkorchid darkred darksalmon darkseagreen
    darkslateblue darkslategray darkslategrey darkturquoise darkviolet deeppink deepskyblue
    dimgray dimgrey dodgerblue firebrick floralwhite forestgreen fuchsia gainsboro ghostwhite
    gold goldenrod gray green greenyellow grey honeydew hotpink indianred indigo ivory khaki
    lavender lavenderblush lawngreen lemonchiffon lightblue lightcoral lightcyan
    lightgoldenrodyellow lightgray lightgreen lightgrey lightpink lightsalmon lightseagreen
    lightskyblue lightslategray lightslategrey lightsteelblue lightyellow lime limegreen linen
    magenta maroon mediumaquamarine mediumblue mediumorchid mediumpurple mediumseagreen
    mediumslateblue mediumspringgreen mediumturquoise mediumvioletred midnightblue mintcream
    mistyrose moccasin navajowhite navy oldlace olive olivedrab orange orangered orchid
    palegoldenrod palegreen paleturquoise palevioletred papayawhip peachpuff peru pink plum
    powderblue purple rebeccapurple red rosybrown royalblue saddlebrown salmon sandybrown
    seagreen seashell sienna silver skyblue slateblue slategray slategrey snow springgreen
    steelblue tan teal thistle tomato turquoise violet wheat white whitesmoke yellow yellowgreen
    """.split()
)


def is_colour(text: str) -> bool:
    """Whether ``text`` is a CSS colour name or #rgb / #rrggbb."""
    c = text.strip()
    if c.startswith("#"):
        return len(c) in (4, 7) and all(ch in "0123456789abcdefABCDEF" for ch in c[1:])
    return c.lower() in CSS_COLOURS or c.lower() == "none"


def parse_palette(text: str | Sequence[str] | None) -> tuple[str, ...] | None:
    """Colours from 'red,#00ff00,...' (CSS names or #rgb/#rrggbb); None keeps the default."""
    if text is None:
        return None
    items = [s.strip() for s in (text.split(",") if isinstance(text, str) else text) if s.strip()]
    if not items:
        raise ParseError("--colours needs at least one colour, e.g. '#f4c27a,#7fb3d5'")
    for c in items:
        if not is_colour(c):
            import difflib

            close = difflib.get_close_matches(c.lower(), sorted(CSS_COLOURS), n=3, cutoff=0.6)
            hint = f"; did you mean {', '.join(repr(x) for x in close)}?" if close else ""
            raise ParseError(f"colour {c[:40]!r} is not a CSS colour name or #rgb / #rrggbb{hint}")
    return tuple(items)


def _path_data(pts: np.ndarray, closed: bool = True) -> list[str]:
    """SVG path data for a batch of polylines (m, k, 2), one string each."""
    m, k, _ = pts.shape
    if m == 0:
        return []
    fmt = "M" + " L".join(["%.5g %.5g"] * k) + ("Z" if closed else "")
    flat = pts.reshape(m, 2 * k)
    return [fmt % tuple(row) for row in flat.tolist()]


#: The outline width in pixels of tiles at least STROKE_FULL_PX across; smaller tiles get
#: proportionally thinner outlines, and tiles under STROKE_MIN_PX none (their colours show the
#: tiling; a 1.2 px outline on every 3 px tile would paint the picture the stroke colour).
STROKE_PX = 1.2
STROKE_FULL_PX = 14.0
STROKE_MIN_PX = 2.5


def stroke_px_for(tile_px: float) -> float:
    """The default outline width (pixels) for tiles ``tile_px`` pixels across."""
    if tile_px < STROKE_MIN_PX:
        return 0.0
    return min(STROKE_PX, STROKE_PX * tile_px / STROKE_FULL_PX)


def tile_size(patch: Any) -> float:
    """A patch's typical tile size: the square root of its tiles' mean area (prototile areas
    times the transforms' determinants, so scaled tiles count as drawn)."""
    areas = np.abs(np.asarray([signed_area(p.outline) for p in patch.prototiles], dtype=float))
    t = patch.transform
    det = np.abs(t[:, 0, 0] * t[:, 1, 1] - t[:, 0, 1] * t[:, 1, 0])
    return float(np.sqrt(np.mean(areas[patch.prototile] * det)))


def patch_to_svg(
    patch: Any,
    palette: Sequence[str] | None = None,
    stroke: str = "#222",
    stroke_width: float | None = None,
    labels: bool = False,
    markings: bool = True,
    vectors: tuple[Sequence[float], Sequence[float], Sequence[float]] | None = None,
    size: int = 800,
    region: Any = None,
    background: str | None = "#ffffff",
    width: int | None = None,
    height: int | None = None,
    stroke_width_px: float | None = None,
    overlay: Sequence[tuple[np.ndarray, str, float]] = (),
) -> str:
    """SVG text for a patch.

    ``palette[c % len(palette)]`` fills tiles of colour c; ``labels`` writes each edge's label
    inside the tile near its midpoint; ``markings`` draws prototile markings; ``vectors`` =
    (origin, v1, v2) draws the translation vectors as arrows; ``region`` sets the view box and
    clips to it (default: the patch's bounds). The image's longer side is ``size`` pixels,
    or its width is ``width`` / its height ``height`` (the other side follows the aspect).
    ``overlay`` is lines drawn over the tiles: (segments (m, 2, 2), colour, width as a
    multiple of the outline's) per set, e.g. supertile outlines.
    """
    if region is None and len(patch):
        region = patch.bounds()
        clip = False
    else:
        clip = region is not None
    return "\n".join(svg_lines([patch], palette, stroke, stroke_width, labels, markings, vectors, size, region,
                               background, width, height, stroke_width_px, clip=clip, overlay=overlay))


def svg_lines(
    patches: Iterable[Any],
    palette: Sequence[str] | None = None,
    stroke: str = "#222",
    stroke_width: float | None = None,
    labels: bool = False,
    markings: bool = True,
    vectors: tuple[Sequence[float], Sequence[float], Sequence[float]] | None = None,
    size: int = 800,
    region: Any = None,
    background: str | None = "#ffffff",
    width: int | None = None,
    height: int | None = None,
    stroke_width_px: float | None = None,
    clip: bool = True,
    overlay: Sequence[tuple[np.ndarray, str, float]] = (),
) -> Iterator[str]:
    """The lines of :func:`patch_to_svg`'s SVG for the union of ``patches`` (a stream of
    patches, e.g. ``Tiling.iter_patches``), one patch at a time: the view box comes from
    ``region`` (needed before any tile; None: the unit box), each patch adds a filled
    ``<path>`` per colour (and one of markings), so only one patch's text is held at once.
    Edge labels are held until the end (their size follows the tile count): draw them on
    patches that fit in memory. ``clip``: clip to the region and frame it."""
    palette = tuple(palette) if palette else PALETTE
    if size <= 0:
        raise ParameterError(f"image size must be positive, not {size}")
    x0, y0, x1, y1 = as_region(region).bounds if region is not None else (0.0, 0.0, 1.0, 1.0)
    w, h = x1 - x0, y1 - y0
    # far from the origin (more than 10 region sizes) the drawing is moved to it, by a whole
    # number, since coordinates are written to 5 significant digits
    shift = np.zeros(2)
    if max(abs(x0), abs(x1), abs(y0), abs(y1)) > 10 * max(w, h):
        shift = np.round([(x0 + x1) / 2, (y0 + y1) / 2])
        x0, x1, y0, y1 = x0 - shift[0], x1 - shift[0], y0 - shift[1], y1 - shift[1]
    pad = 0.02 * max(w, h)
    vb = (x0 - pad, -(y1 + pad), w + 2 * pad, h + 2 * pad)
    if width is not None:
        scale = width / vb[2]
    elif height is not None:
        scale = height / vb[3]
    else:
        scale = size / max(vb[2], vb[3])
    patches = iter(patches)
    first = next(patches, None)
    if first is not None:
        patches = itertools.chain([first], patches)
    line = (STROKE_PX if stroke_width_px is None else stroke_width_px) / scale  # frame and vectors
    if stroke_width is not None:
        sw = stroke_width
    elif stroke_width_px is not None or first is None or not len(first):
        sw = line
    else:  # outlines as wide as the tiles allow: thinner for small tiles, none for tiny ones
        sw = stroke_px_for(tile_size(first) * scale) / scale
    width_px = round(vb[2] * scale)
    height_px = round(vb[3] * scale)
    refuse_over("pixels", width_px * height_px, MAX_PNG_PIXELS, hint=f"a {width_px} x {height_px} image; "
                "give a smaller --width/--height/--dpi")
    if not is_colour(stroke):
        raise ParseError(f"stroke colour {stroke[:40]!r} is not a CSS colour name or #rgb / #rrggbb")
    yield (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width_px}" height="{height_px}" '
           f'viewBox="{vb[0]:.6g} {vb[1]:.6g} {vb[2]:.6g} {vb[3]:.6g}">')
    if background:
        yield (f'<rect x="{vb[0]:.6g}" y="{vb[1]:.6g}" width="{vb[2]:.6g}" height="{vb[3]:.6g}" '
               f'fill="{html.escape(background)}"/>')
    if clip:
        # the clip path is applied to the y-flipped group below, so it is in tile coordinates
        yield f'<clipPath id="region"><rect x="{x0:.6g}" y="{y0:.6g}" width="{w:.6g}" height="{h:.6g}"/></clipPath>'
    clip_attr = ' clip-path="url(#region)"' if clip else ""
    yield (f'<g transform="scale(1,-1)"{clip_attr} stroke="{html.escape(stroke)}" '
           f'stroke-width="{sw:.4g}" stroke-linejoin="round">')
    tiles = 0
    label_items: list[tuple[float, float, str]] = []
    for patch in patches:
        tiles += len(patch)
        yield from _tile_lines(patch, palette, markings, labels, sw, label_items, shift)
    for segments, colour, factor in overlay:
        if not is_colour(colour):
            raise ParseError(f"overlay colour {colour[:40]!r} is not a CSS colour name or #rgb / #rrggbb")
        segs = np.asarray(segments, dtype=float).reshape(-1, 2, 2) - shift
        if len(segs):
            yield (f'<path fill="none" stroke="{html.escape(colour)}" stroke-width="{factor * max(sw, line / 2):.4g}" '
                   f'stroke-linecap="round" d="{" ".join(_path_data(segs, closed=False))}"/>')
    if clip and tiles:
        # a frame on the region's border: tiles cut by the clip end on a line, not in stubs
        # (drawn at twice the width, half of it inside the clip)
        yield (f'<rect x="{x0:.6g}" y="{y0:.6g}" width="{w:.6g}" height="{h:.6g}" fill="none" '
               f'stroke-width="{2 * max(sw, line / 2):.4g}"/>')
    if vectors is not None:
        o, v1, v2 = (np.asarray(v, dtype=float) for v in vectors)
        o = o - shift
        yield ('<defs><marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="6" '
               'markerHeight="6" orient="auto"><path d="M0 0 L10 5 L0 10z" fill="#c00"/></marker></defs>')
        for v in (v1, v2):
            e = o + v
            yield (f'<line x1="{o[0]:.6g}" y1="{o[1]:.6g}" x2="{e[0]:.6g}" y2="{e[1]:.6g}" '
                   f'stroke="#c00" stroke-width="{2 * line:.4g}" marker-end="url(#arrow)"/>')
    yield "</g>"
    if label_items:
        fs = 0.15 * (max(w, h) / max(1.0, np.sqrt(tiles))) if tiles else 0.1
        yield f'<g font-size="{fs:.4g}" text-anchor="middle" dominant-baseline="middle" fill="#000">'
        for lx, ly, lab in label_items:
            yield f'<text x="{lx:.5g}" y="{-ly:.5g}">{html.escape(lab)}</text>'
        yield "</g>"
    yield "</svg>"


def _tile_lines(patch: Any, palette: Sequence[str], markings: bool, labels: bool, sw: float,
                label_items: list[tuple[float, float, str]], shift: np.ndarray) -> Iterator[str]:
    """One patch's tiles, moved by ``-shift``: a filled path per colour, then one path of
    markings; its edge labels (with ``labels``) are appended to ``label_items``."""
    by_colour: dict[int, list[str]] = {}
    mark_paths: list[str] = []
    for p, idx, pts in patch.groups():
        data = _path_data(pts - shift)
        for c, d in zip(patch.colour[idx].tolist(), data):
            by_colour.setdefault(c, []).append(d)
        proto = patch.prototiles[p]
        if markings and proto.marking:
            for mk in proto.marking:
                mpts = Affine.apply(patch.transform[idx], mk)
                mark_paths.extend(_path_data(mpts - shift, closed=False))
        if labels and proto.edge_labels is not None:
            outline = proto.outline
            if proto.corners is not None:  # shaped edges: one label per tiling edge, on its chord
                corner_pts = outline[list(proto.corners)]
                mids = (corner_pts + np.roll(corner_pts, -1, axis=0)) / 2
                texts = [proto.edge_labels[c] for c in proto.corners]
            else:
                mids = (outline + np.roll(outline, -1, axis=0)) / 2
                texts = list(proto.edge_labels)
            cen = outline.mean(axis=0)
            inset = mids + 0.18 * (cen - mids)
            where = Affine.apply(patch.transform[idx], inset) - shift  # (m, k, 2)
            for tile_pts in where:
                for (lx, ly), lab in zip(tile_pts.tolist(), texts):
                    label_items.append((lx, ly, str(lab)))
    for c in sorted(by_colour):
        fill = palette[c % len(palette)]
        yield f'<path fill="{html.escape(fill)}" d="{" ".join(by_colour[c])}"/>'
    if mark_paths:
        yield f'<path fill="none" stroke-width="{sw * 0.8:.4g}" d="{" ".join(mark_paths)}"/>'


def svg_to_png(svg: str, path: str | Path, dpi: float = 96.0) -> None:
    """Write SVG text as a PNG file (needs cairosvg: ``pip install 'tilekit[png]'``)."""
    try:
        import cairosvg
    except (ImportError, OSError) as exc:
        raise TilekitError(
            f"PNG output needs cairosvg and the cairo library ({exc.__class__.__name__}); "
            "install it with: pip install 'tilekit[png]', or write .svg instead"
        ) from None
    try:
        cairosvg.svg2png(bytestring=svg.encode("utf-8"), write_to=str(path), scale=dpi / 96.0)
    except MemoryError:
        raise TilekitError("the PNG is too large to draw; give a smaller --width/--height/--dpi") from None
    except Exception as exc:  # cairo's own errors (e.g. an image larger than 32767 pixels)
        if type(exc).__name__ in ("CairoError", "Error"):
            raise TilekitError(f"cannot draw the PNG ({exc}); give a smaller --width/--height/--dpi") from None
        raise


def write_svg(svg: str, path: str | Path, dpi: float = 96.0) -> Path:
    """Write SVG text to ``path`` as .svg, or as .png through cairosvg (chosen by the suffix;
    a PNG has the SVG's pixel size scaled by ``dpi``/96, within MAX_PNG_PIXELS)."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".svg", ".png"):
        raise ParameterError(f"output file {str(path)!r} must end in .svg or .png")
    if suffix == ".png":
        _check_pixels(svg, dpi)
    try:
        if suffix == ".svg":
            path.write_text(svg, encoding="utf-8")
        else:
            svg_to_png(svg, path, dpi)
    except OSError as exc:
        raise TilekitError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from None
    return path


def _check_pixels(svg: str, dpi: float) -> None:
    head = svg[: svg.index(">")]
    try:
        w = float(head.split(' width="')[1].split('"')[0]) * dpi / 96
        h = float(head.split(' height="')[1].split('"')[0]) * dpi / 96
    except (IndexError, ValueError):
        return
    refuse_over("pixels", w * h, MAX_PNG_PIXELS, hint=f"a {w:.0f} x {h:.0f} PNG; give a smaller --width/--height/--dpi")


def write_image(patch: Any, path: str | Path, **options: Any) -> Path:
    """Write ``patch`` to ``path`` as .svg or .png (chosen by the suffix); ``dpi`` scales a PNG,
    the other options are :func:`patch_to_svg`'s."""
    if Path(path).suffix.lower() not in (".svg", ".png"):  # fail before drawing
        raise ParameterError(f"output file {str(path)!r} must end in .svg or .png")
    dpi = float(options.pop("dpi", 96.0) or 96.0)
    return write_svg(patch_to_svg(patch, **options), path, dpi)
