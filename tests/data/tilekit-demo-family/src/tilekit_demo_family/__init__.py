"""A tilekit family plugin: running-bond brick walls (rows of a x b bricks, each row shifted).

The whole plugin is this module and one entry point in pyproject.toml:
``[project.entry-points.tilekit] demo_bricks = "tilekit_demo_family"``. It also owns a result
table, ``brick_sizes`` (created by its Alembic branch in ``migrations/``), which its search
``brick-sizes`` fills with one row per brick a x b (integer sides, a >= b, area <= N).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import sqlalchemy as sa

import tilekit
from tilekit.errors import ParameterError
from tilekit.plugins import CatalogueRecord, ChunkResult, Family, ResultTable, Search, SearchParam
from tilekit.tiling import PeriodicTiling, Prototile

FAMILY = "bricks"


class BrickWall(PeriodicTiling):
    """Bricks of width ``a`` and height ``b``; each row is shifted by ``shift`` * a."""

    def __init__(self, a: float = 2.0, b: float = 1.0, shift: float = 0.5, name: str = "") -> None:
        if not (a > 0 and b > 0):
            raise ParameterError(f"brick sides must be positive, got a={a}, b={b}")
        if not 0 <= shift < 1:
            raise ParameterError(f"shift must be in [0, 1), got {shift}")
        self.a, self.b, self.shift = float(a), float(b), float(shift)
        brick = Prototile(np.array([[0, 0], [a, 0], [a, b], [0, b]], dtype=float), name="brick")
        super().__init__([brick], [0], np.eye(3)[None], (a, 0.0), (shift * a, b),
                         family=FAMILY, name=name or f"bricks-{a:g}x{b:g}-{shift:g}")

    def spec(self) -> dict[str, Any]:
        return {"a": self.a, "b": self.b, "shift": self.shift, "name": self.name}

    def properties(self) -> dict[str, Any]:
        return {
            "periodic": True,
            "k_hedral": 1,
            "k_isohedral": 1,
            # a shifted row puts a brick corner inside the neighbouring brick's long edge
            "edge_to_edge": self.shift == 0,
            "brick_width": self.a,
            "brick_height": self.b,
        }

    def describe(self) -> str:
        return (f"running bond: {self.a:g} x {self.b:g} bricks, rows shifted by "
                f"{self.shift:g} of a brick")

    def configure(self, **options: Any) -> BrickWall:
        unknown = set(options) - {"params"}
        if unknown:
            raise ParameterError(f"bricks take only --param a,b,shift; got {', '.join(sorted(unknown))}")
        values = list(options.get("params", []))
        if not 1 <= len(values) <= 3:
            raise ParameterError(f"bricks take 1 to 3 parameters (a, b, shift), got {len(values)}")
        a, b, shift = values + [self.a, self.b, self.shift][len(values):]
        return BrickWall(a, b, shift)


def from_spec(spec: Mapping[str, Any]) -> BrickWall:
    try:
        return BrickWall(spec["a"], spec["b"], spec.get("shift", 0.5), name=spec.get("name", ""))
    except (KeyError, TypeError) as exc:
        raise ParameterError(f"brick spec needs numbers a and b: {exc}") from None


@tilekit.hookimpl
def tilekit_families():
    return [Family(FAMILY, "Brick walls: one a x b rectangle, rows shifted (demo plugin)", from_spec)]


@tilekit.hookimpl
def tilekit_catalogue_records():
    wall = BrickWall(2.0, 1.0, 0.5, name="running-bond")
    return [
        CatalogueRecord(
            FAMILY,
            wall.name,
            wall.spec(),
            title="running bond of 2 x 1 bricks",
            # brickwork is the textbook example of wallpaper group cmm (2*22)
            properties={**wall.properties(), "symmetry_group": "2*22", "wallpaper_group": "cmm"},
            aliases=["stretcher-bond"],
        )
    ]


METADATA = sa.MetaData()
BRICK_SIZES = sa.Table(
    "brick_sizes",
    METADATA,
    sa.Column("name", sa.String(80), primary_key=True),
    sa.Column("a", sa.Integer, nullable=False),
    sa.Column("b", sa.Integer, nullable=False),
    sa.Column("area", sa.Integer, nullable=False, index=True),
    sa.Column("square", sa.Boolean, nullable=False),
    sa.Column("run_id", sa.Integer),
)


def size_chunks(params):
    return [{"area": n} for n in range(1, params["max_area"] + 1)]


def size_run_chunk(params, chunk):
    n = chunk["area"]
    rows = [{"name": f"bricks-{n // b}x{b}-0.5", "a": n // b, "b": b, "area": n, "square": n // b == b}
            for b in range(1, int(n ** 0.5) + 1) if n % b == 0]
    return ChunkResult(rows={"brick_sizes": rows}, counts={"bricks": len(rows)})


SIZES = Search("brick-sizes", "integer bricks a x b with a >= b and area up to max_area", FAMILY,
               [SearchParam("max_area", int, 12, "largest area", min=1, max=10_000)],
               size_chunks, size_run_chunk)


@tilekit.hookimpl
def tilekit_searches():
    return [SIZES]


@tilekit.hookimpl
def tilekit_result_tables():
    return [ResultTable(BRICK_SIZES, key=("name",), family="brick-sizes", name_column="name",
                        spec=lambda row: {"a": row["a"], "b": row["b"], "shift": 0.5, "name": row["name"]},
                        tiling_family=FAMILY)]


@tilekit.hookimpl
def tilekit_migration_locations():
    return [str(Path(__file__).parent / "migrations")]


# --------------------------------------------------------------------------- its web page
# A page of its own in `tilekit serve` (/bricks?a=2&b=1&shift=0.5), a menu link to it, a link
# from its tilings' pages, its result rows linking to it, and its script: the web hooks of
# docs/plugins.md, the same way the isohedral and Penrose editors arrive.

#: The wall drawn on the page covers this many bricks across and up (a bounded picture).
PAGE_BRICKS = 8


def wall_path(a: float, b: float, shift: float = 0.5) -> str:
    return f"/bricks?a={a:g}&b={b:g}&shift={shift:g}"


def bricks_page(request: Any, web: Any) -> str:
    """``/bricks?a=2&b=1&shift=0.5``: a running-bond wall drawn in the site's layout."""
    import html
    import math

    from tilekit.render import patch_to_svg

    q = request.query_params
    try:
        a, b, shift = (float(q.get(k, d)) for k, d in (("a", "2"), ("b", "1"), ("shift", "0.5")))
    except ValueError:
        raise ParameterError("a, b and shift are numbers, e.g. /bricks?a=2&b=1&shift=0.5") from None
    if not all(math.isfinite(v) for v in (a, b, shift)):
        raise ParameterError(f"a={a:g}, b={b:g}, shift={shift:g}: the numbers must be finite")
    wall = BrickWall(a, b, shift)  # ParameterError for a side <= 0 or a shift outside [0, 1)
    if max(a, b) > 1000 * min(a, b):  # a bounded picture: the wall is PAGE_BRICKS bricks square
        raise ParameterError(f"a={a:g}, b={b:g}: the sides may be at most 1000 times apart")
    region = (0.0, 0.0, PAGE_BRICKS * wall.a, PAGE_BRICKS * wall.b)
    patch = wall.patch(region)
    svg = patch_to_svg(patch, region=region, size=480)
    body = (f'<h1 id="bricks-title">Brick wall {a:g} x {b:g}, rows shifted by {shift:g}</h1>'
            f'<p id="count"></p><figure id="wall" data-bricks="{len(patch)}">{svg}</figure>'
            f"<p>{html.escape(wall.describe())}</p>")
    return web.page("brick walls", body, scripts=["plugins/demo_bricks/bricks.js"])


@tilekit.hookimpl
def tilekit_web_routes(web):
    from tilekit.plugins import WebRoute

    return [WebRoute("/bricks", bricks_page)]


@tilekit.hookimpl
def tilekit_web_menu_links(web):
    return [("/bricks", "brick walls")]


@tilekit.hookimpl
def tilekit_web_tiling_links(web, name, tiling):
    if isinstance(tiling, BrickWall):
        return [(wall_path(tiling.a, tiling.b, tiling.shift), "open in the brick wall page")]
    return None


@tilekit.hookimpl
def tilekit_web_render_cell(table, column, value, row):
    if table == "brick_sizes" and column == "name":
        import html

        return f'<a class="brick" href="{html.escape(wall_path(row["a"], row["b"]))}">{html.escape(str(value))}</a>'
    return None


@tilekit.hookimpl
def tilekit_web_static():
    return [("demo_bricks", Path(__file__).parent / "static")]
