"""No input can crash, hang or exhaust the machine (issue 27): every case the issue lists.

Each command runs in its own process under an address-space cap (RLIMIT_AS) and a timeout,
as a new user's shell would run it, so a runaway case fails this test instead of taking the
machine: it must exit 2 with one line ``error: ...`` naming the problem, print no traceback
and finish within a few seconds. Cases: files that are not regular files (FIFOs, /dev/zero
and links to it) and files too large or nested too deep; numbers with two signs or foreign
digits; specs of the wrong types; PNG headers of huge images; solvers past their budget;
worker counts past the machine; scheduler and host addresses that cannot work; and SQLite
files that are not tilekit's, which must be left byte for byte as they were.
"""

from __future__ import annotations

import hashlib
import json
import os
import random
import sqlite3
import struct
import subprocess
import sys
import time
import zlib
from pathlib import Path

import pytest
from click.testing import CliRunner

from tilekit.cli import cli
from tilekit.errors import TilekitError

#: Address-space cap of every command (Python with NumPy, shapely, SQLAlchemy and numba fit in
#: well under 1 GB of it; a case that allocates for its input instead would fail).
MEMORY_CAP = 2 * 1024**3
#: A command that takes longer has not refused its input up front. Start-up alone is about a
#: second on the shared 2-core machine; the bound leaves room for its load.
SECONDS = 12.0
#: A command still running then hangs: it is killed and the case fails.
HANG = 60.0

_RUNNER = """
import resource, sys
resource.setrlimit(resource.RLIMIT_AS, ({cap}, {cap}))
from tilekit.cli import main
main(sys.argv[1:])
"""


def run_capped(catalogue: str, *args: str, cwd: Path | None = None) -> tuple[int | None, str, float]:
    """(exit code or None when it hung, stderr, seconds) of ``tilekit ARGS`` under the cap."""
    env = dict(os.environ, TILEKIT_CATALOGUE=catalogue, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    env.pop("TILEKIT_DASK_SCHEDULER", None)
    start = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-c", _RUNNER.format(cap=MEMORY_CAP), *args], env=env, cwd=cwd,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        _, err = proc.communicate(timeout=HANG)
        code = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, 9)
        _, err = proc.communicate()
        code = None
    return code, err, time.perf_counter() - start


def assert_refused(result: tuple[int | None, str, float], fragment: str = "") -> str:
    code, err, seconds = result
    assert code is not None, f"hung past {HANG} s"
    lines = err.strip().splitlines()
    assert "Traceback" not in err, err[-2000:]
    assert code == 2, (code, err[-2000:])
    assert len(lines) == 1 and lines[0].startswith("error: "), err[-2000:]
    assert fragment in lines[0], lines[0]
    assert seconds < SECONDS, f"took {seconds:.1f} s: {lines[0]}"
    return lines[0]


# --------------------------------------------------------------------------- hostile files


def _png(path: Path, width: int, height: int, data: bytes) -> Path:
    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", data) + chunk(b"IEND", b""))
    return path


def _bomb(path: Path, side: int) -> Path:
    """A real side x side greyscale PNG of zeros: a few hundred kB that decode to side^2 bytes."""
    packer = zlib.compressobj(9)
    row = b"\x00" * (side + 1)
    return _png(path, side, side, b"".join([packer.compress(row) for _ in range(side)] + [packer.flush()]))


def _wang(n: int, colours: int) -> str:
    """A .wang set of n distinct tiles over ``colours`` colour tokens."""
    rows = [f"c{i % colours} c{(i // colours) % colours} c{(i // colours**2) % colours} c{(i * 7) % colours}  t{i}"
            for i in range(n)]
    return "name: big\ntiles: N E S W\n" + "\n".join(rows) + "\n"


