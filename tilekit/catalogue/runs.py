"""Search runs in the catalogue: runs, their chunks as leased claims, their workers.

A run's chunks are claimed by workers (any number of processes or machines on one catalogue):
a claim sets the chunk's lease owner and expiry inside the database's write lock (``BEGIN
IMMEDIATE`` on SQLite, ``FOR UPDATE SKIP LOCKED`` on PostgreSQL), the worker's heartbeat
pushes the expiry on, and recording the chunk writes its results, rows, records and done
mark in one transaction; a chunk whose lease expired (its worker died) is claimed again.
A run reads ``running`` only while one of its workers has a fresh heartbeat.
"""

from __future__ import annotations

import json
import os
import socket
import time
import uuid
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from datetime import datetime
from typing import Any

import sqlalchemy as sa
from sqlalchemy.engine import Connection

from tilekit.catalogue.codec import batches, json_ok, upsert
from tilekit.catalogue.tables import BATCH, CHUNKS, RESULTS, RUNS, WORKERS
from tilekit.errors import CatalogueError, NotFoundError, ParameterError
from tilekit.models import RUN_STATUSES, utcnow
from tilekit.plugins import ChunkResult

#: Environment variable: seconds a chunk lease lasts without a heartbeat (default 30).
LEASE_ENV = "TILEKIT_LEASE_SECONDS"

#: Final statuses: nothing more is claimed.
FINAL = ("done", "failed", "cancelled")


def lease_seconds() -> float:
    """How long a lease lives without a heartbeat (``$TILEKIT_LEASE_SECONDS``, default 30)."""
    try:
        value = float(os.environ.get(LEASE_ENV, "") or 30.0)
    except ValueError:
        value = 30.0
    return min(max(value, 0.5), 3600.0)


HOST = socket.gethostname()


