"""Every fenced example in README.md and docs/ runs (issue 26): see tests/docrunner.py for the rules.

Blocks run in document order and share their document's folder, catalogue and namespace; a fast
block never depends on a slow one, so ``-m 'not slow'`` runs a consistent subset.
"""

from __future__ import annotations

import os
import subprocess
import sysconfig
from pathlib import Path

import pytest
from cliutil import postgres_server
from docrunner import (
    DOCS,
    POSTGRES_SERVER,
    ROOT,
    RUN_LANGUAGES,
    Block,
    DocState,
    all_blocks,
    benchmark_invocations,
    blocks,
    check_benchmark_arguments,
    check_benchmark_block,
    console_commands,
    postgres_database,
    run_block,
)

BLOCKS = [b for b in all_blocks() if b.lang in RUN_LANGUAGES]
_STATES: dict[str, DocState] = {}


def _marks(block: Block) -> list:
    # A document's blocks share a folder and a namespace: README's test command runs pytest-xdist
    # with ``--dist loadfile``, so this file's tests run on one worker, in document order.
    if block.tag in ("slow", "server"):
        return [pytest.mark.slow]
    if block.tag == "benchmark" and os.environ.get("TILEKIT_DOC_BENCHMARKS") == "1":
        return [pytest.mark.slow]
    return []


def _state(block: Block, factory: pytest.TempPathFactory) -> DocState:
    key = block.doc.relative_to(ROOT).as_posix()
    if key not in _STATES:
        _STATES[key] = DocState.create(block.doc, factory.mktemp(key.replace("/", "-").replace(".md", "")))
    return _STATES[key]


@pytest.mark.parametrize("block", [pytest.param(b, id=b.id, marks=_marks(b)) for b in BLOCKS])
def test_documented_example_runs(block: Block, tmp_path_factory, request) -> None:
    if block.tag == "ci":
        # README's set-up commands: .ci/run takes them from README by these markers and runs them.
        ci = (ROOT / ".ci" / "run").read_text()
        assert "setup-command" in ci and "test-command" in ci
        return
    if block.tag == "benchmark" and os.environ.get("TILEKIT_DOC_BENCHMARKS") != "1":
        for argv in benchmark_invocations(block):
            check_benchmark_arguments(argv)
        check_benchmark_block(block)  # minutes to hours: checked, not run
        return
    if block.tag == "postgres":
        # the same server as the catalogue's PostgreSQL tests (conftest): part of the suite, so
        # without one the block fails rather than passing unrun
        server = postgres_server(request.config)
        if not server:
            pytest.fail(f"{block.id} needs a PostgreSQL server: set {POSTGRES_SERVER} or --postgres "
                        "(README's test command starts one)")
        state = _state(block, tmp_path_factory)
        with postgres_database(state, server):
            run_block(block, state)
        return
    run_block(block, _state(block, tmp_path_factory))


def test_every_markdown_file_with_examples_is_read() -> None:
    assert ROOT / "README.md" in DOCS
    assert sum(1 for d in DOCS for b in blocks(d) if b.lang in RUN_LANGUAGES) == len(BLOCKS) > 40


def test_every_example_language_is_run_or_data() -> None:
    """A block in an unknown language would silently never run: name it or make it data."""
    data = {"toml", "ini", "text", "json", "csv", "svg", "xml"}
    unknown = {(b.id, b.lang) for b in all_blocks() if b.lang not in RUN_LANGUAGES | data}
    assert unknown == set()


def test_console_blocks_start_with_a_command() -> None:
    for b in BLOCKS:
        if b.lang == "console":
            assert console_commands(b.text), b.id


def test_readme_has_exactly_two_setup_commands_that_ci_runs_in_order() -> None:
    tags = [b.tag for b in blocks(ROOT / "README.md") if b.tag == "ci"]
    assert len(tags) == 2
    text = (ROOT / "README.md").read_text()
    assert text.index("<!-- setup-command -->") < text.index("<!-- test-command -->")
    ci = (ROOT / ".ci" / "run").read_text()
    assert ci.index("$setup") < ci.index("$tests")


def test_the_runner_fails_a_wrong_documented_value(tmp_path) -> None:
    bad = Block(ROOT / "README.md", 1, "python", "x = 2 + 2\nx  # -> 5", "fast")
    with pytest.raises(AssertionError, match="says 5"):
        run_block(bad, DocState.create(ROOT / "README.md", tmp_path))


def test_the_runner_fails_a_command_whose_output_drifted(tmp_path) -> None:
    state = DocState.create(ROOT / "README.md", tmp_path)
    run_block(Block(ROOT / "README.md", 1, "console", "$ echo 'made 12 tiles'\nmade ... tiles", "fast"), state)
    with pytest.raises(AssertionError, match="where the docs say"):
        run_block(Block(ROOT / "README.md", 2, "console", "$ echo 'made 12 tiles'\nmade 13 tiles", "fast"), state)
    with pytest.raises(AssertionError, match="status 2"):
        run_block(Block(ROOT / "README.md", 3, "console", "$ echo fine\nerror: ...", "fast"), state)