def _edge(points: int) -> str:
    """An IH16 edge shape 'b=...' with ``points`` interior points (a fine zigzag)."""
    body = ":".join(f"{(i + 1) / (points + 1):.6f},{0.001 * ((i % 2) * 2 - 1):.4f}" for i in range(points))
    return f"b=0,0:{body}:1,0"


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Path:
    d = tmp_path_factory.mktemp("hostile")
    for name in ("fifo.toml", "fifo.wang", "fifo.isohedral.json", "fifo.json", "fifo.png", "fifo.svg",
                 "fifo.csv", "fifo.sqlite"):
        os.mkfifo(d / name)
    for name in ("zero.toml", "zero.wang", "zero.isohedral.json", "zero.json", "zero.png"):
        (d / name).symlink_to("/dev/zero")
    deep = 100_000
    (d / "deep.toml").write_text("a = " + "[" * deep + "]" * deep + "\n")
    (d / "deeptable.toml").write_text("a = " + "{b = " * 3000 + "1" + "}" * 3000 + "\n")
    (d / "deep.json").write_text("[" * deep + "]" * deep)
    (d / "deep.isohedral.json").write_text("[" * deep + "]" * deep)
    (d / "huge.json").write_text("[[0,0],[1e308,0],[0,1e308]]")
    (d / "big5000.wang").write_text(_wang(5000, 5000))
    (d / "big40k.wang").write_text(_wang(40_000, 50))
    rng = random.Random(1)  # 10,000 random tiles over 3,000 colours: CaDiCaL needs minutes
    tiles = sorted({tuple(rng.randrange(3000) for _ in range(4)) for _ in range(10_200)})[:10_000]
    (d / "random10k.wang").write_text("name: random\ntiles: N E S W\n" + "".join(
        " ".join(f"c{c}" for c in t) + "\n" for t in tiles))
    (d / "oversize.toml").write_bytes(b"# " + b"x" * (17 << 20) + b"\n")
    _png(d / "h65535.png", 65535, 65535, zlib.compress(b"\x00" * 100))
    _bomb(d / "bomb.png", 16000)
    specs = {
        "params-text": {"ih": 16, "params": "abc"}, "params-int": {"ih": 16, "params": 5},
        "params-nested": {"ih": 16, "params": [[0.3]]}, "params-null": {"ih": 16, "params": [None]},
        "edges-list": {"ih": 16, "edges": ["b=0,0:1,0"]}, "edges-int": {"ih": 16, "edges": {"b": 5}},
        "colouring-int": {"ih": 16, "colouring": 5}, "ih-true": {"ih": True}, "ih-float": {"ih": 16.5},
    }
    for key, spec in specs.items():
        (d / f"{key}.isohedral.json").write_text(json.dumps(spec))
    (d / "params-400digits.isohedral.json").write_text('{"ih": 16, "params": [' + "9" * 400 + "]}")
    (d / "ih-400digits.isohedral.json").write_text('{"ih": ' + "9" * 400 + "}")
    return d


@pytest.fixture(scope="module")
def catalogue(tmp_path_factory) -> str:
    url = f"sqlite:///{tmp_path_factory.mktemp('hostilecat') / 'cat.sqlite'}"
    result = CliRunner().invoke(cli, ["--catalogue", url, "list", "--limit", "1"])
    assert result.exit_code == 0, result.output
    return url


