"""Wang textures (§7.5): megapixels per second of a 16k x 16k texture from the 8 tiles of
Figure 6.9 at 128 px, against a NumPy peer that pastes the tiles by fancy indexing, and the
peak memory of a streamed 64k x 64k PNG.

Both sides use the same scanline fill (``scanline_fill`` / ``scanline_rows`` with one seed) and
their pixels are checked equal before anything is timed; the PNG files are decoded (Pillow) and
compared. Timings are min / median of ``--runs`` runs in one process.

    python benchmarks/bench_wang_texture.py                      # pixels (5 runs) and PNG (3 runs), 16k x 16k
    python benchmarks/bench_wang_texture.py --huge 65536         # one 64k x 64k PNG: time, peak RSS
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


def timed(fn, runs: int) -> tuple[float, float]:
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times), statistics.median(times)


def load() -> str:
    return "load average " + " ".join(f"{v:.2f}" for v in os.getloadavg())


def pixels(tex: TextureTiles, side: int, runs: int) -> None:
    mpx = side * side / 1e6
    ours = render_texture(tex, side, side, method="scanline", seed=1)
    for order in ("gather", "transpose"):
        assert (peer_paste(tex, side, 1, order) == ours).all()
    del ours
    print(f"pixels in memory, {side} x {side} ({mpx:.0f} Mpx), {load()}")
    rows = [("tilekit render_texture (row blocks into one array)", lambda: render_texture(tex, side, side, "scanline", 1)),
            ("peer: fill + one gather of tile rows", lambda: peer_paste(tex, side, 1, "gather")),
            ("peer: fill + tiles[grid].transpose", lambda: peer_paste(tex, side, 1, "transpose"))]
    for name, fn in rows:
        lo, med = timed(fn, runs)
        print(f"  {name}: {lo:.2f} / {med:.2f} s = {mpx / med:.0f} Mpx/s (median)")


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
    for name, fn in rows:
        lo, med = timed(fn, runs)
        path = peer_path if name.startswith("peer") else ours_path
        print(f"  {name}: {lo:.2f} / {med:.2f} s = {mpx / med:.0f} Mpx/s (median), {path.stat().st_size / 2**20:.0f} MiB")


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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--side", type=int, default=16384)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--png-runs", type=int, default=3)
    ap.add_argument("--level", type=int, default=6)
    ap.add_argument("--huge", type=int, default=0, help="write one streamed PNG of this side instead")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--folder", default=tempfile.gettempdir())
    args = ap.parse_args()
    tex = tiles()
    folder = Path(args.folder)
    render_texture(tex, 256, 256, "scanline", 1)  # compile the scanline kernel outside the timings
    if args.huge:
        huge(tex, args.huge, args.level, args.threads, folder)
        return
    pixels(tex, args.side, args.runs)
    png(tex, args.side, args.png_runs, args.level, folder)


if __name__ == "__main__":
    main()
