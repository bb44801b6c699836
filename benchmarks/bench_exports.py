"""Patch.adjacency against the strongest simple peer, in one process, on the same patch; and
the exports' memory and speed.

    python benchmarks/bench_exports.py adjacency --tiles 1e5 --runs 3
    python benchmarks/bench_exports.py adjacency --tiles 1e6 --runs 1 --no-peer
    python benchmarks/bench_exports.py memory --tiles 1e5
    python benchmarks/bench_exports.py cut --tiles 1e5 --runs 5

``adjacency``: :meth:`tilekit.Patch.adjacency` (welded vertices, edges split at the vertices
inside them, pairs by packed integer keys) against :func:`shapely_adjacency`, what a Shapely 2
user writes: the tiles' coordinates rounded to 1e-9 (without which float noise
hides shared edges), an STRtree of the boxes, and one vectorised DE-9IM ``relate`` per
candidate pair (touching: interiors disjoint, boundaries meet; edge neighbours: the boundaries
meet in a line). Both give edge and vertex pairs, checked equal every round. Figures are
min and median CPU seconds (``time.process_time``) and wall seconds over the rounds.

``cut``: the cut lines chained into paths (:func:`tilekit.export.cut_paths`, walks that use
each segment once, from the odd-degree vertices first) against ``shapely.line_merge`` of the
same segments (the library call: it merges lines through vertices of degree 2 only), both
checked to draw every segment once: paths (the cutter's head lifts), min / median seconds.

``memory``: tracemalloc peaks per tile of the adjacency, the GeoJSON text, the cut SVG and the
DXF drawing (the figures behind ADJACENCY_BYTES_PER_TILE and MAX_DXF_TILES in tilekit/limits.py).
"""

from __future__ import annotations

import argparse
import io
import os
import statistics
import tempfile
import time
import tracemalloc

import numpy as np
import shapely
import shapely.affinity

import tilekit
from tilekit import export

#: (label, catalogue name): edge-to-edge, then not edge-to-edge.
CASES = [("3.4.6.4 (edge-to-edge)", "3.4.6.4"), ("penrose-p3 rhombs (edge-to-edge)", "penrose-p3"),
         ("chair (not edge-to-edge)", "chair"), ("pentomino-F (not edge-to-edge)", "pentomino-F")]


def patch_with(cat, name: str, tiles: float):
    """A patch of the named tiling over its default region scaled to hold about ``tiles``."""
    tiling = cat.tiling(name)
    region = tiling.default_region()
    est = tiling.estimate_tiles(region)
    region = shapely.affinity.scale(region, (tiles / est) ** 0.5, (tiles / est) ** 0.5)
    patch = tiling.patch(region)
    while len(patch) < 0.8 * tiles:
        region = shapely.affinity.scale(region, 1.2, 1.2)
        patch = tiling.patch(region)
    return patch


def shapely_adjacency(patch) -> tuple[np.ndarray, np.ndarray]:
    """The peer: (edge pairs, vertex pairs) as sorted (k, 2) arrays i < j. Coordinates rounded
    to 1e-9 (without it float noise hides shared edges), candidate pairs by an STRtree of the
    boxes, and ONE vectorised DE-9IM ``relate`` per pair: touching when the interiors are
    disjoint and the boundaries meet, an edge when the boundaries meet in a line (dimension 1).
    (An STRtree ``touches`` query plus the boundary intersection's length gives the same pairs,
    8x slower; ``relate_pattern`` after a ``touches`` query, 1.6x slower.)"""
    g = shapely.transform(patch.geometries(), lambda c: np.round(c, 9))
    i, j = shapely.STRtree(g).query(g)
    keep = i < j
    i, j = i[keep], j[keep]
    m = shapely.relate(g[i], g[j]).astype("U9").view("U1").reshape(-1, 9)
    touch = (m[:, 0] == "F") & (m[:, 4] != "F")
    edge = touch & (m[:, 4] == "1")
    out = []
    for k in (edge, touch & ~edge):
        p = np.column_stack([i[k], j[k]])
        out.append(p[np.lexsort((p[:, 1], p[:, 0]))])
    return out[0], out[1]


def timed(fn, *args):
    c, w = time.process_time(), time.perf_counter()
    out = fn(*args)
    return out, time.process_time() - c, time.perf_counter() - w


def adjacency(cat, tiles: float, runs: int, peer: bool = True) -> None:
    print(f"load: {os.getloadavg()}")
    print("| patch | tiles | split vertices | tilekit CPU s (min / median) | tilekit wall s (min / median) "
          "| peer CPU s (min / median) | peer wall s (min / median) | peer/tilekit CPU (min / median) |")
    print("|---|---|---|---|---|---|---|---|")
    for label, name in CASES:
        patch = patch_with(cat, name, tiles)
        ours, theirs, ratio = [], [], []
        for _ in range(runs):
            patch = tilekit.Patch(patch.prototiles, patch.prototile, patch.transform, patch.colour, patch.aspect)
            adj, c1, w1 = timed(patch.adjacency)
            if peer:
                (edge, vertex), c2, w2 = timed(shapely_adjacency, patch)  # builds geometries itself
                assert np.array_equal(adj.edge, edge), (name, len(adj.edge), len(edge))
                assert np.array_equal(adj.vertex, vertex), (name, len(adj.vertex), len(vertex))
            else:
                c2 = w2 = float("nan")
            ours.append((c1, w1))
            theirs.append((c2, w2))
            ratio.append(c2 / c1)

        def mm(xs):
            return f"{min(xs):.3f} / {statistics.median(xs):.3f}"

        print(f"| {label} | {len(patch):,} | {adj.split:,} | {mm([o[0] for o in ours])} | {mm([o[1] for o in ours])} "
              f"| {mm([t[0] for t in theirs])} | {mm([t[1] for t in theirs])} | {min(ratio):.1f} / {statistics.median(ratio):.1f} |")
    print(f"load: {os.getloadavg()}")


