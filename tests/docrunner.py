"""Runs the fenced examples of README.md and docs/ (tests/test_docs.py), so that docs can't drift.

Blocks, in document order, each document in a fresh working folder of its own:

- ```python: executed statement by statement in one namespace per document. An expression
  statement whose line ends in ``# -> VALUE`` (a Python literal) must evaluate to VALUE (floats to
  1e-9 relative).
- ```console: lines starting with ``$ `` are commands for bash; the lines after a command, up to
  the next command, are its expected output (stdout and stderr together), compared as doctest
  does with ELLIPSIS (``...`` matches anything) and whitespace normalised. A command whose
  expected output starts with ``error:`` must exit with status 2, every other one with 0.
- ```bash / ```sh: the block is one bash script (``set -euo pipefail``) that must exit 0.

A block is tagged by an HTML comment on the line right before its fence:

- ``<!-- run: slow -->``: needs minutes; runs in the slow tests only.
- ``<!-- run: server -->``: each command starts a server; it passes when the server answers
  HTTP on the address it printed, and is then stopped.
- ``<!-- run: benchmark -->``: a measurement that takes minutes to hours; runs when
  ``TILEKIT_DOC_BENCHMARKS=1``. Otherwise each ``python benchmarks/X.py ARGS`` in it is checked to
  name a script whose argument parser accepts ARGS (``--help`` must not be among them), every
  other ``benchmarks/X.py`` it names must exist, and the rest is checked without being run:
  a Python block must compile and its imports resolve, a shell block must parse (``bash -n``).
- ``<!-- run: postgres -->``: needs a PostgreSQL server: runs when ``TILEKIT_TEST_POSTGRES``
  names one (skipped otherwise), with ``DATABASE_URL`` set to a fresh database on it, dropped
  afterwards.
- ``<!-- setup-command -->`` / ``<!-- test-command -->``: README's two set-up commands, which
  .ci/run runs verbatim in order; not run again here.

Other languages (toml, ini, text) are data, shown not run.

The working folder holds symlinks to the checkout's top-level folders (tests, catalogue, docs,
benchmarks, and what ``pip install '.[extra]'`` reads: pyproject.toml, setup.py, README.md,
tilekit, migrations), so examples are written as a user types them in a checkout, and what they
write stays out of it. ``TILEKIT_CATALOGUE`` points at a catalogue file in the folder. ``pip install``
goes into a virtual environment of the document's own (``venv`` in the folder, first on ``PATH``
and, for the test environment's ``tilekit`` and the in-process Python blocks, on ``PYTHONPATH``),
never into the environment that runs the tests; that environment's packages are visible to it
(a ``.pth`` file), so pip finds tilekit installed, as it is for a user. (``PIP_TARGET`` is no
isolation for this: pip ignores installed packages under it, so a plugin's ``tilekit``
requirement would be fetched from an index, and it breaks pip's isolated builds of a source
folder with "Cannot set --home and --prefix together".)
"""

from __future__ import annotations

import ast
import contextlib
import doctest
import importlib
import io
import math
import os
import re
import shlex
import signal
import subprocess
import sys
import sysconfig
import time
import tokenize
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
RUN_LANGUAGES = {"python", "console", "bash", "sh"}
TAG = re.compile(r"^<!--\s*(run:\s*(?P<tag>[a-z]+)|(?P<ci>setup-command|test-command))\b.*-->\s*$")
FENCE = re.compile(r"^```(?P<lang>[A-Za-z0-9_+-]*)\s*$")
LINKED = ("tests", "catalogue", "docs", "benchmarks",
          # what `pip install '.[extra]'` reads, as in a checkout
          "pyproject.toml", "setup.py", "README.md", "tilekit", "migrations")
TIMEOUT = {"fast": 300, "slow": 3600, "server": 180, "benchmark": 6 * 3600, "postgres": 300}
POSTGRES_SERVER = "TILEKIT_TEST_POSTGRES"