# (case id, argv with {d} for the files folder and {out} for an output stem, fragment)
CASES: list[tuple[str, list[str], str]] = [
    # memory that no estimate counted
    ("edge 1,000 points", ["render", "IH16", "--edge", _edge(1000), "-o", "{out}.svg"], "over the limit of 100"),
    ("edge 6,000 points", ["render", "IH16", "--edge", _edge(6000), "-o", "{out}.svg"], "over the limit of 100"),
    ("torus 600 x 600", ["wang", "solve", "jeandel-rao", "--rows", "600", "--cols", "600", "--torus"], "SAT variables"),
    ("torus 600 x 600, variables raised", ["wang", "solve", "jeandel-rao", "--rows", "600", "--cols", "600", "--torus",
                                           "--max-variables", "100000000"], "memory available"),
    ("10,000-tile set, past its budget", ["wang", "solve", "{d}/random10k.wang", "--rows", "3", "--cols", "3",
                                          "--time-limit", "1"], "within 1 CPU second"),
    ("40,000-tile set", ["wang", "solve", "{d}/big40k.wang", "--rows", "1", "--cols", "1"], "at most 10,000"),
    ("/dev/zero --system", ["render", "--system", "{d}/zero.toml", "--family", "substitution", "-o", "{out}.svg"],
     "is a device"),
    ("/dev/zero .wang", ["wang", "render", "{d}/zero.wang", "-o", "{out}.svg"], "is a device"),
    ("/dev/zero --texture", ["wang", "render", "stochastic-2colour", "--texture", "{d}/zero.toml", "-o", "{out}.svg"],
     "is a device"),
    ("/dev/zero spec file", ["render", "--system", "{d}/zero.isohedral.json", "-o", "{out}.svg"], "is a device"),
    ("/dev/zero goal", ["escherize", "{d}/zero.json", "-o", "{out}"], "is a device"),
    ("/dev/zero density", ["sample", "--density", "{d}/zero.png", "-n", "10", "-o", "{out}.csv"], "is a device"),
    ("17 MB system file", ["render", "--system", "{d}/oversize.toml", "--family", "substitution", "-o", "{out}.svg"],
     "over the limit"),
    # hangs
    ("FIFO catalogue", ["--catalogue", "{d}/fifo.sqlite", "list"], "FIFO"),
    ("FIFO --system", ["render", "--system", "{d}/fifo.toml", "--family", "substitution", "-o", "{out}.svg"], "FIFO"),
    ("FIFO .wang", ["wang", "render", "{d}/fifo.wang", "-o", "{out}.svg"], "FIFO"),
    ("FIFO --texture", ["wang", "render", "stochastic-2colour", "--texture", "{d}/fifo.toml", "-o", "{out}.svg"], "FIFO"),
    ("FIFO spec file", ["render", "--system", "{d}/fifo.isohedral.json", "-o", "{out}.svg"], "FIFO"),
    ("FIFO goal", ["escherize", "{d}/fifo.json", "-o", "{out}"], "FIFO"),
    ("FIFO density", ["sample", "--density", "{d}/fifo.png", "-n", "10", "-o", "{out}.csv"], "FIFO"),
    ("FIFO --set file", ["search", "wang-periodicity", "--set", "{d}/fifo.wang"], "FIFO"),
    ("FIFO render output", ["render", "4^4", "-o", "{d}/fifo.svg"], "FIFO"),
    ("FIFO sample output", ["sample", "--density", "ramp", "-n", "10", "-o", "{d}/fifo.csv"], "FIFO"),
    ("FIFO wang output", ["wang", "render", "stochastic-2colour", "-o", "{d}/fifo.svg"], "FIFO"),
    ("256 workers", ["search", "k-uniform", "--k", "1", "--executor", "process", "--workers", "256"], "at most"),
    ("builder 300 x 300", ["wang", "solve", "jeandel-rao", "--rows", "300", "--cols", "300", "--method", "builder",
                           "--time-limit", "2"], "within"),
    ("backtrack 300 x 300", ["wang", "solve", "jeandel-rao", "--rows", "300", "--cols", "300", "--method", "backtrack",
                             "--time-limit", "2"], "within"),
    # tracebacks
    *[(f"two signs {opt[:2]}", opt, "not a valid integer") for opt in (
        ["list", "--limit", "-+4"], ["list", "--offset", "+-4"], ["render", "penrose-p3", "--depth", "-+4", "-o", "x.svg"],
        ["search", "k-uniform", "--resume", "-+4"], ["search", "k-uniform", "--k", "-+4"],
        ["wang", "solve", "jeandel-rao", "--rows", "-+4", "--cols", "3"],
        ["sample", "--density", "ramp", "-n", "+-4", "-o", "x.csv"])],
    ("nested TOML --system", ["render", "--system", "{d}/deep.toml", "--family", "substitution", "-o", "{out}.svg"],
     "nest more than"),
    ("nested TOML tables", ["render", "--system", "{d}/deeptable.toml", "--family", "substitution", "-o", "{out}.svg"],
     "nest more than"),
    ("nested TOML --texture", ["wang", "render", "stochastic-2colour", "--texture", "{d}/deep.toml", "-o", "{out}.svg"],
     "nest more than"),
    ("nested JSON goal", ["escherize", "{d}/deep.json", "-o", "{out}"], "nest more than"),
    ("nested JSON spec", ["render", "--system", "{d}/deep.isohedral.json", "-o", "{out}.svg"], "nest more than"),
    *[(f"spec {key}", ["render", "--system", f"{{d}}/{key}.isohedral.json", "-o", "{out}.svg"], fragment)
      for key, fragment in (("params-text", "params must be a list"), ("params-int", "params must be a list"),
                            ("params-nested", "params[1] must be a number"), ("params-null", "params[1] must be a number"),
                            ("params-400digits", "finite number"), ("ih-400digits", "isohedral type"),
                            ("edges-list", "edges must be a table"), ("edges-int", "edges.b must be a string"),
                            ("colouring-int", "colouring must be a string"), ("ih-true", "ih must be"),
                            ("ih-float", "ih must be"))],
    ("PNG 65535^2 header", ["sample", "--density", "{d}/h65535.png", "-n", "10", "-o", "{out}.csv"], "density pixels"),
    ("PNG 16000^2 bomb", ["sample", "--density", "{d}/bomb.png", "-n", "10", "-o", "{out}.csv"], "density pixels"),
    ("--scheduler ::::", ["search", "k-uniform", "--k", "1", "--executor", "dask", "--scheduler", "::::"],
     "not a scheduler address"),
    ("unreachable scheduler", ["search", "k-uniform", "--k", "1", "--executor", "dask", "--scheduler",
                               "tcp://127.0.0.1:9"], "cannot reach"),
    ("serve unicode host", ["serve", "--host", "ħöšт" * 20], "--host"),
    ("serve 256.1.1.1", ["serve", "--host", "256.1.1.1"], "not an IPv4 address"),
    ("escherize 1e308", ["escherize", "{d}/huge.json", "-o", "{out}"], "within ±1e+09"),
    # silently accepted before
    ("runs Arabic-Indic digit", ["runs", "١"], "not a run number"),
    ("--order ''", ["list", "--order", ""], "order key"),
    ("--order --name", ["list", "--order", "--name"], "order key"),
]


