"""The k-uniform search: the D-symbol enumeration per k, with and without its symmetry breaking.

No Python package enumerates k-uniform tilings (the Antwerp library draws them from a
notation; the "k-uniform-solver" script glues tile edges and reports a week of CPU with
duplicates left for a separate pruner). The peer here is the plain D-symbol search:
the same stars, face-first order and checks, but every labelling of every star is tried
(what one writes first; it was tilekit's own first version). Both run in this process on the
same type multisets and must give the same tilings.

Run: python benchmarks/bench_kuniform.py [--k 1 2 3] [--plain-max-k 3] [--layout] [--tes DIR]
(--tes: also check that the search's symbols for each k are exactly those of a tes-catalog
checkout's k-uniform files, read by the plugin's .tes reader)
--profile-run K: the whole run for K through the run layer in this process (executor local, a
scratch SQLite catalogue), under cProfile: wall and CPU seconds and the costliest functions.
--placements K: for every tiling to K, how many placements the GomJau-Hogg writer tries
before it writes a notation (no cap), and the CPU seconds of the ones that fail.
The whole stored run (chunks, records, wallpaper groups) is timed from the shell:
/usr/bin/time tilekit --catalogue sqlite:////tmp/k.sqlite search k-uniform --k 4 --executor process --workers 2
"""

from __future__ import annotations

import argparse
import collections
import cProfile
import itertools
import os
import pstats
import tempfile
import time

from tilekit.plugins.kuniform.dsymbol import (
    DSymbol,
    Star,
    minimal_symbols,
    stabilizer_classes,
    vertex_types,
)
from tilekit.plugins.kuniform.search import chunks, star_rows, tiling_of, tilings_with_types
from tilekit.plugins.kuniform.tescatalog import match_files
from tilekit.regular.notation import VertexType


def enumerate_k(k: int, symmetry_breaking: bool) -> tuple[dict, float]:
    found: dict = {}
    started = time.process_time()
    for chunk in chunks({"k": k}):  # the run's own multisets
        rows = star_rows([VertexType.parse(t).polygons for t in chunk["types"]])
        for _row, sym in minimal_symbols(rows, symmetry_breaking=symmetry_breaking):
            found.setdefault(sym.canonical_form(), sym)
    return found, time.process_time() - started


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--k", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--plain-max-k", type=int, default=3, help="largest k for the plain search")
    ap.add_argument("--layout", action="store_true", help="also time laying every tiling out")
    ap.add_argument("--tes", metavar="DIR", help="a tes-catalog checkout to compare each k's symbols with")
    ap.add_argument("--profile-run", type=int, metavar="K", help="profile the whole run for K (run layer, one process)")
    ap.add_argument("--placements", type=int, metavar="K", help="placements the notation writer needs, k = 1..K")
    return ap


def profile_run(k: int) -> None:
    from tilekit.catalogue import open_catalogue
    from tilekit.search import run_search

    with tempfile.TemporaryDirectory() as tmp:
        cat = open_catalogue(f"sqlite:///{tmp}/k{k}.sqlite")
        prof = cProfile.Profile()
        wall, cpu = time.perf_counter(), time.process_time()
        prof.enable()
        run = run_search(cat, "k-uniform", {"k": k}, executor="local")
        prof.disable()
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        records = list(cat.query(family="k-uniform"))
        print(f"k = {k}: {cat.run(run).summary['found']} tilings, {wall:.1f} s wall, {cpu:.1f} s CPU; "
              f"{sum('gomjau' in r.properties for r in records)} with a GomJau-Hogg notation")
        cat.close()
    pstats.Stats(prof).sort_stats("cumulative").print_stats(25)


def placements(kmax: int) -> None:
    from tilekit.plugins.kuniform import gomjau

    calls = [0]
    inner = gomjau._write_placed

    def counted(*args, **kw):
        calls[0] += 1
        return inner(*args, **kw)

    gomjau._write_placed = counted
    for k in range(1, kmax + 1):
        needed: collections.Counter = collections.Counter()
        for types in itertools.combinations_with_replacement([t.polygons for t in vertex_types()], k):
            if k >= 2 and len(set(types)) == 1:
                continue
            for sym in tilings_with_types(types):
                calls[0] = 0
                started = time.process_time()
                text, why = gomjau.write_outcome(sym, max_placements=None)
                if text is not None:
                    needed[calls[0]] += 1
                else:
                    print(f"k = {k}: none ({why}), {time.process_time() - started:.1f} s CPU")
        print(f"k = {k}: placements tried before a notation was written: {dict(sorted(needed.items()))}")


def main() -> None:
    args = build_parser().parse_args()
    if args.profile_run or args.placements:
        if args.profile_run:
            profile_run(args.profile_run)
        if args.placements:
            placements(args.placements)
        print(f"load average {os.getloadavg()[0]:.2f}")
        return
    print(f"load average {os.getloadavg()[0]:.2f}; stars: {sum(len(stabilizer_classes(t.polygons)) for t in vertex_types())}"
          f" ({Star.__name__} = vertex type x stabilizer class)")
    print("| k | tilings | search CPU s | plain search CPU s | plain / search |" + (" layout CPU s |" if args.layout else ""))
    print("|---|---|---|---|---|" + ("---|" if args.layout else ""))
    for k in args.k:
        found, t = enumerate_k(k, True)
        if k <= args.plain_max_k:
            plain, tp = enumerate_k(k, False)
            assert set(plain) == set(found), "the two searches disagree"
            ratio = f"**{tp / t:.1f}x**"
            tp_text = f"{tp:.2f}"
        else:
            tp_text, ratio = "—", "—"
        row = f"| {k} | {len(found)} | {t:.2f} | {tp_text} | {ratio} |"
        if args.layout:
            started = time.process_time()
            for sym in found.values():
                tiling_of(sym)
            row += f" {time.process_time() - started:.2f} |"
        if args.tes:
            theirs, refused = match_files(args.tes, k)
            ours = {DSymbol.decode(s.encode()).encode() for s in found.values()}
            same = ours == {enc for enc, (kk, _i) in theirs.items() if kk == k} and not refused
            row += f" tes-catalog k = {k}: {sum(1 for kk, _i in theirs.values() if kk == k)} files, " \
                   f"{'the same symbols' if same else 'DIFFERENT'} |"
        print(row, flush=True)
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
