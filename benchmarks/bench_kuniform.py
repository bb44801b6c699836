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
The whole stored run (chunks, records, wallpaper groups) is timed from the shell:
/usr/bin/time tilekit --catalogue sqlite:////tmp/k.sqlite search k-uniform --k 4 --executor process --workers 2
"""

from __future__ import annotations

import argparse
import os
import time

from tilekit.plugins.kuniform.dsymbol import (
    DSymbol,
    Star,
    minimal_symbols,
    stabilizer_classes,
    vertex_types,
)
from tilekit.plugins.kuniform.search import chunks, star_rows, tiling_of
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
    return ap


def main() -> None:
    args = build_parser().parse_args()
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
