"""Substitution speed against the strongest simple peers, side by side in one process.

Peers (each checked to produce the same placements as tilekit, as a set):

- ``peer_components``: the NumPy subdivision a competent user writes: every level at once,
  maps held as six affine component arrays (a00, a01, a02, a10, a11, a12), children composed
  by element-wise multiply-adds broadcast over (children, parents) per label, no 3x3
  matmuls. Integer lattice maps for the hat (exact, as tilekit), per-level rules for the
  spectre. Its output is the six arrays (48 bytes a tile); tilekit's is the Patch's (n, 3, 3).
- ``complex_draw``: the book's recursive DRAW (§6.1) with maps as complex numbers
  z -> a z + b or a conj(z) + b, for the similarity systems.

Run the tables:             python benchmarks/bench_substitution.py [--runs 5] [--big]
                            python benchmarks/bench_substitution.py --memory   (bytes per tile)
Streams (issue 13, goal 6): python benchmarks/bench_substitution.py --stream spectre:8 --sink null
                            (--sink geojson --out FILE, --sink whole for the unchunked patch;
                            one mode per process, so its peak RSS is its own)
Run as pytest-benchmark:    pytest benchmarks/bench_substitution.py --benchmark-enable
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
import tracemalloc
from functools import partial

import numpy as np

from tilekit.geometry import Affine
from tilekit.plugins.substitution import builtin_systems, tiling
from tilekit.plugins.substitution.engine import assemble, generate
from tilekit.plugins.substitution.hat import TO_CARTESIAN, TO_LATTICE
from tilekit.polygon import centroid

#: From one obtuse Robinson triangle, depth 14 gives F(30) = 832,040 half-rhombs.
DEPTH = 14

#: (system, depth) near 10^6 tiles, and (with --big) 4-19 x 10^6 (the hat refuses more than
#: 5 x 10^6 tiles without a region, so its largest whole supertile here is depth 7).
CASES = [("penrose-p3", 14), ("penrose-p2", 14), ("ammann-beenker", 8), ("chair", 10), ("hat", 7), ("spectre", 7)]
BIG = [("penrose-p3", 16), ("penrose-p2", 16), ("ammann-beenker", 9), ("chair", 11), ("spectre", 8)]


# ----------------------------------------------------------------------------- peers


def compose_components(label, comps, children, matrices):
    """One level of the component peer: (labels, (6, n) components) -> the children's."""
    labs, outs = [], []
    for j, (kids, mats) in enumerate(zip(children, matrices)):
        idx = np.flatnonzero(label == j)
        if not len(idx) or not len(kids):
            continue
        a = comps[:, idx]
        m = np.asarray(mats)
        out = np.empty((6, len(m), len(idx)), dtype=np.result_type(a, m))
        m00, m01, m02 = m[:, 0, 0, None], m[:, 0, 1, None], m[:, 0, 2, None]
        m10, m11, m12 = m[:, 1, 0, None], m[:, 1, 1, None], m[:, 1, 2, None]
        for r in (0, 3):  # rows of the parent's 2x3 part
            out[r] = a[r] * m00 + a[r + 1] * m10
            out[r + 1] = a[r] * m01 + a[r + 1] * m11
            out[r + 2] = a[r] * m02 + a[r + 1] * m12 + a[r + 2]
        outs.append(out.reshape(6, -1))
        labs.append(np.repeat(np.asarray(kids), len(idx)))
    return np.concatenate(labs), np.concatenate(outs, axis=1)


