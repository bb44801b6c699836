"""polyomino family: rows of polyforms on other grids leave the isohedral columns NULL

Revision ID: p0002_polyform_grids
Revises: p0001_polyominoes
Create Date: 2026-12-03

The ``polyforms`` search stores forms of every grid in the polyominoes table (its ``grid``
column); on grids the isohedral test has not run on, the five flags are NULL (not tested)
rather than a false "no".
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "p0002_polyform_grids"
down_revision = "p0001_polyominoes"
branch_labels = None
depends_on = None

_FLAGS = ("translation", "halfturn", "quarterturn", "reflection", "isohedral")


def upgrade() -> None:
    with op.batch_alter_table("polyominoes") as batch:
        for col in _FLAGS:
            batch.alter_column(col, existing_type=sa.Boolean(), nullable=True)


def downgrade() -> None:
    op.execute("DELETE FROM polyominoes WHERE isohedral IS NULL")
    with op.batch_alter_table("polyominoes") as batch:
        for col in _FLAGS:
            batch.alter_column(col, existing_type=sa.Boolean(), nullable=False)
