"""Wang textures (§7.5): megapixels per second of a 16k x 16k texture from the 8 tiles of
Figure 6.9 at 128 px, against a NumPy peer that pastes the tiles by fancy indexing, and the
peak memory of a streamed 64k x 64k PNG.

Both sides use the same scanline fill (``scanline_fill`` / ``scanline_rows`` with one seed) and
their pixels are checked equal before anything is timed; the PNG files are decoded (Pillow) and
compared. Timings are min / median of ``--runs`` runs in one process, the contenders taking
turns within each round, and each ratio is the median of the rounds' ratios.

    python benchmarks/bench_wang_texture.py                      # pixels (5 runs) and PNG (3 runs), 16k x 16k
    python benchmarks/bench_wang_texture.py --huge 65536         # one 64k x 64k PNG: time, peak RSS
    python benchmarks/bench_wang_texture.py --peer-memory 16384  # the peer's PNG alone: time, peak RSS
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from tilekit.plugins.wang import get_tileset, scanline_fill
from tilekit.plugins.wang.exemplars import example
from tilekit.plugins.wang.synth import render_texture, write_texture
from tilekit.plugins.wang.texture import TextureTiles, make_texture_tiles

TILE = 128


def tiles() -> TextureTiles:
    return make_texture_tiles(example("pebbles", 512, seed=1), get_tileset("stochastic-2colour"), tile=TILE, seed=2)


def peer_paste(tex: TextureTiles, side: int, seed: int, order: str = "gather") -> np.ndarray:
    """What a NumPy user writes: the fill's grid, then every tile's pixels pasted by one fancy
    index. ``gather`` indexes tile pixel rows straight into the output's layout (no transpose);
    ``transpose`` indexes whole tiles and transposes (rows, cols, T, T, 3) into place."""
    n = side // TILE
    grid = scanline_fill(tex.tileset, n, n, seed=seed)
    if order == "transpose":
        return tex.pixels[grid].transpose(0, 2, 1, 3, 4).reshape(side, side, 3)
    return tex.rows[grid[:, None, :], np.arange(TILE)[None, :, None]].reshape(side, side, 3)


def peer_png(tex: TextureTiles, side: int, seed: int, path: Path, level: int) -> None:
    from PIL import Image

    Image.fromarray(peer_paste(tex, side, seed)).save(path, compress_level=level)


def load() -> str:
    return "load average " + " ".join(f"{v:.2f}" for v in os.getloadavg())


def interleaved(rows: list, runs: int) -> list[list[float]]:
    """Seconds of each of ``rows`` (name, fn) over ``runs`` rounds, the rows taking turns within
    a round (A B C A B C ...), so a change of the machine's load touches all alike."""
    times: list[list[float]] = [[] for _ in rows]
    for _ in range(runs):
        for k, (_, fn) in enumerate(rows):
            t = time.perf_counter()
            fn()
            times[k].append(time.perf_counter() - t)
    return times


def report(rows: list, times: list[list[float]], mpx: float, peer: int, sizes: dict | None = None) -> None:
    for k, (name, _) in enumerate(rows):
        ratio = statistics.median(p / t for p, t in zip(times[peer], times[k]))
        extra = f", {sizes[name] / 2**20:.0f} MiB" if sizes and name in sizes else ""
        print(f"  {name}: {min(times[k]):.2f} / {statistics.median(times[k]):.2f} s = "
              f"{mpx / statistics.median(times[k]):.0f} Mpx/s (median){extra}; peer / this, median of pairs: {ratio:.2f}")


def pixels(tex: TextureTiles, side: int, runs: int) -> None:
    mpx = side * side / 1e6
    ours = render_texture(tex, side, side, method="scanline", seed=1)
    for order in ("gather", "transpose"):
        assert (peer_paste(tex, side, 1, order) == ours).all()
    del ours
    print(f"pixels in memory, {side} x {side} ({mpx:.0f} Mpx), {load()}")
    rows = [("tilekit render_texture", lambda: render_texture(tex, side, side, "scanline", 1)),
            ("peer: fill + one gather of tile rows", lambda: peer_paste(tex, side, 1, "gather")),
            ("peer: fill + tiles[grid].transpose", lambda: peer_paste(tex, side, 1, "transpose"))]
    report(rows, interleaved(rows, runs), mpx, peer=1)


