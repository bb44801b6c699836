"""The demo plugin's own result table (its Alembic branch ``demo_bricks``).

Revision ID: d0001
Revises:
Create Date: 2026-12-01
"""

import sqlalchemy as sa
from alembic import op

revision = "d0001"
down_revision = None
branch_labels = ("demo_bricks",)
depends_on = None


def upgrade() -> None:
    op.create_table(
        "brick_sizes",
        sa.Column("name", sa.String(80), primary_key=True),
        sa.Column("a", sa.Integer(), nullable=False),
        sa.Column("b", sa.Integer(), nullable=False),
        sa.Column("area", sa.Integer(), nullable=False),
        sa.Column("square", sa.Boolean(), nullable=False),
        sa.Column("run_id", sa.Integer()),
    )
    op.create_index("ix_brick_sizes_area", "brick_sizes", ["area"])


def downgrade() -> None:
    op.drop_index("ix_brick_sizes_area", table_name="brick_sizes")
    op.drop_table("brick_sizes")
