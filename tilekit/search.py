"""Search runs: validate parameters, split into chunks, run them, record each as it finishes.

A run's chunks are stored when it is created; each finished chunk's results, its catalogue
records and its "done" mark are written in one transaction
(:meth:`tilekit.catalogue.Catalogue.record_chunk`), so a run that is interrupted and resumed
loses nothing and repeats nothing. Executors: ``local`` (in this process), ``process``
(a ``concurrent.futures`` process pool) and ``dask`` (a ``dask.distributed`` cluster).
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterable, Mapping
from typing import Any

import pluggy

from tilekit.catalogue import Catalogue, auto_type
from tilekit.errors import NotFoundError, ParameterError, SearchError, TilekitError
from tilekit.plugins import ChunkResult, Search, get_plugin_manager, get_search

__all__ = ["EXECUTORS", "run_search", "validate_params"]

EXECUTORS: tuple[str, ...] = ("local", "process", "dask")

#: ``progress(done, total)`` is called once at the start and after every recorded chunk.
Progress = Callable[[int, int], None]


def _coerce(search: Search, name: str, typ: type, value: Any) -> Any:
    if value is None:
        return None
    where = f"search {search.name!r}: parameter {name!r}"
    if typ is bool:
        if isinstance(value, bool):
            return value
        if isinstance(value, str) and isinstance(auto_type(value), bool):
            return auto_type(value)
        raise ParameterError(f"{where} takes true or false, got {value!r}")
    if typ is int:
        if isinstance(value, bool):
            raise ParameterError(f"{where} takes an integer, got {value!r}")
        if isinstance(value, int):
            return value
        if isinstance(value, float) and value.is_integer():
            return int(value)
        if isinstance(value, str) and isinstance(auto_type(value), int) and not isinstance(auto_type(value), bool):
            return int(value)
        raise ParameterError(f"{where} takes an integer, got {value!r}")
    if typ is float:
        if isinstance(value, bool):
            raise ParameterError(f"{where} takes a number, got {value!r}")
        if isinstance(value, int | float):
            return float(value)
        try:
            return float(value)
        except (TypeError, ValueError):
            raise ParameterError(f"{where} takes a number, got {value!r}") from None
    if typ is str:
        if isinstance(value, str):
            return value
        raise ParameterError(f"{where} takes text, got {value!r}")
    return typ(value)


def validate_params(search: Search, params: Mapping[str, Any] | None) -> dict[str, Any]:
    """Check ``params`` against the search's SearchParams: names, required ones, types.

    Returns the complete parameter dict (defaults filled in). Raises ParameterError naming
    the offending parameter and the valid ones.
    """
    params = dict(params or {})
    declared = {p.name: p for p in search.params}
    for key in params:
        if key not in declared:
            close = NotFoundError("parameter", key, declared)
            raise ParameterError(f"search {search.name!r}: {close}") from None
    out: dict[str, Any] = {}
    for p in search.params:
        value = params.get(p.name, p.default)
        if value is None and p.required:
            raise ParameterError(
                f"search {search.name!r} needs the parameter {p.name!r}"
                + (f" ({p.help})" if p.help else "")
            )
        out[p.name] = _coerce(search, p.name, p.type, value)
    return out


def _timed(run_chunk: Callable[[Mapping[str, Any], Mapping[str, Any]], ChunkResult],
           params: Mapping[str, Any], chunk: Mapping[str, Any]) -> tuple[ChunkResult, float]:
    """Run one chunk and time it (module level, so process pools and dask can pickle it)."""
    start = time.perf_counter()
    result = run_chunk(params, chunk)
    return result, time.perf_counter() - start


def _check_result(search: Search, index: int, result: Any) -> ChunkResult:
    if not isinstance(result, ChunkResult):
        raise SearchError(
            f"search {search.name!r}: run_chunk returned {type(result).__name__} for chunk {index}, "
            "not a ChunkResult"
        )
    return result


class _ChunkFailed(Exception):
    """A chunk's run_chunk raised ``error`` (an ordinary exception, not an interrupt)."""

    def __init__(self, index: int, error: Exception) -> None:
        super().__init__(index, error)
        self.index = index
        self.error = error


def _run_local(search, params, pending, record) -> None:
    for index, chunk in pending:
        try:
            result, seconds = _timed(search.run_chunk, params, chunk)
        except Exception as exc:
            raise _ChunkFailed(index, exc) from exc
        record(index, result, seconds)


def _record_future(future: Any, index: int, record: Any) -> None:
    """Record a finished pool or dask future's chunk; a chunk that raised fails the run."""
    try:
        result, seconds = future.result()
    except Exception as exc:
        raise _ChunkFailed(index, exc) from exc
    record(index, result, seconds)


def _run_process(search, params, pending, record, workers: int | None) -> None:
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    pool = ProcessPoolExecutor(max_workers=workers)
    try:
        futures = {pool.submit(_timed, search.run_chunk, params, chunk): index for index, chunk in pending}
        remaining = set(futures)
        while remaining:
            done, remaining = wait(remaining, return_when=FIRST_COMPLETED)
            for future in sorted(done, key=futures.__getitem__):
                _record_future(future, futures[future], record)
    except BaseException:
        pool.shutdown(wait=True, cancel_futures=True)
        raise
    pool.shutdown(wait=True)


def _dask_client(workers: int | None, scheduler: str | None) -> Any:
    try:
        from dask.distributed import Client
    except ImportError:
        raise SearchError(
            "the dask executor needs dask.distributed; install it with: pip install 'tilekit[dask]'"
        ) from None
    address = scheduler or os.environ.get("TILEKIT_DASK_SCHEDULER")
    if address:
        return Client(address)
    return Client(n_workers=workers or 1, threads_per_worker=1, processes=True, dashboard_address=None)