@dataclass(frozen=True)
class Block:
    doc: Path
    line: int  # 1-based line of the opening fence
    lang: str
    text: str
    tag: str  # fast | slow | server | benchmark | ci

    @property
    def id(self) -> str:
        return f"{self.doc.relative_to(ROOT).as_posix()}:{self.line}"


def blocks(doc: Path) -> list[Block]:
    """The fenced blocks of one Markdown file, with their tags (every language)."""
    out: list[Block] = []
    lines = doc.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if m and m.group("lang"):
            start, lang = i, m.group("lang").lower()
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            tag = "fast"
            k = start - 1
            while k >= 0 and not lines[k].strip():
                k -= 1
            if k >= 0:
                t = TAG.match(lines[k].strip())
                if t:
                    tag = "ci" if t.group("ci") else t.group("tag")
            out.append(Block(doc, start + 1, lang, "\n".join(lines[start + 1:j]), tag))
            i = j + 1
        else:
            i += 1
    return out


def all_blocks() -> list[Block]:
    return [b for d in DOCS for b in blocks(d)]


class DocError(AssertionError):
    pass


@dataclass
class DocState:
    """One document's working folder, environment and Python namespace."""

    doc: Path
    folder: Path
    namespace: dict[str, Any] = field(default_factory=dict)
    done: set[int] = field(default_factory=set)
    extra_env: dict[str, str] = field(default_factory=dict)
    paths: list[str] = field(default_factory=list)  # what the document's blocks put on sys.path

    @classmethod
    def create(cls, doc: Path, folder: Path) -> DocState:
        folder.mkdir(parents=True, exist_ok=True)
        for name in LINKED:
            link = folder / name
            if not link.exists():
                link.symlink_to(ROOT / name)
        state = cls(doc, folder, {"__name__": "__doc_example__"})
        state._make_venv()
        return state

    @property
    def venv(self) -> Path:
        return self.folder / "venv"

    @property
    def site(self) -> Path:
        """The document's own site-packages, where its ``pip install`` puts packages."""
        return Path(sysconfig.get_path("purelib", vars={"base": str(self.venv), "platbase": str(self.venv)}))

    def _make_venv(self) -> None:
        """A venv without pip of its own (made in a fraction of a second): a ``.pth`` file adds
        the test environment's site-packages after its own, and ``bin/pip`` runs that pip with
        the venv's interpreter, so it installs into the venv."""
        if self.venv.exists():
            return
        subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(self.venv)], check=True)
        self.site.mkdir(parents=True, exist_ok=True)
        tested = sysconfig.get_path("purelib")
        (self.site / "_tilekit_docs_test_env.pth").write_text(f"import site; site.addsitedir({tested!r})\n")
        python = self.venv / "bin" / "python"
        for name in ("pip", "pip3"):
            script = self.venv / "bin" / name
            script.write_text(f"#!{python}\nimport sys\nfrom pip._internal.cli.main import main\n"
                              "sys.exit(main())\n")
            script.chmod(0o755)

    def env(self) -> dict[str, str]:
        env = dict(os.environ)
        env["TILEKIT_CATALOGUE"] = f"sqlite:///{self.folder / 'catalogue.sqlite'}"
        env.pop("PIP_TARGET", None)
        env["VIRTUAL_ENV"] = str(self.venv)
        env["PYTHONPATH"] = os.pathsep.join(p for p in (str(self.site), env.get("PYTHONPATH", "")) if p)
        env["PATH"] = os.pathsep.join([str(self.venv / "bin"), str(Path(sys.executable).parent), env.get("PATH", "")])
        env["COLUMNS"] = "200"
        env.pop("TILEKIT_PLUGINS", None)
        env.update(self.extra_env)
        return env


def run_block(block: Block, state: DocState) -> None:
    if block.lang == "python":
        _run_python(block, state)
    elif block.lang == "console":
        _run_console(block, state)
    elif block.lang in ("bash", "sh"):
        _run_bash(block, state)
    state.done.add(block.line)


