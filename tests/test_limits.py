"""Limits before allocation (issue 14): every command that can make a large object estimates
its size and refuses in one line naming the estimate, the limit and the option, quickly and
under a memory cap (each command runs in a subprocess with RLIMIT_AS set, so an allocation
of the object itself would be a MemoryError traceback or an OOM, not a clean refusal).
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from tilekit import limits
from tilekit.cli import cli
from tilekit.cli_types import BoundedInt, FiniteFloat

#: Address-space cap for the refusing commands (imports of numpy/shapely/sqlalchemy fit).
MEMORY_CAP = 2 * 1024**3

_RUNNER = """
import resource, sys
resource.setrlimit(resource.RLIMIT_AS, ({cap}, {cap}))
from tilekit.cli import main
main(sys.argv[1:])
"""


@pytest.fixture(scope="module")
def catalogue(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("limits") / "cat.sqlite"
    result = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{path}", "list", "--limit", "1"])
    assert result.exit_code == 0, result.output
    return path


def capped(catalogue: Path, *args: str) -> tuple[int, str, float]:
    env = dict(os.environ, TILEKIT_CATALOGUE=f"sqlite:///{catalogue}", OPENBLAS_NUM_THREADS="1",
               OMP_NUM_THREADS="1")
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", _RUNNER.format(cap=MEMORY_CAP), *args], env=env,
                          capture_output=True, text=True, timeout=120)
    return proc.returncode, proc.stderr, time.perf_counter() - start


CASES = [
    # (command line, fragment of the one-line error)
    (["render", "penrose-p3", "--depth", "20", "-o", "{out}.svg"], "--max-tiles"),
    (["render", "penrose-p3", "--region", "-1e6,-1e6,1e6,1e6", "-o", "{out}.svg"], "--max-tiles"),
    (["render", "chair", "--depth", "30", "-o", "{out}.svg"], "--max-tiles"),
    (["render", "spectre", "--depth", "8", "-o", "{out}.svg"], "--max-tiles"),
    (["render", "hat", "--depth", "12", "-o", "{out}.svg"], "--max-tiles"),
    (["render", "4^4", "--region", "-2200,-2200,2200,2200", "-o", "{out}.svg"], "--max-tiles"),
    (["render", "stochastic-2colour", "--region", "0,0,3000,3000", "-o", "{out}.svg"], "--max-tiles"),
    (["render", "--system", "{system}", "--depth", "30", "-o", "{out}.svg"], "--max-tiles"),
    (["render", "4^4", "--region", "-1e200,-1e200,1e200,1e200", "-o", "{out}.svg"], "outside"),
    (["wang", "solve", "jeandel-rao", "--rows", "2000", "--cols", "2000"], "--max-tiles"),
    (["wang", "solve", "jeandel-rao", "--rows", "100000", "--cols", "100000"], "--max-tiles"),
    (["wang", "solve", "jeandel-rao", "--rows", "900", "--cols", "900"], "--max-variables"),
    (["wang", "render", "stochastic-2colour", "--rows", "3000", "--cols", "3000", "-o", "{out}.svg"], "--max-tiles"),
    (["wang", "render", "stochastic-2colour", "--size", "100000", "-o", "{out}.png"], "--size"),
]


@pytest.mark.parametrize("args,fragment", CASES, ids=[" ".join(a[:4]) for a, _ in CASES])
def test_refused_quickly_under_memory_cap(catalogue, tmp_path, args, fragment):
    from tilekit.plugins.substitution import system_dir

    system = str(system_dir() / "chair.toml")
    argv = [a.format(out=tmp_path / "out", system=system) for a in args]
    code, err, seconds = capped(catalogue, *argv)
    lines = err.strip().splitlines()
    assert code == 2, err
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    assert fragment in lines[0], lines[0]
    assert seconds < 60
    assert not (tmp_path / "out.svg").exists()


def test_refusal_names_estimate_limit_and_option(catalogue):
    # tilekit render penrose-p3 --depth 20: the star's ten halves, each M^20 e (Fibonacci
    # numbers), over 2,000,000
    import tilekit.plugins.substitution as sub

    estimate = sub.tiling("penrose-p3", depth=20).estimate_tiles()
    assert estimate == 10 * (102_334_155 + 165_580_141)  # per half: F(40) acute + F(41) obtuse
    code, err, _ = capped(catalogue, "render", "penrose-p3", "--depth", "20", "-o", "/nonexistent/x.svg")
    assert code == 2
    assert f"{int(estimate):,} tiles" in err and f"{limits.MAX_TILES:,}" in err and "--max-tiles N" in err


def test_max_tiles_raises_the_limit(catalogue, tmp_path):
    # tilekit render penrose-p3 --depth 8 --max-tiles 100 is refused; the default draws it
    out = tmp_path / "p3.svg"
    base = ["--catalogue", f"sqlite:///{catalogue}", "render", "penrose-p3", "--depth", "8", "-o", str(out)]
    refused = CliRunner().invoke(cli, [*base, "--max-tiles", "100"])
    assert refused.exit_code == 2 and "over the limit of 100" in refused.stderr
    assert not out.exists()
    drawn = CliRunner().invoke(cli, base)
    assert drawn.exit_code == 0 and out.exists()


def test_estimates_bound_the_patch(catalogue):
    # the estimate is an upper bound (within a small factor) of what patch() makes
    import tilekit
    import tilekit.plugins.substitution as sub

    for tiling in (sub.tiling("penrose-p3", depth=6), sub.tiling("chair"), sub.tiling("spectre", depth=2)):
        made = len(tiling.patch(tiling.default_region()))
        est = tiling.estimate_tiles()
        assert made <= est <= 40 * max(made, 1), (tiling.name, made, est)
    cat = tilekit.open_catalogue(f"sqlite:///{catalogue}")
    sq = cat.tiling("4^4")
    cat.close()
    region = (-10, -10, 10, 10)
    assert len(sq.patch(region)) <= sq.estimate_tiles(region) <= 2 * 22 * 22


def test_bounded_types():
    # tilekit list --limit 10**30, --where and run ids: one-line errors, not OverflowError
    import click

    with pytest.raises(click.BadParameter, match="out of range"):
        BoundedInt(0).convert("1" * 30, None, None)
    with pytest.raises(click.BadParameter, match="out of range"):
        BoundedInt(0).convert("9" * 5000, None, None)
    with pytest.raises(click.BadParameter, match="not a valid integer"):
        BoundedInt(0).convert("١٢", None, None)  # Arabic-Indic digits: isdigit() but not ASCII
    assert BoundedInt(0).convert("12", None, None) == 12
    for bad in ("inf", "nan", "1e308"):
        with pytest.raises(click.BadParameter):
            FiniteFloat(1e9).convert(bad, None, None)


@pytest.mark.parametrize("args", [
    ["list", "--limit", "1" * 30], ["list", "--offset", "1" * 30], ["runs", "9" * 40],
    ["search", "vertex-species", "--resume", "9" * 40], ["list", "--where", "k_hedral=" + "9" * 5000],
    ["render", "IH41", "--param", "1e308", "-o", "x.svg"], ["wang", "solve", "jeandel-rao", "--rows", "3",
                                                               "--cols", "3", "--fix", "0,0=" + "9" * 5000],
])
def test_huge_numbers_are_one_line_errors(catalogue, args):
    result = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{catalogue}", *args])
    assert result.exit_code == 2, result.output
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr


def test_hundred_colour_colouring_is_cheap():
    # tilekit render IH41 --set colouring=... with 100 colours in cycles 2,3,5,...,23 (order
    # 223,092,870): colours come from the cycles, no power table (166 GiB) is built
    import numpy as np

    from tilekit.colouring import Colouring

    perm, base = [], 0
    for p in (2, 3, 5, 7, 11, 13, 17, 19, 23):
        perm += [base + (i + 1) % p for i in range(p)]
        base += p
    col = Colouring((0,), tuple(perm), tuple(perm))
    a = np.array([0, 1, 223_092_870, -1, 10**15])
    got = col.colour(np.zeros(5, dtype=np.int64), a, np.zeros(5, dtype=np.int64))
    # perm^a(0) on the 2-cycle {0, 1}: parity of a
    assert got.tolist() == [0, 1, 0, 1, 0]


def test_hundred_colour_set_renders_under_memory_cap(catalogue, tmp_path):
    # tilekit render IH41 --set colouring=(1)(p)(p), 100 colours in cycles 2, 3, 5, ..., 23
    # (order 223,092,870; a power table would take 166 GiB): drawn quickly under the cap
    perm, base = [], 0
    for p in (2, 3, 5, 7, 11, 13, 17, 19, 23):
        perm += [base + (i + 1) % p for i in range(p)]
        base += p
    cycle = "(" + " ".join(str(v + 1) for v in perm) + ")"
    out = tmp_path / "c.svg"
    code, err, seconds = capped(catalogue, "render", "IH41", "--set", f"colouring=(1){cycle}{cycle}", "-o", str(out))
    assert code == 0, err
    assert out.exists() and seconds < 60
