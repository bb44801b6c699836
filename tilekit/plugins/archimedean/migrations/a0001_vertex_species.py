"""The vertex_species result table of the archimedean plugin (its own Alembic branch).

Revision ID: a0001
Revises:
Create Date: 2026-12-01
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op
from sqlalchemy.dialects.postgresql import JSONB

revision: str = "a0001"
down_revision: str | Sequence[str] | None = None
branch_labels: str | Sequence[str] | None = ("archimedean",)
depends_on: str | Sequence[str] | None = None

JSONType = sa.JSON().with_variant(JSONB(), "postgresql")


def upgrade() -> None:
    op.create_table(
        "vertex_species",
        sa.Column("vertex_type", sa.String(200), nullable=False),
        sa.Column("species", sa.String(200), nullable=False),
        sa.Column("polygons", JSONType, nullable=False),
        sa.Column("valence", sa.Integer(), nullable=False),
        sa.Column("types_in_species", sa.Integer()),
        sa.Column("geometry", sa.String(16), nullable=False),
        sa.Column("status", sa.String(40), nullable=False),
        sa.Column("angle_sum", sa.String(8)),
        sa.Column("angle_excess", sa.Float()),
        sa.Column("species_tiles", sa.Boolean()),
        sa.Column("tiles_per_unit", sa.Integer()),
        sa.Column("reason", sa.Text()),
        sa.Column("contradictions", sa.Text()),
        sa.Column("search_radius", sa.Float()),
        sa.Column("reached_radius", sa.Float()),
        sa.Column("nodes", sa.Integer()),
        sa.Column("backtracks", sa.Integer()),
        sa.Column("seconds", sa.Float()),
        sa.Column("euler_vertices", sa.Float()),
        sa.Column("euler_feasible", sa.Boolean()),
        sa.Column("solid", sa.String(80)),
        sa.Column("solid_class", sa.String(40)),
        sa.Column("run_id", sa.Integer()),
        sa.PrimaryKeyConstraint("vertex_type", name="pk_vertex_species"),
    )
    for column in ("species", "valence", "geometry", "status", "run_id"):
        op.create_index(f"ix_vertex_species_{column}", "vertex_species", [column])


def downgrade() -> None:
    op.drop_table("vertex_species")
