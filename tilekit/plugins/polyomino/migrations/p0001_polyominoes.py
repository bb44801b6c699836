"""polyomino family: the polyominoes result table

Revision ID: p0001_polyominoes
Revises:
Create Date: 2026-12-01
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "p0001_polyominoes"
down_revision = None
branch_labels = ("polyomino",)
depends_on = None


def upgrade() -> None:
    op.create_table(
        "polyominoes",
        sa.Column("code", sa.Text, primary_key=True),
        sa.Column("name", sa.Text, nullable=True),
        sa.Column("grid", sa.Text, nullable=False, server_default="square"),
        sa.Column("cells", sa.Integer, nullable=False),
        sa.Column("cell_list", sa.Text, nullable=False),
        sa.Column("holes", sa.Boolean, nullable=False),
        sa.Column("hole_count", sa.Integer, nullable=False, server_default="0"),
        sa.Column("symmetry", sa.Text, nullable=False),
        sa.Column("boundary", sa.Text, nullable=False),
        sa.Column("translation", sa.Boolean, nullable=False),
        sa.Column("halfturn", sa.Boolean, nullable=False),
        sa.Column("quarterturn", sa.Boolean, nullable=False),
        sa.Column("reflection", sa.Boolean, nullable=False),
        sa.Column("isohedral", sa.Boolean, nullable=False),
        sa.Column("ih_types", sa.Text, nullable=False, server_default=""),
        sa.Column("factorisations", sa.Text, nullable=False, server_default="[]"),
        sa.Column("tiles", sa.Text, nullable=True),
        sa.Column("anisohedral_k", sa.Integer, nullable=True),
        sa.Column("heesch", sa.Integer, nullable=True),
        sa.Column("heesch_holes", sa.Integer, nullable=True),
        sa.Column("witness", sa.Text, nullable=True),
        sa.Column("verdict", sa.Text, nullable=True),
        sa.Column("run_id", sa.Integer, nullable=True),
    )
    for col in ("name", "grid", "cells", "holes", "symmetry", "translation", "halfturn",
                "quarterturn", "reflection", "isohedral", "tiles", "run_id"):
        op.create_index(f"ix_polyominoes_{col}", "polyominoes", [col])


def downgrade() -> None:
    op.drop_table("polyominoes")
