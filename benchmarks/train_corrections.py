"""Make the shipped correction table of the penrose sampler (docs/sampling.md, "Correction step").

Ostromoukhov, Donohue and Jodoin displace each sample by a precomputed vector chosen by the
tile's structural context; here the vectors are fitted once by Lloyd relaxation of
uniform-density sets (tilekit.sampling.train_corrections) and written, reviewably, to
catalogue/substitution/sampling/penrose-corrections.csv. Needs the 'sampling' extra.

    python benchmarks/train_corrections.py            # about two minutes on the 2-core dev box
"""

from __future__ import annotations

import time

import numpy as np

from tilekit.plugins.substitution.sampling import CORRECTION_BINS, correction_path
from tilekit.sampling import train_corrections, write_corrections


def main() -> None:
    t0 = time.perf_counter()
    # sizes over a factor phi^2 (one substitution's growth in count), so that the leaves' E =
    # integral / tau sweeps through every bin of (0, 1]
    sizes = np.round(3000 * ((1 + 5**0.5) / 2) ** (2 * np.arange(20) / 20)).astype(int)
    rows = train_corrections("penrose", CORRECTION_BINS, sizes=sizes, seeds=2, iterations=8, per_point=30)
    path = write_corrections(rows, correction_path("penrose"))
    print(f"wrote {path}: {int((rows[:, 4] >= 5).sum())} of {len(rows)} (context, bin) pairs, "
          f"{int(rows[:, 4].sum())} points, {time.perf_counter() - t0:.1f} s")


if __name__ == "__main__":
    main()
