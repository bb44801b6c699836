"""A search for run-layer tests, and a ``tilekit`` command line that has it.

``ticks``: chunk i (0 <= i < chunks) sleeps ``sleep`` seconds, appends "i pid" to the file
named by ``$TICKS_LOG`` (so a test counts every computation, across processes), and yields
the JSON result {"i": i, "square": i*i} and the count {"ticks": 1}.

Run as ``python tests/data/ticks.py [tilekit options...]``: the ``tilekit`` CLI with this
search registered (process pools inherit it by fork).
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

import tilekit  # noqa: E402
from tilekit.plugins import ChunkResult, Search, SearchParam  # noqa: E402


def tick_chunks(params):
    return ({"i": i} for i in range(params["chunks"]))


def tick_run_chunk(params, chunk):
    i = int(chunk["i"])
    if params["fail_at"] == i:
        raise ValueError(f"tick {i} fails")
    time.sleep(params["sleep"])
    log = os.environ.get("TICKS_LOG")
    if log:
        with open(log, "a", encoding="utf-8") as fh:
            fh.write(f"{i} {os.getpid()}\n")
    return ChunkResult(results=[{"i": i, "square": i * i}], counts={"ticks": 1})


TICKS = Search(
    name="ticks",
    summary="test chunks that sleep and log each computation",
    family="archimedean",
    params=[
        SearchParam("chunks", int, 20, "number of chunks", min=1, max=100_000),
        SearchParam("sleep", float, 0.05, "seconds per chunk", min=0.0, max=60.0),
        SearchParam("fail_at", int, -1, "the chunk that raises (-1: none)", min=-1),
    ],
    chunks=tick_chunks,
    run_chunk=tick_run_chunk,
)


class TicksPlugin:
    @tilekit.hookimpl
    def tilekit_searches(self):
        return [TICKS]


def main() -> None:
    import tilekit.plugins as plugins
    from tilekit.cli import main as cli_main

    plugins._pm = plugins.make_plugin_manager([TicksPlugin()])
    cli_main(sys.argv[1:])


if __name__ == "__main__":
    main()