def pid_alive(pid: int) -> bool:
    """Whether process ``pid`` on this host is alive (a zombie is not)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            state = fh.read().rsplit(b")", 1)[-1].split()[0]
        return state != b"Z"
    except (OSError, IndexError):
        return True


@dataclass
class RunInfo:
    """A search run as ``tilekit runs`` shows it.

    ``status`` is the stored status, except that a run stored as running with no live
    worker reads ``interrupted``. ``seconds`` is wall-clock time (the union of its workers'
    lifetimes), ``worker_seconds`` the summed time of its recorded chunks.
    """

    id: int
    kind: str
    params: dict[str, Any]
    status: str
    chunks_total: int
    chunks_done: int
    created_at: datetime | None
    started_at: datetime | None
    finished_at: datetime | None
    seconds: float
    summary: dict[str, Any] | None
    error: str | None
    worker_seconds: float = 0.0
    rows: int = 0
    workers_alive: int = 0
    chunks_leased: int = 0
    counts: dict[str, Any] = field(default_factory=dict)

    @property
    def progress(self) -> str:
        return f"{self.chunks_done}/{self.chunks_total}"


def _union_seconds(intervals: Iterable[tuple[float, float]]) -> float:
    total, end = 0.0, None
    start = None
    for a, b in sorted(intervals):
        if b < a:
            continue
        if end is None or a > end:
            if end is not None:
                total += end - start
            start, end = a, b
        else:
            end = max(end, b)
    if end is not None:
        total += end - start
    return total


def _add_counts(into: dict[str, Any], counts: Mapping[str, Any] | None) -> None:
    for key, value in (counts or {}).items():
        if isinstance(value, bool) or not isinstance(value, int | float):
            continue
        into[key] = into.get(key, 0) + value


class RunsMixin:
    """The run, chunk, lease and worker methods of :class:`tilekit.catalogue.Catalogue`."""

    engine: Any

    # ------------------------------------------------------------------ creating

    def create_run(self, kind: str, params: Mapping[str, Any], chunks: Iterable[Mapping[str, Any]]) -> int:
        """Store a new queued run and its chunks (all pending); return its id.

        ``chunks`` may be any iterable: it is read and written in batches, in the same
        transaction, so a huge split never sits in memory and a failed split leaves no run.
        """
        json_ok(f"search {kind!r}", "the parameters", dict(params))
        with self._errors("creating a run"), self.engine.begin() as conn:
            run_id = conn.execute(
                sa.insert(RUNS)
                .values(kind=kind, params=dict(params), status="queued", chunks_total=0,
                        chunks_done=0, seconds=0.0)
                .returning(RUNS.c.id)
            ).scalar_one()
            total = 0
            batch: list[dict[str, Any]] = []
            for chunk in chunks:
                json_ok(f"search {kind!r}", f"chunk {total}", dict(chunk))
                batch.append({"run_id": run_id, "index": total, "spec": dict(chunk),
                              "status": "pending", "attempts": 0})
                total += 1
                if len(batch) >= BATCH:
                    conn.execute(sa.insert(CHUNKS), batch)
                    batch = []
            if batch:
                conn.execute(sa.insert(CHUNKS), batch)
            conn.execute(sa.update(RUNS).where(RUNS.c.id == run_id).values(chunks_total=total))
        return int(run_id)

    # ------------------------------------------------------------------ reading

    def _live_workers(self, conn: Connection, run_id: int, now: float, ttl: float) -> int:
        rows = conn.execute(
            sa.select(WORKERS.c.host, WORKERS.c.pid, WORKERS.c.heartbeat)
            .where(WORKERS.c.run_id == run_id, WORKERS.c.finished.is_(None))
        ).all()
        return sum(1 for host, pid, beat in rows
                   if beat > now - ttl and (host != HOST or pid_alive(int(pid))))

    def _info(self, conn: Connection, row: Any) -> RunInfo:
        now, ttl = time.time(), lease_seconds()
        alive = self._live_workers(conn, row.id, now, ttl)
        agg = conn.execute(
            sa.select(
                sa.func.coalesce(sa.func.sum(CHUNKS.c.seconds), 0.0),
                sa.func.coalesce(sa.func.sum(CHUNKS.c.rows), 0),
                sa.func.count().filter(CHUNKS.c.status == "done"),
                sa.func.count().filter(CHUNKS.c.status == "leased"),
            ).where(CHUNKS.c.run_id == row.id)
        ).one()
        spans = conn.execute(
            sa.select(WORKERS.c.started, sa.func.coalesce(WORKERS.c.finished, WORKERS.c.heartbeat))
            .where(WORKERS.c.run_id == row.id)
        ).all()
        status = row.status
        if status == "running" and alive == 0:
            status = "interrupted"
        return RunInfo(
            id=row.id, kind=row.kind, params=row.params or {}, status=status,
            chunks_total=row.chunks_total, chunks_done=int(agg[2]),
            created_at=row.created_at, started_at=row.started_at, finished_at=row.finished_at,
            seconds=_union_seconds((float(a), float(b)) for a, b in spans) if spans else float(row.seconds or 0.0),
            summary=row.summary, error=row.error, worker_seconds=float(agg[0]), rows=int(agg[1]),
            workers_alive=alive, chunks_leased=int(agg[3]),
        )

    def runs(self, kind: str | None = None) -> list[RunInfo]:
        """Every run (of one search kind), oldest first."""
        stmt = sa.select(RUNS).order_by(RUNS.c.id)
        if kind is not None:
            stmt = stmt.where(RUNS.c.kind == kind)
        with self._errors("reading runs"), self.engine.connect() as conn:
            return [self._info(conn, r) for r in conn.execute(stmt).all()]

    def run(self, run_id: int) -> RunInfo:
        """One run, or NotFoundError naming the existing run ids."""
        with self._errors("reading a run"), self.engine.connect() as conn:
            row = conn.execute(sa.select(RUNS).where(RUNS.c.id == int(run_id))).first()
            if row is None:
                ids = conn.execute(sa.select(RUNS.c.id).order_by(RUNS.c.id)).scalars().all()
                raise NotFoundError("run", str(run_id), [str(i) for i in ids])
            return self._info(conn, row)

    def chunks_done(self, run_id: int) -> int:
        """How many chunks of the run are recorded (one indexed count)."""
        with self._errors("reading a run"), self.engine.connect() as conn:
            return int(conn.execute(
                sa.select(sa.func.count()).where(CHUNKS.c.run_id == run_id, CHUNKS.c.status == "done")
            ).scalar_one())

    def run_chunks(self, run_id: int) -> list[dict[str, Any]]:
        """Every chunk of a run: index, status, seconds, rows, lease owner, spec."""
        with self._errors("reading chunks"), self.engine.connect() as conn:
            rows = conn.execute(
                sa.select(CHUNKS.c.index, CHUNKS.c.status, CHUNKS.c.seconds, CHUNKS.c.rows,
                          CHUNKS.c.lease_owner, CHUNKS.c.attempts, CHUNKS.c.spec)
                .where(CHUNKS.c.run_id == run_id)
                .order_by(CHUNKS.c.index)
            ).all()
        return [{"index": i, "status": s, "seconds": sec, "rows": n, "lease_owner": o,
                 "attempts": a, "spec": spec} for i, s, sec, n, o, a, spec in rows]

    def pending_chunks(self, run_id: int) -> list[tuple[int, dict[str, Any]]]:
        """(index, chunk) of every chunk of the run not yet done, in index order."""
        with self._errors("reading chunks"), self.engine.connect() as conn:
            rows = conn.execute(
                sa.select(CHUNKS.c.index, CHUNKS.c.spec)
                .where(CHUNKS.c.run_id == run_id, CHUNKS.c.status != "done")
                .order_by(CHUNKS.c.index)
            ).all()
        return [(int(i), spec) for i, spec in rows]

    def iter_results(self, run_id: int) -> Iterator[dict[str, Any]]:
        """Every JSON result of a run, in chunk order, streamed."""
        with self._errors("reading results"), self.engine.connect() as conn:
            result = conn.execution_options(stream_results=True, yield_per=1000).execute(
                sa.select(RESULTS.c.data)
                .where(RESULTS.c.run_id == run_id)
                .order_by(RESULTS.c.chunk_index, RESULTS.c.id)
            )
            for (data,) in result:
                yield data

    def results(self, run_id: int) -> list[dict[str, Any]]:
        """Every JSON result of a run, in chunk order (see :meth:`iter_results` to stream)."""
        return list(self.iter_results(run_id))

    def run_counts(self, run_id: int) -> dict[str, Any]:
        """The ``counts`` of every recorded chunk of a run, summed."""
        total: dict[str, Any] = {}
        with self._errors("reading chunks"), self.engine.connect() as conn:
            for (counts,) in conn.execution_options(stream_results=True, yield_per=1000).execute(
                sa.select(CHUNKS.c.counts).where(CHUNKS.c.run_id == run_id, CHUNKS.c.status == "done")
            ):
                _add_counts(total, counts)
        return total

    # ------------------------------------------------------------------ workers and leases

    def start_worker(self, run_id: int, session: str) -> str:
        """Register a worker of the run (this process) and mark the run running; return its
        owner token ``host/pid/uuid``. Refuses a run that is done, failed or cancelled."""
        owner = f"{HOST}/{os.getpid()}/{uuid.uuid4().hex[:12]}"
        now = time.time()
        with self._errors("starting a worker"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=False)
            status = conn.execute(sa.select(RUNS.c.status).where(RUNS.c.id == run_id)).scalar()
            if status is None:
                raise NotFoundError("run", str(run_id), [])
            conn.execute(sa.insert(WORKERS).values(
                run_id=run_id, owner=owner, session=session, host=HOST, pid=os.getpid(),
                started=now, heartbeat=now, finished=None, stop=False, chunks_done=0))
            if status not in FINAL:
                conn.execute(
                    sa.update(RUNS).where(RUNS.c.id == run_id)
                    .values(status="running", error=None, finished_at=None,  # a resumed run is not finished
                            started_at=sa.func.coalesce(RUNS.c.started_at, utcnow()))
                )
        return owner

    def heartbeat(self, owner: str) -> bool:
        """Refresh a worker's heartbeat and its leases; True if it should stop (asked to, or
        the run was cancelled, failed or finished meanwhile)."""
        now = time.time()
        with self._errors("refreshing a lease"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=False)
            conn.execute(sa.update(WORKERS).where(WORKERS.c.owner == owner).values(heartbeat=now))
            conn.execute(
                sa.update(CHUNKS)
                .where(CHUNKS.c.lease_owner == owner, CHUNKS.c.status == "leased")
                .values(lease_expires=now + lease_seconds())
            )
            row = conn.execute(
                sa.select(WORKERS.c.stop, RUNS.c.status)
                .join(RUNS, RUNS.c.id == WORKERS.c.run_id)
                .where(WORKERS.c.owner == owner)
            ).first()
        return row is None or bool(row[0]) or row[1] in FINAL

    def _reap_dead_local_workers(self, conn: Connection, run_id: int, now: float) -> None:
        """Workers of this host whose process is gone: finished, their leases free at once
        (no need to wait for the expiry)."""
        rows = conn.execute(
            sa.select(WORKERS.c.owner, WORKERS.c.pid, WORKERS.c.heartbeat)
            .where(WORKERS.c.run_id == run_id, WORKERS.c.finished.is_(None), WORKERS.c.host == HOST)
        ).all()
        dead = [(owner, beat) for owner, pid, beat in rows if not pid_alive(int(pid))]
        for owner, beat in dead:
            conn.execute(sa.update(WORKERS).where(WORKERS.c.owner == owner).values(finished=beat))
            conn.execute(
                sa.update(CHUNKS)
                .where(CHUNKS.c.lease_owner == owner, CHUNKS.c.status == "leased")
                .values(status="pending", lease_owner=None, lease_expires=None)
            )

    def claim(self, run_id: int, owner: str, n: int = 1) -> list[tuple[int, dict[str, Any]]] | None:
        """Lease up to ``n`` claimable chunks (pending, or leased with an expired lease) to
        ``owner``. Returns them; ``[]`` when none is claimable now but others hold leases
        (wait and try again); ``None`` when there is nothing left to do (every chunk done,
        or the run is finished, failed or cancelled)."""
        now = time.time()
        ttl = lease_seconds()
        with self._errors("claiming chunks"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=False)
            status = conn.execute(sa.select(RUNS.c.status).where(RUNS.c.id == run_id)).scalar()
            if status is None or status in FINAL:
                return None
            self._reap_dead_local_workers(conn, run_id, now)
            claimable = sa.and_(
                CHUNKS.c.run_id == run_id,
                sa.or_(CHUNKS.c.status == "pending",
                       sa.and_(CHUNKS.c.status == "leased", CHUNKS.c.lease_expires < now)),
            )
            stmt = sa.select(CHUNKS.c.id, CHUNKS.c.index, CHUNKS.c.spec).where(claimable).order_by(CHUNKS.c.index).limit(n)
            if conn.dialect.name == "postgresql":
                stmt = stmt.with_for_update(skip_locked=True)
            rows = conn.execute(stmt).all()
            if rows:
                conn.execute(
                    sa.update(CHUNKS).where(CHUNKS.c.id.in_([r.id for r in rows]))
                    .values(status="leased", lease_owner=owner, lease_expires=now + ttl,
                            attempts=CHUNKS.c.attempts + 1)
                )
                return [(int(r.index), r.spec) for r in rows]
            left = conn.execute(
                sa.select(sa.func.count()).where(CHUNKS.c.run_id == run_id, CHUNKS.c.status != "done")
            ).scalar_one()
            return [] if left else None

    def finish_worker(self, owner: str, *, release: bool = True) -> None:
        """A worker ends: its leases are given back and its lifetime closed."""
        now = time.time()
        with self._errors("finishing a worker"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=False)
            if release:
                conn.execute(
                    sa.update(CHUNKS)
                    .where(CHUNKS.c.lease_owner == owner, CHUNKS.c.status == "leased")
                    .values(status="pending", lease_owner=None, lease_expires=None)
                )
            conn.execute(sa.update(WORKERS).where(WORKERS.c.owner == owner, WORKERS.c.finished.is_(None))
                         .values(finished=now, heartbeat=now))

    def stop_session(self, session: str) -> None:
        """Ask every worker of a session to stop after its current chunk."""
        with self._errors("stopping workers"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=False)
            conn.execute(sa.update(WORKERS).where(WORKERS.c.session == session).values(stop=True))

    def session_owners(self, session: str) -> list[str]:
        with self._errors("reading workers"), self.engine.connect() as conn:
            return list(conn.execute(sa.select(WORKERS.c.owner).where(WORKERS.c.session == session)).scalars())

    # ------------------------------------------------------------------ recording

    def record_chunk(
        self, run_id: int, index: int, result: ChunkResult, seconds: float | None = None,
        owner: str | None = None,
    ) -> bool:
        """Store a chunk's results, rows and records and mark it done, in ONE transaction.

        Returns False (writing nothing) if the chunk was already done, so a chunk computed
        twice (an expired lease whose first worker came back) is never stored twice.
        """
        if not isinstance(result, ChunkResult):
            raise CatalogueError(
                f"run {run_id} chunk {index}: expected a ChunkResult, got {type(result).__name__}"
            )
        for item in result.results:
            if not isinstance(item, dict):
                raise CatalogueError(
                    f"run {run_id} chunk {index}: a result is a {type(item).__name__}, not a JSON object"
                )
            json_ok(f"run {run_id} chunk {index}", "a result", item)
        json_ok(f"run {run_id} chunk {index}", "the counts", dict(result.counts))
        prepared = self._prepare_rows(run_id, index, result.rows)
        n_rows = sum(len(rows) for _, rows in prepared) + len(result.results)
        with self._errors(f"recording run {run_id} chunk {index}"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=bool(result.records))
            marked = conn.execute(
                sa.update(CHUNKS)
                .where(CHUNKS.c.run_id == run_id, CHUNKS.c.index == index, CHUNKS.c.status != "done")
                .values(status="done", seconds=seconds, finished_at=utcnow(), rows=n_rows,
                        counts=dict(result.counts) or None, lease_expires=None)
            ).rowcount
            if marked != 1:
                exists = conn.execute(
                    sa.select(CHUNKS.c.id).where(CHUNKS.c.run_id == run_id, CHUNKS.c.index == index)
                ).first()
                if exists is None:
                    raise CatalogueError(f"run {run_id} has no chunk {index}")
                return False
            if result.results:
                for batch in batches(
                    [{"run_id": run_id, "chunk_index": index, "data": item} for item in result.results]
                ):
                    conn.execute(sa.insert(RESULTS), list(batch))
            for rt, rows in prepared:
                self._upsert_rows(conn, rt, rows)
            if result.records:
                upsert(conn, list(result.records), replace=True)
            conn.execute(
                sa.update(RUNS).where(RUNS.c.id == run_id).values(chunks_done=RUNS.c.chunks_done + 1)
            )
            if owner is not None:
                conn.execute(sa.update(WORKERS).where(WORKERS.c.owner == owner)
                             .values(chunks_done=WORKERS.c.chunks_done + 1, heartbeat=time.time()))
        return True

    # ------------------------------------------------------------------ ending

    def finish_run(
        self,
        run_id: int,
        status: str,
        *,
        summary: Mapping[str, Any] | None = None,
        error: str | None = None,
        seconds: float = 0.0,
    ) -> None:
        """Set a run's status (and summary / error). A run already done or cancelled keeps
        its status; ``interrupted`` is written only while no worker of the run is alive."""
        if status not in RUN_STATUSES:
            raise ParameterError(f"run status {status!r} is not one of: {', '.join(RUN_STATUSES)}")
        values: dict[str, Any] = {"status": status, "error": error}
        if status in ("done", "failed", "interrupted", "cancelled"):
            values["finished_at"] = utcnow()
        if summary is not None:
            json_ok(f"run {run_id}", "the summary", dict(summary))
            values["summary"] = dict(summary)
        with self._errors("finishing a run"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=False)
            row = conn.execute(sa.select(RUNS.c.status).where(RUNS.c.id == run_id)).first()
            if row is None:
                raise NotFoundError("run", str(run_id), [])
            if row[0] in ("done", "cancelled") and status != row[0]:
                return
            if status == "interrupted" and self._live_workers(conn, run_id, time.time(), lease_seconds()):
                return
            spans = conn.execute(
                sa.select(WORKERS.c.started, sa.func.coalesce(WORKERS.c.finished, WORKERS.c.heartbeat))
                .where(WORKERS.c.run_id == run_id)
            ).all()
            values["seconds"] = _union_seconds((float(a), float(b)) for a, b in spans) if spans else float(seconds)
            conn.execute(sa.update(RUNS).where(RUNS.c.id == run_id).values(**values))

    def reopen_run(self, run_id: int) -> None:
        """A failed run is tried again (its recorded chunks stay done)."""
        with self._errors("reopening a run"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=False)
            conn.execute(sa.update(RUNS).where(RUNS.c.id == run_id, RUNS.c.status == "failed")
                         .values(status="queued", error=None, finished_at=None))

    def cancel_run(self, run_id: int) -> RunInfo:
        """Cancel a run: its workers stop after their current chunk, nothing more is claimed,
        recorded chunks are kept; it cannot be resumed."""
        info = self.run(run_id)
        if info.status in ("done", "cancelled"):
            raise ParameterError(f"run {run_id} is {info.status}; only an unfinished run can be cancelled")
        with self._errors("cancelling a run"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=False)
            conn.execute(sa.update(RUNS).where(RUNS.c.id == run_id)
                         .values(status="cancelled", finished_at=utcnow(), error="cancelled"))
            conn.execute(sa.update(WORKERS).where(WORKERS.c.run_id == run_id).values(stop=True))
        return self.run(run_id)

    def delete_run(self, run_id: int) -> int:
        """Delete a run with its chunks, workers, results and the result-table rows it wrote
        (tilings it added to the catalogue stay). A run with live workers must be cancelled
        first. Returns the number of result rows deleted."""
        info = self.run(run_id)
        if info.workers_alive:
            raise ParameterError(
                f"run {run_id} has {info.workers_alive} live worker(s); cancel it first "
                f"(tilekit runs cancel {run_id})"
            )
        deleted = 0
        with self._errors("deleting a run"), self.engine.begin() as conn:
            self._lock_for_writing(conn, records=False)
            for rt in self.result_tables.values():
                if "run_id" in rt.table.c:
                    deleted += conn.execute(sa.delete(rt.table).where(rt.table.c.run_id == run_id)).rowcount
            deleted += conn.execute(sa.delete(RESULTS).where(RESULTS.c.run_id == run_id)).rowcount
            conn.execute(sa.delete(WORKERS).where(WORKERS.c.run_id == run_id))
            conn.execute(sa.delete(CHUNKS).where(CHUNKS.c.run_id == run_id))
            conn.execute(sa.delete(RUNS).where(RUNS.c.id == run_id))
        return deleted


def run_json(info: RunInfo) -> dict[str, Any]:
    """A run as plain JSON (``tilekit runs --format json``)."""
    item = {k: getattr(info, k) for k in ("id", "kind", "params", "status", "chunks_total", "chunks_done",
                                           "chunks_leased", "rows", "seconds", "worker_seconds",
                                           "workers_alive", "summary", "error")}
    for k in ("created_at", "started_at", "finished_at"):
        value = getattr(info, k)
        item[k] = value.isoformat() if value is not None else None
    return json.loads(json.dumps(item, default=str))
