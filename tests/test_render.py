"""Rendering: SVG structure, PNG through cairosvg, and clear errors for bad output requests."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from tilekit import Affine, Colouring, ParameterError, ParseError, Patch, PeriodicTiling, Prototile
from tilekit.geometry import regular_polygon
from tilekit.render import parse_palette, patch_to_svg, write_image

SVG = "{http://www.w3.org/2000/svg}"


def triangle_patch() -> Patch:
    tri = Prototile(regular_polygon(3), edge_labels=(1, -1, 2))
    unit = np.array([np.eye(3), Affine.half_turn((0.75, math.sqrt(3) / 4))])
    t = PeriodicTiling([tri], [0, 0], unit, (1, 0), (0.5, math.sqrt(3) / 2), Colouring.by_aspect([0, 1]))
    return t.patch((-2, -2, 2, 2))


def test_one_path_per_colour_with_one_subpath_per_tile() -> None:
    patch = triangle_patch()
    root = ET.fromstring(patch_to_svg(patch, palette=["red", "#00f"]))
    paths = [p for p in root.iter(SVG + "path") if p.get("fill") not in (None, "none")]
    assert {p.get("fill") for p in paths} == {"red", "#00f"}  # 2 aspects coloured by aspect
    subpaths = sum(p.get("d").count("M") for p in paths)
    assert subpaths == len(patch)


def test_labels_and_vectors_are_drawn() -> None:
    patch = triangle_patch()
    svg = patch_to_svg(patch, labels=True, vectors=((0, 0), (1, 0), (0.5, 0.8)))
    root = ET.fromstring(svg)
    texts = [t.text for t in root.iter(SVG + "text")]
    assert len(texts) == 3 * len(patch) and set(texts) == {"1", "-1", "2"}
    assert len(list(root.iter(SVG + "line"))) == 2


def test_png_is_written(tmp_path) -> None:
    out = write_image(triangle_patch(), tmp_path / "t.png", size=200)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_bad_requests_are_one_line_errors(tmp_path) -> None:
    with pytest.raises(ParameterError, match=r"\.svg or \.png"):
        write_image(triangle_patch(), tmp_path / "t.jpg")
    with pytest.raises(ParseError, match="not a CSS colour name"):
        parse_palette("red,#12345")
    assert parse_palette("red, #abc") == ("red", "#abc")


def test_region_clip_is_in_tile_coordinates() -> None:
    """The clip rectangle is used inside the y-flipped group, so it must not be flipped itself."""
    root = ET.fromstring(patch_to_svg(triangle_patch(), region=(-1, 0.5, 1.5, 1.5)))
    rect = next(root.iter(SVG + "clipPath")).find(SVG + "rect")
    box = [float(rect.get(k)) for k in ("x", "y", "width", "height")]
    assert box == pytest.approx([-1, 0.5, 2.5, 1.0])
    group = next(g for g in root.iter(SVG + "g") if g.get("clip-path"))
    assert group.get("transform") == "scale(1,-1)"


def _path_points(svg: str) -> np.ndarray:
    root = ET.fromstring(svg)
    d = " ".join(p.get("d") for p in root.iter(SVG + "path") if p.get("fill") not in (None, "none"))
    nums = [float(v) for v in d.replace("M", " ").replace("L", " ").replace("Z", " ").split()]
    return np.array(nums).reshape(-1, 2)


@pytest.mark.parametrize("where", [(1e6, 1e6), (-3.5e5, 7.25e4)])
def test_a_patch_far_from_the_origin_is_drawn_where_its_view_box_is(where) -> None:
    # path coordinates have 5 significant digits: far away the drawing is moved to the origin
    # by a whole number, so the tiles keep their shapes (at (10^6, 10^6) they had collapsed)
    near = triangle_patch()
    shift = np.round(where)
    far = near.transformed(Affine.translation(*shift))
    svg = patch_to_svg(far, region=(shift[0] - 2, shift[1] - 2, shift[0] + 2, shift[1] + 2))
    root = ET.fromstring(svg)
    x, y, w, h = (float(v) for v in root.get("viewBox").split())
    assert (x, y, w, h) == pytest.approx((-2.08, -2.08, 4.16, 4.16))
    assert np.allclose(_path_points(svg), _path_points(patch_to_svg(near, region=(-2, -2, 2, 2))))


def test_a_patch_near_the_origin_is_drawn_in_its_own_coordinates() -> None:
    patch = triangle_patch().transformed(Affine.translation(30.0, 0.0))
    pts = _path_points(patch_to_svg(patch, region=(25, -5, 35, 5)))
    corners = np.concatenate([p for p in patch.polygons()])
    assert pts.min(axis=0) == pytest.approx(corners.min(axis=0), abs=1e-3)
