"""The curved-geometry plugin: regular tilings {p, q} of the sphere and of the hyperbolic plane
(§3.6.2), two families, ``spherical`` and ``hyperbolic``, over one tiling class.

Modules: ``model`` (the sphere and the hyperboloid as 3x3 matrices, the {p, q} tile, its
edge half-turns, the projections), ``layers`` (exact layers: the hyperbolic boundary
automaton, the sphere's breadth-first faces), ``kernels`` (the automaton's compiled step),
``patch`` (ModelPrototile, ModelPatch: transforms on the model, outlines projected,
validation in the Klein model and on the sphere), ``tiling`` (RegularTiling), ``render``
(the Poincaré disc with true arcs; the sphere in orthographic view, or stereographic with
true arcs). The records are
``catalogue/curved/regular.toml``.

The third family, ``curved``, holds the uniform tilings of the sphere and the hyperbolic
plane by Wythoff's construction: ``wythoff`` (the triangle group, the generator, the faces),
``uniform`` (UniformTiling, named by vertex configuration or Wythoff symbol), ``notation``
(vertex configurations), records from ``catalogue/curved/uniform.toml``; ``stars`` (StarTiling:
uniform tilings Wythoff's construction does not give, developed from a vertex star: the
3.3.3.p.p family and every vertex-species type with one, ``catalogue/curved/stars.toml``);
``laves`` (LavesTiling: the duals of the uniform tilings, the Catalan solids and the hyperbolic
Laves tilings, named ``[3.4.3.4]`` or ``V3.4.3.4``, ``catalogue/curved/laves.toml``).
The fourth, ``curved-isohedral``, holds Escher-like isohedral tiles on {p, q}: ``isohedral``
(CurvedIsohedralTiling) and ``delaney`` (the types as Delaney symbols), records from
``catalogue/curved/isohedral.toml``.

``web`` is the plugin's page in ``tilekit serve``: the curved-space viewer (``/curved/NAME``),
the Poincaré disc moved by dragging, the sphere turned.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import tilekit
from tilekit.errors import ParseError
from tilekit.lazy import lazy_exports
from tilekit.plugins import CatalogueRecord, Family, web_pages
from tilekit.plugins.curved import notation  # no NumPy: the core's vertex-type notation
from tilekit.plugins.curved.notation import laves_configuration
from tilekit.resources import catalogue_dir, read_toml
from tilekit.schema import Field, check

if TYPE_CHECKING:  # pragma: no cover
    from tilekit.plugins.curved.tiling import RegularTiling
    from tilekit.plugins.curved.uniform import UniformTiling

#: The families' names (tilekit.plugins.curved.model.SPHERE / HYPERBOLIC, which a test keeps
#: equal): spelled here so that loading the plugin does not import NumPy.
SPHERICAL, HYPERBOLIC = "spherical", "hyperbolic"
#: The uniform tilings' family.
CURVED = "curved"
#: Deformable isohedral tiles on {p, q} (isohedral.py).
CURVED_ISOHEDRAL = "curved-isohedral"

#: Public names, imported on first use (PEP 562): measured start-up cost, the modules load
#: NumPy and shapely (about 0.3 s), which every `tilekit` command would pay when pluggy loads
#: this plugin.
_LAZY = {
    "RegularTiling": "tilekit.plugins.curved.tiling",
    "UniformTiling": "tilekit.plugins.curved.uniform",
    "LavesTiling": "tilekit.plugins.curved.laves",
    "StarLavesTiling": "tilekit.plugins.curved.starlaves",
    "euclidean_tiling": "tilekit.plugins.curved.uniform",
    "ModelPatch": "tilekit.plugins.curved.patch",
    "ModelPrototile": "tilekit.plugins.curved.patch",
    "RegularPolygon": "tilekit.plugins.curved.model",
    "layer_counts": "tilekit.plugins.curved.layers",
    "CurvedIsohedralTiling": "tilekit.plugins.curved.isohedral",
    "hyperbolic_layers": "tilekit.plugins.curved.layers",
}
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)

__all__ = ["CURVED", "CURVED_ISOHEDRAL", "CurvedIsohedralTiling", "HYPERBOLIC", "LavesTiling", "SPHERICAL", "StarLavesTiling", "ModelPatch", "ModelPrototile", "RegularPolygon", "RegularTiling",
           "UniformTiling", "curved_records", "euclidean_tiling", "hyperbolic_layers", "laves_configuration", "laves_records",
           "layer_counts", "star_laves_records",
           "regular", "uniform_records", "uniform_tiling"]

#: The records' data file (one [[tiling]] table each: name, title, p, q, aliases, oeis).
RECORDS_FILE = "regular.toml"
#: The uniform tilings' data file ([enumerate] bounds, [[named]] tilings).
UNIFORM_FILE = "uniform.toml"


def regular(p: int, q: int, **options: Any) -> RegularTiling:
    """The regular tiling {p, q} (options: depth, radius, samples)."""
    # measured start-up cost: the tiling module loads NumPy and shapely (~0.3 s), on first use
    from tilekit.plugins.curved.tiling import RegularTiling

    return RegularTiling(p, q, **options)


def uniform_tiling(configuration: str | None = None, **options: Any) -> UniformTiling:
    """The uniform tiling with this vertex configuration (or ``symbol='2 3 | 7'``; options:
    radius, samples, plane, geometry)."""
    # measured start-up cost: as in regular()
    from tilekit.plugins.curved.uniform import UniformTiling

    return UniformTiling(configuration, **options)


def _uniform_from_spec(spec: Mapping[str, Any]) -> Any:
    # measured start-up cost: as in regular()
    if isinstance(spec, Mapping) and "laves" in spec and "pairing" in spec:  # a vertex-star tiling's dual
        from tilekit.plugins.curved.starlaves import StarLavesTiling

        return StarLavesTiling.from_spec(spec)
    # measured start-up cost: as in regular()
    if isinstance(spec, Mapping) and "laves" in spec:  # a Laves tiling, the dual of a uniform one (laves.py)
        from tilekit.plugins.curved.laves import LavesTiling

        return LavesTiling.from_spec(spec)
    # measured start-up cost: as in regular()
    if isinstance(spec, Mapping) and "pairing" in spec:  # a vertex-star tiling (stars.py)
        from tilekit.plugins.curved.stars import StarTiling

        return StarTiling.from_spec(spec)
    # measured start-up cost: as in regular()
    from tilekit.plugins.curved.uniform import UniformTiling

    return UniformTiling.from_spec(spec)


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
        # the vertex configuration as a name too (3.3.3.3.3.3.3 and 3^7 for {3,7})
        cfg = (rec["p"],) * rec["q"]
        aliases = [*rec["aliases"], ".".join(map(str, cfg)), f"{rec['p']}^{rec['q']}"]
        out.append(CatalogueRecord(family=t.family, name=t.name, spec=t.spec(), title=t.title,
                                   properties=props, aliases=aliases))
    return out


def _uniform_data() -> dict[str, Any]:
    """catalogue/curved/uniform.toml, checked (one-line errors naming the file and the field)."""
    # start-up cost: the construction loads NumPy; records are read only when seeding
    from tilekit.plugins.curved import wythoff

    path = catalogue_dir() / "curved" / UNIFORM_FILE
    bound = Field("int", required=True, range=(2, wythoff.MAX_ORDER))
    named = Field("table", fields={"name": Field("str", required=True), "title": Field("str", default=""),
                                   "configuration": Field("str", required=True)})
    return check(Field("table", fields={
        "enumerate": Field("table", required=True, fields={
            "max_order": bound, "max_prism": bound, "species_max_order": bound,
            "species_max_sides": bound, "species_max_valence": bound}),
        "named": Field("list", items=named, default=[]),
    }), read_toml(path, "curved records"), f"curved records {UNIFORM_FILE}")


def uniform_records() -> list[CatalogueRecord]:
    """The uniform tilings' records (catalogue/curved/uniform.toml): every vertex
    configuration the [enumerate] bounds give, less the regular ones that regular.toml ships
    (records of the spherical and hyperbolic families), named where [[named]] names them."""
    # measured start-up cost: NumPy and the construction (records are built only when seeding)
    from tilekit.plugins.curved import wythoff
    from tilekit.plugins.curved.uniform import UniformTiling

    data = _uniform_data()
    names = {notation.canonical(notation.parse(n["configuration"])): n for n in data["named"]}
    out = []
    regular = {(t["p"],) * t["q"] for t in read_toml(catalogue_dir() / "curved" / RECORDS_FILE, "curved records")
               .get("tiling", []) if isinstance(t, dict) and isinstance(t.get("p"), int) and isinstance(t.get("q"), int)}
    for cfg in wythoff.enumerate_configurations(**data["enumerate"]):
        if cfg in regular:
            continue  # {p,q} shipped as a record of the spherical / hyperbolic family
        rec = names.get(cfg, {})
        t = UniformTiling(notation.dotted(cfg), name=rec.get("name", ""), title=rec.get("title", ""))
        title = t.title or f"{t.configuration}: uniform tiling of the {'sphere' if not t.hyperbolic else 'hyperbolic plane'}"
        aliases = sorted({notation.dotted(cfg), notation.exponent(cfg)} - {t.name})
        out.append(CatalogueRecord(family=CURVED, name=t.name, spec=t.spec(), title=title,
                                   properties=t.properties(), aliases=aliases))
    return out


def _isohedral_from_spec(spec: Mapping[str, Any]) -> Any:
    # measured start-up cost: as in regular()
    from tilekit.plugins.curved.isohedral import CurvedIsohedralTiling

    return CurvedIsohedralTiling.from_spec(spec)


def _isohedral_from_file(path: str) -> Any:
    # measured start-up cost: as in regular()
    from tilekit.plugins.curved.isohedral import from_file

    return from_file(path)


#: The curved isohedral types' data file (the {p, q} whose types are shipped).
ISOHEDRAL_FILE = "isohedral.toml"


def isohedral_records() -> list[CatalogueRecord]:
    """Every isohedral type on each {p, q} of catalogue/curved/isohedral.toml (delaney.py's
    enumeration; properties without drawing, isohedral.type_properties)."""
    # measured start-up cost: NumPy and the curved modules (records are built only when seeding)
    from tilekit.plugins.curved import delaney, model
    from tilekit.plugins.curved.isohedral import type_properties

    pair = Field("list", items=Field("int", range=(3, model.MAX_PQ)))
    data = check(Field("table", fields={"schlafli": Field("list", required=True, items=pair)}),
                 read_toml(catalogue_dir() / "curved" / ISOHEDRAL_FILE, "curved records"),
                 f"curved records {ISOHEDRAL_FILE}")
    out = []
    for pq in data["schlafli"]:
        if len(pq) != 2:
            raise ParseError(f"curved records {ISOHEDRAL_FILE}: schlafli entry {pq} is not [p, q]")
        p, q = model.check_pq(*pq)
        if model.kind_of(p, q) == model.EUCLIDEAN:
            raise ParseError(f"curved records {ISOHEDRAL_FILE}: {{{p},{q}}} is Euclidean (the isohedral family's)")
        if p > delaney.MAX_TYPES_P:
            raise ParseError(f"curved records {ISOHEDRAL_FILE}: {{{p},{q}}}: types are enumerated for p up to "
                             f"{delaney.MAX_TYPES_P}")
        for n, sym in enumerate(delaney.enumerate_types(p, q), 1):
            props = type_properties(sym, p, q, canonical=True)
            name = f"curved-ih-{p}-{q}-{n}"
            title = (f"{{{p},{q}}} isohedral type {n}: {props['edge_kinds']} edges, group {props['orbifold']}, "
                     f"{sym}")
            out.append(CatalogueRecord(family=CURVED_ISOHEDRAL, name=name, title=title, properties=props,
                                       spec={"p": p, "q": q, "symbol": str(sym), "name": name, "title": title}))
    return out


#: The non-Wythoffian uniform tilings' data file (the 3.3.3.p.p family and every vertex type
#: of the vertex-species search's hyperbolic range that has a vertex-transitive tiling, stars.py).
STARS_FILE = "stars.toml"


def _stars_data() -> dict[str, Any]:
    """catalogue/curved/stars.toml, checked (one-line errors naming the file and the field)."""
    # start-up cost: the data file is read only when seeding or resolving a curved name
    entry = Field("table", fields={"configuration": Field("str", required=True),
                                   "pairing": Field("str", required=True)})
    return check(Field("table", fields={
        "max_sides": Field("int", required=True, range=(6, 60)),
        "pairing": Field("str", required=True),
        "species": Field("table", required=True, fields={"max_sides": Field("int", required=True, range=(3, 12)),
                                                         "max_valence": Field("int", required=True, range=(3, 8))}),
        "tiling": Field("list", items=entry, default=[]),
    }), read_toml(catalogue_dir() / "curved" / STARS_FILE, "curved records"), f"curved records {STARS_FILE}")


def _star_configurations() -> list[tuple[tuple[int, ...], str]]:
    """(canonical configuration, pairing) of every record catalogue/curved/stars.toml ships:
    3.3.3.p.p for even p up to max_sides, then each [[tiling]] (a configuration listed twice
    keeps its first pairing)."""

    data = _stars_data()
    out = {(3, 3, 3, p, p): data["pairing"] for p in range(6, data["max_sides"] + 1, 2)}
    for t in data["tiling"]:
        try:
            cfg = notation.canonical(notation.parse(t["configuration"]))
        except ParseError as exc:
            raise ParseError(f"curved records {STARS_FILE}: {exc}") from None
        out.setdefault(cfg, t["pairing"])
    return list(out.items())


def star_records() -> list[CatalogueRecord]:
    """The non-Wythoffian uniform tilings of catalogue/curved/stars.toml, each checked to close
    up round every face (StarTiling refuses a pairing that does not)."""
    # measured start-up cost: NumPy and the construction (records are built only when seeding)
    from tilekit.plugins.curved.stars import StarTiling

    out = []
    for cfg, pairing in _star_configurations():
        t = StarTiling(notation.dotted(cfg), pairing=pairing)
        aliases = sorted({notation.dotted(cfg), notation.exponent(cfg)} - {t.name})
        analogue = " (the analogue of 3^3.4^2)" if cfg[:3] == (3, 3, 3) and len(cfg) == 5 and cfg[3] == cfg[4] else ""
        out.append(CatalogueRecord(family=CURVED, name=t.name, spec=t.spec(), properties=t.properties(),
                                   title=f"{t.configuration}: a non-Wythoffian uniform tiling of the hyperbolic plane"
                                         + analogue, aliases=aliases))
    return out


#: The Laves tilings' data file (the duals of uniform tilings: the Catalan solids, a few hyperbolic ones).
LAVES_FILE = "laves.toml"


def laves_records() -> list[CatalogueRecord]:
    """The Laves tilings of catalogue/curved/laves.toml, each with its rotation-group variant
    where the file asks for one (one-line errors naming the file and the field)."""
    # measured start-up cost: NumPy and the construction (records are built only when seeding)
    from tilekit.plugins.curved.laves import LavesTiling

    entry = Field("table", fields={"name": Field("str", default=""), "title": Field("str", default=""),
                                   "configuration": Field("str", required=True),
                                   "rotations": Field("bool", default=False)})
    where = f"curved records {LAVES_FILE}"
    data = check(Field("table", fields={"tiling": Field("list", required=True, items=entry)}),
                 read_toml(catalogue_dir() / "curved" / LAVES_FILE, "curved records"), where)
    out = []
    for rec in data["tiling"]:
        try:
            cfg = notation.canonical(notation.parse(rec["configuration"]))
        except ParseError as exc:
            raise ParseError(f"{where}: {exc}") from None
        dotted, exp = notation.dotted(cfg), notation.exponent(cfg)
        for group in ("full", "rotations") if rec["rotations"] else ("full",):
            t = LavesTiling(dotted, group=group)
            if rec["name"]:
                t.name = rec["name"] if group == "full" else f"{rec['name']}-rotations"
            where_ = "the sphere" if not t.hyperbolic else "the hyperbolic plane"
            chiral = ", under its rotation group (chiral tiles)" if group == "rotations" else ""
            called = rec["name"].replace("-", " ") + ", " if rec["name"] else ""
            title = rec["title"] or f"[{exp}]: {called}Laves tiling of {where_}, dual of {dotted}{chiral}"
            if rec["title"] and group == "rotations":
                title += chiral
            suffix = "" if group == "full" else "-rotations"
            aliases = sorted({f"[{exp}]{suffix}", f"[{dotted}]{suffix}", f"V{dotted}{suffix}", f"V{exp}{suffix}"}
                             - {t.name})
            out.append(CatalogueRecord(family=CURVED, name=t.name, spec=t.spec(), title=title,
                                       properties=t.properties(), aliases=aliases))
    return out


def star_laves_records() -> list[CatalogueRecord]:
    """The duals of the vertex-star records (catalogue/curved/stars.toml): one Laves record
    ``[3^3.6^2]`` per non-Wythoffian uniform tiling, under its whole group (starlaves.py)."""
    # measured start-up cost: NumPy and the construction (records are built only when seeding)
    from tilekit.plugins.curved.starlaves import StarLavesTiling

    out = []
    for cfg, pairing in _star_configurations():
        dotted, exp = notation.dotted(cfg), notation.exponent(cfg)
        t = StarLavesTiling(dotted, pairing=pairing)
        out.append(CatalogueRecord(family=CURVED, name=t.name, spec=t.spec(), properties=t.properties(),
                                   title=f"[{exp}]: Laves tiling of the hyperbolic plane, dual of the non-Wythoffian "
                                         f"uniform tiling {dotted}",
                                   aliases=sorted({f"[{dotted}]", f"V{dotted}", f"V{exp}"} - {t.name})))
    return out


@tilekit.hookimpl
def tilekit_families() -> list[Family]:
    return [
        Family(
            name=SPHERICAL,
            summary="Regular tilings {p,q} of the sphere: the five Platonic solids (§3.6.2)",
            from_spec=_from_spec(SPHERICAL),
            description=("p-gons, q at each vertex, (p-2)(q-2) < 4; the faces by breadth-first search over the "
                         "edge half-turns, drawn in orthographic projection or (plane=stereographic[:K]) stereographic "
                         "projection from a tile's centre. Options: p, q, samples, plane."),
        ),
        Family(
            name=HYPERBOLIC,
            summary="Regular tilings {p,q} of the hyperbolic plane in the Poincaré disc (§3.6.2)",
            from_spec=_from_spec(HYPERBOLIC),
            description=("p-gons, q at each vertex, (p-2)(q-2) > 4; exact layers by a boundary automaton "
                         "(no tile twice, none lost), or every tile within a radius; edges drawn as true "
                         "arcs. Options: p, q, depth, radius, samples."),
        ),
        Family(
            name=CURVED,
            summary="Uniform tilings of the sphere and the hyperbolic plane by Wythoff's construction (§3.6.2)",
            from_spec=_uniform_from_spec,
            description=("Named by vertex configuration (3.4.4.4, 3.14.14) or Wythoff symbol (p|q r, p q|r, p q r|, "
                         "|p q r): the Archimedean solids, prisms and antiprisms, truncations and snubs of {p,q} in "
                         "the hyperbolic plane; and non-Wythoffian ones developed from a vertex star (3.3.3.6.6, the analogues of "
                         "3^3.4^2; option pairing); and their duals, the Laves tilings ([3.4.3.4] or V3.4.3.4: the "
                         "Catalan solids, [4.6.14] ...; option group=rotations for chiral tiles). Options: configuration, "
                         "symbol, radius, samples, plane, geometry."),
        ),
        Family(
            name=CURVED_ISOHEDRAL,
            summary="Escher-like isohedral tiles on the sphere and the hyperbolic plane: {p,q}'s polygon, "
                    "J/U/S/I edges, tiles with their own symmetry (§7.3)",
            from_spec=_isohedral_from_spec,
            from_file=_isohedral_from_file,
            description=("The regular p-gon of {p,q} with its edges matched by an incidence symbol (§5.2: tile "
                         "symmetry, J/U/S/I edges, hops by half-turns, mirrors or glides) or a pairing (a letter "
                         "once: an S edge; twice: a J pair), deformed by edge shapes; Poincaré's condition checked "
                         "on the Delaney symbol; tiles coloured by a perfect colouring. Records: every type of the "
                         "sphere's {p,q} and of a few hyperbolic ones (curved-ih-P-Q-N). Options: p, q, symbol, "
                         "pairing, edges, radius, samples, colours, plane. Read from a JSON spec file: tilekit "
                         "render --system x.json --family curved-isohedral."),
        ),
    ]


@tilekit.hookimpl
def tilekit_catalogue_records() -> list[CatalogueRecord]:
    return (curved_records() + uniform_records() + star_records() + laves_records() + star_laves_records()
            + isohedral_records())


@tilekit.hookimpl
def tilekit_resolve_name(name: str) -> list[str] | None:
    """A spherical or hyperbolic vertex configuration in any rotation or spelling
    (``4.3.4.4``, ``3.4^3``): the uniform tiling with it (``vertex_configuration`` filter);
    one that no Wythoff symbol gives is a one-line error naming it. A Laves name of one
    (``[3.9.9]``, ``V3.9.9``): its dual, :func:`_resolve_laves`."""
    if name.strip()[:1] in "[Vv":
        return _resolve_laves(name)
    try:
        cfg = notation.parse(name)
    except ParseError:
        return None
    if notation.geometry_of(cfg) == "euclidean":
        return None
    dotted = notation.dotted(notation.canonical(cfg))
    if notation.canonical(cfg) in dict(_star_configurations()):
        return [f"vertex_configuration={dotted}"]
    # start-up cost: the construction loads NumPy, only for a name that is a curved configuration
    from tilekit.errors import ParameterError
    from tilekit.plugins.curved import wythoff

    if not wythoff.symbols_for(cfg) and notation.geometry_of(cfg) == HYPERBOLIC:
        species = _stars_data()["species"]
        if len(cfg) <= species["max_valence"] and max(cfg) <= species["max_sides"]:
            raise ParameterError(f"{dotted} has no vertex-transitive tiling: no Wythoff symbol gives it, and no "
                                 "pairing of its vertex star's edges closes up into one (every pairing was tried: "
                                 "tilekit.plugins.curved.stars.find)")
        raise ParameterError(f"{dotted}: no Wythoff symbol gives it, and the vertex-star records cover hyperbolic "
                             f"types of up to {species['max_valence']} polygons of up to {species['max_sides']} sides; "
                             f"search it: tilekit render 3.3.3.6.6 --set configuration={dotted}")
    sym = wythoff.symbol_for(cfg)  # raises when no uniform tiling has this configuration
    bounds = _uniform_data()["enumerate"]
    if not any(wythoff.recorded(s, **bounds) for s in wythoff.symbols_for(cfg)):
        raise ParameterError(f"{dotted} is the uniform tiling {sym}, which has no catalogue record (records: orders "
                             f"up to {bounds['max_order']}); draw it from any curved record: tilekit render 3.14.14 "
                             f"--set configuration={dotted}")
    return [f"vertex_configuration={dotted}"]


def _resolve_laves(name: str) -> list[str] | None:
    """A Laves name of a spherical or hyperbolic configuration that no record has under that
    spelling: the record of its dual (``dual_configuration`` filter), or a one-line error when
    no uniform tiling has the configuration or no record ships its dual."""
    cfg = laves_configuration(name)
    if cfg is None or notation.geometry_of(cfg) == "euclidean":
        return None  # the laves family's (tilekit_normalise of the archimedean family)
    # start-up cost: the construction loads NumPy, only for a name that is a curved Laves name
    from tilekit.errors import ParameterError
    from tilekit.plugins.curved import wythoff

    dotted = notation.dotted(cfg)
    if cfg in dict(_star_configurations()):  # a non-Wythoffian uniform tiling's dual (starlaves.py)
        return [f"dual_configuration={dotted}", "group=full"]
    if not wythoff.symbols_for(cfg):
        raise ParameterError(f"[{dotted}]: no uniform tiling by Wythoff's construction has the vertex configuration "
                             f"{dotted}, so it has no Laves dual here; e.g. [3.4.3.4], [4.6.10], [4.6.14]")
    shipped = {notation.canonical(notation.parse(t["configuration"]))
               for t in read_toml(catalogue_dir() / "curved" / LAVES_FILE, "curved records").get("tiling", [])
               if isinstance(t, dict) and isinstance(t.get("configuration"), str)}
    if cfg not in shipped:
        raise ParameterError(f"[{dotted}], the dual of the uniform tiling {dotted}, has no catalogue record; draw it "
                             f"from any curved Laves record: tilekit render '[4.6.14]' --set configuration={dotted}")
    return [f"dual_configuration={dotted}", "group=full"]


@tilekit.hookimpl
def tilekit_normalise(key: str, value: str) -> tuple[str, str] | None:
    """``V3.4.3.4`` (Laves's V notation, any rotation) as the bracket name ``[3.4.3.4]`` that
    the Laves records of this family and of the laves family carry."""
    if key != "name" or value.strip()[:1] not in ("V", "v"):
        return None
    cfg = laves_configuration(value)
    if cfg is None:
        return None
    return "name", f"[{notation.exponent(cfg)}]"


@tilekit.hookimpl
def tilekit_cli_commands(cli: Any) -> None:
    # curved/cli.py imports only click and the core's cli_types at its top (the mesh code
    # imports NumPy when the command runs); measured start-up cost: a few milliseconds
    from tilekit.plugins.curved.cli import laves_types_command, sphere_mesh_command

    cli.add_command(sphere_mesh_command)
    cli.add_command(laves_types_command)


# the curved-space viewer (/curved/NAME, /curved?p=7&q=3): web.py, imported when a web app is made
(tilekit_web_routes, tilekit_web_menu_links, tilekit_web_tiling_links,
 tilekit_web_static) = web_pages("tilekit.plugins.curved.web", [("/curved?p=7&q=3", "hyperbolic viewer")])
