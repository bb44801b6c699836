"""Plugin result tables: bulk upserts of a chunk's rows by the table's key, and typed queries
over their columns (streamed), so a family's millions of search results are queried like its
tilings (``tilekit list --family F --where ...``)."""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Mapping
from typing import Any

import sqlalchemy as sa
from sqlalchemy.engine import Connection

from tilekit.catalogue.codec import json_ok
from tilekit.catalogue.entry import Entry
from tilekit.catalogue.filters import (
    Filter,
    Params,
    column_condition,
    parse_filter,
    parse_order,
    quote,
)
from tilekit.errors import CatalogueError, NotFoundError, ParameterError
from tilekit.models import is_json
from tilekit.plugins import ResultTable, normalise, result_tables

#: Bound parameters per statement on SQLite (its limit is 32,766).
_MAX_PARAMS = 30_000


def _plain(value: Any) -> Any:
    """NumPy scalars and the like as plain Python values; non-finite floats refused."""
    if value is None or isinstance(value, str | bool | int):
        return value
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"{value} is not a finite number")
        return value
    item = getattr(value, "item", None)
    if callable(item) and getattr(value, "shape", None) == ():
        return _plain(item())
    return value


class ResultsMixin:
    """The result-table methods of :class:`tilekit.catalogue.Catalogue`."""

    engine: Any
    pm: Any
    _result_tables: dict[str, ResultTable] | None = None

    @property
    def result_tables(self) -> dict[str, ResultTable]:
        """Every installed plugin's result tables, by table name."""
        if self._result_tables is None:
            self._result_tables = result_tables(self.pm)
        return self._result_tables

    def family_table(self, family: str | None) -> ResultTable | None:
        """The result table that holds ``family``'s entries, if it has one."""
        if family is None:
            return None
        for rt in self.result_tables.values():
            if rt.family == family or family in rt.aliases:
                return rt.scoped(family) if rt.scopes else rt
        return None

    def _prepare_rows(
        self, run_id: int, index: int, rows: Mapping[str, Iterable[Mapping[str, Any]]]
    ) -> list[tuple[ResultTable, list[dict[str, Any]]]]:
        """Check a chunk's rows against their tables (names, columns, JSON, finite numbers)."""
        out = []
        for name, items in (rows or {}).items():
            rt = self.result_tables.get(name)
            if rt is None:
                raise NotFoundError("result table", name, self.result_tables)
            columns = rt.table.c
            names = frozenset(c.name for c in columns)
            json_cols = frozenset(c.name for c in columns if is_json(c.type))
            has_run = "run_id" in names
            checked: set[frozenset[str]] = set()  # key sets already found to be columns
            prepared = []
            for item in items:
                if not isinstance(item, Mapping):
                    raise CatalogueError(f"run {run_id} chunk {index}: a row of {name!r} is a "
                                         f"{type(item).__name__}, not a mapping")
                keys = frozenset(item)
                if keys not in checked:
                    unknown = sorted(keys - names)
                    if unknown:
                        raise CatalogueError(
                            f"run {run_id} chunk {index}: table {name!r} has no column {unknown[0]!r} "
                            f"(columns: {', '.join(c.name for c in columns)})"
                        )
                    checked.add(keys)
                row = dict(item)
                for key, value in row.items():
                    kind = type(value)
                    if kind is str or kind is int or kind is bool or value is None:
                        continue
                    if kind is float and math.isfinite(value):
                        continue
                    try:
                        row[key] = _plain(value)
                    except ValueError as exc:
                        raise CatalogueError(f"run {run_id} chunk {index}: {name}.{key}: {exc}") from None
                for key in json_cols & keys:
                    json_ok(f"run {run_id} chunk {index}", f"{name}.{key}", row[key])
                missing = [k for k in rt.key if row.get(k) is None]
                if missing:
                    raise CatalogueError(f"run {run_id} chunk {index}: a row of {name!r} has no key {missing}")
                if has_run:
                    row["run_id"] = run_id
                prepared.append(row)
            if prepared:
                out.append((rt, prepared))
        return out

    def _upsert_rows(self, conn: Connection, rt: ResultTable, rows: list[dict[str, Any]]) -> None:
        """Insert rows, updating (only the given columns of) rows whose key exists."""
        groups: dict[tuple[str, ...], dict[tuple[Any, ...], dict[str, Any]]] = {}
        for row in rows:
            cols = tuple(sorted(row))
            groups.setdefault(cols, {})[tuple(row[k] for k in rt.key)] = row  # last one wins
        dialect = conn.dialect.name
        for cols, by_key in groups.items():
            items = list(by_key.values())
            update = [c for c in cols if c not in rt.key]
            if dialect in ("sqlite", "postgresql"):
                if dialect == "sqlite":
                    from sqlalchemy.dialects.sqlite import insert
                else:
                    from sqlalchemy.dialects.postgresql import insert
                ins = insert(rt.table)
                if update:
                    stmt = ins.on_conflict_do_update(index_elements=list(rt.key),
                                                     set_={c: ins.excluded[c] for c in update})
                else:
                    stmt = ins.on_conflict_do_nothing(index_elements=list(rt.key))
                size = max(1, _MAX_PARAMS // max(1, len(cols)))
                for start in range(0, len(items), size):
                    conn.execute(stmt, items[start : start + size])
            else:  # any other database: look the keys up, then insert or update
                for row in items:
                    where = sa.and_(*(rt.table.c[k] == row[k] for k in rt.key))
                    if conn.execute(sa.select(sa.literal(1)).where(where)).first():
                        if update:
                            conn.execute(sa.update(rt.table).where(where).values({c: row[c] for c in update}))
                    else:
                        conn.execute(sa.insert(rt.table).values(row))

    # ------------------------------------------------------------------ queries

    def _result_select(self, rt: ResultTable, where: Iterable[Any], text: str | None,
                       order_by: str | None) -> sa.Select:
        t = rt.table
        stmt = sa.select(t)
        params = Params()
        conditions = []
        for f in (parse_filter(w) for w in where):
            if f.op in ("=", "!=") and isinstance(f.value, str) and f.key in t.c:
                key, value = normalise(f.key, f.value, self.pm)  # a code in any orientation ...
                if key == f.key and value != f.value:
                    f = Filter(key, f.op, value, value)
            if f.key not in t.c:
                raise NotFoundError("column", f.key, [c.name for c in t.c])
            column = t.c[f.key]
            conditions.append(column_condition(params, f"{quote(t.name)}.{quote(column.name)}", column_kind(column.type), f))
        if conditions:
            stmt = stmt.where(sa.text(" AND ".join(conditions)).bindparams(**params))
        for key, value in rt.where:  # the rows of the family name the table was looked up by
            stmt = stmt.where(t.c[key] == value)
        if text:
            needle = text.lower()
            texts = [c for c in t.c if isinstance(c.type, sa.String | sa.Text)]
            if texts:
                stmt = stmt.where(sa.or_(*(sa.func.lower(c).contains(needle, autoescape=True) for c in texts)))
        if order_by is not None:
            key, descending = parse_order(order_by)
            if key == "name":
                key = rt.name_column or rt.key[0]
            if key not in t.c:
                raise NotFoundError("order key", key, [c.name for c in t.c])
            col = t.c[key]
            stmt = stmt.order_by((col.desc() if descending else col.asc()).nulls_last(),
                                 *(t.c[k].asc() for k in rt.key))
        return stmt

    def _row_entry(self, rt: ResultTable, row: Mapping[str, Any]) -> Entry:
        name_col = rt.name_column or rt.key[0]
        name = row.get(name_col) if row.get(name_col) is not None else row.get(rt.key[0])
        props = {k: v for k, v in row.items() if k not in ("name", "family", "title", "spec")}
        spec = rt.spec(row) if rt.spec is not None else {}
        title = rt.title(row) if rt.title is not None else ""
        return Entry(name=str(name), family=rt.family or rt.name, title=title, spec=spec, properties=props)

    def iter_result_rows(self, table: str | ResultTable, where: Iterable[Any] = (), text: str | None = None,
                         order_by: str | None = None, limit: int | None = None, offset: int = 0,
                         ) -> Iterator[dict[str, Any]]:
        """Rows of a result table matching every filter, streamed (server-side cursor)."""
        rt = table if isinstance(table, ResultTable) else self.result_tables.get(table)
        if rt is None:
            raise NotFoundError("result table", str(table), self.result_tables)
        stmt = self._result_select(rt, where, text, order_by or "name")
        stmt = _paged(stmt, limit, offset)
        with self._errors("querying"), self.engine.connect() as conn:
            result = conn.execution_options(stream_results=True, yield_per=2000).execute(stmt)
            for row in result.mappings():
                yield dict(row)

    def export_rows(self, rt: ResultTable, stream: Any, format: str, where: Iterable[Any] = (),
                    text: str | None = None, order_by: str | None = None) -> int:
        """Write a result table's matching rows straight from the cursor (no Entry objects):
        CSV with one column per table column, JSON Lines or a JSON array of row objects."""
        import csv
        import json

        stmt = self._result_select(rt, where, text, order_by or "name")
        columns = [c.name for c in rt.table.c]
        json_cols = {i for i, c in enumerate(rt.table.c) if is_json(c.type)}
        bool_cols = {i for i, c in enumerate(rt.table.c) if isinstance(c.type, sa.Boolean)}
        count = 0
        with self._errors("exporting"), self.engine.connect() as conn:
            result = conn.execution_options(stream_results=True, yield_per=5000).execute(stmt)
            if format == "csv":
                writer = csv.writer(stream, lineterminator="\n")
                writer.writerow(columns)
                for row in result:
                    if json_cols or bool_cols:
                        row = [("" if v is None else json.dumps(v)) if i in json_cols
                               else ("" if v is None else ("true" if v else "false")) if i in bool_cols
                               else v for i, v in enumerate(row)]
                    writer.writerow(row)
                    count += 1
                return count
            dumps = json.JSONEncoder(ensure_ascii=False).encode
            if format == "json":
                stream.write("[")
            for row in result:
                if format == "json":
                    stream.write(",\n  " if count else "\n  ")
                stream.write(dumps(dict(zip(columns, row))))
                if format == "jsonl":
                    stream.write("\n")
                count += 1
            if format == "json":
                stream.write("\n]\n" if count else "]\n")
        return count

    def count_result_rows(self, table: str | ResultTable, where: Iterable[Any] = (), text: str | None = None) -> int:
        rt = table if isinstance(table, ResultTable) else self.result_tables.get(table)
        if rt is None:
            raise NotFoundError("result table", str(table), self.result_tables)
        sub = self._result_select(rt, where, text, None).subquery()
        with self._errors("counting"), self.engine.connect() as conn:
            return int(conn.execute(sa.select(sa.func.count()).select_from(sub)).scalar_one())

    def result_facet_counts(self, rt: ResultTable, columns: Iterable[str], where: Iterable[Any] = (),
                            text: str | None = None) -> dict[str, list[tuple[Any, int]]]:
        """How many matching rows have each value of each column: ``{column: [(value, rows), ...]}``,
        most first (NULLs left out)."""
        sub = self._result_select(rt, where, text, None).subquery()
        out: dict[str, list[tuple[Any, int]]] = {}
        with self._errors("counting facets"), self.engine.connect() as conn:
            for name in columns:
                col = sub.c[name]
                rows = conn.execute(sa.select(col, sa.func.count()).where(col.is_not(None)).group_by(col)).all()
                out[name] = sorted(((r[0], int(r[1])) for r in rows), key=lambda vc: (-vc[1], str(vc[0])))
        return out

    def result_spread(self, rt: ResultTable) -> dict[str, tuple[int, int]]:
        """``{column: (distinct values, rows having one)}`` for the table's scalar columns (not its
        key, JSON or run columns): what a listing can offer as facets."""
        t = rt.table
        cols = [c for c in t.c if c.name not in rt.key and c.name != "run_id" and not is_json(c.type)]
        if not cols:
            return {}
        stmt = sa.select(*(x for c in cols for x in (sa.func.count(sa.distinct(c)), sa.func.count(c))))
        with self._errors("counting facets"), self.engine.connect() as conn:
            row = conn.execute(stmt).one()
        return {c.name: (int(row[2 * i]), int(row[2 * i + 1])) for i, c in enumerate(cols)}

    def result_entry(self, name: str) -> Entry | None:
        """The result-table row named ``name`` (in a table's name column or key), or None: the
        web's page of a listed row, which a shipped record with that alias must not shadow."""
        return self._result_lookup(name)

    def _result_lookup(self, name: str) -> Entry | None:
        """A result-table row named ``name`` (in a table's name column or key)."""
        with self._errors("looking up a tiling"), self.engine.connect() as conn:
            for rt in self.result_tables.values():
                if rt.family is None:
                    continue
                t = rt.table
                cols = [t.c[rt.name_column]] if rt.name_column else []
                if len(rt.key) == 1 and t.c[rt.key[0]] not in cols:
                    cols.append(t.c[rt.key[0]])
                for col in cols:
                    if not isinstance(col.type, sa.String | sa.Text):
                        continue
                    row = conn.execute(sa.select(t).where(col == name).limit(1)).mappings().first()
                    if row is not None:
                        return self._row_entry(rt, dict(row))
        return None


def column_kind(type_: Any) -> str:
    """Which of filters.COLUMN_KINDS a SQLAlchemy column type is (floats compare ``=`` within a
    tolerance; other numbers exactly)."""
    if isinstance(type_, sa.Boolean):
        return "bool"
    if isinstance(type_, sa.Float):
        return "float"
    if isinstance(type_, sa.Integer | sa.Numeric):
        return "int"
    if is_json(type_):
        return "json"
    return "text"


def _paged(stmt: sa.Select, limit: int | None, offset: int) -> sa.Select:
    if limit is not None:
        if limit < 0:
            raise ParameterError(f"limit must be >= 0, got {limit}")
        stmt = stmt.limit(limit)
    if offset:
        if offset < 0:
            raise ParameterError(f"offset must be >= 0, got {offset}")
        stmt = stmt.offset(offset)
    return stmt
