"""Draw Wang grids: squares split into four coloured triangles, or user textures (ex. 6.8).

Each tile of the set is drawn once inside ``<defs>`` and every cell is a ``<use>`` of it,
so a large grid costs one short element per cell. Edge tiles show one triangle per side in
the colour of that side's edge; corner tiles (Lagae and Dutré) show one quadrant per corner.

A texture maps edge colour tokens to SVG fragments drawn in the frame of an edge: the edge
runs from (0, 0) to (1, 0), and the motif may reach 0.5 to either side of it (SVG y points
down). Every tile clips each edge's motif to its own triangle; since the two tiles sharing
an edge place the motif identically, the halves join across the edge into one figure —
the continuity across tile edges that exercise 6.8 asks for. For corner tiles a texture maps
corner colours to motifs centred on the corner (0, 0), each tile showing the quarter in its
own quadrant, so the four tiles at a lattice point complete one figure. Textures load from
TOML files (:func:`load_texture`) so the markings live outside the program.
"""

from __future__ import annotations

import html
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from tilekit.errors import ParameterError, ParseError
from tilekit.plugins.wang.tileset import CORNERS, SIDES, WangTileSet
from tilekit.render import write_svg
from tilekit.resources import read_toml

#: Fallback colours for tokens without a palette entry.
DEFAULT_COLOURS = (
    "#e63946", "#2a9d8f", "#e9c46a", "#457b9d", "#f4a261", "#8338ec", "#90be6d", "#6c757d",
    "#ff70a6", "#70d6ff", "#bc6c25", "#3a0ca3",
)

# triangles of the unit cell (SVG coordinates, y down), by side N, E, S, W
_TRIANGLES = {
    "N": "0,0 1,0 0.5,0.5",
    "E": "1,0 1,1 0.5,0.5",
    "S": "1,1 0,1 0.5,0.5",
    "W": "0,1 0,0 0.5,0.5",
}
# where each side's edge frame sits in the cell: horizontal edges unrotated, vertical rotated
_FRAMES = {
    "N": "translate(0,0)",
    "S": "translate(0,1)",
    "W": "translate(0,0) rotate(90)",
    "E": "translate(1,0) rotate(90)",
}
# corner quadrants NE, SE, SW, NW
_QUADRANTS = {"NE": (0.5, 0.0), "SE": (0.5, 0.5), "SW": (0.0, 0.5), "NW": (0.0, 0.0)}
# the corner points themselves (centres of corner motifs)
_CORNER_POINTS = {"NE": (1, 0), "SE": (1, 1), "SW": (0, 1), "NW": (0, 0)}


def colour_of(tileset: WangTileSet, token: str, index: int) -> str:
    """The CSS colour of a colour token: the set's palette, else a default by index."""
    return tileset.palette.get(token, DEFAULT_COLOURS[index % len(DEFAULT_COLOURS)])


def load_texture(path: str | Path) -> dict[str, str]:
    """Read a texture file: a TOML table ``[colours]`` of ``TOKEN = '<svg fragment>'``.

    Errors name the file and, from tomllib, the line.
    """
    p = Path(path)
    data = read_toml(p, "texture file")
    table = data.get("colours")
    if not isinstance(table, dict) or not table:
        raise ParseError(f"{p}: needs a [colours] table mapping colour tokens to SVG fragments")
    out: dict[str, str] = {}
    for token, frag in table.items():
        if not isinstance(frag, str) or "<" not in frag:
            raise ParseError(f"{p}: colour {token!r} must map to an SVG fragment string like '<circle .../>'")
        out[str(token)] = frag
    return out