@pytest.mark.parametrize("case,args,fragment", CASES, ids=[c for c, _, _ in CASES])
def test_hostile_command_is_one_line(catalogue, files, tmp_path, case, args, fragment):
    argv = [a.format(d=files, out=tmp_path / "out") for a in args]
    assert_refused(run_capped(catalogue, *argv, cwd=tmp_path), fragment)
    assert not any(tmp_path.glob("out*")), "nothing is written for a refused command"


@pytest.mark.parametrize("args", [["solve", "{d}/big5000.wang", "--rows", "3", "--cols", "3"],
                                  ["render", "{d}/big5000.wang", "--rows", "3", "--cols", "3", "-o", "{out}.svg"]],
                         ids=["solve", "render"])
def test_a_5000_tile_set_works_under_the_cap(catalogue, files, tmp_path, args):
    # wang render / solve of a 5,000-tile, 5,000-colour set took 7.5 GB (colours-squared
    # clauses and tables): now the encoding and the fills are linear in the tiles
    code, err, seconds = run_capped(catalogue, "wang", *[a.format(d=files, out=tmp_path / "out") for a in args])
    assert code == 0, err[-2000:]
    assert seconds < 2 * SECONDS


def test_density_expression_is_never_tried_as_a_path(catalogue, tmp_path):
    # sample --density "x*0.111...": an expression too long to be a file name is evaluated,
    # not refused with "File name too long"
    code, err, _ = run_capped(catalogue, "sample", "--density", "x*0." + "1" * 290, "-n", "10", "-o",
                              str(tmp_path / "p.csv"))
    assert code == 0, err
    assert len((tmp_path / "p.csv").read_text().splitlines()) >= 10


def test_refused_runs_leave_no_run_behind(catalogue, tmp_path):
    # an unreachable scheduler and too many workers are refused before a run is created
    for args in (["--executor", "dask", "--scheduler", "tcp://127.0.0.1:9"], ["--executor", "process", "--workers", "4096"]):
        assert_refused(run_capped(catalogue, "search", "k-uniform", "--k", "1", *args))
    result = CliRunner().invoke(cli, ["--catalogue", catalogue, "runs", "--format", "json"])
    assert result.exit_code == 0 and json.loads(result.stdout) == [], result.output


def test_solver_budgets_are_stated_in_help():
    # every solver the CLI runs has a default time budget, and --help says what it is
    from tilekit import limits

    for args in (["wang", "solve", "--help"], ["wang", "render", "--help"]):
        text = " ".join(CliRunner().invoke(cli, args).output.split())
        assert "--time-limit" in text and f"default: {limits.DEFAULT_SOLVER_SECONDS}" in text, text


# --------------------------------------------------------------------------- the Python API


