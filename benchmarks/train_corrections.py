"""Make the shipped correction tables of the penrose and polyomino samplers (docs/sampling.md).

Ostromoukhov, Donohue and Jodoin (2004), and Ostromoukhov (2007) for polyominoes, displace
each sample by a precomputed vector chosen by the tile's structural context; here the vectors
are fitted once by Lloyd relaxation of uniform-density sets (tilekit.sampling.train_corrections)
and written, reviewably, to catalogue/substitution/sampling/{penrose,polyomino}-corrections.csv.
Needs the 'sampling' extra.

    python benchmarks/train_corrections.py [penrose polyomino]   # ~75 s each on the 2-core dev box
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from tilekit.plugins.substitution.sampling import CORRECTION_BINS, correction_path
from tilekit.sampling import train_corrections, write_corrections

#: The growth of the tile count per substitution: s^2 (phi^2 for the Penrose triangles, 4 for the chair).
GROWTH = {"penrose": ((1 + 5**0.5) / 2) ** 2, "polyomino": 4.0}


def build_parser() -> argparse.ArgumentParser:
    """The command line of this script: the sampling methods to train (default both)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("methods", nargs="*", choices=sorted(GROWTH), default=sorted(GROWTH),
                    metavar="METHOD", help=f"one of {', '.join(sorted(GROWTH))} (default: all)")
    return ap


def main() -> None:
    for method in build_parser().parse_args().methods:
        t0 = time.perf_counter()
        # sizes over one substitution's growth in count, so that the leaves' E = integral / tau
        # sweeps through every bin of (0, 1]
        sizes = np.round(3000 * GROWTH[method] ** (np.arange(20) / 20)).astype(int)
        rows = train_corrections(method, CORRECTION_BINS, sizes=sizes, seeds=2, iterations=8, per_point=30)
        path = write_corrections(rows, correction_path(method))
        print(f"wrote {path}: {int((rows[:, 4] >= 5).sum())} of {len(rows)} (context, bin) pairs, "
              f"{int(rows[:, 4].sum())} points, {time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main()
