"""Core tables: tilings, aliases, typed properties, search runs, chunks and results.

Revision ID: 0001
Revises:
Create Date: 2026-11-22
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op
from sqlalchemy.dialects.postgresql import JSONB

revision: str = "0001"
down_revision: str | Sequence[str] | None = None
branch_labels: str | Sequence[str] | None = ("tilekit",)
depends_on: str | Sequence[str] | None = None

JSONType = sa.JSON().with_variant(JSONB(), "postgresql")


def upgrade() -> None:
    op.create_table(
        "tilings",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("family", sa.String(64), nullable=False),
        sa.Column("name", sa.String(200), nullable=False),
        sa.Column("title", sa.String(400), nullable=False),
        sa.Column("spec", JSONType, nullable=False),
        sa.Column("periodic", sa.Boolean(), nullable=True),
        sa.Column("k_hedral", sa.Integer(), nullable=True),
        sa.Column("k_isohedral", sa.Integer(), nullable=True),
        sa.Column("edge_to_edge", sa.Boolean(), nullable=True),
        sa.Column("symmetry_group", sa.String(16), nullable=True),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("updated_at", sa.DateTime(timezone=True), nullable=False),
        sa.PrimaryKeyConstraint("id", name="pk_tilings"),
        sa.UniqueConstraint("name", name="uq_tilings_name"),
    )
    for column in ("family", "periodic", "k_hedral", "k_isohedral", "edge_to_edge", "symmetry_group"):
        op.create_index(f"ix_tilings_{column}", "tilings", [column])

    op.create_table(
        "tiling_aliases",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("alias", sa.String(200), nullable=False),
        sa.Column("tiling_id", sa.Integer(), nullable=False),
        sa.ForeignKeyConstraint(
            ["tiling_id"], ["tilings.id"], name="fk_tiling_aliases_tiling_id_tilings", ondelete="CASCADE"
        ),
        sa.PrimaryKeyConstraint("id", name="pk_tiling_aliases"),
        sa.UniqueConstraint("alias", name="uq_tiling_aliases_alias"),
    )
    op.create_index("ix_tiling_aliases_tiling_id", "tiling_aliases", ["tiling_id"])

    op.create_table(
        "tiling_properties",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("tiling_id", sa.Integer(), nullable=False),
        sa.Column("key", sa.String(64), nullable=False),
        sa.Column("position", sa.Integer(), nullable=True),
        sa.Column("kind", sa.String(8), nullable=False),
        sa.Column("value_text", sa.Text(), nullable=True),
        sa.Column("value_num", sa.Float(), nullable=True),
        sa.Column("value_bool", sa.Boolean(), nullable=True),
        sa.ForeignKeyConstraint(
            ["tiling_id"], ["tilings.id"], name="fk_tiling_properties_tiling_id_tilings", ondelete="CASCADE"
        ),
        sa.PrimaryKeyConstraint("id", name="pk_tiling_properties"),
    )
    op.create_index("ix_tiling_properties_tiling_id", "tiling_properties", ["tiling_id"])
    op.create_index("ix_tiling_properties_key_text", "tiling_properties", ["key", "value_text", "tiling_id"])
    op.create_index("ix_tiling_properties_key_num", "tiling_properties", ["key", "value_num", "tiling_id"])

    op.create_table(
        "runs",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("kind", sa.String(100), nullable=False),
        sa.Column("params", JSONType, nullable=False),
        sa.Column("status", sa.String(16), nullable=False),
        sa.Column("chunks_total", sa.Integer(), nullable=False),
        sa.Column("chunks_done", sa.Integer(), nullable=False),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("started_at", sa.DateTime(timezone=True), nullable=True),
        sa.Column("finished_at", sa.DateTime(timezone=True), nullable=True),
        sa.Column("seconds", sa.Float(), nullable=False),
        sa.Column("summary", JSONType, nullable=True),
        sa.Column("error", sa.Text(), nullable=True),
        sa.PrimaryKeyConstraint("id", name="pk_runs"),
    )
    op.create_index("ix_runs_kind", "runs", ["kind"])
    op.create_index("ix_runs_status", "runs", ["status"])

    op.create_table(
        "run_chunks",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("run_id", sa.Integer(), nullable=False),
        sa.Column("index", sa.Integer(), nullable=False),
        sa.Column("spec", JSONType, nullable=False),
        sa.Column("status", sa.String(16), nullable=False),
        sa.Column("seconds", sa.Float(), nullable=True),
        sa.Column("finished_at", sa.DateTime(timezone=True), nullable=True),
        sa.ForeignKeyConstraint(
            ["run_id"], ["runs.id"], name="fk_run_chunks_run_id_runs", ondelete="CASCADE"
        ),
        sa.PrimaryKeyConstraint("id", name="pk_run_chunks"),
        sa.UniqueConstraint("run_id", "index", name="uq_run_chunks_run_id_index"),
    )
    op.create_index("ix_run_chunks_run_id", "run_chunks", ["run_id"])

    op.create_table(
        "run_results",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("run_id", sa.Integer(), nullable=False),
        sa.Column("chunk_index", sa.Integer(), nullable=False),
        sa.Column("data", JSONType, nullable=False),
        sa.ForeignKeyConstraint(
            ["run_id"], ["runs.id"], name="fk_run_results_run_id_runs", ondelete="CASCADE"
        ),
        sa.PrimaryKeyConstraint("id", name="pk_run_results"),
    )
    op.create_index("ix_run_results_run_chunk", "run_results", ["run_id", "chunk_index"])


def downgrade() -> None:
    op.drop_table("run_results")
    op.drop_table("run_chunks")
    op.drop_table("runs")
    op.drop_table("tiling_properties")
    op.drop_table("tiling_aliases")
    op.drop_table("tilings")
