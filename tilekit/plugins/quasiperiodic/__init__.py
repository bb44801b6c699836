"""The quasiperiodic family plugin: n-fold rhombic tilings by de Bruijn's multigrid (§6.3, §7.2).

Modules: ``star`` (the n-fold star: grid directions, rhomb kinds, how a pair of grids places
its rhomb), ``multigrid`` (the rhombs of a region from the grid lines crossing it),
``project`` (the same tilings by cut-and-project: the acceptance window, exact frequencies,
the independent check), ``tiling`` (:class:`QuasiperiodicTiling`: options n, gamma,
singular; patch, iter_patches). The catalogue records are the classical orders listed in
``catalogue/quasiperiodic/multigrids.toml``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import tilekit
from tilekit.lazy import lazy_exports
from tilekit.plugins import CatalogueRecord, Family, web_pages

if TYPE_CHECKING:  # pragma: no cover
    from tilekit.plugins.quasiperiodic.tiling import QuasiperiodicTiling

#: The family's name (tilekit.plugins.quasiperiodic.tiling.FAMILY, which a test keeps equal):
#: spelled here so that loading the plugin does not import NumPy.
FAMILY = "quasiperiodic"

#: Public names, imported on first use (PEP 562): measured start-up cost, the modules load
#: NumPy and shapely (about 0.3 s), which every `tilekit` command would pay when pluggy loads
#: this plugin.
_LAZY = {
    "Star": "tilekit.plugins.quasiperiodic.star",
    "star": "tilekit.plugins.quasiperiodic.star",
    "Rhombs": "tilekit.plugins.quasiperiodic.multigrid",
    "SingularGrid": "tilekit.plugins.quasiperiodic.multigrid",
    "rhombs": "tilekit.plugins.quasiperiodic.multigrid",
    "Window": "tilekit.plugins.quasiperiodic.project",
    "window": "tilekit.plugins.quasiperiodic.project",
    "frequencies": "tilekit.plugins.quasiperiodic.project",
    "QuasiperiodicTiling": "tilekit.plugins.quasiperiodic.tiling",
    "SingularWarning": "tilekit.plugins.quasiperiodic.tiling",
    "default_gamma": "tilekit.plugins.quasiperiodic.tiling",
}
__getattr__, __dir__ = lazy_exports(__name__, _LAZY, pinned=("star", "tiling"))

__all__ = [
    "FAMILY",
    "QuasiperiodicTiling",
    "Rhombs",
    "SingularGrid",
    "SingularWarning",
    "Star",
    "Window",
    "default_gamma",
    "frequencies",
    "multigrid_records",
    "rhombs",
    "star",
    "tiling",
    "window",
]

#: The records' data file (one [[tiling]] table each: name, title, n, optional gamma, aliases).
RECORDS_FILE = "multigrids.toml"


def tiling(n: int = 5, **options: Any) -> QuasiperiodicTiling:
    """The multigrid tiling of order ``n`` with options ``gamma`` and ``singular``."""
    # measured start-up cost: the tiling module loads NumPy and shapely (~0.3 s), on first use
    from tilekit.plugins.quasiperiodic.tiling import QuasiperiodicTiling

    return QuasiperiodicTiling(n, **options)


def _from_spec(spec: Mapping[str, Any]) -> QuasiperiodicTiling:
    # measured start-up cost: as in tiling()
    from tilekit.plugins.quasiperiodic.tiling import QuasiperiodicTiling

    return QuasiperiodicTiling.from_spec(spec)


def multigrid_records() -> list[CatalogueRecord]:
    """The shipped records, read from catalogue/quasiperiodic/multigrids.toml (one-line errors
    naming the file and the field)."""
    # measured start-up cost: the tiling module, as in tiling() (records are built only when seeding)
    from tilekit.plugins.quasiperiodic.tiling import QuasiperiodicTiling
    from tilekit.resources import catalogue_dir, read_toml
    from tilekit.schema import Field, check

    path = catalogue_dir() / FAMILY / RECORDS_FILE
    where = f"quasiperiodic records {RECORDS_FILE}"
    record = Field("table", fields={
        "name": Field("str", required=True),
        "title": Field("str", default=""),
        "n": Field("int", required=True, range=(4, 50)),
        "gamma": Field("list", items=Field("number")),
        "aliases": Field("list", items=Field("str"), default=[]),
    })
    data = check(Field("table", fields={"tiling": Field("list", required=True, items=record)}),
                 read_toml(path, "quasiperiodic records"), where)
    out = []
    for rec in data["tiling"]:
        t = QuasiperiodicTiling(rec["n"], rec.get("gamma"), name=rec["name"], title=rec["title"])
        out.append(CatalogueRecord(family=FAMILY, name=t.name, spec=t.spec(), title=t.title,
                                   properties=t.properties(), aliases=list(rec["aliases"])))
    return out


@tilekit.hookimpl
def tilekit_families() -> list[Family]:
    return [
        Family(
            name=FAMILY,
            summary="Quasiperiodic rhomb tilings of any order n by de Bruijn's multigrid (§6.3, §7.2)",
            from_spec=_from_spec,
            description=(
                "N grids of parallel lines (n for odd n, n/2 for even n) with offsets gamma; every "
                "crossing of two lines is a rhomb. Any region, anywhere, from the lines crossing it; "
                "checked against cut-and-project. Options: n=4..50, gamma=G[,G...], singular=refuse|perturb."
            ),
        )
    ]


@tilekit.hookimpl
def tilekit_catalogue_records() -> list[CatalogueRecord]:
    return multigrid_records()


# the web app (tilekit serve): the pages are this plugin's (web.py), the web layer names none
(tilekit_web_routes, tilekit_web_menu_links, tilekit_web_tiling_links,
 tilekit_web_static) = web_pages("tilekit.plugins.quasiperiodic.web", [("/multigrid", "multigrid offsets")])