@contextlib.contextmanager
def postgres_database(state: DocState, server: str):
    """A fresh database on the PostgreSQL server, as ``DATABASE_URL`` of the document's
    commands while the block runs; dropped afterwards."""
    import uuid

    import sqlalchemy as sa

    admin = sa.create_engine(server, isolation_level="AUTOCOMMIT")
    name = f"tilekit_docs_{uuid.uuid4().hex[:12]}"
    with admin.connect() as conn:
        conn.execute(sa.text(f'CREATE DATABASE "{name}"'))
    state.extra_env["DATABASE_URL"] = sa.engine.make_url(server).set(database=name).render_as_string(
        hide_password=False)
    try:
        yield
    finally:
        state.extra_env.pop("DATABASE_URL", None)
        with admin.connect() as conn:
            conn.execute(sa.text(f'DROP DATABASE IF EXISTS "{name}" WITH (FORCE)'))
        admin.dispose()


# -- python ---------------------------------------------------------------------------------


def _arrow_comments(code: str) -> dict[int, str]:
    out = {}
    for tok in tokenize.generate_tokens(io.StringIO(code).readline):
        if tok.type == tokenize.COMMENT and tok.string.startswith("# ->"):
            out[tok.start[0]] = tok.string[4:].strip()
    return out


def _same(value: Any, expected: Any) -> bool:
    if isinstance(expected, float) or isinstance(value, float):
        try:
            return math.isclose(float(value), float(expected), rel_tol=1e-9, abs_tol=1e-12)
        except (TypeError, ValueError):
            return False
    if isinstance(expected, tuple) and isinstance(value, tuple | list) and len(value) == len(expected):
        return all(_same(v, e) for v, e in zip(value, expected))
    if isinstance(expected, list) and isinstance(value, list | tuple) and len(value) == len(expected):
        return all(_same(v, e) for v, e in zip(value, expected))
    return bool(value == expected)


def _run_python(block: Block, state: DocState) -> None:
    code = block.text
    try:
        tree = ast.parse(code, filename=block.id)
    except SyntaxError as e:
        raise DocError(f"{block.id}: not Python: {e}") from None
    arrows = _arrow_comments(code)
    old_env = dict(os.environ)
    old_cwd = os.getcwd()
    os.environ.update(state.env())
    os.chdir(state.folder)
    saved_path = list(sys.path)
    sys.path[:0] = [str(state.site), *state.paths]
    try:
        for stmt in tree.body:
            where = f"{block.doc.relative_to(ROOT)}:{block.line + stmt.lineno}"
            try:
                if isinstance(stmt, ast.Expr):
                    value = eval(compile(ast.Expression(stmt.value), where, "eval"), state.namespace)
                    expected = arrows.get(stmt.end_lineno)
                    if expected is not None:
                        want = ast.literal_eval(expected)
                        if not _same(value, want):
                            raise DocError(f"{where}: the example says {expected}, the code gives {value!r}")
                else:
                    exec(compile(ast.Module([stmt], []), where, "exec"), state.namespace)
            except DocError:
                raise
            except Exception as e:  # noqa: BLE001 - reported with the line that raised
                raise DocError(f"{where}: {type(e).__name__}: {e}") from e
    finally:
        # a block may add to sys.path (docs/plugins.md puts a package's source on it): the
        # addition lasts for the document's later blocks, never for the tests that run after it
        added = [p for p in sys.path if p not in saved_path and p != str(state.site)]
        state.paths.extend(str((state.folder / p).resolve()) for p in added if p not in state.paths)
        sys.path[:] = saved_path
        # modules the block imported from the document's venv or from a path it added leave
        # with it, so a package a document installed is not importable after the document
        roots = (str(state.site), str(state.folder), *state.paths)
        for name, module in list(sys.modules.items()):
            if (getattr(module, "__file__", None) or "").startswith(roots):
                del sys.modules[name]
        importlib.invalidate_caches()
        os.chdir(old_cwd)
        os.environ.clear()
        os.environ.update(old_env)