def png(tex: TextureTiles, side: int, runs: int, level: int, folder: Path) -> None:
    from PIL import Image

    Image.MAX_IMAGE_PIXELS = None  # our own files, decoded to check them
    mpx = side * side / 1e6
    ours_path, peer_path = folder / "ours.png", folder / "peer.png"
    write_texture(tex, ours_path, side, side, method="scanline", seed=1, level=level)
    peer_png(tex, side, 1, peer_path, level)
    with Image.open(ours_path) as a, Image.open(peer_path) as b:
        assert (np.asarray(a) == np.asarray(b)).all(), "the two PNGs differ"
    print(f"PNG file, {side} x {side}, zlib level {level}, {load()}")
    rows = [("tilekit write_texture, streamed, 1 thread",
             lambda: write_texture(tex, ours_path, side, side, "scanline", 1, level=level, threads=1)),
            ("tilekit write_texture, streamed, 2 threads",
             lambda: write_texture(tex, ours_path, side, side, "scanline", 1, level=level, threads=2)),
            ("peer: paste + Pillow save", lambda: peer_png(tex, side, 1, peer_path, level))]
    times = interleaved(rows, runs)
    sizes = {rows[0][0]: ours_path.stat().st_size, rows[1][0]: ours_path.stat().st_size,
             rows[2][0]: peer_path.stat().st_size}
    report(rows, times, mpx, peer=2, sizes=sizes)
    print(f"  ({load()})")


def huge(tex: TextureTiles, side: int, level: int, threads: int, folder: Path) -> None:
    path = folder / "huge.png"
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print(f"streamed PNG {side} x {side}, zlib level {level}, {threads} thread(s), {load()}")
    t = time.perf_counter()
    info = write_texture(tex, path, side, side, method="scanline", seed=1, level=level, threads=threads)
    dt = time.perf_counter() - t
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print(f"  {dt:.1f} s = {side * side / 1e6 / dt:.0f} Mpx/s; file {info['bytes'] / 2**30:.3f} GiB "
          f"(estimated {info['estimate'] / 2**30:.3f}); peak RSS {peak / 1024:.0f} MiB "
          f"({before / 1024:.0f} MiB before writing); {load()}")
    path.unlink()


def peer_memory(tex: TextureTiles, side: int, level: int, folder: Path) -> None:
    path = folder / "peer.png"
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    t = time.perf_counter()
    peer_png(tex, side, 1, path, level)
    dt = time.perf_counter() - t
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print(f"peer PNG {side} x {side}, zlib level {level}: {dt:.1f} s; peak RSS {peak / 1024:.0f} MiB "
          f"({before / 1024:.0f} MiB before writing); {load()}")
    path.unlink()


def build_parser() -> argparse.ArgumentParser:
    """The command line this benchmark takes (docs/benchmarks.md shows its invocations)."""
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--side", type=int, default=16384)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--png-runs", type=int, default=3)
    ap.add_argument("--level", type=int, default=6)
    ap.add_argument("--huge", type=int, default=0, help="write one streamed PNG of this side instead")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--peer-memory", type=int, default=0, help="write one peer PNG of this side instead")
    ap.add_argument("--folder", default=None, help="where the PNGs go (default: a new private temporary folder)")
    return ap


def main() -> None:
    args = build_parser().parse_args()
    if args.folder:
        run(args, Path(args.folder))
    else:
        with tempfile.TemporaryDirectory(prefix="bench-wang-texture-") as folder:
            run(args, Path(folder))


def run(args: argparse.Namespace, folder: Path) -> None:
    tex = tiles()
    render_texture(tex, 256, 256, "scanline", 1)  # compile the scanline kernel outside the timings
    if args.huge:
        huge(tex, args.huge, args.level, args.threads, folder)
    elif args.peer_memory:
        peer_memory(tex, args.peer_memory, args.level, folder)
    else:
        pixels(tex, args.side, args.runs)
        png(tex, args.side, args.png_runs, args.level, folder)


if __name__ == "__main__":
    main()
