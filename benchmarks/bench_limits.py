"""The measured costs behind tilekit/limits.py (issue 27): peak bytes per SAT variable and
clause, per tile of a patch and of each export, per tile the patch builder places, per
squared outline vertex of a tile's overlap check.

Each case runs in a fresh process: its inputs are built, the high-water mark of its resident
memory is reset (``/proc/self/clear_refs``), the work runs, and the peak growth over the
resident size before it is what the work cost. The table prints that peak, the units it is
divided by, and the estimate tilekit refuses by (``limits``), with their ratio; the test
tests/test_limits_measured.py runs the SMALL cases and fails when a ratio leaves 0.5-2.

Run:  python benchmarks/bench_limits.py            (every case; a few minutes)
      python benchmarks/bench_limits.py --small    (the cases the test runs)
      python benchmarks/bench_limits.py --only sat  (cases whose engine starts with 'sat')
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import textwrap
from dataclasses import dataclass, field

_PRELUDE = """
import json, sys, time
def _status(key):
    with open('/proc/self/status') as fh:
        for line in fh:
            if line.startswith(key):
                return int(line.split()[1]) * 1024
"""


@dataclass
class Case:
    """One measurement: ``setup`` builds the inputs, ``work`` allocates what is measured and
    sets the variables named in ``units``; ``estimate`` is a Python expression over them
    (with ``limits`` and ``export`` imported) giving the bytes tilekit's checks assume."""

    engine: str
    label: str
    setup: str
    work: str
    units: tuple[str, ...]
    estimate: str
    small: bool = False
    per: str = field(default="")


