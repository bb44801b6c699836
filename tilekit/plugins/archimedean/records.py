"""Catalogue records and the family objects of the archimedean plugin.

Two families: ``archimedean`` (the 11 Archimedean tilings, the chiral 3^4.6 in both hands,
plus the vertex types classified by the vertex-species search) and ``laves`` (their 11 duals).
Records are built from the shipped construction data, so seeding a catalogue grows no patch.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from tilekit.errors import ParameterError, ParseError
from tilekit.plugins import CatalogueRecord
from tilekit.plugins.archimedean import construct
from tilekit.regular.notation import VertexType, format_sequence, parse_sequence
from tilekit.schema import Field, check, shown
from tilekit.symmetry import ORBIFOLD
from tilekit.tiling import Tiling


def species_text(vt: VertexType) -> str:
    """A species as the sorted sequence in exponent form (``3^3.4^2`` holds 3^2.4.3.4 too)."""
    return format_sequence(vt.species)


def _hands(vt: VertexType) -> list[str]:
    return ["l", "r"] if construct.is_chiral(vt) else [""]


def _group(name: str) -> dict[str, Any]:
    data = construct.cached_data().get("symmetry", {}).get(name)
    if data is None:
        return {}
    iuc = data["wallpaper_group"]
    return {"symmetry_group": ORBIFOLD[iuc], "wallpaper_group": iuc, "orbifold": ORBIFOLD[iuc],
            "k_isohedral": int(data["k_isohedral"]), "k_isogonal": int(data["k_isogonal"])}


#: The names people use (Grünbaum & Shephard, Conway's "tille" names), found by show, render
#: and list --text. Chiral types get them on their left-handed record, as for the plain name.
COMMON_NAMES: dict[str, list[str]] = {
    "3^6": ["triangular", "deltille"],
    "4^4": ["square", "quadrille"],
    "6^3": ["hexagonal", "hextille"],
    "3.6.3.6": ["trihexagonal", "kagome", "hexadeltille"],
    "4.8^2": ["truncated square", "truncquadrille"],
    "3.12^2": ["truncated hexagonal", "truncated hextille"],
    "3.4.6.4": ["rhombitrihexagonal", "rhombihexadeltille"],
    "4.6.12": ["truncated trihexagonal", "truncated rhombitrihexagonal", "truncated trihexadeltille"],
    "3^4.6": ["snub hexagonal", "snub trihexagonal", "snub hextille"],
    "3^3.4^2": ["elongated triangular", "isosnub quadrille"],
    "3^2.4.3.4": ["snub square", "snub quadrille"],
}
LAVES_NAMES: dict[str, list[str]] = {
    "3.6.3.6": ["rhombille"],
    "4.8^2": ["tetrakis square", "kisquadrille"],
    "3.12^2": ["triakis triangular", "kisdeltille"],
    "3.4.6.4": ["deltoidal trihexagonal", "tetrille"],
    "4.6.12": ["kisrhombille"],
    "3^4.6": ["floret pentagonal", "6-fold pentille"],
    "3^3.4^2": ["prismatic pentagonal", "iso(4-)pentille"],
    "3^2.4.3.4": ["cairo", "cairo pentagonal", "4-fold pentille"],
}


def common_aliases(names: list[str], suffix: str = "") -> list[str]:
    """Each name, its dashed spelling, and both with ``suffix`` (' tiling')."""
    out = []
    for n in names:
        for v in (n, n.replace(" ", "-")):
            out += [v, v + suffix] if suffix else [v]
    return list(dict.fromkeys(out))


def handed_aliases(names: list[str], hand: str) -> list[str]:
    """The common names of one hand of a chiral tiling: 'snub hexagonal left', 'left snub
    hexagonal', 'snub-hexagonal-l' ... (the unhanded name stays with the left hand)."""
    if not hand:
        return []
    word = {"l": "left", "r": "right"}[hand]
    out = []
    for n in names:
        out += [f"{n} {word}", f"{word} {n}", f"{n} {hand}", f"{n} ({word})", f"{n}-{hand}".replace(" ", "-"),
                f"{word}-{n}".replace(" ", "-")]
    return out


def _hand_word(hand: str) -> str:
    return {"l": ", left-handed", "r": ", right-handed"}.get(hand, "")


def archimedean_record(vt: VertexType, hand: str, extra: Mapping[str, Any] | None = None) -> CatalogueRecord:
    t = construct.archimedean_tiling(vt, hand)
    props = t.properties()
    props.pop("colours", None)
    props.update({"kind": "tiling", "species": species_text(vt), "valence": len(vt.polygons),
                  "polygon_counts": [int(sum(1 for p in t.unit_prototile if vt.sizes[p] == s)) for s in vt.sizes]})
    props.update(_group(t.name))
    if extra:
        props.update(extra)
        props["kind"] = "tiling"
    aliases = [a for a in vt.aliases() if hand != "r"]
    if hand == "l":
        aliases = [str(vt)] + aliases
    if hand:
        aliases.append(f"({vt}){hand}")
    if hand != "r":
        aliases += common_aliases(COMMON_NAMES.get(str(vt), []))
    aliases += handed_aliases(COMMON_NAMES.get(str(vt), []), hand)
    return CatalogueRecord(
        family="archimedean",
        name=t.name,
        spec=t.spec(),
        title=f"Archimedean tiling ({vt}){_hand_word(hand)}",
        properties=props,
        aliases=aliases,
    )