def peer_components(name: str, depth: int) -> tuple[np.ndarray, np.ndarray]:
    """(labels or colours, (6, n) float components) of the same patch as ``tilekit_call``."""
    s = builtin_systems()[name]
    if name == "hat":
        lab = np.array([s.seed])
        comps = np.array([[1], [0], [0], [0], [1], [0]], dtype=np.int64)
        for n in range(depth, 0, -1):
            lab, comps = compose_components(lab, comps, [r.children for r in s.rules_at(n)], s.lattice_rules_at(n))
        colours = [np.full(len(b), 1 + j) if j else (np.linalg.det(b[:, :2, :2]) < 0).astype(int) for j, b in enumerate(s.base)]
        col, comps = compose_components(lab, comps, colours, s.base)
        # Cartesian = C @ L @ C^-1, C = [[1, 1/2], [0, sqrt3/2]]: the same FMAs, once
        left = np.c_[TO_CARTESIAN[:2, :2], np.zeros(2)].reshape(6, 1)
        right = TO_LATTICE
        t = np.empty((6, comps.shape[1]))
        for r in (0, 3):
            t[r] = comps[r] * right[0, 0] + comps[r + 1] * right[1, 0]
            t[r + 1] = comps[r] * right[0, 1] + comps[r + 1] * right[1, 1]
            t[r + 2] = comps[r] * right[0, 2] + comps[r + 1] * right[1, 2] + comps[r + 2]
        out = np.empty_like(t)
        for r in (0, 3):
            for c in range(3):
                out[r + c] = left[r] * t[c] + left[r + 1] * t[3 + c]
        return col, out
    if name == "spectre":
        t0 = np.eye(3)
        if depth % 2 == 1 and s.reflect:
            t0 = t0 @ np.diag([-1.0, 1.0, 1.0])
        lab, comps = np.array([s.seed]), t0[:2].reshape(6, 1)
        for n in range(depth, 0, -1):
            rules = s.rules_at(n)
            lab, comps = compose_components(lab, comps, [r.children for r in rules], [r.matrices for r in rules])
        colours = [(np.arange(len(b)) > 0).astype(np.int64) for b in s.base]
        return compose_components(lab, comps, colours, s.base)
    seed = Affine.scaling(s.scale**depth)
    lab, comps = np.array([s.seed]), seed[:2].reshape(6, 1)
    children, matrices = [r.children for r in s.rules], [r.matrices for r in s.rules]
    for _ in range(depth):
        lab, comps = compose_components(lab, comps, children, matrices)
    return lab, comps


def tilekit_call(name: str, depth: int) -> tuple[np.ndarray, np.ndarray]:
    """tilekit's generation of the same patch: (labels or colours, (n, 3, 3) transforms)."""
    s = builtin_systems()[name]
    if name in ("hat", "spectre"):
        _, transform, colour = s.generate(depth)
        return colour, transform
    return generate(s, depth, Affine.scaling(s.scale**depth), s.seed)


def _canonical(label: np.ndarray, comps: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    q = np.round(comps / (1e-4 * max(1.0, float(np.abs(comps[[0, 1, 3, 4]]).max())))).astype(np.int64)
    order = np.lexsort((*q[::-1], label))
    return label[order], comps[:, order]


def check_equal(tk: tuple[np.ndarray, np.ndarray], peer: tuple[np.ndarray, np.ndarray]) -> None:
    """The same placements as a set (orders differ): labels equal and maps within 1e-9."""
    lt, t = tk
    comps = t[:, :2, :].reshape(-1, 6).T
    assert np.allclose(t[:, 2], [0.0, 0.0, 1.0])
    a, ca = _canonical(np.asarray(lt), comps)
    b, cb = _canonical(np.asarray(peer[0]), np.asarray(peer[1], dtype=float))
    assert len(a) == len(b) and np.array_equal(a, b), "labels differ"
    scale = max(1.0, float(np.abs(ca).max()))
    assert np.allclose(ca, cb, rtol=0, atol=1e-9 * scale), "maps differ"


def complex_draw(name: str, depth: int) -> list:
    """DRAW(i0, M0, l) of §6.1 with each similarity as (a, b, reflected): z -> a z + b."""
    s = builtin_systems()[name]
    rules = []
    for r in s.rules:
        kids = []
        for j, m in zip(r.children, r.matrices):
            flip = m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0] < 0
            kids.append((int(j), complex(m[0, 0], m[1, 0]), complex(m[0, 2], m[1, 2]), bool(flip)))
        rules.append(kids)
    out: list = []

    def draw(i0: int, a: complex, b: complex, f: bool, level: int) -> None:
        if level == 0:
            out.append((i0, a, b, f))
            return
        for j, a2, b2, f2 in rules[i0]:
            if f:
                draw(j, a * a2.conjugate(), a * b2.conjugate() + b, not f2, level - 1)
            else:
                draw(j, a * a2, a * b2 + b, f2, level - 1)

    draw(s.seed, complex(s.scale**depth), 0j, False, depth)
    return out


