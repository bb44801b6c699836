"""How tilings are stored: the :class:`Entry` a query returns, the typed property rows (one
per list element), the shared indexed columns, and the insert-or-replace of records by name."""

from __future__ import annotations

import json
import math
import numbers
import re
from collections.abc import Iterator, Mapping, Sequence
from typing import Any

import sqlalchemy as sa
from sqlalchemy.engine import Connection

from tilekit.catalogue.entry import SHARED_COLUMNS
from tilekit.catalogue.tables import ALIASES, BATCH, PROPS, TILINGS
from tilekit.catalogue.vocabulary import normalise_properties
from tilekit.errors import CatalogueError
from tilekit.models import utcnow
from tilekit.plugins import CatalogueRecord

#: Keys an Entry row uses itself; a property may not take these names.
RESERVED_KEYS = frozenset({"name", "family", "title", "spec", "aliases", "id"})
_KEY_RE = re.compile(r"^[a-z][a-z0-9_]*$")



def scalar_row(key: str, value: Any, owner: str) -> dict[str, Any]:
    kind = type(value)  # fast path for the plain types; ABC checks below for numpy and co.
    if kind is str:
        return {"kind": "str", "value_text": value, "value_num": None, "value_bool": None}
    if kind is int:
        return {"kind": "int", "value_text": None, "value_num": float(value), "value_bool": None}
    if kind is bool:
        return {"kind": "bool", "value_text": None, "value_num": None, "value_bool": value}
    row: dict[str, Any] = {"value_text": None, "value_num": None, "value_bool": None}
    if value is None:
        row["kind"] = "null"
    elif isinstance(value, bool):
        row["kind"], row["value_bool"] = "bool", value
    elif isinstance(value, numbers.Integral):
        row["kind"], row["value_num"] = "int", float(int(value))
    elif isinstance(value, numbers.Real):
        v = float(value)
        if not math.isfinite(v):
            raise CatalogueError(f"record {owner!r}: property {key!r} is {v}, not a finite number")
        row["kind"], row["value_num"] = "float", v
    elif isinstance(value, str):
        row["kind"], row["value_text"] = "str", value
    else:
        raise CatalogueError(
            f"record {owner!r}: property {key!r} has a {type(value).__name__}; "
            "properties are str, int, float, bool, null or lists of them"
        )
    return row


def json_row(owner: str, key: str, value: Any) -> dict[str, Any]:
    """A nested value (list of lists, object) kept whole as JSON text: shown, ~-searchable."""
    json_ok(f"record {owner!r}", f"property {key!r}", value)
    return {"key": key, "position": None, "kind": "json", "value_text": json.dumps(value),
            "value_num": None, "value_bool": None}