def _api_cases():
    from tilekit.geometry import as_region
    from tilekit.plugins import families
    from tilekit.plugins.polyomino.model import Polyomino

    fams = families()
    return [
        ("as_region 400 digits", lambda: as_region((10**400, 0, 1, 1))),
        ("as_region 5,000 digits", lambda: as_region((10**5000, 0, 1, 1))),
        ("Polyomino.parse 25 digits", lambda: Polyomino.parse("1234567890123456789012345,0;0,0")),
        ("polyomino tiling IH28", lambda: fams["polyomino"].from_spec({"name": "pentomino-F", "tiling": "IH28"})),
        ("substitution system []", lambda: fams["substitution"].from_spec({"system": []})),
        ("substitution depth inf", lambda: fams["substitution"].from_spec({"system": "chair", "depth": float("inf")})),
        ("wang seed inf", lambda: fams["wang"].from_spec({"set": "jeandel-rao", "seed": float("inf")})),
        ("isohedral ih true", lambda: fams["isohedral"].from_spec({"ih": True})),
        ("archimedean not a table", lambda: fams["archimedean"].from_spec([1, 2])),
        ("k-uniform not a table", lambda: fams["k-uniform"].from_spec("3.3.3.3.3.3")),
    ]


@pytest.mark.parametrize("index", range(10))
def test_python_api_raises_tilekit_errors(index):
    name, call = _api_cases()[index]
    with pytest.raises(TilekitError) as info:
        call()
    message = str(info.value)
    assert message and "\n" not in message and len(message) < 400, (name, message)


# --------------------------------------------------------------------------- foreign files


def _md5(path: Path) -> str:
    return hashlib.md5(path.read_bytes()).hexdigest()


def _foreign(path: Path, kind: str) -> None:
    """A SQLite file (or not) that tilekit did not make."""
    if kind == "not sqlite":
        path.write_bytes(b"PK\x03\x04 a zip, say" + bytes(range(256)) * 8)
        return
    conn = sqlite3.connect(path)
    if kind.endswith("wal"):
        conn.execute("PRAGMA journal_mode=WAL")
    if kind.startswith("unknown revision"):
        conn.execute("CREATE TABLE alembic_version (version_num VARCHAR(32) PRIMARY KEY)")
        conn.execute("INSERT INTO alembic_version VALUES ('deadbeef0001')")
        conn.execute("CREATE TABLE tilings (id INTEGER PRIMARY KEY, name TEXT)")
    elif kind == "own tilings table":
        conn.execute("CREATE TABLE tilings (x INTEGER, shape BLOB)")
        conn.execute("INSERT INTO tilings VALUES (1, x'00ff')")
    elif kind == "other tables":
        conn.execute("CREATE TABLE customers (id INTEGER PRIMARY KEY, name TEXT)")
        conn.execute("INSERT INTO customers VALUES (1, 'Escher')")
    conn.commit()
    conn.close()


FOREIGN = ["unknown revision", "unknown revision wal", "own tilings table", "other tables", "not sqlite"]
COMMANDS = [["list", "--limit", "1"], ["show", "IH1"], ["runs"], ["catalogue", "upgrade"], ["catalogue", "seed"],
            ["search", "k-uniform", "--k", "1"], ["render", "4^4", "-o", "{out}.svg"]]


@pytest.mark.parametrize("kind", FOREIGN)
def test_foreign_files_are_left_byte_for_byte(tmp_path, kind):
    # every command refuses in one line and the file's bytes (md5) are unchanged: not even
    # PRAGMA journal_mode=WAL (header bytes 18-19) is written before the file is known
    path = tmp_path / "theirs.sqlite"
    _foreign(path, kind)
    before = _md5(path)
    names = sorted(p.name for p in tmp_path.iterdir())
    for args in COMMANDS:
        argv = [a.format(out=tmp_path / "out") for a in args]
        line = assert_refused(run_capped(f"sqlite:///{path}", *argv, cwd=tmp_path))
        assert "left untouched" in line, line
        assert _md5(path) == before, (kind, args)
    assert sorted(p.name for p in tmp_path.iterdir()) == names, "no -wal, -shm or output file was made"


# --------------------------------------------------------------------------- the pieces