def test_benchmark_commands_split_at_shell_operators_outside_quotes() -> None:
    """A benchmark block's command line is split into simple commands at ``;``, ``&&`` and ``|``
    but not inside quotes: a polyhex code such as 'hex:0,0;3,0' is one word."""
    block = Block(ROOT / "x.md", 1, "console",
                  "$ tilekit search --codes 'hex:0,0;3,0' && python benchmarks/a.py --grid hex 'b;c' | head -1 # note\n", "benchmark")
    assert benchmark_invocations(block) == [["benchmarks/a.py", "--grid", "hex", "b;c"]]


def test_the_runner_runs_bash_blocks_with_errexit(tmp_path) -> None:
    state = DocState.create(ROOT / "README.md", tmp_path)
    with pytest.raises(AssertionError, match="exited 1"):
        run_block(Block(ROOT / "README.md", 1, "bash", "false\necho after", "fast"), state)
    # a shell word like heesch>=2 unquoted makes a file named '=2': the example must quote it
    run_block(Block(ROOT / "README.md", 2, "bash", "echo a>=2", "fast"), state)
    assert (tmp_path / "=2").exists()


def test_pip_in_examples_installs_into_the_documents_own_venv(tmp_path) -> None:
    """A documented ``pip install`` of a package that needs tilekit finds tilekit installed and
    lands in the document's venv, seen by ``tilekit`` and the Python blocks, never in the
    environment that runs the tests."""
    state = DocState.create(ROOT / "README.md", tmp_path)
    package = tmp_path / "docs-pip-probe"
    (package / "docs_pip_probe").mkdir(parents=True)
    (package / "docs_pip_probe" / "__init__.py").write_text("ANSWER = 42\n")
    (package / "pyproject.toml").write_text(
        '[build-system]\nrequires = ["setuptools>=61"]\nbuild-backend = "setuptools.build_meta"\n'
        '[project]\nname = "docs-pip-probe"\nversion = "1.0"\ndependencies = ["tilekit"]\n'
        '[tool.setuptools]\npackages = ["docs_pip_probe"]\n')
    # --no-build-isolation: setuptools comes from the test environment, nothing is downloaded
    run_block(Block(ROOT / "README.md", 1, "bash",
                    "pip install --no-build-isolation ./docs-pip-probe\n"
                    "python -c 'import docs_pip_probe, tilekit'", "fast"), state)
    assert (state.site / "docs_pip_probe" / "__init__.py").is_file()
    assert not (Path(sysconfig.get_path("purelib")) / "docs_pip_probe").exists()
    run_block(Block(ROOT / "README.md", 2, "python",
                    "import docs_pip_probe\ndocs_pip_probe.ANSWER  # -> 42", "fast"), state)
    done = subprocess.run(["tilekit", "--help"], env=state.env(), capture_output=True, text=True)
    assert done.returncode == 0
    assert "PIP_TARGET" not in state.env()


def test_a_benchmark_block_is_checked_not_run(tmp_path) -> None:
    ok = Block(ROOT / "docs/benchmarks.md", 1, "python",
               "import time\nfrom tilekit.plugins.wang import solve\ntime.sleep(3600)", "benchmark")
    check_benchmark_block(ok)  # returns at once: the sleep is not run
    bad = Block(ROOT / "docs/benchmarks.md", 2, "python", "from tilekit.plugins.wang import no_such_name", "benchmark")
    with pytest.raises(AssertionError, match="no_such_name"):
        check_benchmark_block(bad)
    with pytest.raises(AssertionError, match="no benchmark file"):
        check_benchmark_block(Block(ROOT / "docs/benchmarks.md", 3, "console",
                                    "$ pytest benchmarks/bench_nothing.py --benchmark-enable", "benchmark"))
    with pytest.raises(AssertionError, match="not a shell script"):
        check_benchmark_block(Block(ROOT / "docs/benchmarks.md", 4, "bash", "for x in; do", "benchmark"))
    # only scripts run by Python are checked against their parser
    assert benchmark_invocations(Block(ROOT / "docs/benchmarks.md", 5, "console",
                                       "$ pytest benchmarks/bench_core.py --benchmark-enable\n"
                                       "$ .venv/bin/python benchmarks/bench_wang.py --fills-only", "benchmark")) == [
        ["benchmarks/bench_wang.py", "--fills-only"]]


def test_a_server_block_passes_when_the_server_answers_and_fails_when_it_exits(tmp_path) -> None:
    state = DocState.create(ROOT / "README.md", tmp_path)
    # prints "Serving HTTP on 127.0.0.1 port N (http://127.0.0.1:N/)", then answers 200 at /
    run_block(Block(ROOT / "README.md", 1, "bash", "python -u -m http.server 0 --bind 127.0.0.1", "server"), state)
    with pytest.raises(AssertionError, match="exited 3"):
        run_block(Block(ROOT / "README.md", 2, "bash", "sh -c 'echo starting; exit 3'", "server"), state)
