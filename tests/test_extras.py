"""A missing optional extra never ends in a traceback (issue 26): for each extra, a command that
needs it runs in a subprocess whose import system refuses the extra's modules (a meta-path
blocker, as if the extra were not installed) and must print one line ``error: ...`` naming the
extra's ``pip install 'tilekit[EXTRA]'`` and exit 2.

The Python-only extras (plot, geo, graph) are covered the same way in test_exports.py
(``test_a_missing_optional_dependency_names_its_extra``)."""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

BLOCKER = r"""
import sys

blocked = set(sys.argv[1].split(","))


class Blocker:
    "Refuses every module of the blocked distributions, as if they were not installed."

    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in blocked:
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None


sys.meta_path.insert(0, Blocker())
from tilekit.cli import main

main(sys.argv[2:])
"""


@pytest.fixture(scope="module")
def work(tmp_path_factory):
    """A folder with a seeded catalogue, a goal polygon and a small PNG."""
    folder = tmp_path_factory.mktemp("extras")
    from tilekit import open_catalogue

    open_catalogue(f"sqlite:///{folder / 'cat.sqlite'}").close()
    (folder / "goal.json").write_text(json.dumps([[0, 0], [1, 0], [1, 1], [0, 1]]))
    return folder


def _png(folder: Path) -> Path:
    """A 4 x 4 grey PNG written without Pillow (zlib and struct only)."""
    import struct
    import zlib

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    raw = b"".join(b"\x00" + bytes([x * 60 for x in range(4)]) for _ in range(4))
    data = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 4, 4, 8, 0, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    path = folder / "grey.png"
    path.write_bytes(data)
    return path


# (extra, modules hidden, command); {dir} is the work folder, {pg} the test server's URL
CASES = [
    ("escher", "scipy", ["escherize", "{dir}/goal.json", "--types", "IH1", "-o", "{dir}/esc"]),
    ("escher", "threadpoolctl", ["escherize", "{dir}/goal.json", "--types", "IH1", "-o", "{dir}/esc"]),
    ("escher", "scipy", ["escherize-penrose", "{dir}/goal.json", "-o", "{dir}/pen"]),
    ("escher", "threadpoolctl", ["escherize-penrose", "{dir}/goal.json", "-o", "{dir}/pen"]),
    ("web", "starlette", ["serve", "--port", "0"]),
    ("web", "uvicorn", ["serve", "--port", "0"]),
    ("postgresql", "psycopg", ["--catalogue", "{pg}", "list", "--count"]),
    ("png", "cairosvg", ["render", "4.8.8", "-o", "{dir}/x.png"]),
    ("dxf", "ezdxf", ["render", "4.8.8", "-o", "{dir}/x.dxf"]),
    ("sampling", "scipy", ["sample", "--density", "ramp", "--method", "penrose", "-n", "50", "--relax", "1",
                           "-o", "{dir}/p.csv"]),
    ("sampling", "PIL", ["sample", "--density", "{dir}/grey.png", "--method", "penrose", "-n", "50",
                         "-o", "{dir}/p.csv"]),
    ("texture", "PIL", ["wang", "texture", "{dir}/grey.png", "--tile", "8", "-o", "{dir}/tiles.png"]),
    ("cms", "pycryptosat", ["search", "polyomino-classify", "--max-cells", "3", "--solver", "cryptominisat5"]),
    ("dask", "dask,distributed", ["search", "wang-periodicity", "--max-m", "1", "--executor", "dask"]),
]


def test_every_cli_extra_has_a_case():
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    python_only = {"plot", "geo", "graph", "test"}  # test_exports.py checks the first three
    assert {extra for extra, _, _ in CASES} == set(extras) - python_only


@pytest.mark.parametrize(("extra", "hidden", "command"), CASES, ids=[f"{e}-{h}" for e, h, _ in CASES])
def test_a_missing_extra_is_one_line_naming_it(work, extra, hidden, command):
    pg = "postgresql+psycopg://nobody@127.0.0.1:1/none"  # the driver is refused before any connection
    _png(work)
    args = [a.format(dir=work, pg=pg) for a in command]
    env = {"TILEKIT_CATALOGUE": f"sqlite:///{work / 'cat.sqlite'}", "PATH": "/usr/bin:/bin",
           "HOME": str(work), "NUMBA_CACHE_DIR": str(work / "numba")}
    proc = subprocess.run([sys.executable, "-c", BLOCKER, hidden, *args], capture_output=True, text=True,
                          timeout=300, env=env, cwd=work)
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2, (proc.returncode, proc.stderr[-2000:])
    assert "Traceback" not in proc.stderr and len(lines) == 1, proc.stderr[-2000:]
    assert lines[0].startswith("error: ") and f"pip install 'tilekit[{extra}]'" in lines[0], lines[0]