def _tile_def(
    tileset: WangTileSet, t: int, texture: Mapping[str, str] | None, stroke: str, background: str
) -> str:
    row = tileset.tiles[t]
    parts = [f'<g id="wt{t}">']
    if tileset.corners is not None:
        for name, k in zip(CORNERS, range(4)):
            c = int(tileset.corners[t, k])
            token = tileset.corner_colours[c]
            fill = colour_of(tileset, token, c) if texture is None else background
            x, y = _QUADRANTS[name]
            parts.append(f'<rect x="{x}" y="{y}" width="0.5" height="0.5" fill="{fill}"/>')
            if texture is not None:
                motif = texture.get(token)
                if motif is None:
                    raise ParameterError(
                        f"texture has no motif for corner colour {token!r}; it covers {sorted(texture)}"
                    )
                cx, cy = _CORNER_POINTS[name]
                parts.append(
                    f'<g clip-path="url(#clip{name})"><g transform="translate({cx},{cy})">{motif}</g></g>'
                )
    else:
        for side, k in zip(SIDES, range(4)):
            token = tileset.colours[int(row[k])]
            fill = colour_of(tileset, token, int(row[k])) if texture is None else background
            parts.append(f'<polygon points="{_TRIANGLES[side]}" fill="{fill}"/>')
            if texture is not None:
                motif = texture.get(token)
                if motif is None:
                    raise ParameterError(
                        f"texture has no motif for edge colour {token!r}; it covers {sorted(texture)}"
                    )
                parts.append(
                    f'<g clip-path="url(#clip{side})"><g transform="{_FRAMES[side]}">{motif}</g></g>'
                )
    if stroke:
        parts.append(f'<rect x="0" y="0" width="1" height="1" fill="none" stroke="{stroke}" stroke-width="0.02"/>')
    parts.append("</g>")
    return "".join(parts)


def wang_svg(
    grid: np.ndarray,
    tileset: WangTileSet,
    texture: Mapping[str, str] | str | Path | None = None,
    size: int = 800,
    stroke: str = "#222",
    title: str | None = None,
    background: str = "#fdf6e3",
) -> str:
    """SVG text of a grid of tiles (row 0 at the top, as printed).

    ``texture`` is a mapping from edge colour tokens to SVG fragments in the edge frame, or
    the path of a texture file; without it each side is a plain coloured triangle (corner
    sets: a coloured quadrant per corner). With a texture, tiles are ``background`` under
    the motifs; ``stroke`` outlines each tile ('' for none).
    """
    g = np.asarray(grid)
    if g.ndim != 2 or g.size == 0 or not np.issubdtype(g.dtype, np.integer):
        raise ParameterError(f"wang_svg needs a non-empty 2-D integer grid, got shape {g.shape}")
    if g.min() < 0 or g.max() >= len(tileset):
        raise ParameterError(f"grid holds tile indices outside 0..{len(tileset) - 1} of set {tileset.name!r}")
    if isinstance(texture, str | Path):
        texture = load_texture(texture)
    rows, cols = g.shape
    scale = size / max(rows, cols)
    used = np.unique(g).tolist()
    defs = [
        f'<clipPath id="clip{side}"><polygon points="{pts}"/></clipPath>' for side, pts in _TRIANGLES.items()
    ]
    defs += [
        f'<clipPath id="clip{name}"><rect x="{x}" y="{y}" width="0.5" height="0.5"/></clipPath>'
        for name, (x, y) in _QUADRANTS.items()
    ]
    defs += [_tile_def(tileset, t, texture, stroke, background) for t in used]
    ii, jj = np.divmod(np.arange(rows * cols), cols)
    uses = "".join(
        f'<use xlink:href="#wt{t}" x="{j}" y="{i}"/>' for t, i, j in zip(g.ravel().tolist(), ii.tolist(), jj.tolist())
    )
    head = (
        f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
        f'width="{cols * scale:.6g}" height="{rows * scale:.6g}" viewBox="0 0 {cols} {rows}">'
    )
    label = f"<title>{html.escape(title)}</title>" if title else ""
    return head + label + "<defs>" + "".join(defs) + "</defs>" + uses + "</svg>"


def write_wang_image(
    grid: np.ndarray, tileset: WangTileSet, path: str | Path, **options: object
) -> Path:
    """Write :func:`wang_svg` to ``path`` (.svg, or .png through cairosvg)."""
    return write_svg(wang_svg(grid, tileset, **options), path)  # type: ignore[arg-type]
