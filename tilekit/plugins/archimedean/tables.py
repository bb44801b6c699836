"""The archimedean plugin's result table: one row per vertex type the vertex-species search
classified (Euclidean, spherical or hyperbolic), created by the plugin's own Alembic branch
(``migrations/``, branch ``archimedean``). Only the types that tile become catalogue tilings."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import sqlalchemy as sa

from tilekit.models import JSONType
from tilekit.plugins import ResultTable

METADATA = sa.MetaData()

VERTEX_SPECIES = sa.Table(
    "vertex_species",
    METADATA,
    sa.Column("vertex_type", sa.String(200), primary_key=True),
    sa.Column("species", sa.String(200), nullable=False, index=True),
    sa.Column("polygons", JSONType, nullable=False),
    sa.Column("valence", sa.Integer, nullable=False, index=True),
    sa.Column("types_in_species", sa.Integer),
    sa.Column("geometry", sa.String(16), nullable=False, index=True),
    sa.Column("status", sa.String(40), nullable=False, index=True),
    sa.Column("angle_sum", sa.String(8)),
    sa.Column("angle_excess", sa.Float),
    sa.Column("species_tiles", sa.Boolean),
    sa.Column("tiles_per_unit", sa.Integer),
    sa.Column("reason", sa.Text),
    sa.Column("contradictions", sa.Text),
    sa.Column("search_radius", sa.Float),
    sa.Column("reached_radius", sa.Float),
    sa.Column("nodes", sa.Integer),
    sa.Column("backtracks", sa.Integer),
    sa.Column("seconds", sa.Float),
    sa.Column("euler_vertices", sa.Float),
    sa.Column("euler_feasible", sa.Boolean),
    sa.Column("solid", sa.String(80)),
    sa.Column("solid_class", sa.String(40)),
    sa.Column("run_id", sa.Integer, index=True),
)

#: the columns a row takes from the search's per-type findings
COLUMNS = frozenset(c.name for c in VERTEX_SPECIES.c) - {"run_id"}

MIGRATIONS = Path(__file__).parent / "migrations"  # the hook names this folder itself


def _spec(row: Mapping[str, Any]) -> dict[str, Any]:
    return {"kind": "vertex_type", "vertex_type": row["vertex_type"]}


def _title(row: Mapping[str, Any]) -> str:
    return f"Vertex type {row['vertex_type']}: {row['geometry']}, {row['status']}"


RESULT_TABLE = ResultTable(
    table=VERTEX_SPECIES,
    key=("vertex_type",),
    family="vertex-species",
    name_column="vertex_type",
    spec=_spec,
    title=_title,
    tiling_family="archimedean",
)


def row_of(props: Mapping[str, Any]) -> dict[str, Any]:
    """A table row from the search's properties of one vertex type."""
    return {k: v for k, v in props.items() if k in COLUMNS}
