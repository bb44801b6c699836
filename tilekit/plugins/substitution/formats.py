"""The three substitution file dialects as schemas (similarity rules, keypoint placement, hat
metatiles), read by one loader, :func:`read_system_data`: the shape of every field is checked
here, declaratively (tilekit.schema); the engines' loaders then only resolve names and check
the geometry. See docs/families/substitution.md for what each field means."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from tilekit.errors import ParseError
from tilekit.schema import Field, check

__all__ = ["HAT", "KEYPOINT", "SIMILARITY", "read_system_data"]

EXPR = Field("expr")
POINT = Field("list", items=EXPR, length=(2, 2), error="{path}: a point must be [x, y], got {value!r}")
POLYLINE = Field("list", items=POINT, length=(2, None))
INDEX = Field("int", range=(0, None))
PROPERTIES = Field("table", error="[properties] must be a table")
NAME = Field("str")
CONSTANTS = Field("table", default={}, values=EXPR, error="[constants] must be a table")
#: Fields every dialect has: what the system is called and which engine reads it.
COMMON = {"name": NAME, "title": NAME, "engine": Field("str"), "properties": PROPERTIES}


def _outlines(key: str) -> Field:
    """``[[prototile]]`` / ``[[tile]]``: named outlines with optional marking polylines."""
    entry = Field(
        "table",
        error=f"[[{key}]] #{{n}} needs an 'outline'",
        fields={
            "name": NAME,
            "outline": Field("list", required=True, items=POINT, length=(3, None),
                             missing=f"[[{key}]] #{{n}} needs an 'outline'",
                             error=f"{key} #{{n}}: outline must be a list of at least 3 [x, y] points"),
            "marking": Field("list", default=[], items=POLYLINE,
                             error=f"{key} #{{n}}: marking must be a list of polylines, each a list of [x, y] points"),
        },
    )
    return Field("list", items=entry, length=(1, None), error=f"no [[{key}]] tables")


#: A placed tile: ``tile`` and either a 2x3 (or 3x3) ``matrix`` or the ``vertices`` images.
PLACED = Field(
    "table",
    error="{path}: needs 'tile'",
    fields={
        "tile": Field("ref", required=True, error="{path}: tile reference {value!r} is not a name or index"),
        "matrix": Field("list", items=Field("list", items=EXPR, length=(3, 3)), length=(2, 3),
                        error="{path}: matrix must be 2 or 3 rows of 3 entries"),
        "vertices": Field("list", items=POINT, length=(3, 3),
                          error="{path}: 'vertices' must list the images of the child's vertices 0, 1, 2"),
    },
)

RULE = Field(
    "table",
    error="rule #{n} has no 'parent'",
    fields={
        "parent": Field("ref", required=True, missing="rule #{n} has no 'parent'",
                        error="rule #{n} parent: tile reference {value!r} is not a name or index"),
        "child": Field("list", required=True, items=PLACED, length=(1, None),
                       error="rule #{n}: no [[rule.child]] entries"),
    },
)

#: ``engine = "similarity"`` (the default): rules of similarities (§6.1).
SIMILARITY = Field(
    "table",
    error="top level must be a table",
    fields={
        **COMMON,
        "kind": Field("str", default="exact", choices=("exact", "indented", "overlapping"),
                      error="kind {value!r} is not one of exact, indented, overlapping"),
        "scale": Field("expr", required=True, missing="missing the expansion constant 'scale'"),
        "constants": CONSTANTS,
        "prototile": replace(_outlines("prototile"), required=True),
        "rule": Field("list", required=True, items=RULE, length=(1, None), error="no [[rule]] tables"),
        "seed": Field("ref", error="seed: tile reference {value!r} is not a name or index"),
        "tile": _outlines("tile"),
        "assemble": Field("table", values=PLACED, error="[assemble] must be a table"),
        "pairing": Field(
            "table",
            error="[pairing] must be a table",
            fields={
                "edge": Field("list", required=True, items=INDEX, length=(2, 2),
                              error="[pairing] edge must be two vertex indices of the half-tile"),
                "mirror": PLACED,
                "turn": PLACED,
            },
        ),
        "properties": PROPERTIES,
    },
)

_INDEX_PAIR = Field("list", items=INDEX, length=(2, 2))

#: ``engine = "keypoint"``: supertiles placed rigidly by keypoints (the spectre).
KEYPOINT = Field(
    "table",
    error="top level must be a table",
    fields={
        **COMMON,
        "constants": CONSTANTS,
        "labels": Field("list", required=True, items=Field("str"), length=(1, None),
                        error="'labels' must be a list of names"),
        "seed": Field("str", error="seed {value!r} is not a label"),
        "tile": Field(
            "table", required=True, error="[tile] needs an 'outline'",
            fields={
                "name": Field("str", default="tile"),
                "outline": Field("list", required=True, items=Field("list", items=EXPR, length=(2, 2)),
                                 length=(3, None), missing="[tile] needs an 'outline'",
                                 error="[tile] outline must be a list of at least 3 [x, y] points"),
                "quad": Field("list", required=True, items=INDEX, length=(4, 4),
                              error="[tile] quad must be 4 vertex indices of the outline"),
            },
        ),
        "base": Field(
            "table", default={}, error="[base] must be a table, not {value.__class__.__name__}",
            values=Field(
                "list", length=(1, None),
                error="{path} must be a non-empty list of {{rotate = A, translate = [x, y]}} tables",
                items=Field("table", error="{path} must be a {{rotate = A, translate = [x, y]}} table", fields={
                    "rotate": Field("expr", default=0),
                    "translate": Field("list", default=[0, 0], items=EXPR, length=(2, 2),
                                       error="{path} must be [x, y], got {value!r}"),
                }),
            ),
        ),
        "placement": Field(
            "table", required=True, error="[placement] must be a table, not {value.__class__.__name__}",
            missing="[placement] needs 'steps' = [[angle, from, to], ...]",
            fields={
                "steps": Field("list", required=True, length=(1, None),
                               items=Field("list", length=(3, 3),
                                           error="[placement] step #{n} must be [angle, from keypoint 0..3, to keypoint 0..3]"),
                               error="[placement] needs 'steps' = [[angle, from, to], ...]"),
                "reflect": Field("bool", default=False),
                "next_quad": Field("list", required=True, items=_INDEX_PAIR, length=(4, 4),
                                   error="[placement] next_quad must be four [slot, keypoint 0..3] pairs"),
            },
        ),
        "rules": Field("table", default={}, values=Field("list", items=Field("str")),
                       error="[rules] must be a table, not {value.__class__.__name__}"),
        "properties": PROPERTIES,
    },
)

_PAIRS = Field("list", length=(1, None), items=Field("list", items=Field("number"), length=(2, 2)),
               error="{path} must be a list of [a, b] lattice pairs")
_HAT_PLACEMENT = Field(
    "table",
    error="{path} must be a table",
    fields={
        "match": Field("list"),
        "rotate": Field("number", default=0),
        "reflect": Field("bool", default=False),
        "translate": Field("list", default=[0, 0], items=Field("number"), length=(2, 2),
                           error="{path} must be [a, b], a lattice pair"),
    },
)
_LABEL = Field("str", choices=("H", "T", "P", "F"))
_MEMBER = Field(
    "table",
    error="{path} must be a table {{a = EXPR, b = EXPR, title = TEXT}}",
    fields={
        "a": Field("expr", required=True, missing="{path} needs 'a' and 'b' (edge lengths)"),
        "b": Field("expr", required=True, missing="{path} needs 'a' and 'b' (edge lengths)"),
        "title": Field("str"),
        "aperiodic": Field("bool"),
        "aliases": Field("list", default=[], items=Field("str"), error="{path} must be a list of names"),
    },
)

#: ``engine = "hat-metatiles"``: the hat's metatiles H, T, P, F and their cluster.
HAT = Field(
    "table",
    error="top level must be a table",
    fields={
        **COMMON,
        "name": Field("str", default="hat"),
        "title": Field("str", default="hat"),
        "labels": Field("list", required=True, choices=(["H", "T", "P", "F"],),
                        error="'labels' must be [\"H\", \"T\", \"P\", \"F\"] (the outline construction is specific to them)"),
        "seed": Field("str", default="H", choices=("H", "T", "P", "F"), error="seed {value!r} is not one of H, T, P, F"),
        "tile": Field("table", required=True, error="[tile] needs an 'outline' of lattice pairs", fields={
            "name": Field("str", default="hat"),
            "outline": replace(_PAIRS, required=True, error="[tile] outline must be a list of [a, b] lattice pairs",
                               missing="[tile] needs an 'outline' of lattice pairs"),
        }),
        "metatiles": Field(
            "table", required=True, error="[metatiles.X] tables are missing",
            fields={
                label: Field("table", required=True, error=f"[metatiles.{label}] needs 'outline' and 'hats'", fields={
                    "outline": replace(_PAIRS, required=True, missing=f"[metatiles.{label}] needs 'outline' and 'hats'"),
                    "hats": Field("list", required=True, items=_HAT_PLACEMENT,
                                  error=f"[metatiles.{label}] needs 'outline' and 'hats'"),
                })
                for label in ("H", "T", "P", "F")
            },
        ),
        "cluster": Field(
            "table", required=True, error="[cluster] needs 'attach' and 'children'",
            fields={
                "attach": Field("list", required=True, error="[cluster] needs 'attach' and 'children'"),
                "children": Field("table", required=True, error="[cluster] needs 'attach' and 'children'",
                                  fields={label: Field("list", required=True, items=INDEX, length=(1, None),
                                                       error=f"[cluster.children] {label} must list cluster tile indices")
                                          for label in ("H", "T", "P", "F")}),
            },
        ),
        "continuum": Field(
            "table", default={}, error="[continuum] must be a table",
            fields={
                "equilateral": Field("str", error="[continuum] equilateral must name a system"),
                "members": Field("table", default={}, values=_MEMBER, error="[continuum.members] must be a table"),
            },
        ),
        "properties": PROPERTIES,
    },
)

DIALECTS: dict[str, Field] = {"similarity": SIMILARITY, "keypoint": KEYPOINT, "hat-metatiles": HAT}


def read_system_data(data: Any, source: str, engine: str | None = None) -> tuple[str, dict[str, Any]]:
    """(engine, data checked against its dialect's schema, defaults filled in). ``engine``
    None: the file's own ``engine`` field, "similarity" when it has none."""
    where = f"substitution system {source}"
    if engine is None:
        engine = data.get("engine", "similarity") if isinstance(data, Mapping) else "similarity"
        if engine not in ("similarity", "keypoint"):
            raise ParseError(f"{where}: engine {engine!r} is not 'similarity' or 'keypoint'")
    return engine, check(DIALECTS[engine], data, where)