def property_rows(owner: str, properties: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Typed rows for every property; a list becomes one row per element (``position``)."""
    rows: list[dict[str, Any]] = []
    for key, value in properties.items():
        if not isinstance(key, str) or not _KEY_RE.match(key):
            raise CatalogueError(f"record {owner!r}: property key {key!r} is not snake_case")
        if key in RESERVED_KEYS:
            raise CatalogueError(
                f"record {owner!r}: property key {key!r} is reserved ({', '.join(sorted(RESERVED_KEYS))})"
            )
        if isinstance(value, list | tuple):
            if not value:
                rows.append({"key": key, "position": None, "kind": "empty",
                             "value_text": None, "value_num": None, "value_bool": None})
            elif any(isinstance(item, list | tuple | dict) for item in value):
                rows.append(json_row(owner, key, value))
            else:
                for i, item in enumerate(value):
                    rows.append({"key": key, "position": i, **scalar_row(key, item, owner)})
        elif isinstance(value, dict):
            rows.append(json_row(owner, key, value))
        else:
            rows.append({"key": key, "position": None, **scalar_row(key, value, owner)})
    return rows


def shared_values(owner: str, properties: Mapping[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, typ in SHARED_COLUMNS.items():
        value = properties.get(key)
        if key == "symmetry_group" and value is None:
            # families report the wallpaper group as "wallpaper_group" (tilekit.symmetry)
            value = properties.get("wallpaper_group")
        if value is None:
            out[key] = None
        elif typ is bool:
            if not isinstance(value, bool):
                raise CatalogueError(f"record {owner!r}: property {key!r} must be true or false, got {value!r}")
            out[key] = value
        elif typ is int:
            if isinstance(value, bool) or not isinstance(value, numbers.Integral):
                raise CatalogueError(f"record {owner!r}: property {key!r} must be an integer, got {value!r}")
            out[key] = int(value)
        else:
            if not isinstance(value, str):
                raise CatalogueError(f"record {owner!r}: property {key!r} must be text, got {value!r}")
            out[key] = value
    return out


def json_ok(owner: str, what: str, value: Any) -> None:
    try:
        json.dumps(value, allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise CatalogueError(f"{owner}: {what} is not plain JSON ({exc})") from None


def batches(items: Sequence[Any], size: int = BATCH) -> Iterator[Sequence[Any]]:
    for start in range(0, len(items), size):
        yield items[start : start + size]




def upsert(conn: Connection, records: list[CatalogueRecord], *, replace: bool) -> tuple[int, int]:
    """Insert or (if ``replace``) replace records by name inside the caller's transaction."""
    prepared: dict[str, tuple[dict[str, Any], list[dict[str, Any]], list[str]]] = {}
    for rec in records:
        if not isinstance(rec, CatalogueRecord):
            raise CatalogueError(f"expected a CatalogueRecord, got {type(rec).__name__}")
        if not isinstance(rec.name, str) or not rec.name.strip():
            raise CatalogueError(f"a record of family {rec.family!r} has an empty name")
        if not isinstance(rec.family, str) or not rec.family:
            raise CatalogueError(f"record {rec.name!r} has no family")
        if rec.name in prepared:
            raise CatalogueError(f"two records are named {rec.name!r}")
        if not isinstance(rec.spec, dict):
            raise CatalogueError(f"record {rec.name!r}: spec is a {type(rec.spec).__name__}, not a JSON object")
        json_ok(f"record {rec.name!r}", "spec", rec.spec)
        props = normalise_properties(rec.properties or {})
        row = {
            "family": rec.family,
            "name": rec.name,
            "title": rec.title or "",
            "spec": rec.spec,
            **shared_values(rec.name, props),
        }
        aliases = [a for a in dict.fromkeys(rec.aliases or ()) if a and a != rec.name]
        prepared[rec.name] = (row, property_rows(rec.name, props), aliases)
    if not prepared:
        return 0, 0

    t, a, p = TILINGS, ALIASES, PROPS
    names = list(prepared)
    existing: dict[str, int] = {}
    for batch in batches(names):
        for tid, name in conn.execute(sa.select(t.c.id, t.c.name).where(t.c.name.in_(batch))):
            existing[name] = tid
    to_replace = [n for n in names if n in existing] if replace else []
    to_insert = [n for n in names if n not in existing]

    ids: dict[str, int] = {}
    if to_replace:
        replace_ids = [existing[n] for n in to_replace]
        for batch in batches(replace_ids):
            conn.execute(sa.delete(p).where(p.c.tiling_id.in_(batch)))
            conn.execute(sa.delete(a).where(a.c.tiling_id.in_(batch)))
        now = utcnow()
        for name in to_replace:
            row = dict(prepared[name][0])
            row.pop("name")
            conn.execute(sa.update(t).where(t.c.id == existing[name]).values(**row, updated_at=now))
            ids[name] = existing[name]
    if to_insert:
        for batch in batches(to_insert):
            result = conn.execute(
                sa.insert(t).returning(t.c.id, t.c.name), [prepared[n][0] for n in batch]
            )
            for tid, name in result:
                ids[name] = tid

    # aliases: refuse one that already names or aliases a different tiling
    wanted_aliases = {alias: name for name in ids for alias in prepared[name][2]}
    if wanted_aliases:
        alias_list = list(wanted_aliases)
        own_ids = set(ids.values())
        for batch in batches(alias_list):
            for alias, tid in conn.execute(sa.select(a.c.alias, a.c.tiling_id).where(a.c.alias.in_(batch))):
                if tid not in own_ids:
                    raise CatalogueError(
                        f"alias {alias!r} of {wanted_aliases[alias]!r} already belongs to another tiling"
                    )
            for (name,) in conn.execute(sa.select(t.c.name).where(t.c.name.in_(batch))):
                if name != wanted_aliases[name]:
                    raise CatalogueError(
                        f"alias {name!r} of {wanted_aliases[name]!r} is the name of another tiling"
                    )
        seen: dict[str, str] = {}
        for name in ids:
            for alias in prepared[name][2]:
                if alias in seen and seen[alias] != name:
                    raise CatalogueError(f"alias {alias!r} is claimed by both {seen[alias]!r} and {name!r}")
                seen[alias] = name
        alias_rows = [{"alias": alias, "tiling_id": ids[name]} for alias, name in seen.items()]
        for batch in batches(alias_rows):
            conn.execute(sa.insert(a), list(batch))

    prop_rows = [{"tiling_id": ids[name], **row} for name in ids for row in prepared[name][1]]
    for batch in batches(prop_rows, 5000):
        conn.execute(sa.insert(p), list(batch))
    return len(to_insert), len(to_replace)
