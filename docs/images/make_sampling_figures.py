"""Figures and tables of docs/sampling.md: stipple pictures, radially averaged power spectra,
nearest-neighbour spacing, counts and density fidelity of the three samplers and their peers.

Needs matplotlib (a script-only need, not a tilekit dependency) and the 'sampling' extra:
    pip install matplotlib 'tilekit[sampling]'
    python docs/images/make_sampling_figures.py          # writes docs/images/sampling-*.png, prints the tables
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy.stats import qmc  # noqa: E402

from tilekit.density import density_from  # noqa: E402
from tilekit.sampling import density_fidelity, normalised_spacing, radial_power_spectrum, sample  # noqa: E402

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent.parent / "benchmarks"))
from bench_sampling import numpy_dart_throwing  # noqa: E402

#: (method, apply the correction table, Lloyd iterations)
SETS = [("penrose", False, 0), ("penrose", True, 0), ("polyomino", False, 0), ("polyomino", True, 0), ("wang", True, 0)]


def label(method: str, correct: bool, relax: int = 0) -> str:
    text = method + (" + corrections" if correct and method != "wang" else "")
    return text + (f" + {relax} Lloyd" if relax else "")


def source_image() -> Path:
    """A test image for the stipples (drawn here, read back as a PNG like any user's image):
    a dark disc with a bright halo, bright letters, a horizontal gradient underneath."""
    import cairosvg

    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="256" height="256">'
           '<defs><linearGradient id="g"><stop offset="0" stop-color="#000"/><stop offset="1" stop-color="#fff"/>'
           '</linearGradient><radialGradient id="r"><stop offset="0.55" stop-color="#111"/>'
           '<stop offset="0.75" stop-color="#eee"/><stop offset="1" stop-color="#333"/></radialGradient></defs>'
           '<rect width="256" height="256" fill="url(#g)"/><circle cx="128" cy="110" r="95" fill="url(#r)"/>'
           '<text x="128" y="135" font-size="70" font-family="sans-serif" font-weight="bold" fill="#fff" '
           'text-anchor="middle">7.4</text></svg>')
    path = HERE / "sampling-source.png"
    cairosvg.svg2png(bytestring=svg.encode(), write_to=str(path))
    return path


def stipples() -> None:
    image = str(source_image())
    columns = [("ramp", density_from("ramp"), 6000), ("radial", density_from("radial"), 6000),
               ("sampling-source.png", density_from(image), 20000)]
    fig, axes = plt.subplots(len(SETS), len(columns), figsize=(4 * len(columns), 4 * len(SETS)))
    for r, (method, correct, relax) in enumerate(SETS):
        for c, (name, d, n) in enumerate(columns):
            s = sample(d, n, method, seed=1, relax=relax, correct=correct)
            ax = axes[r, c]
            ax.set_xlim(0, 1)
            ax.set_ylim(0, 1)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            ax.set_facecolor("black")
            ax.scatter(s.points[:, 0], s.points[:, 1], s=0.6 if n > 10000 else 1.2, c="w", linewidths=0)
            ax.set_title(f"{label(method, correct, relax)}: {name}, N = {s.count}", fontsize=9)
    fig.tight_layout()
    fig.savefig(HERE / "sampling-stipple.png", dpi=110)
    plt.close(fig)


def peers(n: int, seed: int) -> dict[str, np.ndarray]:
    radius = 0.75 / math.sqrt(n)
    return {
        "uniform random": np.random.default_rng(seed).random((n, 2)),
        "dart throwing (NumPy)": numpy_dart_throwing(n, radius, seed=seed),
        # fill_space: asking random(n) stops Bridson's growing front before the square is full
        "qmc.PoissonDisk (fill)": qmc.PoissonDisk(2, radius=0.775 / math.sqrt(n), seed=seed).fill_space(),
    }


def spectra(n: int = 4096, seeds: int = 5, size: int = 256) -> list[tuple[str, float, float, float]]:
    uniform = density_from("uniform", size=64)
    curves: dict[str, list[np.ndarray]] = {}
    spacing: dict[str, list[tuple[float, float]]] = {}
    freq = None
    for seed in range(seeds):
        sets = {label(m, c, r): sample(uniform, n, m, seed=seed, relax=r, correct=c).points for m, c, r in SETS}
        sets["penrose + corrections + 4 Lloyd"] = sample(uniform, n, "penrose", seed=seed, relax=4).points
        sets.update(peers(n, seed))
        for name, pts in sets.items():
            freq, p = radial_power_spectrum(pts, size=size)
            curves.setdefault(name, []).append(p)
            spacing.setdefault(name, []).append(normalised_spacing(pts))
    fig, ax = plt.subplots(figsize=(8, 5))
    for name, ps in curves.items():
        style = "--" if name in ("uniform random", "dart throwing (NumPy)", "qmc.PoissonDisk (fill)") else "-"
        ax.plot(freq / math.sqrt(n), np.mean(ps, axis=0), style, label=name, linewidth=1.2)
    ax.set_xlabel("radial frequency / sqrt(N)  (1 = the mean spacing's frequency)")
    ax.set_ylabel("radially averaged power (1 = white noise)")
    ax.set_ylim(0, 5)  # the tilings' lattice and quasicrystal peaks go above; the table has the numbers
    ax.set_title(f"Radially averaged power spectrum, uniform density, N = {n}, mean of {seeds} seeds")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(HERE / "sampling-spectrum.png", dpi=110)
    plt.close(fig)
    rows = []
    for name, ps in curves.items():
        low = (freq > 1) & (freq < 0.5 * math.sqrt(n))
        sp = np.array(spacing[name])
        rows.append((name, float(sp[:, 0].min()), float(sp[:, 1].mean()), float(np.mean([p[low].mean() for p in ps]))))
    return rows


def fidelity(n: int = 20000) -> list[tuple[str, str, int, float, int, float]]:
    rows = []
    for spec in ("uniform", "ramp", "radial", "rings"):
        d = density_from(spec)
        for m, c, r in SETS:
            s = sample(d, n, m, seed=3, relax=r, correct=c)
            f = density_fidelity(s.points, d, grid=8)
            rows.append((label(m, c, r), spec, s.count, 100 * (s.count - n) / n, f["dof"], f["chi2"]))
    return rows


def main() -> None:
    stipples()
    print("| points | min NN / sqrt(1/N) (least of 5 seeds) | mean NN / sqrt(1/N) | mean power at 1 < f < sqrt(N)/2 |")
    print("|---|---|---|---|")
    for name, lo, mean, low in spectra():
        print(f"| {name} | {lo:.3f} | {mean:.3f} | {low:.3f} |")
    print("(PoissonDisk fill: N is its own count, about 4096)")
    print()
    print("| method | density | N (asked 20000) | miss | chi2 (dof) on 8 x 8 cells |")
    print("|---|---|---|---|---|")
    for name, spec, count, miss, dof, chi2 in fidelity():
        print(f"| {name} | {spec} | {count} | {miss:+.2f}% | {chi2:.1f} ({dof}) |")


if __name__ == "__main__":
    main()
