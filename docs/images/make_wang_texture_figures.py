"""Figures and the measures table of docs/families/wang-textures.md: textures from three examples
the project generates itself (noise, pebbles, bricks), cuts against straight seams, repetition
against one tile repeated, and primitives strewn over the plane.

Needs matplotlib (a script-only need) and the 'texture' extra:
    pip install matplotlib 'tilekit[texture]'
    python docs/images/make_wang_texture_figures.py     # writes docs/images/wang-texture-*.png, prints the table
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from tilekit.plugins.wang import get_tileset  # noqa: E402
from tilekit.plugins.wang.exemplars import example  # noqa: E402
from tilekit.plugins.wang.quality import (  # noqa: E402
    autocorrelation,
    cut_error,
    periodic_texture,
    repetition,
    seam_error,
)
from tilekit.plugins.wang.scatter import load_motifs, scatter_points, scatter_svg  # noqa: E402
from tilekit.plugins.wang.synth import render_texture  # noqa: E402
from tilekit.plugins.wang.texture import make_texture_tiles  # noqa: E402
from tilekit.render import write_svg  # noqa: E402

HERE = Path(__file__).parent
ROOT = HERE.parent.parent
KINDS = ("noise", "pebbles", "bricks")
SETS = ("stochastic-2colour", "corner-3colour")
TILE, SIDE, EXAMPLE = 128, 1024, 512


def build(kind: str) -> dict:
    ex = example(kind, EXAMPLE, seed=1)
    out = {"example": ex}
    for name in SETS:
        ts = get_tileset(name)
        cut = make_texture_tiles(ex, ts, tile=TILE, seed=2, tries=8)
        flat = make_texture_tiles(ex, ts, tile=TILE, straight=True, positions=cut.meta["positions"])
        out[name] = {"cut": cut, "flat": flat, "image": render_texture(cut, SIDE, SIDE, seed=3),
                     "flat_image": render_texture(flat, SIDE, SIDE, seed=3)}
    out["periodic"] = periodic_texture(out[SETS[0]]["cut"].pixels[0], SIDE, SIDE)
    return out


def outline(labels: np.ndarray) -> np.ndarray:
    """Pixels where the patch changes (the cuts)."""
    edge = np.zeros(labels.shape, dtype=bool)
    edge[:, 1:] |= labels[:, 1:] != labels[:, :-1]
    edge[1:, :] |= labels[1:, :] != labels[:-1, :]
    return edge


def panels(results: dict) -> None:
    fig, axes = plt.subplots(len(KINDS), 4, figsize=(16, 4.3 * len(KINDS)))
    for r, kind in enumerate(KINDS):
        res = results[kind]
        shown = [(res["example"], f"{kind}: the example (generated)"),
                 (res[SETS[0]]["image"], f"{SETS[0]}: 8 tiles, scanline fill"),
                 (res[SETS[1]]["image"], f"{SETS[1]}: 81 tiles, random access"),
                 (res["periodic"], "one tile repeated (periodic)")]
        for c, (img, title) in enumerate(shown):
            ax = axes[r, c]
            ax.imshow(img[:EXAMPLE, :EXAMPLE], interpolation="nearest")
            ax.set_title(title, fontsize=10)
            ax.set_xticks([])
            ax.set_yticks([])
    fig.suptitle(f"Wang textures from generated examples ({TILE} px tiles; all at the same scale, "
                 f"{EXAMPLE} x {EXAMPLE} px)", fontsize=13)
    fig.tight_layout()
    fig.savefig(HERE / "wang-texture-examples.png", dpi=72)
    plt.close(fig)


def seams(results: dict) -> None:
    res = results["pebbles"]
    fig, axes = plt.subplots(2, 3, figsize=(15, 10.5))
    for r, name in enumerate(SETS):
        cut, flat = res[name]["cut"], res[name]["flat"]
        for c, (tex, label) in enumerate(((flat, "straight seams"), (cut, "minimum-error cuts"))):
            crop = res[name]["flat_image" if tex is flat else "image"][:384, :384]
            axes[r, c].imshow(crop, interpolation="nearest")
            ce = cut_error(tex.pixels, tex.labels)
            axes[r, c].set_title(f"{name}, {label}\nacross a seam {ce['across']:.0f}, "
                                 f"within a patch {ce['within']:.0f}", fontsize=10)
        tiles = cut.pixels[:4].copy()
        for k in range(4):
            tiles[k][outline(cut.labels[k])] = (255, 0, 255)
        grid = np.concatenate([np.concatenate(list(tiles[:2]), axis=1), np.concatenate(list(tiles[2:4]), axis=1)])
        axes[r, 2].imshow(grid, interpolation="nearest")
        axes[r, 2].set_title(f"{name}: tiles 0-3 with their cuts (magenta)", fontsize=10)
        for ax in axes[r]:
            ax.set_xticks([])
            ax.set_yticks([])
    fig.suptitle("Pebbles, the same patches joined by straight seams and by minimum-error cuts\n"
                 "(mean squared colour difference of neighbouring pixels)", fontsize=12)
    fig.tight_layout()
    fig.savefig(HERE / "wang-texture-seams.png", dpi=72)
    plt.close(fig)


def correlations(results: dict) -> None:
    res = results["pebbles"]
    shown = [(res[SETS[0]]["image"], SETS[0]), (res[SETS[1]]["image"], SETS[1]), (res["periodic"], "one tile repeated")]
    fig, axes = plt.subplots(1, 3, figsize=(15, 5.2))
    for ax, (img, title) in zip(axes, shown):
        r = autocorrelation(img, max_lag=SIDE // 4)
        rep = repetition(img, TILE)
        ax.imshow(r, cmap="magma", vmin=-0.2, vmax=1, extent=(-SIDE // 4, SIDE // 4, SIDE // 4, -SIDE // 4))
        ax.set_title(f"{title}: peak {rep['peak']:.2f} at lag {rep['lag']}", fontsize=10)
    fig.suptitle(f"Autocorrelation of {SIDE} px pebble textures (lags up to {SIDE // 4} px; tiles {TILE} px)",
                 fontsize=12)
    fig.tight_layout()
    fig.savefig(HERE / "wang-texture-repetition.png", dpi=72)
    plt.close(fig)


def strewn() -> None:
    motifs = load_motifs(ROOT / "catalogue" / "wang" / "textures" / "scatter-garden.toml")
    pts, ids = scatter_points(0, 0, 900, 450, tile=128, per_tile=12, seed=5)
    write_svg(scatter_svg(pts, ids, 900, 450, 128 / 12**0.5, motifs), HERE / "wang-scatter.png")


def table(results: dict) -> None:
    print("| example | set | seam error across tile edges / inside tiles | cut: across / within a patch "
          "(straight seams) | repetition peak (one tile repeated) |")
    print("|---|---|---|---|---|")
    for kind in KINDS:
        res = results[kind]
        per = repetition(res["periodic"], TILE)["peak"]
        for name in SETS:
            s = seam_error(res[name]["image"], TILE)
            c, f = (cut_error(res[name][k].pixels, res[name][k].labels) for k in ("cut", "flat"))
            rep = repetition(res[name]["image"], TILE)
            print(f"| {kind} | {name} | {s['edge']:.0f} / {s['inside']:.0f} = {s['ratio']:.2f} | "
                  f"{c['across']:.0f} / {c['within']:.0f} ({f['across']:.0f} / {f['within']:.0f}) | "
                  f"{rep['peak']:.2f} ({per:.2f}) |")


def main() -> None:
    results = {kind: build(kind) for kind in KINDS}
    panels(results)
    seams(results)
    correlations(results)
    strewn()
    table(results)


if __name__ == "__main__":
    main()
