"""Runs shared by many workers: chunk leases, worker heartbeats, per-chunk rows and counts.

Revision ID: 0003
Revises: 0002
Create Date: 2026-12-01
"""

from __future__ import annotations

from collections.abc import Sequence

import sqlalchemy as sa
from alembic import op
from sqlalchemy.dialects.postgresql import JSONB

revision: str = "0003"
down_revision: str | Sequence[str] | None = "0002"
branch_labels: str | Sequence[str] | None = None
depends_on: str | Sequence[str] | None = None

JSONType = sa.JSON().with_variant(JSONB(), "postgresql")


def upgrade() -> None:
    with op.batch_alter_table("run_chunks") as batch:
        batch.add_column(sa.Column("lease_owner", sa.String(200), nullable=True))
        batch.add_column(sa.Column("lease_expires", sa.Float(), nullable=True))
        batch.add_column(sa.Column("attempts", sa.Integer(), nullable=False, server_default="0"))
        batch.add_column(sa.Column("rows", sa.Integer(), nullable=True))
        batch.add_column(sa.Column("counts", JSONType, nullable=True))
        batch.create_index("ix_run_chunks_run_status", ["run_id", "status", "index"])
    op.create_table(
        "run_workers",
        sa.Column("id", sa.Integer(), nullable=False),
        sa.Column("run_id", sa.Integer(), nullable=False),
        sa.Column("owner", sa.String(200), nullable=False),
        sa.Column("session", sa.String(200), nullable=False),
        sa.Column("host", sa.String(200), nullable=False),
        sa.Column("pid", sa.Integer(), nullable=False),
        sa.Column("started", sa.Float(), nullable=False),
        sa.Column("heartbeat", sa.Float(), nullable=False),
        sa.Column("finished", sa.Float(), nullable=True),
        sa.Column("stop", sa.Boolean(), nullable=False),
        sa.Column("chunks_done", sa.Integer(), nullable=False),
        sa.ForeignKeyConstraint(["run_id"], ["runs.id"], name="fk_run_workers_run_id_runs", ondelete="CASCADE"),
        sa.PrimaryKeyConstraint("id", name="pk_run_workers"),
        sa.UniqueConstraint("owner", name="uq_run_workers_owner"),
    )
    op.create_index("ix_run_workers_run_id", "run_workers", ["run_id"])
    op.create_index("ix_run_workers_session", "run_workers", ["session"])


def downgrade() -> None:
    op.drop_index("ix_run_workers_session", table_name="run_workers")
    op.drop_index("ix_run_workers_run_id", table_name="run_workers")
    op.drop_table("run_workers")
    with op.batch_alter_table("run_chunks") as batch:
        batch.drop_index("ix_run_chunks_run_status")
        batch.drop_column("counts")
        batch.drop_column("rows")
        batch.drop_column("attempts")
        batch.drop_column("lease_expires")
        batch.drop_column("lease_owner")
