"""The polyomino family's result table, on the plugin's own metadata (created by its Alembic branch).

One row per free polyform of any grid (``grid`` column; a polyomino is the square grid's
polyform): the canonical code is the natural key; ``result_table()`` is the
``tilekit.plugins.ResultTable`` the ``tilekit_result_tables`` hook returns. The rows are listed
as family ``polyform`` (every grid) or ``polyomino`` (the family's name since part 1: the
square grid's rows only).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import sqlalchemy as sa

metadata = sa.MetaData()

TABLE = sa.Table(
    "polyominoes",
    metadata,
    sa.Column("code", sa.Text, primary_key=True),  # canonical free code: x/. rows (square), GRID:x,y;... others
    sa.Column("name", sa.Text, nullable=True, index=True),  # e.g. pentomino-F
    sa.Column("grid", sa.Text, nullable=False, default="square", index=True),
    sa.Column("cells", sa.Integer, nullable=False, index=True),
    sa.Column("cell_list", sa.Text, nullable=False),  # JSON [[x, y], ...] of canonical cells (column, row)
    sa.Column("holes", sa.Boolean, nullable=False, index=True),
    sa.Column("hole_count", sa.Integer, nullable=False, default=0),
    sa.Column("symmetry", sa.Text, nullable=False, index=True),  # C1 C2 C4 D1 D2 D4
    sa.Column("boundary", sa.Text, nullable=False),  # letters 0-3 = E N W S, counter-clockwise
    sa.Column("translation", sa.Boolean, nullable=True, index=True),  # NULL: not tested (polyforms on other grids)
    sa.Column("halfturn", sa.Boolean, nullable=True, index=True),
    sa.Column("quarterturn", sa.Boolean, nullable=True, index=True),
    sa.Column("reflection", sa.Boolean, nullable=True, index=True),
    sa.Column("isohedral", sa.Boolean, nullable=True, index=True),
    sa.Column("ih_types", sa.Text, nullable=False, default=""),  # e.g. IH41,IH46
    sa.Column("factorisations", sa.Text, nullable=False, default="[]"),  # JSON
    # part 2 of the issue (nullable until its searches fill them)
    sa.Column("tiles", sa.Text, nullable=True, index=True),  # true / false / undecided
    sa.Column("anisohedral_k", sa.Integer, nullable=True),
    sa.Column("heesch", sa.Integer, nullable=True),
    sa.Column("heesch_holes", sa.Integer, nullable=True),
    sa.Column("witness", sa.Text, nullable=True),  # JSON
    sa.Column("verdict", sa.Text, nullable=True),
    sa.Column("run_id", sa.Integer, nullable=True, index=True),
)

KEY: tuple[str, ...] = ("code",)
NAME_COLUMN = "code"


def row_spec(row: Mapping[str, Any]) -> dict:
    """A result row -> the spec the polyomino family's ``from_spec`` reads (show / render):
    a stored classification witness (coronas, or an anisohedral tiling) comes along."""
    spec = {"code": row["code"], "name": row.get("name") or row["code"]}
    if row.get("witness"):  # a non-tiler's coronas, or a torus tiling (k classes; k = 1 off the boundary test)
        spec["witness"] = json.loads(row["witness"])
    if row.get("tiles") is not None and (row.get("grid") or "square") != "square":
        # classified on another grid: drawn with its tilings and witnesses (model), not cell by cell
        spec["classified"] = True
    return spec


def row_title(row: Mapping[str, Any]) -> str:
    if row.get("verdict") and row.get("tiles") is not None:
        kind = row["verdict"]
    elif row.get("isohedral") is None and row.get("grid", "square") != "square":
        kind = "with holes" if row.get("holes") else "not classified"
    else:
        kind = "isohedral" if row.get("isohedral") else ("with holes" if row.get("holes") else "not isohedral")
    grid = row.get("grid") or "square"
    cell = "omino" if grid == "square" else grid
    return f"{row.get('name') or row['code']}: {row['cells']}-{cell}, {row.get('symmetry', '')}, {kind}"


def result_table():
    """The ResultTable for the run layer (None with a tilekit.plugins that has no ResultTable)."""
    import tilekit.plugins as plugins

    cls = getattr(plugins, "ResultTable", None)
    if cls is None:  # pragma: no cover - an older run layer
        return None
    return cls(table=TABLE, key=KEY, family="polyomino", name_column=NAME_COLUMN, spec=row_spec,
               title=row_title, aliases=("polyform",), scopes=(("polyomino", "grid", "square"),))