# -- shell ----------------------------------------------------------------------------------


def console_commands(text: str) -> list[tuple[str, list[str]]]:
    """(command, expected output lines) pairs of a console block."""
    out: list[tuple[str, list[str]]] = []
    for line in text.splitlines():
        if line.startswith("$ "):
            out.append((line[2:], []))
        elif out:
            out[-1][1].append(line)
        elif line.strip():
            raise DocError(f"console block starts with output, not a '$ ' command: {line!r}")
    return out


def _shell(command: str, state: DocState, timeout: float) -> subprocess.CompletedProcess:
    try:
        return subprocess.run(
            ["bash", "-c", "set -euo pipefail\n" + command], cwd=state.folder, env=state.env(),
            capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL,
        )
    except subprocess.TimeoutExpired as e:
        raise DocError(f"timed out after {timeout:g} s: {command}") from e


def _run_console(block: Block, state: DocState) -> None:
    if block.tag == "server":
        for command, _ in console_commands(block.text):
            _run_server(command, state, block)
        return
    checker = doctest.OutputChecker()
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    for command, expected_lines in console_commands(block.text):
        done = _shell(command, state, TIMEOUT[block.tag])
        got = done.stdout + done.stderr
        expected = "\n".join(expected_lines).strip()
        want_error = expected.startswith("error:")
        if want_error and done.returncode != 2:
            raise DocError(f"{block.id}: `{command}` should fail with status 2, got {done.returncode}:\n{got}")
        if not want_error and done.returncode != 0:
            raise DocError(f"{block.id}: `{command}` exited {done.returncode}:\n{got[-3000:]}")
        if expected and not checker.check_output(expected + "\n", got, flags):
            raise DocError(f"{block.id}: `{command}` printed\n{got[-3000:]}\nwhere the docs say\n{expected}")


def _run_bash(block: Block, state: DocState) -> None:
    if block.tag == "server":
        for command in _script_commands(block.text):
            _run_server(command, state, block)
        return
    done = _shell(block.text, state, TIMEOUT[block.tag])
    if done.returncode != 0:
        raise DocError(f"{block.id}: exited {done.returncode}:\n{(done.stdout + done.stderr)[-3000:]}")


def _script_commands(text: str) -> list[str]:
    return [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]


SERVING = re.compile(r"https?://[0-9A-Za-z.\[\]:-]+")


def _run_server(command: str, state: DocState, block: Block) -> None:
    """Start a server command; pass when it answers HTTP at the address it printed."""
    proc = subprocess.Popen(["bash", "-c", "exec " + command] if not command.lstrip().startswith("pip ")
                            else ["bash", "-c", command],
                            cwd=state.folder, env=state.env(), stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, start_new_session=True)
    if command.lstrip().startswith("pip "):
        out, _ = proc.communicate(timeout=600)
        if proc.returncode != 0:
            raise DocError(f"{block.id}: `{command}` exited {proc.returncode}:\n{out[-2000:]}")
        return
    printed: list[str] = []
    deadline = time.monotonic() + TIMEOUT["server"]
    fd = proc.stdout.fileno()

    def read_some() -> str:
        # the pipe is non-blocking: a text wrapper's read() fails on a pipe with no data yet
        try:
            return os.read(fd, 1 << 16).decode(errors="replace")
        except BlockingIOError:
            return ""

    try:
        url = None
        os.set_blocking(fd, False)
        while time.monotonic() < deadline and url is None:
            if proc.poll() is not None:
                rest = read_some()
                raise DocError(f"{block.id}: `{command}` exited {proc.returncode}:\n{''.join(printed) + rest}")
            chunk = read_some()
            printed.append(chunk)
            m = SERVING.search("".join(printed))
            if m:
                url = m.group(0).replace("0.0.0.0", "127.0.0.1")
            time.sleep(0.1)
        if url is None:
            raise DocError(f"{block.id}: `{command}` printed no address within {TIMEOUT['server']} s")
        while time.monotonic() < deadline:
            try:
                with urllib.request.urlopen(url.rstrip("/") + "/", timeout=5) as r:
                    if r.status == 200:
                        return
            except OSError:
                time.sleep(0.2)
        raise DocError(f"{block.id}: `{command}` did not answer HTTP at {url}")
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


