"""The curved-geometry plugin: regular tilings {p, q} of the sphere and of the hyperbolic plane
(§3.6.2), two families, ``spherical`` and ``hyperbolic``, over one tiling class.

Modules: ``model`` (the sphere and the hyperboloid as 3x3 matrices, the {p, q} tile, its
edge half-turns, the projections), ``layers`` (exact layers: the hyperbolic boundary
automaton, the sphere's breadth-first faces), ``kernels`` (the automaton's compiled step),
``patch`` (ModelPrototile, ModelPatch: transforms on the model, outlines projected,
validation in the Klein model and on the sphere), ``tiling`` (RegularTiling), ``render``
(the Poincaré disc with true arcs; the sphere in orthographic view). The records are
``catalogue/curved/regular.toml``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import tilekit
from tilekit.lazy import lazy_exports
from tilekit.plugins import CatalogueRecord, Family

if TYPE_CHECKING:  # pragma: no cover
    from tilekit.plugins.curved.tiling import RegularTiling

#: The families' names (tilekit.plugins.curved.model.SPHERE / HYPERBOLIC, which a test keeps
#: equal): spelled here so that loading the plugin does not import NumPy.
SPHERICAL, HYPERBOLIC = "spherical", "hyperbolic"

#: Public names, imported on first use (PEP 562): measured start-up cost, the modules load
#: NumPy and shapely (about 0.3 s), which every `tilekit` command would pay when pluggy loads
#: this plugin.
_LAZY = {
    "RegularTiling": "tilekit.plugins.curved.tiling",
    "ModelPatch": "tilekit.plugins.curved.patch",
    "ModelPrototile": "tilekit.plugins.curved.patch",
    "RegularPolygon": "tilekit.plugins.curved.model",
    "layer_counts": "tilekit.plugins.curved.layers",
    "hyperbolic_layers": "tilekit.plugins.curved.layers",
}
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)

__all__ = ["HYPERBOLIC", "SPHERICAL", "ModelPatch", "ModelPrototile", "RegularPolygon", "RegularTiling",
           "curved_records", "hyperbolic_layers", "layer_counts", "regular"]

#: The records' data file (one [[tiling]] table each: name, title, p, q, aliases, oeis).
RECORDS_FILE = "regular.toml"


def regular(p: int, q: int, **options: Any) -> RegularTiling:
    """The regular tiling {p, q} (options: depth, radius, samples)."""
    # measured start-up cost: the tiling module loads NumPy and shapely (~0.3 s), on first use
    from tilekit.plugins.curved.tiling import RegularTiling

    return RegularTiling(p, q, **options)


def _from_spec(want: str) -> Any:
    def build(spec: Mapping[str, Any]) -> RegularTiling:
        # measured start-up cost: as in regular()
        from tilekit.plugins.curved.tiling import RegularTiling

        return RegularTiling.from_spec(spec, want=want)

    return build


def curved_records() -> list[CatalogueRecord]:
    """The shipped records from catalogue/curved/regular.toml (one-line errors naming the
    file and the field)."""
    # measured start-up cost: the tiling module, as in regular() (records are built only when seeding)
    from tilekit.plugins.curved.tiling import RegularTiling
    from tilekit.resources import catalogue_dir, read_toml
    from tilekit.schema import Field, check

    path = catalogue_dir() / "curved" / RECORDS_FILE
    where = f"curved records {RECORDS_FILE}"
    record = Field("table", fields={
        "name": Field("str", required=True),
        "title": Field("str", default=""),
        "p": Field("int", required=True, range=(3, 60)),
        "q": Field("int", required=True, range=(3, 60)),
        "oeis": Field("str"),
        "aliases": Field("list", items=Field("str"), default=[]),
    })
    data = check(Field("table", fields={"tiling": Field("list", required=True, items=record)}),
                 read_toml(path, "curved records"), where)
    out = []
    for rec in data["tiling"]:
        t = RegularTiling(rec["p"], rec["q"], name=rec["name"], title=rec["title"])
        props = t.properties()
        if rec.get("oeis"):
            props["oeis"] = rec["oeis"]
        out.append(CatalogueRecord(family=t.family, name=t.name, spec=t.spec(), title=t.title,
                                   properties=props, aliases=list(rec["aliases"])))
    return out


@tilekit.hookimpl
def tilekit_families() -> list[Family]:
    return [
        Family(
            name=SPHERICAL,
            summary="Regular tilings {p,q} of the sphere: the five Platonic solids (§3.6.2)",
            from_spec=_from_spec(SPHERICAL),
            description=("p-gons, q at each vertex, (p-2)(q-2) < 4; the faces by breadth-first search over the "
                         "edge half-turns, drawn in orthographic projection. Options: p, q, samples."),
        ),
        Family(
            name=HYPERBOLIC,
            summary="Regular tilings {p,q} of the hyperbolic plane in the Poincaré disc (§3.6.2)",
            from_spec=_from_spec(HYPERBOLIC),
            description=("p-gons, q at each vertex, (p-2)(q-2) > 4; exact layers by a boundary automaton "
                         "(no tile twice, none lost), or every tile within a radius; edges drawn as true "
                         "arcs. Options: p, q, depth, radius, samples."),
        ),
    ]


@tilekit.hookimpl
def tilekit_catalogue_records() -> list[CatalogueRecord]:
    return curved_records()