def draw_as_components(out: list) -> tuple[np.ndarray, np.ndarray]:
    lab = np.array([o[0] for o in out])
    a = np.array([o[1] for o in out])
    b = np.array([o[2] for o in out])
    f = np.array([o[3] for o in out])
    sgn = np.where(f, -1.0, 1.0)  # a conj(z): columns (Re a, Im a) and (Im a, -Re a)
    return lab, np.stack([a.real, -a.imag * sgn, b.real, a.imag, a.real * sgn, b.imag])


# ----------------------------------------------------------------------------- timing


def timed(f, runs: int) -> tuple[list[float], object]:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        f()  # the result is dropped before the next run, so runs do not share memory
        times.append(time.perf_counter() - start)
    return times, f()


def fmt(ts: list[float]) -> str:
    return f"{min(ts):.3f} / {statistics.median(ts):.3f}"


def main_speed(cases: list[tuple[str, int]], runs: int, draw: bool) -> None:
    tilekit_call("penrose-p3", 3), tilekit_call("hat", 2), tilekit_call("spectre", 2)  # compile once
    print(f"min / median of {runs} runs, seconds; ratio = peer median / tilekit median")
    print(f"{'system':16s} {'depth':>5s} {'tiles':>11s} {'tilekit':>15s} {'M/s':>6s} {'components peer':>15s} {'M/s':>6s} {'ratio':>6s}")
    for name, depth in cases:
        t_tk, tk = timed(partial(tilekit_call, name, depth), runs)
        t_peer, peer = timed(partial(peer_components, name, depth), runs)
        check_equal(tk, peer)
        n = len(tk[0])
        del peer
        ratio = statistics.median(t_peer) / statistics.median(t_tk)
        print(f"{name:16s} {depth:5d} {n:11,d} {fmt(t_tk):>15s} {n / statistics.median(t_tk) / 1e6:6.1f} "
              f"{fmt(t_peer):>15s} {n / statistics.median(t_peer) / 1e6:6.1f} {ratio:6.2f}")
        if draw and name not in ("hat", "spectre") and n < 2_000_000:
            t_draw, out = timed(partial(complex_draw, name, depth), max(1, min(runs, 5)))
            check_equal(tk, draw_as_components(out))
            ratio = statistics.median(t_draw) / statistics.median(t_tk)
            print(f"{'  complex DRAW':16s} {'':5s} {len(out):11,d} {'':15s} {'':6s} {fmt(t_draw):>15s} "
                  f"{n / statistics.median(t_draw) / 1e6:6.1f} {ratio:6.1f}")
        del tk


def main_memory(cases: list[tuple[str, int]]) -> None:
    """tracemalloc peak of one generation (NumPy allocations are traced), bytes per tile."""
    tilekit_call("penrose-p3", 3), tilekit_call("hat", 2), tilekit_call("spectre", 2)
    print(f"{'system':16s} {'depth':>5s} {'tiles':>11s} {'peak MB':>9s} {'bytes/tile':>11s} {'peer bytes/tile':>16s}")
    for name, depth in cases:
        tracemalloc.start()
        lab, t = tilekit_call(name, depth)
        n = len(lab)
        del lab, t
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        tracemalloc.start()
        out = peer_components(name, depth)
        del out
        peer = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        print(f"{name:16s} {depth:5d} {n:11,d} {peak / 1e6:9.1f} {peak / n:11.0f} {peer / n:16.0f}")