def _run_dask(search, params, pending, record, workers: int | None, scheduler: str | None) -> None:
    from dask.distributed import as_completed

    client = _dask_client(workers, scheduler)
    futures: dict[Any, int] = {}
    try:
        for index, chunk in pending:
            future = client.submit(_timed, search.run_chunk, params, chunk, pure=False)
            futures[future] = index
        for future in as_completed(list(futures)):
            _record_future(future, futures[future], record)
    except BaseException:
        client.cancel(list(futures))
        raise
    finally:
        client.close()


def run_search(
    catalogue: Catalogue,
    name: str | None,
    params: Mapping[str, Any] | None = None,
    executor: str = "local",
    workers: int | None = None,
    resume_run: int | None = None,
    progress: Progress | None = None,
    *,
    pm: pluggy.PluginManager | None = None,
    scheduler: str | None = None,
    on_run: Callable[[int], None] | None = None,
) -> int:
    """Run (or resume) the search ``name`` and return the run id.

    A new run validates ``params`` against the search's SearchParams, stores the chunks and
    runs them; ``resume_run`` continues an earlier run of the same search with its stored
    parameters, running only the chunks not yet done. Chunks run with ``executor``:
    ``local`` (in-process), ``process`` (a process pool of ``workers``) or ``dask``
    (``scheduler`` address, ``$TILEKIT_DASK_SCHEDULER``, or a local cluster of ``workers``).
    The run ends ``done``; ``failed`` (SearchError) if a chunk raised; ``interrupted`` if
    interrupted (e.g. Ctrl-C; the interrupt propagates). ``on_run(run_id)`` is called once
    the run exists (so a caller knows which run to resume); ``progress(done, total)`` at the
    start and after every recorded chunk.
    """
    pm = pm or catalogue._pm or get_plugin_manager()
    if executor not in EXECUTORS:
        raise ParameterError(f"executor {executor!r} is not one of: {', '.join(EXECUTORS)}")
    if workers is not None and workers < 1:
        raise ParameterError(f"workers must be at least 1, got {workers}")
    if executor == "dask":  # fail before creating or touching a run if dask is missing
        try:
            import dask.distributed  # noqa: F401
        except ImportError:
            _dask_client(workers, scheduler)

    if resume_run is not None:
        info = catalogue.run(resume_run)
        if name is not None and name != info.kind:
            raise SearchError(f"run {info.id} is a {info.kind!r} search, not {name!r}")
        search = get_search(info.kind, pm)
        stored = validate_params(search, info.params)
        if params is not None and validate_params(search, params) != stored:
            raise SearchError(
                f"run {info.id} was started with {stored}; resume it without new parameters"
            )
        params = stored
        run_id = info.id
        if on_run:
            on_run(run_id)
        if info.status == "done":
            if progress:
                progress(info.chunks_done, info.chunks_total)
            return run_id
    else:
        if name is None:
            raise ParameterError("run_search needs a search name or a run to resume")
        search = get_search(name, pm)
        params = validate_params(search, params)
        try:
            chunks = list(search.chunks(params))
        except TilekitError:
            raise
        except Exception as exc:
            raise SearchError(f"search {search.name!r} could not split its work: {exc}") from exc
        run_id = catalogue.create_run(search.name, params, chunks)
        if on_run:
            on_run(run_id)

    info = catalogue.run(run_id)
    total = info.chunks_total
    done = info.chunks_done
    pending = catalogue.pending_chunks(run_id)
    catalogue.start_run(run_id)
    if progress:
        progress(done, total)
    started = time.perf_counter()

    def record(index: int, result: Any, seconds: float) -> None:
        nonlocal done
        result = _check_result(search, index, result)
        if catalogue.record_chunk(run_id, index, result, seconds):
            done += 1
        if progress:
            progress(done, total)

    try:
        if executor == "local":
            _run_local(search, params, pending, record)
        elif executor == "process":
            _run_process(search, params, pending, record, workers)
        else:
            _run_dask(search, params, pending, record, workers, scheduler)
    except (KeyboardInterrupt, SystemExit):
        catalogue.finish_run(run_id, "interrupted", error="interrupted", seconds=time.perf_counter() - started)
        raise
    except Exception as exc:
        where, cause = "", exc
        if isinstance(exc, _ChunkFailed):
            where, cause = f" in chunk {exc.index}", exc.error
        message = f"{type(cause).__name__}: {' '.join(str(cause).split())}"
        catalogue.finish_run(run_id, "failed", error=message + where, seconds=time.perf_counter() - started)
        raise SearchError(
            f"run {run_id} ({search.name}) failed{where}: {message}; "
            f"fix the cause and resume it (tilekit search {search.name} --resume {run_id})"
        ) from cause

    try:
        summary = _summarize(search, params, catalogue.results(run_id))
    except TilekitError as exc:
        catalogue.finish_run(run_id, "failed", error=str(exc), seconds=time.perf_counter() - started)
        raise
    catalogue.finish_run(run_id, "done", summary=summary, seconds=time.perf_counter() - started)
    return run_id


def _summarize(search: Search, params: Mapping[str, Any], results: list[dict[str, Any]]) -> dict[str, Any]:
    if search.summarize is None:
        return {"results": len(results)}
    try:
        summary = search.summarize(params, results)
    except TilekitError:
        raise
    except Exception as exc:
        raise SearchError(f"search {search.name!r} could not summarise its results: {exc}") from exc
    return dict(summary or {})


def describe_params(search: Search) -> Iterable[str]:
    """One line per parameter: ``name (type, default): help``."""
    for p in search.params:
        default = "required" if p.required else f"default {p.default!r}"
        yield f"{p.name} ({p.type.__name__}, {default}): {p.help}"
