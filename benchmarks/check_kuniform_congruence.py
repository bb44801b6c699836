"""No two stored k-uniform records are congruent: every pair that shares the cheap invariants
is tested by an isometry search on the laid-out geometry (tilekit.symmetry.congruence, which
does not use the D-symbol), within a time budget.

Run: python benchmarks/check_kuniform_congruence.py CATALOGUE_URL --k 7 [--budget 3600]
The cheap invariants of a record: its wallpaper group (found by tilekit.symmetry when the run
stored it), its multiset of vertex-orbit types and the number of tiles of each size per unit
area (read from the layout). Records that differ in any of them cannot be congruent; every
pair that agrees on all of them is tested. Prints the pairs, the time, and any congruent pair
(a bug: two records for one tiling), and exits 1 if there is one or the budget ran out.
"""

from __future__ import annotations

import argparse
import collections
import itertools
import sys
import time

import numpy as np

from tilekit.catalogue import open_catalogue
from tilekit.plugins.kuniform.search import from_spec
from tilekit.symmetry import congruence


def invariants(tiling, group: str, orbit_types: list) -> tuple:
    """(group, orbit types, tiles of each size per unit area to 6 digits)."""
    area = abs(tiling.v1[0] * tiling.v2[1] - tiling.v1[1] * tiling.v2[0])
    sizes = np.array([len(tiling.prototiles[int(p)].outline) for p in tiling.unit_prototile])
    per_size = tuple((int(s), round(float(np.sum(sizes == s)) / area, 6)) for s in np.unique(sizes))
    return group, tuple(sorted(map(str, orbit_types))), per_size


def build_parser() -> argparse.ArgumentParser:
    """The command line this check takes (docs/benchmarks.md shows its invocation)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("catalogue", help="catalogue URL, e.g. sqlite:////tmp/k7.sqlite")
    ap.add_argument("--k", type=int, required=True)
    ap.add_argument("--budget", type=float, default=3600.0, help="seconds of CPU for the pair tests (default 3600)")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    cat = open_catalogue(args.catalogue)
    records = [r for r in cat.query(family="k-uniform", limit=1_000_000) if r.properties.get("k") == args.k]
    cat.close()
    t0 = time.process_time()
    tilings = [from_spec(r.spec) for r in records]
    by_key = collections.defaultdict(list)
    for i, (r, t) in enumerate(zip(records, tilings)):
        by_key[invariants(t, r.properties["wallpaper_group"], r.properties["orbit_types"])].append(i)
    laid = time.process_time() - t0
    pairs = [p for group in by_key.values() for p in itertools.combinations(group, 2)]
    sizes = collections.Counter(len(g) for g in by_key.values())
    print(f"k = {args.k}: {len(records)} records laid out in {laid:.1f} s CPU; {len(by_key)} invariant classes "
          f"(sizes: {sorted(sizes.items())}); {len(pairs)} pairs share every invariant", flush=True)
    t1 = time.process_time()
    bad = []
    for n, (i, j) in enumerate(pairs, 1):
        if congruence(tilings[i], tilings[j]) is not None or congruence(tilings[j], tilings[i]) is not None:
            bad.append((records[i].name, records[j].name))
            print("CONGRUENT:", records[i].name, "|", records[j].name, flush=True)
        if time.process_time() - t1 > args.budget:
            print(f"budget of {args.budget:g} s CPU spent after {n} of {len(pairs)} pairs", flush=True)
            return 1
        if n % 500 == 0:
            print(f"{n} pairs, {time.process_time() - t1:.1f} s", flush=True)
    print(f"{len(pairs)} pairs tested both ways in {time.process_time() - t1:.1f} s CPU: "
          f"{len(bad)} congruent", flush=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
