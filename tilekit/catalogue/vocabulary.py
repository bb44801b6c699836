"""The shared property vocabulary: the keys every family fills where they apply (``sides``,
``aperiodic``, ``periodic``, ``wallpaper_group`` ...), what each means, and the older names
that are read as aliases of them (``polygons`` -> ``sides``, ``known_aperiodic`` ->
``aperiodic``).

One table, read by three places: records are normalised to the shared names when they are
written (:func:`normalise_properties`), filters and orderings resolve an alias before they
become SQL (:func:`canonical_key`), and ``tilekit keys`` prints the table. Standard library
only, like the filters: the catalogue's read path without SQLAlchemy imports it.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class SharedKey:
    """A property every family that can answer it stores under this ``name``."""

    name: str
    type: str  # as ``tilekit keys`` prints types: bool, int, text, list of int ...
    meaning: str
    aliases: tuple[str, ...] = ()
    example: str = ""


#: The shared vocabulary (docs/catalogue.md#shared-properties lists it with the families).
SHARED_KEYS: tuple[SharedKey, ...] = (
    SharedKey("sides", "list of int",
              "numbers of sides of the prototiles, as polygons (corners where the outline turns; for the "
              "isohedral types and Laves tilings the tiling vertices of the tile)",
              ("polygons", "edges", "tile_vertices"), "sides=6"),
    SharedKey("aperiodic", "bool",
              "the prototiles (with their matching rules) admit tilings but no periodic one; false when a "
              "periodic tiling by them is known", ("known_aperiodic",), "aperiodic=true"),
    SharedKey("periodic", "bool", "this tiling has two independent translations", (), "periodic=false"),
    SharedKey("symmetry_group", "text",
              "the tiling's wallpaper group; IUC name or orbifold symbol match alike", (), "symmetry_group=p6m"),
    SharedKey("wallpaper_group", "text", "the wallpaper group's IUC name (p6m); *632 matches too",
              (), "wallpaper_group=p4g"),
    SharedKey("orbifold", "text", "the wallpaper group's orbifold symbol (*632); p6m matches too",
              (), "orbifold=*442"),
    SharedKey("edge_to_edge", "bool", "every edge of a tile is a whole edge of its neighbour", (),
              "edge_to_edge=true"),
    SharedKey("k_hedral", "int", "the number of prototiles (up to congruence)", ("prototiles",), "prototiles=2"),
    SharedKey("k_isohedral", "int", "the number of transitivity classes of tiles under the symmetry group",
              ("transitivity", "tile_transitivity"), "k_isohedral=1"),
    SharedKey("k_isogonal", "int", "the number of transitivity classes of vertices", ("vertex_transitivity",),
              "k_isogonal=1"),
    SharedKey("tiles_per_unit", "int", "tiles in one translational unit (a period cell)", (),
              "tiles_per_unit<=2"),
    SharedKey("vertex_type", "text", "the vertex configuration(s), e.g. 3.4.6.4 (any rotation or reflection "
              "matches; 3^4.6 = 3.3.3.3.6)", (), "vertex_type=4.3.4.6"),
)

#: Old or family-specific name -> the shared name.
KEY_ALIASES: dict[str, str] = {alias: key.name for key in SHARED_KEYS for alias in key.aliases}

SHARED_BY_NAME: dict[str, SharedKey] = {key.name: key for key in SHARED_KEYS}


def canonical_key(key: str) -> str:
    """The shared name of a filter or order key (``polygons`` -> ``sides``); others unchanged."""
    return KEY_ALIASES.get(key, key)


def _as_sides(value: Any) -> Any:
    """``sides`` is always a sorted list of distinct ints (an int becomes a list of one)."""
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        return [value]
    if isinstance(value, list | tuple) and all(isinstance(v, int) and not isinstance(v, bool) for v in value):
        return sorted(set(value))
    return value


def normalise_properties(properties: Mapping[str, Any]) -> dict[str, Any]:
    """A record's properties under the shared names: an alias key is renamed to its shared key
    (the shared key wins when a record has both, as a catalogue refreshed from an older
    installation does), ``sides`` becomes a sorted list, and a periodic tiling's prototiles are
    not aperiodic (``periodic=true`` implies ``aperiodic=false``)."""
    out: dict[str, Any] = {}
    for key, value in properties.items():
        shared = KEY_ALIASES.get(key)
        if shared is None:
            out[key] = value
        elif shared not in properties and shared not in out:
            out[shared] = value
    if "sides" in out:
        out["sides"] = _as_sides(out["sides"])
    if out.get("periodic") is True and out.get("aperiodic") is None:
        out["aperiodic"] = False
    return out


def shared_filter(f: Any) -> Any:
    """A parsed filter with its key under the shared name (``edges=6`` -> ``sides=6``)."""
    from dataclasses import replace

    key = canonical_key(f.key)
    return f if key == f.key else replace(f, key=key)


@dataclass(frozen=True)
class KeyInfo:
    """One line of ``tilekit keys``: a queryable key, its type, the families that have it, how
    many tilings do, an example filter, and its aliases and meaning when it is a shared key."""

    key: str
    type: str
    families: tuple[str, ...]
    tilings: int
    example: str
    aliases: tuple[str, ...] = ()
    meaning: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"key": self.key, "type": self.type, "families": list(self.families), "tilings": self.tilings,
                "example": self.example, "aliases": list(self.aliases), "meaning": self.meaning}


_KIND_NAMES = {"int": "int", "float": "float", "str": "text", "bool": "bool", "json": "json"}


def _type_name(kinds: set[str], is_list: bool) -> str:
    named = {_KIND_NAMES[k] for k in kinds if k in _KIND_NAMES}
    if named == {"int", "float"}:
        named = {"number"}
    base = " or ".join(sorted(named)) or "null"
    return f"list of {base}" if is_list else base


def _example(key: str, texts: list[str], nums: list[float], kinds: set[str]) -> str:
    if key in SHARED_BY_NAME and SHARED_BY_NAME[key].example:
        return SHARED_BY_NAME[key].example
    if "bool" in kinds:
        return f"{key}=true"
    if nums:
        value = min(nums)
        return f"{key}>={int(value) if float(value).is_integer() else round(value, 6)}"
    if texts:
        text = min(texts, key=len)
        if "json" in kinds:
            return f"{key}~TEXT"
        if len(text) > 24:
            return f"{key}~{text.split()[0][:24]}"
        return f"{key}={text!r}" if any(c in text for c in " <>=!~;") else f"{key}={text}"
    return f"{key}!=VALUE"


def key_infos(rows: Any, counts: Any) -> list[KeyInfo]:
    """KeyInfos from rows of ``(key, kind, family, max position, min text, min number)`` grouped
    by key, kind and family, and rows of ``(key, family, tilings)``: shared keys first, in the
    vocabulary's order, then by name."""
    by_key: dict[str, dict[str, Any]] = {}
    for key, kind, family, position, text, num in rows:
        item = by_key.setdefault(key, {"kinds": set(), "families": {}, "list": False, "texts": [], "nums": []})
        item["kinds"].add(kind)
        item["families"].setdefault(family, 0)
        item["list"] = item["list"] or position is not None
        if text is not None:
            item["texts"].append(str(text))
        if num is not None and kind in ("int", "float"):
            item["nums"].append(float(num))
    for key, family, count in counts:
        if key in by_key:
            by_key[key]["families"][family] = int(count)
    order = {k.name: i for i, k in enumerate(SHARED_KEYS)}
    infos = []
    for key in sorted(by_key, key=lambda k: (order.get(k, len(order)), k)):
        item = by_key[key]
        shared = SHARED_BY_NAME.get(key)
        infos.append(KeyInfo(
            key=key,
            type=_type_name(item["kinds"], item["list"]),
            families=tuple(sorted(item["families"])),
            tilings=sum(item["families"].values()),
            example=_example(key, item["texts"], item["nums"], item["kinds"]),
            aliases=shared.aliases if shared else (),
            meaning=shared.meaning if shared else "",
        ))
    return infos