def test_bounded_reader(tmp_path):
    """tilekit.files.read_bytes: regular files only (a FIFO refused at once, not after a
    blocking open), the size checked before reading and again while reading."""
    from tilekit.errors import ParseError
    from tilekit.files import check_output, read_bytes, read_text

    ok = tmp_path / "ok.toml"
    ok.write_text("a = 1\n")
    assert read_bytes(ok, "data file") == b"a = 1\n"
    os.mkfifo(tmp_path / "pipe")
    start = time.perf_counter()
    for path, fragment in ((tmp_path / "pipe", "FIFO"), ("/dev/zero", "device"), (tmp_path, "directory"),
                           (tmp_path / "missing", "does not exist"), (ok, "over the limit of 3")):
        with pytest.raises(ParseError, match=fragment):
            read_bytes(path, "data file", limit=3)
    assert time.perf_counter() - start < 1.0
    # /proc files are regular but say they are empty: the bound holds while reading
    with pytest.raises(ParseError, match="grew past the limit of 100"):
        read_bytes("/proc/self/maps", "data file", limit=100)
    (tmp_path / "latin1.toml").write_bytes("caf\xe9".encode("latin-1"))
    with pytest.raises(ParseError, match="not UTF-8"):
        read_text(tmp_path / "latin1.toml", "data file")
    check_output(tmp_path / "new.svg")  # a path that does not exist yet is fine
    check_output(ok)
    for path in (tmp_path / "pipe", "/dev/null", tmp_path):
        with pytest.raises(TilekitError, match="give a regular file path"):
            check_output(path)


def test_bounded_documents():
    """schema.parse_json / parse_toml: nesting, NaN, huge integers are one ParseError."""
    from tilekit.errors import ParseError
    from tilekit.limits import MAX_NESTING
    from tilekit.schema import Field, check, parse_json, parse_toml

    assert parse_json("[[1]]", "x") == [[1]]
    assert parse_json("[" * MAX_NESTING + "]" * MAX_NESTING, "x") is not None
    for text, fragment in (("[" * (MAX_NESTING + 1) + "]" * (MAX_NESTING + 1), "nest more than"),
                           ("[" * 100_000 + "]" * 100_000, "nest more than"), ("[NaN]", "NaN is not a JSON number"),
                           ("[" + "9" * 5000 + "]", "not valid JSON"), ("{", "not valid JSON")):
        with pytest.raises(ParseError, match=fragment):
            parse_json(text, "x.json")
    for text, fragment in (("a = " + "[" * 2000 + "]" * 2000, "nest more than"), ("a = " + "9" * 5000, "not valid TOML"),
                           ("a = = 1", "not valid TOML")):
        with pytest.raises(ParseError, match=fragment):
            parse_toml(text, "x.toml")
    number = Field("number")
    for value in (float("inf"), float("nan"), 10**400):
        with pytest.raises(ParseError, match="must be a finite number"):
            check(number, value, "spec")
    with pytest.raises(ParseError, match=r"outside -\d+\.\.\d+"):
        check(Field("int"), 2**70, "spec")


def test_a_locked_catalogue_is_waited_for(monkeypatch):
    """A worker whose catalogue is locked past SQLite's busy timeout retries within a lease
    time (its heartbeat keeps its leases) instead of dying; other errors are not retried."""
    from tilekit import search
    from tilekit.errors import CatalogueError

    monkeypatch.setattr(search, "POLL_SECONDS", 0.01)
    calls = []

    def locked_twice() -> str:
        calls.append(1)
        if len(calls) < 3:
            raise CatalogueError("catalogue sqlite:///c.sqlite: claiming failed: database is locked")
        return "claimed"

    assert search._patiently(locked_twice) == "claimed" and len(calls) == 3
    with pytest.raises(CatalogueError, match="no such table"):
        search._patiently(lambda: (_ for _ in ()).throw(CatalogueError("no such table: runs")))
    monkeypatch.setenv("TILEKIT_LEASE_SECONDS", "0.05")
    start = time.perf_counter()
    with pytest.raises(CatalogueError, match="locked"):
        search._patiently(lambda: (_ for _ in ()).throw(CatalogueError("database is locked")))
    assert time.perf_counter() - start < 1.0


def test_available_memory_honours_the_address_space_cap():
    """Under ``ulimit -v`` the memory a refusal compares against is what the cap leaves."""
    code = ("import resource; resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30)); "
            "from tilekit.limits import available_memory; print(available_memory())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert 0 < float(out.stdout) < 3 << 30