def peak(fn) -> tuple[float, float]:
    """(tracemalloc peak bytes, wall seconds of an untraced run: tracing slows Python code)."""
    w = time.perf_counter()
    fn()
    w = time.perf_counter() - w
    tracemalloc.start()
    fn()
    _, top = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    return top, w


def memory(cat, tiles: float) -> None:
    print(f"load: {os.getloadavg()}")
    print("| patch | tiles | export | peak bytes / tile (tracemalloc) | wall s (untraced) |")
    print("|---|---|---|---|---|")
    tmp = tempfile.mkdtemp()
    for label, name in CASES[:3]:
        patch = patch_with(cat, name, tiles)
        n = len(patch)
        jobs = [
            ("adjacency", lambda patch=patch: patch.adjacency()),
            ("GeoJSON to a file", lambda patch=patch: export.write_text(export.iter_geojson(patch), os.path.join(tmp, "p.geojson"))),
            ("JSON with neighbours to a file", lambda patch=patch: export.write_text(export.iter_json(patch), os.path.join(tmp, "p.json"))),
            ("cut SVG to a file", lambda patch=patch: export.write_text(export.iter_cut_svg(patch), os.path.join(tmp, "p.cut.svg"))),
            ("DXF (ezdxf)", lambda patch=patch: patch.to_dxf(os.path.join(tmp, "p.dxf"))),
            ("plot (one PolyCollection, Agg)", lambda patch=patch: _plot(patch)),
        ]
        for what, fn in jobs:
            top, w = peak(fn)
            print(f"| {label} | {n:,} | {what} | {top / n:,.0f} | {w:.2f} |")
    print(f"load: {os.getloadavg()}")


def cut(cat, tiles: float, runs: int) -> None:
    print(f"load: {os.getloadavg()}")
    print("| patch | tiles | segments | tilekit paths | tilekit s (min / median) | line_merge paths | "
          "line_merge s (min / median) | cut SVG bytes: segments -> paths |")
    print("|---|---|---|---|---|---|---|---|")
    for label, name in CASES:
        patch = patch_with(cat, name, tiles)
        (_, _, segs), = export.cut_segments(patch)
        t_ours, t_peer = [], []
        for _ in range(runs):
            (paths,), cpu, _ = timed(export.cut_paths, patch)
            t_ours.append(cpu)
            merged, cpu, _ = timed(lambda s=segs: shapely.line_merge(shapely.MultiLineString(list(s))))
            t_peer.append(cpu)
        pieces = shapely.get_parts(merged)
        drawn = sum(len(p) - 1 for p in np.split(paths.points, paths.starts[1:-1]))
        peer_drawn = int(sum(shapely.get_num_coordinates(pieces) - 1))
        if drawn != len(segs) or peer_drawn != len(segs) or paths.segments != len(segs):
            raise SystemExit(f"{name}: {drawn} / {peer_drawn} segments drawn, not {len(segs)}")
        before = sum(len(t) for t in _segment_svg(segs))
        after = sum(len(t) for t in export.iter_cut_svg(patch))
        print(f"| {label} | {len(patch):,} | {len(segs):,} | {len(paths):,} | {min(t_ours):.3f} / "
              f"{statistics.median(t_ours):.3f} | {len(pieces):,} | {min(t_peer):.3f} / {statistics.median(t_peer):.3f} "
              f"| {before:,} -> {after:,} |")
    print(f"load: {os.getloadavg()}")


def _segment_svg(segs: np.ndarray):
    """The path data of one ``M a L b`` per segment (the cut SVG before the paths)."""
    for s in range(0, len(segs), 4096):
        flat = segs[s : s + 4096].reshape(-1, 4)
        yield " ".join(["M%.10g %.10g L%.10g %.10g"] * len(flat)) % tuple(flat.reshape(-1).tolist())


def _plot(patch) -> None:
    import matplotlib  # optional dependency (plot extra), only for this row

    matplotlib.use("Agg")
    ax = patch.plot()
    ax.figure.savefig(io.BytesIO(), format="png", dpi=100)


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("what", choices=["adjacency", "memory", "cut"])
    ap.add_argument("--tiles", type=float, default=1e5)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--no-peer", action="store_true", help="time tilekit alone (large patches)")
    ap.add_argument("--catalogue", default=f"sqlite:///{tempfile.gettempdir()}/bench_exports.sqlite")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    cat = tilekit.open_catalogue(args.catalogue)
    if args.what == "adjacency":
        adjacency(cat, args.tiles, args.runs, peer=not args.no_peer)
    elif args.what == "cut":
        cut(cat, args.tiles, args.runs)
    else:
        memory(cat, args.tiles)


if __name__ == "__main__":
    main()