# -- benchmarks -----------------------------------------------------------------------------


def _pipeline_parts(command: str) -> list[list[str]]:
    """The simple commands of a shell line as word lists: split at ``&&``, ``||``, ``;`` and ``|``
    outside quotes (a quoted ``;``, as in a polyhex code, stays in its word), a `` #`` comment dropped."""
    lex = shlex.shlex(command.split(" #")[0], posix=True, punctuation_chars=";&|")
    lex.whitespace_split = True
    lex.commenters = ""
    parts: list[list[str]] = [[]]
    for tok in lex:
        if tok in (";", "&&", "||", "|"):
            parts.append([])
        else:
            parts[-1].append(tok)
    return [p for p in parts if p]


def benchmark_invocations(block: Block) -> list[list[str]]:
    """The ``python benchmarks/X.py ARGS`` commands of a block, as argument lists."""
    lines = console_commands(block.text) if block.lang == "console" else [(c, []) for c in _script_commands(block.text)]
    out = []
    for command, _ in lines:
        for words in _pipeline_parts(command):
            for i, w in enumerate(words):
                # a script run by Python; `pytest benchmarks/X.py` is a pytest-benchmark suite
                if (w.startswith("benchmarks/") and w.endswith(".py") and i > 0
                        and Path(words[i - 1]).name.startswith("python")):
                    out.append(words[i:])
    return out


def check_benchmark_block(block: Block) -> None:
    """A benchmark block checked without running it: the benchmark files it names exist; Python
    compiles and its imports resolve; shell commands parse."""
    for name in re.findall(r"\bbenchmarks/[\w./-]+\.py\b", block.text):
        if not (ROOT / name).is_file():
            raise DocError(f"{block.id}: no benchmark file {name}")
    if block.lang == "python":
        try:
            tree = ast.parse(block.text, filename=block.id)
        except SyntaxError as e:
            raise DocError(f"{block.id}: not Python: {e}") from None
        imports = [stmt for stmt in tree.body if isinstance(stmt, ast.Import | ast.ImportFrom)]
        try:
            exec(compile(ast.Module(imports, []), block.id, "exec"), {"__name__": "__doc_benchmark__"})
        except ImportError as e:
            raise DocError(f"{block.id}: {type(e).__name__}: {e}") from None
        return
    script = ("\n".join(c for c, _ in console_commands(block.text)) if block.lang == "console"
              else block.text)
    done = subprocess.run(["bash", "-n"], input=script, capture_output=True, text=True)
    if done.returncode != 0:
        raise DocError(f"{block.id}: not a shell script: {done.stderr.strip()}")


def check_benchmark_arguments(argv: list[str]) -> None:
    """The script exists and its parser (``build_parser()``) accepts the arguments."""
    script = ROOT / argv[0]
    if not script.is_file():
        raise DocError(f"no benchmark script {argv[0]}")
    if "--help" in argv or "-h" in argv:
        raise DocError(f"{argv}: --help is not a measurement")
    namespace: dict[str, Any] = {"__name__": "__doc_benchmark__", "__file__": str(script)}
    exec(compile(script.read_text(), str(script), "exec"), namespace)
    if "build_parser" not in namespace:
        raise DocError(f"{argv[0]} has no build_parser() to check its documented arguments against")
    parser = namespace["build_parser"]()
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        try:
            parser.parse_args(argv[1:])
        except SystemExit as e:
            raise DocError(f"{' '.join(argv)}: {err.getvalue().strip()}") from e