def laves_record(vt: VertexType, hand: str) -> CatalogueRecord:
    t = construct.laves_tiling(vt, hand)
    props = t.properties()
    props.pop("colours", None)
    props["species"] = species_text(vt)
    props.update(_group(t.name))
    aliases = [f"[{vt.dotted}]{hand}"]
    if hand == "l":
        aliases.append(f"[{vt}]")
        aliases.append(f"[{vt.dotted}]")
    if hand != "r":
        aliases += common_aliases(LAVES_NAMES.get(str(vt), []))
    aliases += handed_aliases(LAVES_NAMES.get(str(vt), []), hand)
    return CatalogueRecord(
        family="laves",
        name=t.name,
        spec=t.spec(),
        title=f"Laves tiling [{vt}]{_hand_word(hand)}, dual of ({vt})",
        properties=props,
        aliases=list(dict.fromkeys(a for a in aliases if a != t.name)),
    )


def tiling_types() -> list[VertexType]:
    """The vertex types with a constructed tiling in the shipped data."""
    return sorted((VertexType.of(parse_sequence(k)) for k in construct.cached_data().get("archimedean", {})),
                  key=lambda v: (len(v.polygons), v.polygons))


def catalogue_records() -> list[CatalogueRecord]:
    out: list[CatalogueRecord] = []
    for vt in tiling_types():
        for hand in _hands(vt):
            out.append(archimedean_record(vt, hand))
    for vt in tiling_types():
        for hand in _hands(vt):
            out.append(laves_record(vt, hand))
    return out


def vertex_type_records(vt: VertexType, props: Mapping[str, Any]) -> list[CatalogueRecord]:
    """Records the vertex-species search upserts for one type: the tiling record(s) with the
    search's findings for a type that tiles, otherwise a vertex-type record."""
    if props.get("status") == "tiles":
        extra = {k: v for k, v in props.items() if k not in ("kind",)}
        return [archimedean_record(vt, hand, extra) for hand in _hands(vt)]
    p = dict(props)
    p["species"] = species_text(vt)
    if p.get("geometry") == "euclidean":
        p["periodic"] = False
        p["tiles_plane"] = False
        title = f"Vertex type {vt}: no tiling ({p.get('status')})"
    elif p.get("geometry") == "spherical":
        title = f"Vertex type {vt}: spherical" + (f", the {p['solid']}" if p.get("solid") else "")
    else:
        title = f"Vertex type {vt}: hyperbolic"
    return [CatalogueRecord(
        family="archimedean",
        name=str(vt),
        spec={"kind": "vertex_type", "vertex_type": str(vt)},
        title=title,
        properties=p,
        aliases=[a for a in [vt.dotted] if a != str(vt)],
    )]


#: An archimedean or Laves spec: the vertex type, its kind, the hand of a chiral one.
SPEC = Field("table", fields={
    "kind": Field("str"),
    "vertex_type": Field("str", required=True, missing="the spec has no vertex_type (e.g. '3.4.6.4')"),
    "hand": Field("str"),
})


def _checked(spec: Any, family: str) -> dict[str, Any]:
    if not isinstance(spec, Mapping):
        raise ParseError(f"the {family} spec must be a JSON object like {{'vertex_type': '3.4.6.4'}}, not {shown(spec)}")
    return check(SPEC, {k: v for k, v in spec.items() if v is not None}, f"{family} spec")


def archimedean_from_spec(spec: Mapping[str, Any]) -> Tiling:
    spec = _checked(spec, "archimedean")
    kind = spec.get("kind")
    vt = VertexType.parse(spec["vertex_type"])
    if kind == "archimedean":
        return construct.archimedean_tiling(vt, spec.get("hand", ""))
    if kind == "vertex_type":
        if vt.geometry != "euclidean":
            raise ParameterError(f"vertex type {vt} is {vt.geometry}: it has no plane tiling to draw")
        if str(vt) in construct.cached_data().get("archimedean", {}):
            return construct.archimedean_tiling(vt)
        raise ParameterError(f"vertex type {vt} admits no tiling of the plane: nothing to draw")
    raise ParseError(f"archimedean spec kind {kind!r} is not 'archimedean' or 'vertex_type'")


def laves_from_spec(spec: Mapping[str, Any]) -> Tiling:
    spec = _checked(spec, "laves")
    if spec.get("kind") != "laves":
        raise ParseError(f"laves spec kind {shown(spec.get('kind'))} is not 'laves'")
    return construct.laves_tiling(spec["vertex_type"], spec.get("hand", ""))
