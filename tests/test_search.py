"""Search runs: parameter validation, chunked execution, interruption and resume, executors.

The test search enumerates the rectangles a x b (a <= b, integer sides) of area n for
n = 1..max_area: each tiles the plane as a lattice tiling (a PeriodicTiling of one tile),
and there are ceil(d(n)/2) of them for area n, d(n) the number of divisors (OEIS A038548).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent / "data"))

import testkit  # noqa: E402

import tilekit  # noqa: E402
from tilekit.catalogue import open_catalogue  # noqa: E402
from tilekit.errors import NotFoundError, ParameterError, SearchError  # noqa: E402
from tilekit.plugins import CatalogueRecord, ChunkResult, Search, SearchParam  # noqa: E402
from tilekit.search import run_search, validate_params  # noqa: E402

#: chunk areas whose run_chunk raises KeyboardInterrupt / ValueError (set by tests)
INTERRUPT_AT: set[int] = set()
FAIL_AT: set[int] = set()
#: areas whose chunk completed, in completion order (local executor only)
COMPLETED: list[int] = []

#: A038548: number of divisors of n that are <= sqrt(n), n = 1..24
A038548 = [1, 1, 1, 2, 1, 2, 1, 2, 2, 2, 1, 3, 1, 2, 2, 3, 1, 3, 1, 3, 2, 2, 1, 4]


def rect_chunks(params):
    return [{"area": n} for n in range(1, params["max_area"] + 1)]


def rect_run_chunk(params, chunk):
    n = chunk["area"]
    if n in INTERRUPT_AT:
        raise KeyboardInterrupt
    if n in FAIL_AT:
        raise ValueError(f"cannot do area {n}")
    shapes = [(a, n // a) for a in range(1, math.isqrt(n) + 1) if n % a == 0]
    results = [{"area": n, "width": a, "height": b} for a, b in shapes]
    records = []
    if params["store"]:
        for a, b in shapes:
            spec = {
                "kind": "periodic",
                "prototiles": [{"outline": [[0, 0], [a, 0], [a, b], [0, b]]}],
                "unit": [{"prototile": 0, "transform": [[1, 0, 0], [0, 1, 0]], "aspect": 0}],
                "v1": [a, 0], "v2": [0, b], "name": f"rect-{a}x{b}", "family": testkit.FAMILY,
            }
            records.append(CatalogueRecord(testkit.FAMILY, f"rect-{a}x{b}", spec, title=f"{a} x {b} rectangles",
                                           properties={"periodic": True, "k_hedral": 1, "area": n}))
    COMPLETED.append(n)
    return ChunkResult(results=results, records=records)


def rect_summarize(params, results):
    return {"rectangles": len(results), "squares": sum(r["width"] == r["height"] for r in results)}


RECTS = Search(
    name="rects",
    summary="rectangles with integer sides and area up to max_area",
    family=testkit.FAMILY,
    params=[
        SearchParam("max_area", int, None, "largest area", required=True),
        SearchParam("store", bool, True, "store each rectangle tiling in the catalogue"),
        SearchParam("label", str, "", "free text"),
        SearchParam("scale", float, 1.0, "unused scale"),
    ],
    chunks=rect_chunks,
    run_chunk=rect_run_chunk,
    summarize=rect_summarize,
)


class RectPlugin:
    @tilekit.hookimpl
    def tilekit_searches(self):
        return [RECTS]


@pytest.fixture(autouse=True)
def _reset_flags():
    INTERRUPT_AT.clear()
    FAIL_AT.clear()
    COMPLETED.clear()
    yield
    INTERRUPT_AT.clear()
    FAIL_AT.clear()


@pytest.fixture
def pm(monkeypatch):
    return testkit.isolated_pm(monkeypatch, testkit.GridPlugin(), RectPlugin())


@pytest.fixture
def cat(db_url, pm):
    catalogue = open_catalogue(db_url, pm=pm)
    yield catalogue
    catalogue.close()


def expected_results(max_area: int) -> list[dict]:
    return [{"area": n, "width": a, "height": n // a}
            for n in range(1, max_area + 1) for a in range(1, n + 1) if n % a == 0 and a * a <= n]


# --------------------------------------------------------------------------- parameters


def test_validate_params_fills_defaults_and_coerces():
    assert validate_params(RECTS, {"max_area": "12"}) == {"max_area": 12, "store": True, "label": "", "scale": 1.0}
    assert validate_params(RECTS, {"max_area": 3.0, "store": "false", "scale": 2})["store"] is False


@pytest.mark.parametrize(
    "params, fragment",
    [
        ({}, "needs the parameter 'max_area'"),
        ({"max_area": 3, "max_aera": 4}, "unknown parameter 'max_aera'; did you mean 'max_area'"),
        ({"max_area": "three"}, "'max_area' takes an integer"),
        ({"max_area": 2.5}, "'max_area' takes an integer"),
        ({"max_area": True}, "'max_area' takes an integer"),
        ({"max_area": 3, "store": "maybe"}, "'store' takes true or false"),
        ({"max_area": 3, "scale": "wide"}, "'scale' takes a number"),
        ({"max_area": 3, "label": 7}, "'label' takes text"),
    ],
)
def test_bad_parameters_name_the_culprit(cat, pm, params, fragment):
    with pytest.raises(ParameterError) as info:
        run_search(cat, "rects", params, pm=pm)
    assert fragment in str(info.value) and "\n" not in str(info.value)
    assert cat.runs() == []  # nothing was created


def test_unknown_search_and_executor(cat, pm):
    with pytest.raises(NotFoundError, match="did you mean 'rects'"):
        run_search(cat, "rect", {"max_area": 2}, pm=pm)
    with pytest.raises(ParameterError, match="local, process, dask"):
        run_search(cat, "rects", {"max_area": 2}, executor="threads", pm=pm)
    with pytest.raises(ParameterError, match="workers"):
        run_search(cat, "rects", {"max_area": 2}, executor="process", workers=0, pm=pm)


# --------------------------------------------------------------------------- running


def test_local_run_records_every_chunk(cat, pm):
    calls = []
    run_id = run_search(cat, "rects", {"max_area": 24}, pm=pm, progress=lambda d, t: calls.append((d, t)))
    info = cat.run(run_id)
    assert (info.status, info.chunks_done, info.chunks_total) == ("done", 24, 24)
    assert info.started_at is not None and info.finished_at is not None and info.seconds > 0
    results = cat.results(run_id)
    assert results == expected_results(24)
    per_area = [sum(r["area"] == n for r in results) for n in range(1, 25)]
    assert per_area == A038548
    # squares of area <= 24: 1, 4, 9, 16
    assert info.summary == {"rectangles": sum(A038548), "squares": 4}
    assert calls == [(i, 24) for i in range(25)]
    # the records are in the catalogue and are real tilings
    assert cat.count_matching(where=["area>=1"]) == sum(A038548)
    tiling = cat.tiling("rect-2x3")
    assert tiling.patch((0, 0, 7, 7)).validate((0, 0, 7, 7))


def test_interrupted_run_resumes_without_redoing_or_duplicating(cat, pm):
    INTERRUPT_AT.add(8)
    announced: list[int] = []
    with pytest.raises(KeyboardInterrupt):
        run_search(cat, "rects", {"max_area": 12}, pm=pm, on_run=announced.append)
    (info,) = cat.runs()
    assert announced == [info.id]
    assert (info.status, info.chunks_done) == ("interrupted", 7)
    assert COMPLETED == [1, 2, 3, 4, 5, 6, 7]
    assert len(cat.results(info.id)) == sum(A038548[:7])
    assert [i for i, _ in cat.pending_chunks(info.id)] == list(range(7, 12))

    INTERRUPT_AT.clear()
    COMPLETED.clear()
    progress = []
    assert run_search(cat, None, resume_run=info.id, pm=pm, progress=lambda d, t: progress.append(d)) == info.id
    assert COMPLETED == [8, 9, 10, 11, 12]  # only the chunks not yet done
    assert progress == [7, 8, 9, 10, 11, 12]
    done = cat.run(info.id)
    assert (done.status, done.chunks_done) == ("done", 12)
    assert cat.results(info.id) == expected_results(12)  # nothing lost, nothing twice
    assert done.summary == {"rectangles": sum(A038548[:12]), "squares": 3}
    assert len(cat.runs()) == 1

    COMPLETED.clear()
    assert run_search(cat, "rects", resume_run=info.id, pm=pm) == info.id  # done: nothing to do
    assert COMPLETED == []


def test_failed_chunk_marks_run_failed_and_can_be_resumed(cat, pm):
    FAIL_AT.add(3)
    with pytest.raises(SearchError) as info:
        run_search(cat, "rects", {"max_area": 5}, pm=pm)
    message = str(info.value)
    assert "failed in chunk 2" in message and "cannot do area 3" in message and "--resume 1" in message
    run = cat.run(1)
    assert run.status == "failed" and "ValueError: cannot do area 3" in run.error
    assert run.chunks_done == 2
    FAIL_AT.clear()
    run_search(cat, "rects", resume_run=1, pm=pm)
    assert cat.run(1).status == "done" and cat.run(1).error is None
    assert cat.results(1) == expected_results(5)


def test_resume_checks_kind_and_parameters(cat, pm):
    INTERRUPT_AT.add(2)
    with pytest.raises(KeyboardInterrupt):
        run_search(cat, "rects", {"max_area": 4}, pm=pm)
    INTERRUPT_AT.clear()
    with pytest.raises(SearchError, match="resume it without new parameters"):
        run_search(cat, "rects", {"max_area": 9}, resume_run=1, pm=pm)
    with pytest.raises(NotFoundError):
        run_search(cat, "rects", resume_run=42, pm=pm)
    # same parameters are fine
    run_search(cat, "rects", {"max_area": 4}, resume_run=1, pm=pm)
    assert cat.run(1).status == "done"


def test_process_pool_gives_the_same_results(cat, pm):
    run_id = run_search(cat, "rects", {"max_area": 16, "store": False}, executor="process", workers=2, pm=pm)
    info = cat.run(run_id)
    assert (info.status, info.chunks_done) == ("done", 16)
    assert sorted(cat.results(run_id), key=lambda r: (r["area"], r["width"])) == expected_results(16)
    assert cat.count() == 11  # store=False: no records


def test_dask_executor_without_dask_says_what_to_install(cat, pm, monkeypatch):
    monkeypatch.setitem(sys.modules, "dask", None)
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    with pytest.raises(SearchError) as info:
        run_search(cat, "rects", {"max_area": 3}, executor="dask", pm=pm)
    assert "pip install 'tilekit[dask]'" in str(info.value)
    assert cat.runs() == []


def test_chunk_returning_the_wrong_type_fails_the_run(cat, pm, monkeypatch):
    bad = Search("bad", "returns a dict", testkit.FAMILY, [], lambda p: [{}], lambda p, c: {"oops": 1})

    class BadPlugin:
        @tilekit.hookimpl
        def tilekit_searches(self):
            return [bad]

    pm.register(BadPlugin())
    with pytest.raises(SearchError, match="not a ChunkResult"):
        run_search(cat, "bad", {}, pm=pm)
    assert cat.runs(kind="bad")[0].status == "failed"


def test_failing_summary_fails_the_run_but_keeps_its_results(cat, pm):
    def broken_summary(params, results):
        raise ZeroDivisionError("no squares")

    flaky = Search("flaky", "bad summary", testkit.FAMILY, RECTS.params, rect_chunks, rect_run_chunk,
                   summarize=broken_summary)

    class FlakyPlugin:
        @tilekit.hookimpl
        def tilekit_searches(self):
            return [flaky]

    pm.register(FlakyPlugin())
    with pytest.raises(SearchError, match="could not summarise its results: no squares"):
        run_search(cat, "flaky", {"max_area": 4, "store": False}, pm=pm)
    (info,) = cat.runs(kind="flaky")
    assert info.status == "failed" and "no squares" in info.error
    assert info.chunks_done == 4 and cat.results(info.id) == expected_results(4)