def peer_unique_centres(system, proto: np.ndarray, transform: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The NumPy peer of whole-tile assembly: each half mapped to its whole tile (one
    batched matmul), then one ``np.unique`` of a packed (tile, quantised centroid) int64
    key keeps the first of each (one grid: a pair straddling a cell edge would survive
    twice, which the check against tilekit would catch)."""
    whole_p = system.assemble_tile[proto]
    whole_t = np.matmul(transform, system.assemble_matrix[proto])
    c = np.array([centroid(t.outline) for t in system.output_prototiles])[whole_p]
    x = whole_t[:, 0, 0] * c[:, 0] + whole_t[:, 0, 1] * c[:, 1] + whole_t[:, 0, 2]
    y = whole_t[:, 1, 0] * c[:, 0] + whole_t[:, 1, 1] * c[:, 1] + whole_t[:, 1, 2]
    q = 1e-4
    qx = np.floor((x - x.min()) / q).astype(np.int64)
    qy = np.floor((y - y.min()) / q).astype(np.int64)
    key = (whole_p << 60) | (qx << 30) | qy
    _, first = np.unique(key, return_index=True)
    first.sort()
    return whole_p[first], whole_t[first]


def main_api(runs: int, radius: float) -> None:
    """Item 2: whole rhombs from halves, and ``tiling("penrose-p3").patch(region)``, at the
    engine's size, min / median of ``runs``."""
    s = builtin_systems()["penrose-p3"]
    t = tiling("penrose-p3")
    t.patch((0, 0, 3, 3))
    seed = Affine.scaling(s.scale**DEPTH)
    halves = generate(s, DEPTH, seed, s.seed)
    assemble(s, *generate(s, 3, seed, s.seed))
    t_gen, _ = timed(partial(generate, s, DEPTH, seed, s.seed), runs)
    t_asm, whole = timed(partial(assemble, s, *halves), runs)
    t_peer, peer = timed(partial(peer_unique_centres, s, *halves), runs)
    assert len(whole[0]) == len(peer[0])
    check_equal(whole, (peer[0], peer[1][:, :2, :].reshape(-1, 6).T))
    region = (-radius, -radius, radius, radius)
    t_api, patch = timed(partial(t.patch, region), runs)
    med = statistics.median
    n_h, n_w, n_p = len(halves[0]), len(whole[0]), len(patch)
    print(f"min / median of {runs} runs, seconds (Penrose P3, depth {DEPTH})")
    print(f"engine: {n_h:,} half-rhombs in {fmt(t_gen)} ({n_h / med(t_gen) / 1e6:.1f} M/s)")
    print(f"assembly into {n_w:,} rhombs: {fmt(t_asm)} ({med(t_asm) / med(t_gen):.2f}x the generation); "
          f"NumPy np.unique peer {fmt(t_peer)} (peer / tilekit {med(t_peer) / med(t_asm):.2f})")
    rate_engine = n_w / (med(t_gen) + med(t_asm))
    print(f"engine + assembly: {rate_engine / 1e6:.2f} M rhombs/s")
    print(f"tiling('penrose-p3').patch({region}): {n_p:,} rhombs in {fmt(t_api)} "
          f"({n_p / med(t_api) / 1e6:.2f} M/s; engine + assembly / API = {rate_engine / (n_p / med(t_api)):.2f}x)")


# ----------------------------------------------------------------------------- pytest-benchmark


def run_engine(depth: int = DEPTH) -> tuple[int, float]:
    s = builtin_systems()["penrose-p3"]
    start = time.perf_counter()
    proto, _ = generate(s, depth, Affine.scaling(s.scale**depth), s.seed)
    return len(proto), time.perf_counter() - start


def run_engine_with_assembly(depth: int = DEPTH) -> tuple[int, int, float]:
    s = builtin_systems()["penrose-p3"]
    start = time.perf_counter()
    proto, tr = generate(s, depth, Affine.scaling(s.scale**depth), s.seed)
    whole, _ = assemble(s, proto, tr)
    return len(proto), len(whole), time.perf_counter() - start


def test_engine_p3(benchmark) -> None:
    n, _ = benchmark.pedantic(run_engine, rounds=3, iterations=1)
    assert n == 832_040


def test_peer_components_p3(benchmark) -> None:
    lab, _ = benchmark.pedantic(lambda: peer_components("penrose-p3", DEPTH), rounds=3, iterations=1)
    assert len(lab) == 832_040


def test_outputs_equal_small() -> None:
    for name, depth in [("penrose-p3", 8), ("penrose-p2", 8), ("ammann-beenker", 4), ("chair", 5), ("hat", 3), ("spectre", 3)]:
        check_equal(tilekit_call(name, depth), peer_components(name, depth))
    tk = tilekit_call("penrose-p3", 8)
    check_equal(tk, draw_as_components(complex_draw("penrose-p3", 8)))


def main_stream(case: str, sink: str, out: str | None, chunk: int) -> None:
    """One stream (or, ``sink='whole'``, the unchunked generation) of a depth-N patch:
    tiles, seconds, tiles/s and the process's peak RSS (ru_maxrss: interpreter, imports and
    all). ``null`` counts the chunks' tiles; ``geojson`` writes them to ``out``."""
    import resource

    from tilekit.export import write_patches
    from tilekit.plugins.substitution.tiling import KeypointTiling

    name, depth_text = case.split(":")
    depth = int(depth_text)
    t = tiling(name).configure(depth=depth)
    list(tiling(name).configure(depth=2).iter_patches(chunk_tiles=64))  # compile and cache first
    rss0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    t0 = time.perf_counter()
    if sink == "whole":  # the unchunked arrays, bypassing the memory refusal (the engine itself)
        if isinstance(t, KeypointTiling):
            n = len(t.system.generate(depth)[1])
        else:
            lam = Affine.scaling(t.system.scale**depth)
            protos, maps = t.seed_cluster()
            parts = [generate(t.system, depth, lam @ m, int(p)) for p, m in zip(protos, maps)]
            n = len(assemble(t.system, np.concatenate([a for a, _ in parts]), np.concatenate([b for _, b in parts]))[0])
    elif sink == "null":
        n = sum(len(p) for p in t.iter_patches(chunk_tiles=chunk))
    else:
        n = write_patches(t.iter_patches(chunk_tiles=chunk), out)
    dt = time.perf_counter() - t0
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    size = f", file {os.path.getsize(out) / 1e9:.2f} GB ({os.path.getsize(out) / n:.0f} bytes/tile)" if out else ""
    print(f"{name} depth {depth} {sink:8s} chunk {chunk:,}: {n:,} tiles in {dt:.1f} s = {n / dt / 1e6:.2f} M tiles/s; "
          f"peak RSS {rss / 1e6:.0f} MB ({(rss - rss0) / n:.1f} bytes/tile over the {rss0 / 1e6:.0f} MB before){size}")


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--big", action="store_true", help="the 10^6-10^7 sizes too")
    ap.add_argument("--memory", action="store_true", help="bytes per tile (tracemalloc peak) instead of speed")
    ap.add_argument("--no-draw", action="store_true")
    ap.add_argument("--api", type=float, metavar="R", help="item 2: assembly and patch((-R, -R, R, R)) instead")
    ap.add_argument("--only", help="comma-separated system names")
    ap.add_argument("--stream", metavar="NAME:DEPTH", help="goal 6: stream the depth-N patch instead")
    ap.add_argument("--sink", choices=["null", "geojson", "whole"], default="null")
    ap.add_argument("--out", help="the GeoJSON file of --sink geojson")
    ap.add_argument("--chunk", type=int, default=1 << 20, help="tiles per chunk of --stream")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    if args.stream:
        main_stream(args.stream, args.sink, args.out, args.chunk)
        return
    cases = CASES + (BIG if args.big else [])
    if args.only:
        cases = [c for c in cases if c[0] in args.only.split(",")]
    if args.api:
        main_api(args.runs, args.api)
    elif args.memory:
        main_memory(cases)
    else:
        main_speed(cases, args.runs, not args.no_draw)
    sys.stdout.flush()


if __name__ == "__main__":
    main()