def measure(case: Case) -> dict:
    """Run ``case`` in a fresh interpreter; its peak growth, seconds and units."""
    report = "{" + ", ".join(f"{u!r}: {u}" for u in case.units) + "}"
    code = _PRELUDE + textwrap.dedent(case.setup) + textwrap.dedent("""
        from tilekit import limits, export
        open('/proc/self/clear_refs', 'w').write('5')
        _base = _status('VmRSS')
        _t = time.perf_counter()
        """) + textwrap.dedent(case.work) + textwrap.dedent(f"""
        _peak = _status('VmHWM')
        _units = {report}
        print(json.dumps({{"bytes": _peak - _base, "seconds": time.perf_counter() - _t,
                          "estimate": float({case.estimate}), **_units}}))
        """)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=1800)
    if out.returncode:
        raise RuntimeError(f"{case.engine} {case.label}: {out.stderr[-3000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


_WANG = """
import random
from tilekit.plugins.wang.sat import sat_size, sat_solve
from tilekit.plugins.wang.tileset import get_tileset, parse_tileset
def random_set(n, k, seed=1):
    rng = random.Random(seed)
    rows = set()
    while len(rows) < n:
        rows.add(tuple(rng.randrange(k) for _ in range(4)))
    return parse_tileset("name: r\\ntiles: N E S W\\n" + "".join(" ".join("c%d" % x for x in r) + "\\n" for r in rows))
ts = {ts}
V, C, L = sat_size(ts, {r}, {c}, {torus})
"""


def _sat(label: str, ts: str, r: int, c: int, torus: bool, small: bool = False) -> Case:
    # time_limit=None: solved in this process, so its peak is the whole cost (with a time
    # limit CaDiCaL runs in a forked child holding the same solver; the clause blocks stay here)
    return Case("sat (wang, cadical195)", label, _WANG.format(ts=ts, r=r, c=c, torus=torus),
                f"res = sat_solve(ts, {r}, {c}, torus={torus}, time_limit=None)\n", ("V", "C"),
                "limits.sat_bytes(V, C)", small, per="clause")


_BUILDER = """
from tilekit.plugins.wang.solve import builder_solve
from tilekit.plugins.wang.tileset import get_tileset
ts = get_tileset("{name}")
"""


def _builder(name: str, n: int, torus: bool, small: bool = False) -> Case:
    per = "limits.BUILDER_BYTES_PER_TORUS_TILE" if torus else "limits.BUILDER_BYTES_PER_TILE"
    return Case("builder (wang)", f"{name} {n} x {n}{' torus' if torus else ''}", _BUILDER.format(name=name),
                f"r = builder_solve(ts, {n}, {n}, torus={torus}, time_limit=None)\ntiles = {n} * {n}\n",
                ("tiles",), f"tiles * {per}", small, per="tile")


_EXPORT = """
from tilekit.plugins.isohedral import isohedral_tiling
from tilekit.export import write_patch
n = {n}
body = ":".join(f"{{(i + 1) / (n + 1):.6f}},{{0.001 * ((i % 2) * 2 - 1):.4f}}" for i in range(n))
t = isohedral_tiling("IH16", edges=[f"b=0,0:{{body}}:1,0"] if n else [])
region = (-{r}, -{r}, {r}, {r})
verts = len(t.prototiles[0].outline)
"""

_WRITE = {
    ".svg": "p = t.patch(region); tiles = len(p); t.render_svg(p)\n",
    ".geojson": "p = t.patch(region); tiles = len(p); write_patch(p, {path!r})\n",
    ".json": "p = t.patch(region); tiles = len(p); write_patch(p, {path!r})\n",
}


def _export(fmt: str, n: int, r: int, small: bool = False) -> Case:
    path = f"/tmp/bench_limits_{os.getpid()}{fmt}"
    return Case(f"export {fmt}", f"IH16, {n} points an edge", _EXPORT.format(n=n, r=r), _WRITE[fmt].format(path=path),
                ("tiles", "verts"), f"tiles * export.memory_per_tile({fmt!r}, verts, t.bytes_per_tile)", small, per="tile")


_GENERATION = """
import tilekit.plugins.substitution as sub
sub.tiling("{name}", depth=2).patch(sub.tiling("{name}", depth=2).default_region())  # compiled kernels loaded
t = sub.tiling("{name}", depth={depth})
region = t.default_region()
"""


def _generation(name: str, depth: int, small: bool = False) -> Case:
    return Case("patch generation (substitution)", f"{name} depth {depth}", _GENERATION.format(name=name, depth=depth),
                "p = t.patch(region); tiles = len(p)\n", ("tiles",), "tiles * t.bytes_per_tile",
                small, per="tile")


_PERIODIC = """
from tilekit.plugins import families
t = families()["{family}"].from_spec({spec!r})
t.patch((-3, -3, 3, 3))  # compiled kernels loaded
region = (-{r}, -{r}, {r}, {r})
"""

#: periodic tilings by name: (family, spec)
_SPECS = {
    "3.4.6.4": ("archimedean", {"kind": "archimedean", "vertex_type": "3.4.6.4"}),
    "4^4": ("archimedean", {"kind": "archimedean", "vertex_type": "4.4.4.4"}),
    "IH41": ("isohedral", {"ih": 41}),
    "pentomino-F": ("polyomino", {"name": "pentomino-F"}),
}


def _periodic(name: str, r: int, small: bool = False) -> Case:
    family, spec = _SPECS[name]
    return Case("patch generation (periodic)", f"{name} in ±{r}", _PERIODIC.format(family=family, spec=spec, r=r),
                "p = t.patch(region); tiles = len(p)\n", ("tiles",), "tiles * t.bytes_per_tile",
                small, per="tile")


def _adjacency(name: str, size: int, small: bool = False) -> Case:
    """A patch's adjacency: a substitution patch of depth ``size``, or a periodic one in ±size."""
    if name in ("penrose-p3", "chair", "spectre", "hat"):
        setup, label = _GENERATION.format(name=name, depth=size), f"{name} depth {size}"
    else:
        family, spec = _SPECS[name]
        setup, label = _PERIODIC.format(family=family, spec=spec, r=size), f"{name} in ±{size}"
    return Case("adjacency", label, setup + "p = t.patch(region)\n", "a = p.adjacency(); tiles = len(p)\n", ("tiles",),
                "tiles * limits.ADJACENCY_BYTES_PER_VERTEX * export.outline_vertices(p.prototiles)", small,
                per="tile")


_OVERLAP = """
from tilekit.plugins.isohedral import isohedral_tiling
n = {n}
body = ":".join(f"{{(i + 1) / (n + 1):.6f}},{{0.001 * ((i % 2) * 2 - 1):.4f}}" for i in range(n))
edge = f"b=0,0:{{body}}:1,0"
"""


def _overlap(n: int) -> Case:
    # the check_overlaps of an IH16 tile with an n-point edge (Patch.validate of its 3 x 3
    # units); no estimate in tilekit: limits.MAX_EDGE_POINTS bounds it
    return Case("tile overlap check (isohedral)", f"IH16, {n} points an edge", _OVERLAP.format(n=n),
                "t = isohedral_tiling('IH16', edges=[edge]); verts = len(t.prototiles[0].outline)\n",
                ("verts",), "0", per="squared vertex")


CASES: list[Case] = [
    _sat("jeandel-rao 100 x 100", "get_tileset('jeandel-rao')", 100, 100, False),
    _sat("stochastic-2colour 200 x 200 torus", "get_tileset('stochastic-2colour')", 200, 200, True),
    _sat("stochastic-2colour 150 x 150", "get_tileset('stochastic-2colour')", 150, 150, False, small=True),
    _sat("corner-2colour 150 x 150 torus", "get_tileset('corner-2colour')", 150, 150, True),
    _sat("checkerboard-2 300 x 300 torus", "get_tileset('checkerboard-2')", 300, 300, True),
    _sat("2,000 random tiles of 500 colours, 6 x 6", "random_set(2000, 500)", 6, 6, False),
    _sat("300 random tiles of 6 colours, 20 x 20", "random_set(300, 6)", 20, 20, False, small=True),
    _builder("stochastic-2colour", 40, False, small=True),
    _builder("stochastic-2colour", 80, False),
    _builder("corner-2colour", 60, False),
    _builder("checkerboard-2", 30, True, small=True),
    _builder("stochastic-2colour", 40, True),
    _export(".svg", 0, 60, small=True),
    _export(".svg", 25, 40),
    _export(".svg", 100, 25, small=True),
    _export(".geojson", 0, 60),
    _export(".geojson", 100, 25, small=True),
    _export(".json", 0, 60),
    _export(".json", 100, 25),
    _generation("penrose-p3", 12, small=True),
    _generation("penrose-p3", 14),
    _generation("chair", 8),
    _generation("chair", 10),
    _generation("spectre", 5, small=True),
    _generation("hat", 5),
    _generation("ammann-beenker", 7),
    _periodic("3.4.6.4", 300, small=True),
    _periodic("4^4", 1000),
    _periodic("IH41", 300),
    _adjacency("penrose-p3", 10, small=True),
    _adjacency("chair", 8),
    _adjacency("pentomino-F", 150),
    _adjacency("3.4.6.4", 60),
    _overlap(25),
    _overlap(50),
    _overlap(100),
]


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--small", action="store_true", help="only the cases tests/test_limits_measured.py runs")
    ap.add_argument("--only", default="", help="only cases whose engine starts with this")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    print(f"load: {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f} "
          f"(1/5/15 min), {os.cpu_count()} CPUs")
    print(f"{'engine':34} {'case':42} {'peak MB':>8} {'s':>6}  {'units':30} {'B/unit':>9} {'est/meas':>8}")
    for case in CASES:
        if (args.small and not case.small) or not case.engine.startswith(args.only):
            continue
        m = measure(case)
        units = {u: m[u] for u in case.units}
        main_unit = {"clause": "C", "tile": "tiles", "squared vertex": "verts"}[case.per]
        count = units[main_unit] ** (2 if case.per == "squared vertex" else 1)
        shown = ", ".join(f"{k}={v:,}" for k, v in units.items())
        print(f"{case.engine:34} {case.label:42} {m['bytes'] / 2**20:8.1f} {m['seconds']:6.2f}  {shown:30} "
              f"{m['bytes'] / count:9.0f} {ratio(m):>8}", flush=True)


def ratio(m: dict) -> str:
    """estimate / measured, or '-' for a cost tilekit bounds by a limit instead of an estimate."""
    return f"{m['estimate'] / max(m['bytes'], 1):.2f}" if m["estimate"] else "-"


if __name__ == "__main__":
    main()
