"""Wang textures (Kaplan §7.5): tiles from an example image (Cohen, Shade, Hiller, Deussen 2003;
corner tiles after Lagae and Dutré 2006), minimum-error cuts (Efros and Freeman 2001), textures
streamed to PNG, random-access windows, primitive distribution, and the measures.

The checks are independent of the code they test where it matters: tile edges are compared with
the example at the patch positions the atlas records (not through the cut's label maps), the
dynamic programme against brute force, PNG files through Pillow and a strict zlib decode.
"""

from __future__ import annotations

import io
import itertools
import struct
import sys
import tracemalloc
import zlib
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit.errors import ParameterError, ParseError
from tilekit.limits import LimitError
from tilekit.plugins.wang import cli as wang_cli
from tilekit.plugins.wang import (
    exemplars,
    get_tileset,
    quality,
    random_access_fill,
    scanline_fill,
    scatter,
    synth,
    texture,
)
from tilekit.plugins.wang.fill import scanline_rows
from tilekit.plugins.wang.sampling import PATCH_POINTS, SEAM_DISTANCE
from tilekit.plugins.wang.tileset import from_corners
from tilekit.pngstream import FILTERS, PngWriter, write_png

PIL = pytest.importorskip("PIL")
from PIL import Image  # noqa: E402

EDGE, CORNER = "stochastic-2colour", "corner-2colour"


def noise_image(size: int, seed: int = 0) -> np.ndarray:
    """Independent random pixels: no two windows agree, so any misplaced pixel is caught."""
    return np.random.default_rng(seed).integers(0, 256, (size, size, 3), dtype=np.uint8)


def decode(data: bytes) -> tuple[dict[bytes, list[bytes]], bytes]:
    """A PNG's chunks by type (every CRC checked) and its IDAT stream inflated by zlib, which
    checks the Adler-32 of the whole stream."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    chunks: dict[bytes, list[bytes]] = {}
    pos = 8
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        (crc,) = struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])
        assert crc == zlib.crc32(body, zlib.crc32(kind))
        chunks.setdefault(kind, []).append(body)
        pos += 12 + n
    assert list(chunks)[0] == b"IHDR" and list(chunks)[-1] == b"IEND"
    return chunks, zlib.decompress(b"".join(chunks[b"IDAT"]))


# ---------------------------------------------------------------------- the PNG writer


@pytest.mark.parametrize("channels", [1, 2, 3, 4])
@pytest.mark.parametrize("threads", [1, 3])
def test_png_rows_round_trip_for_every_filter(channels, threads):
    # PNG specification (ISO/IEC 15948) §9: filter types 0-4; Pillow decodes what we wrote
    rng = np.random.default_rng(channels)
    img = rng.integers(0, 256, (41, 29, channels), dtype=np.uint8)
    img[25:] = img[:16]  # repeated rows, so deflate finds matches across blocks
    for name in FILTERS:
        buf = io.BytesIO()
        with PngWriter(buf, 29, 41, channels, filter=name, threads=threads, text={"Title": "t"}) as png:
            for a, b in ((0, 7), (7, 8), (8, 41)):
                png.write(img[a:b])
        chunks, raw = decode(buf.getvalue())
        rows = np.frombuffer(raw, dtype=np.uint8).reshape(41, 29 * channels + 1)
        if name != "adaptive":
            assert (rows[:, 0] == FILTERS[name]).all()
        got = np.asarray(Image.open(io.BytesIO(buf.getvalue())))
        assert (got.reshape(img.shape) == img).all(), name
        assert chunks[b"tEXt"] == [b"Title\0t"]


@settings(max_examples=40, deadline=None)
@given(h=st.integers(1, 12), w=st.integers(1, 12), channels=st.sampled_from([1, 2, 3, 4]),
       kind=st.sampled_from(sorted(FILTERS)), threads=st.integers(1, 3), level=st.integers(0, 9),
       cuts=st.lists(st.integers(0, 12), max_size=4), seed=st.integers(0, 2**32 - 1))
def test_png_round_trips_any_block_split(h, w, channels, kind, threads, level, cuts, seed):
    img = np.random.default_rng(seed).integers(0, 256, (h, w, channels), dtype=np.uint8)
    edges = sorted({0, h, *(c for c in cuts if c < h)})
    buf = io.BytesIO()
    with PngWriter(buf, w, h, channels, level=level, filter=kind, threads=threads) as png:
        for a, b in zip(edges, edges[1:]):
            png.write(img[a:b])
    _, raw = decode(buf.getvalue())
    assert len(raw) == h * (w * channels + 1)
    assert (np.asarray(Image.open(io.BytesIO(buf.getvalue()))).reshape(img.shape) == img).all()


def test_png_none_filter_stores_the_bytes():
    # filter type 0 (None): each row is its type byte followed by the raw bytes
    img = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)
    buf = io.BytesIO()
    write_png(buf, img, filter="none")
    _, raw = decode(buf.getvalue())
    assert raw == b"\0" + img[0].tobytes() + b"\0" + img[1].tobytes()


def test_png_writer_refuses_wrong_rows_and_removes_unfinished_files(tmp_path):
    path = tmp_path / "x.png"
    with pytest.raises(ParameterError, match="closed after 1 rows"):
        with PngWriter(path, 4, 3) as png:
            png.write(np.zeros((1, 4, 3), dtype=np.uint8))
            png.close()
    assert not path.exists()
    with pytest.raises(ParameterError, match="4 rows written to a PNG 3 rows high"):
        with PngWriter(path, 4, 3) as png:
            png.write(np.zeros((4, 4, 3), dtype=np.uint8))
    assert not path.exists()
    with pytest.raises(ParameterError, match=r"\(k, 4, 3\) uint8"):
        with PngWriter(path, 4, 3) as png:
            png.write(np.zeros((1, 5, 3), dtype=np.uint8))
    for bad in ({"width": 0}, {"channels": 5}, {"level": 10}, {"filter": "best"}, {"threads": -1}):
        args = {"width": 4, "height": 3, "channels": 3} | {k: v for k, v in bad.items() if k in ("width", "channels")}
        opts = {k: v for k, v in bad.items() if k not in ("width", "channels")}
        with pytest.raises(ParameterError):
            PngWriter(io.BytesIO(), args["width"], args["height"], args["channels"], **opts)


# ---------------------------------------------------------------------- the cut


def brute_force(cost: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> float:
    rows, width = cost.shape
    band = (width - 1) // 2
    best = np.inf
    for path in itertools.product(*[range(int(a), int(b) + 1) for a, b in zip(lo, hi)]):
        if all(abs(path[i + 1] - path[i]) <= 1 for i in range(rows - 1)):
            best = min(best, sum(cost[r, s + band] for r, s in enumerate(path)))
    return best


@pytest.mark.parametrize("length,band,start", [(5, 2, 0), (7, 3, 1), (8, 2, 1), (7, 1, 0), (6, 3, 0)])
def test_min_error_paths_equal_brute_force(length, band, start):
    # Efros and Freeman's cut: the least total error over all paths that move at most one
    # column a row, within the wedge; checked against every path
    rng = np.random.default_rng(length * 10 + band)
    cost = rng.random((6, length, 2 * band + 1))
    lo, hi = texture.wedge(length, band, start)
    paths, best = texture.min_error_paths(cost, lo, hi)
    for m in range(6):
        assert best[m] == pytest.approx(brute_force(cost[m], lo, hi))
        s = paths[m]
        assert s[0] == 0 and s[-1] == 0 and (np.abs(np.diff(s)) <= 1).all()
        assert (s >= lo).all() and (s <= hi).all()
        assert cost[m, np.arange(length), s + band].sum() == pytest.approx(best[m])


def test_wedge_keeps_the_ends_and_the_edges():
    lo, hi = texture.wedge(10, 4, start=1)
    assert lo[0] == hi[0] == 0 and lo[-1] == hi[-1] == 0
    assert (hi <= np.minimum(4, np.arange(10))).all()
    assert (np.arange(1, 10) + lo[1:] >= 1).all()  # boundary column >= 1: the W edge's pixels stay W


# ---------------------------------------------------------------------- tiles from an example


def fill_grid(tex, rows, cols, seed, method):
    ts = tex.tileset
    if method == "scanline":
        return scanline_fill(ts, rows, cols, seed=seed)
    return random_access_fill(ts, rows, cols, x0=0, y0=-rows, seed=seed)


def source_position(tex, key):
    return np.array(tex.meta["positions"][tex.meta["sources"].index(key)])


@pytest.mark.parametrize("name,method,band", [(EDGE, "scanline", None), (CORNER, "random-access", None),
                                              (CORNER, "random-access", 0), (EDGE, "scanline", 0)])
def test_tile_edges_are_neighbouring_pixels_of_one_patch(name, method, band):
    # Cohen et al. (edge tiles) and Lagae-Dutre (corner tiles): the pixels on both sides of every
    # tile edge in the texture are two neighbouring rows (or columns) of the example, read at the
    # patch positions the atlas records; edge tiles may differ only at the tile corners (the
    # corner problem), corner tiles nowhere
    t, rows, cols, seed = 32, 5, 6, 4
    ex = noise_image(200, 1)
    ts = get_tileset(name)
    tex = texture.make_texture_tiles(ex, ts, tile=t, band=band, seed=2, tries=3)
    img = synth.render_texture(tex, cols * t, rows * t, method=method, seed=seed)
    grid = fill_grid(tex, rows, cols, seed, method)
    assert (img.reshape(rows, t, cols, t, 3).transpose(0, 2, 1, 3, 4) == tex.pixels[grid]).all()
    h, b = t // 2, tex.meta["band"]
    c = np.arange(t)
    inner = slice(1, t - 1) if ts.kind == "edge" else slice(0, t)
    for i, j in itertools.product(range(rows), range(cols)):
        y, x = i * t, j * t
        if i > 0:  # the edge between this tile (below) and the one above
            if ts.kind == "edge":
                wy, wx = source_position(tex, f"h:{ts.tiles[grid[i, j], 0]}")
                below, above = ex[wy + h, wx + c], ex[wy + h - 1, wx + c]
            else:
                k_nw, k_ne = ts.corners[grid[i, j], 3], ts.corners[grid[i, j], 0]
                (py, px), (qy, qx) = (source_position(tex, f"c:{k}") + h + b for k in (k_nw, k_ne))
                a, z = c[:h], c[h:]  # the west half from the NW corner's patch, the east from the NE's
                below = np.concatenate([ex[py, px + a], ex[qy, qx - t + z]])
                above = np.concatenate([ex[py - 1, px + a], ex[qy - 1, qx - t + z]])
            assert (img[y, x + c][inner] == below[inner]).all()
            assert (img[y - 1, x + c][inner] == above[inner]).all()
        if j > 0:  # the edge between this tile (right) and the one to its left
            if ts.kind == "edge":
                wy, wx = source_position(tex, f"v:{ts.tiles[grid[i, j], 3]}")
                right, left_px = ex[wy + c, wx + h], ex[wy + c, wx + h - 1]
            else:
                k_nw, k_sw = ts.corners[grid[i, j], 3], ts.corners[grid[i, j], 2]
                (py, px), (qy, qx) = (source_position(tex, f"c:{k}") + h + b for k in (k_nw, k_sw))
                a, z = c[:h], c[h:]  # the north half from the NW corner's patch, the south from the SW's
                right = np.concatenate([ex[py + a, px], ex[qy - t + z, qx]])
                left_px = np.concatenate([ex[py + a, px - 1], ex[qy - t + z, qx - 1]])
            assert (img[y + c, x][inner] == right[inner]).all()
            assert (img[y + c, x - 1][inner] == left_px[inner]).all()


def test_edge_tile_corner_pixel_comes_from_one_of_its_two_edges():
    # the corner problem at pixel scale: the corner pixel belongs to the N (or S) patch
    ts = get_tileset(EDGE)
    tex = texture.make_texture_tiles(noise_image(160, 3), ts, tile=16, seed=1, tries=2)
    for lab in tex.labels:
        assert lab[0, 0] == lab[0, -1] == 0 and lab[-1, 0] == lab[-1, -1] == 2  # N, N, S, S


@pytest.mark.parametrize("name,band", [(EDGE, None), (CORNER, 16)])
def test_a_periodic_example_gives_the_periodic_texture(name, band):
    # known answer: an example of period T/2 with patches on a lattice of spacing T/2 (corner
    # patches: T with band T/2) makes every label show the same image, so the texture is the
    # example's period shifted by the patches' common offset, and every cut costs nothing
    t = 32
    cell = noise_image(t // 2, 7)
    ex = np.tile(cell, (10, 10, 1))
    tex = texture.make_texture_tiles(ex, get_tileset(name), tile=t, band=band, seed=5, tries=2)
    oy, ox = np.array(tex.meta["positions"][0]) % (t // 2)
    img = synth.render_texture(tex, 5 * t, 3 * t, seed=1)
    yy, xx = np.mgrid[0:3 * t, 0:5 * t]
    assert (img == cell[(yy + oy) % (t // 2), (xx + ox) % (t // 2)]).all()
    assert tex.meta["cut_error"] == 0 == tex.meta["straight_error"]


def seam_cost_from_labels(tex, ex):
    """The error of every tile's seams recomputed from its label map: in each seam's frame, each
    row's boundary is where the right label starts, and the cost is the squared colour
    difference of the two patches at the pixels on both sides of it (inside the region)."""
    ts, t = tex.tileset, tex.tile
    h, band = t // 2, tex.meta["band"]
    keys, use = texture.tile_sources(ts)
    offsets = texture.label_offsets(ts, t, band, np.array(tex.meta["positions"]))
    seams = texture.EDGE_SEAMS if ts.kind == "edge" else texture.CORNER_SEAMS
    total = np.zeros(len(ts))
    r = np.arange(t)
    exf = ex.astype(np.float64)
    for spec in seams:
        frame, right, left = spec[:3]
        inclusive = spec[3] if len(spec) > 3 else True
        base, first, last = texture._seam_region(t, ts.kind, inclusive)
        lab = texture._FRAMES[frame](tex.labels)
        for k in range(len(ts)):
            imgs = []
            for label in (right, left):
                dy, dx = offsets[use[k, label], label]
                ys = np.clip(r + dy, 0, ex.shape[0] - 1)
                xs = np.clip(r + dx, 0, ex.shape[1] - 1)
                imgs.append(texture._FRAMES[frame](exf[ys[:, None], xs[None, :]][None])[0])
            e = ((imgs[0] - imgs[1]) ** 2).sum(axis=-1)
            for row in range(h):
                cols = np.arange(first[row], last[row] + 1)
                is_right = lab[k, row, cols] == right
                assert (lab[k, row, cols] == np.where(is_right, right, left)).all()
                assert (np.diff(is_right.astype(int)) >= 0).all(), "one boundary a row"
                bnd = cols[np.argmax(is_right)] if is_right.any() else last[row] + 1
                total[k] += sum(e[row, cc] for cc in (bnd - 1, bnd) if first[row] <= cc <= last[row])
    return total


@pytest.mark.parametrize("name,kind,seed", [(EDGE, "pebbles", 0), (EDGE, "noise", 3), (CORNER, "bricks", 1),
                                            (CORNER, "pebbles", 2)])
def test_the_cut_costs_no_more_than_the_straight_seam(name, kind, seed):
    # the straight seam is one of the paths the dynamic programme searches, so the least-error
    # cut never costs more: recomputed tile by tile from the label maps
    ex = exemplars.example(kind, 160, seed)
    ts = get_tileset(name)
    cut = texture.make_texture_tiles(ex, ts, tile=32, seed=seed, tries=1)
    flat = texture.make_texture_tiles(ex, ts, tile=32, seed=seed, tries=1, straight=True)
    assert cut.meta["positions"] == flat.meta["positions"]
    a, b = seam_cost_from_labels(cut, ex), seam_cost_from_labels(flat, ex)
    assert (a <= b + 1e-6).all()
    assert a.sum() < b.sum()
    assert cut.meta["cut_error"] <= cut.meta["straight_error"] == pytest.approx(flat.meta["straight_error"])


def test_straight_seams_are_the_diagonals_and_midlines():
    # edge tiles: each pixel belongs to its nearest edge (diagonals to N and S); corner tiles:
    # to its quadrant's corner
    t = 16
    r, c = np.mgrid[0:t, 0:t]
    edge = texture.make_texture_tiles(noise_image(64), get_tileset(EDGE), tile=t, straight=True, tries=1)
    dist = np.stack([r, t - 1 - c, t - 1 - r, c])  # to N, E, S, W
    nearest = np.where(np.minimum(dist[0], dist[2]) <= np.minimum(dist[1], dist[3]),
                       np.where(dist[0] <= dist[2], 0, 2), np.where(dist[1] < dist[3], 1, 3))
    assert (edge.labels == nearest).all()
    corner = texture.make_texture_tiles(noise_image(64), get_tileset(CORNER), tile=t, straight=True, tries=1)
    quadrant = np.where(r < t // 2, np.where(c < t // 2, 3, 0), np.where(c < t // 2, 2, 1))  # NW NE / SW SE
    assert (corner.labels == quadrant).all()


def test_corner_3colour_has_every_colouring_once():
    # Lagae and Dutre's complete corner set over k colours: one tile per colouring, k^4 = 81
    ts = get_tileset("corner-3colour")
    assert len(ts) == 81 and len({tuple(r) for r in ts.corners.tolist()}) == 81
    assert ts.corner_complete and synth.choose_method(ts) == "random-access"


def test_given_positions_rebuild_the_same_tiles():
    ex = noise_image(160, 4)
    a = texture.make_texture_tiles(ex, get_tileset(CORNER), tile=16, seed=3, tries=4)
    b = texture.make_texture_tiles(ex, get_tileset(CORNER), tile=16, positions=a.meta["positions"])
    assert (a.pixels == b.pixels).all()
    with pytest.raises(ParameterError, match="positions must be 2"):
        texture.make_texture_tiles(ex, get_tileset(CORNER), tile=16, positions=[[0, 0], [150, 0]])


def test_atlas_round_trip(tmp_path):
    tex = texture.make_texture_tiles(exemplars.example("noise", 128), get_tileset(CORNER), tile=16, tries=2)
    path = tex.save(tmp_path / "a.png")
    back = texture.load_texture_tiles(path)
    assert (back.pixels == tex.pixels).all() and back.tileset.to_json() == tex.tileset.to_json()
    assert back.meta == tex.meta and back.tile == 16
    assert np.asarray(Image.open(path)).shape == (4 * 16, 4 * 16, 3)  # 16 tiles in 4 columns


@pytest.mark.parametrize("text,fragment", [
    (None, "has no 'tilekit-wang-texture' text chunk"),
    ("{not json", "chunk is malformed"),
    ('{"version": 1, "tile": 16}', "chunk is malformed"),
    ('{"version": 2, "tile": 16, "columns": 4, "set": SET}', "format version 2"),
    ('{"version": 1, "tile": 32, "columns": 4, "set": SET}', "do not fit its 64 x 64 pixels"),
    ('{"version": 1, "tile": 16, "columns": 4, "set": {"name": "x"}}', "chunk is malformed"),
])
def test_malformed_atlases_are_refused(tmp_path, text, fragment):
    import json

    chunk = None if text is None else text.replace("SET", json.dumps(get_tileset(CORNER).to_json()))
    path = tmp_path / "atlas.png"
    write_png(path, noise_image(64), text=None if chunk is None else {texture.ATLAS_KEY: chunk})
    with pytest.raises(ParseError, match=fragment):
        texture.load_texture_tiles(path)


def test_more_tiles_than_patches_share_patches():
    # a tile's content depends only on its colours: tiles with the same (N, W) colours have the
    # same NW quadrant (Cohen et al.'s construction)
    tex = texture.make_texture_tiles(noise_image(200), get_tileset(EDGE), tile=16, tries=1)
    ts, h = tex.tileset, 8
    for a, b in itertools.combinations(range(len(ts)), 2):
        if ts.tiles[a, 0] == ts.tiles[b, 0] and ts.tiles[a, 3] == ts.tiles[b, 3]:
            assert (tex.pixels[a, :h, :h] == tex.pixels[b, :h, :h]).all()


# ---------------------------------------------------------------------- synthesis


@pytest.fixture(scope="module")
def corner_tex():
    return texture.make_texture_tiles(exemplars.example("pebbles", 192, 2), get_tileset(CORNER), tile=32, tries=2)


@pytest.fixture(scope="module")
def edge_tex():
    return texture.make_texture_tiles(exemplars.example("noise", 160, 1), get_tileset(EDGE), tile=24, tries=2)


@pytest.mark.parametrize("x0,y0,w,h", [(0, 0, 50, 40), (-77, 13, 130, 61), (31, -32, 1, 1),
                                       (2**40 + 5, -(2**40) - 3, 70, 45)])
def test_a_window_equals_the_same_window_of_a_full_render(corner_tex, x0, y0, w, h):
    # Lagae and Dutre's random access: a window computed alone equals, pixel for pixel, the same
    # window of a larger render with the same seed
    big = synth.render_texture(corner_tex, w + 100, h + 90, method="random-access", seed=9, x0=x0 - 37, y0=y0 - 50)
    alone = synth.texture_window(corner_tex, x0, y0, w, h, seed=9)
    assert (alone == big[50:50 + h, 37:37 + w]).all()


def test_streamed_scanline_rows_equal_the_whole_fill():
    ts = get_tileset(EDGE)
    whole = scanline_fill(ts, 41, 17, seed=8)
    for block in (1, 5, 41, 100):
        assert (np.concatenate(list(scanline_rows(ts, 41, 17, seed=8, block=block))) == whole).all()


@pytest.mark.parametrize("method,x0,y0", [("scanline", 0, 0), ("random-access", -45, 1000)])
def test_streamed_png_equals_the_render(tmp_path, edge_tex, corner_tex, method, x0, y0, monkeypatch):
    tex = edge_tex if method == "scanline" else corner_tex
    w, h = 157, 203
    want = synth.render_texture(tex, w, h, method=method, seed=3, x0=x0, y0=y0)
    monkeypatch.setattr(synth, "CHUNK_BYTES", 5000)  # blocks of a few rows, inside and across tiles
    for threads in (1, 2):
        out = tmp_path / f"t{threads}.png"
        info = synth.write_texture(tex, out, w, h, method=method, seed=3, x0=x0, y0=y0, threads=threads)
        assert (np.asarray(Image.open(out)) == want).all()
        assert info["bytes"] == out.stat().st_size
    blocks = list(synth.texture_rows(tex, w, h, method, 3, x0, y0, chunk_bytes=5000))
    assert len(blocks) > 10 and (np.concatenate(blocks) == want).all()


def test_memory_does_not_grow_with_the_height(tmp_path, edge_tex, monkeypatch):
    # streamed in blocks: the peak of Python-tracked memory (NumPy included) while writing a
    # texture 10 times taller stays the same (blocks of 256 KiB and IDAT chunks of 64 KiB, so
    # both heights take many)
    import tilekit.pngstream

    monkeypatch.setattr(synth, "CHUNK_BYTES", 1 << 18)
    monkeypatch.setattr(tilekit.pngstream, "IDAT_BYTES", 1 << 16)
    peaks = []
    for height in (3_000, 30_000):
        tracemalloc.start()
        synth.write_texture(edge_tex, tmp_path / "tall.png", 600, height, seed=1)
        peaks.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()
    assert peaks[1] < 1.2 * peaks[0] + (1 << 20)


def test_scanline_refuses_a_window_and_sets_without_a_fill(edge_tex, corner_tex):
    with pytest.raises(ParameterError, match="needs a set with random access"):
        synth.render_texture(edge_tex, 10, 10, x0=5)
    jr = texture.make_texture_tiles(noise_image(128), get_tileset("jeandel-rao"), tile=8, tries=1)
    with pytest.raises(ParameterError, match="complete edge set"):
        synth.render_texture(jr, 10, 10)
    with pytest.raises(ParameterError, match="it can use random-access"):
        synth.render_texture(corner_tex, 10, 10, method="scanline")
    with pytest.raises(ParameterError, match="width 0"):
        synth.render_texture(corner_tex, 0, 10)


def test_disk_estimate_refuses_before_the_file_is_made(tmp_path, corner_tex, monkeypatch):
    class Usage:
        free = 10_000

    monkeypatch.setattr(synth.shutil, "disk_usage", lambda folder: Usage)
    out = tmp_path / "big.png"
    with pytest.raises(LimitError, match=r"big.png would take about .* GiB .* free in"):
        synth.write_texture(corner_tex, out, 4000, 4000)
    assert not out.exists()


# ---------------------------------------------------------------------- measures


def test_autocorrelation_is_pearsons_r_over_the_overlap():
    img = np.random.default_rng(2).random((20, 24))
    r = quality.autocorrelation(img, max_lag=6)
    x = img - img.mean()
    for dy, dx in ((0, 0), (3, -2), (-6, 6), (5, 1)):
        a = x[max(0, -dy):20 - max(0, dy), max(0, -dx):24 - max(0, dx)]
        b = x[max(0, dy):20 + min(0, dy), max(0, dx):24 + min(0, dx)]
        want = (a * b).sum() / np.sqrt((a * a).sum() * (b * b).sum())
        assert r[6 + dy, 6 + dx] == pytest.approx(want, abs=1e-9)


def test_a_periodic_tiling_of_one_tile_repeats_perfectly(edge_tex):
    # the yardstick: one tile repeated has autocorrelation 1 at the lag of one tile;
    # the Wang texture of the same tiles repeats less
    t = edge_tex.tile
    periodic = quality.periodic_texture(edge_tex.pixels[0], 240, 240)
    rep = quality.repetition(periodic, t)
    assert rep["peak"] == pytest.approx(1.0) and max(abs(v) for v in rep["lag"]) == t
    wang = synth.render_texture(edge_tex, 240, 240, seed=2)
    assert quality.repetition(wang, t)["peak"] < 0.9


def test_seam_stats_streamed_equal_one_pass(edge_tex):
    img = synth.render_texture(edge_tex, 100, 90, seed=5)
    whole = quality.seam_error(img, edge_tex.tile)
    s = quality.SeamStats(edge_tex.tile)
    for a in range(0, 90, 7):
        s.feed(img[a:a + 7], a)
    assert s.result() == pytest.approx(whole)
    # 100 x 90 pixels: 89 x 100 vertical and 90 x 99 horizontal pairs; tile edges at 24, 48, 72
    assert whole["edge_pairs"] == 3 * 100 + 4 * 90 and whole["edge_pairs"] + whole["inside_pairs"] == 89 * 100 + 90 * 99


def test_cut_error_counts_pairs_across_labels():
    pixels = np.zeros((1, 4, 4, 3), dtype=np.uint8)
    pixels[0, :, 2:] = 10
    labels = np.zeros((1, 4, 4), dtype=np.int8)
    labels[0, :, 2:] = 1
    res = quality.cut_error(pixels, labels)
    assert res["cut_pairs"] == 4 and res["across"] == 100.0 and res["within"] == 0.0


# ---------------------------------------------------------------------- primitive distribution


def test_scatter_windows_agree_and_points_are_well_spaced():
    pts, ids = scatter.scatter_points(-300, 40, 700, 500, tile=50, per_tile=12, seed=4)
    sub, sub_ids = scatter.scatter_points(-123, 211, 200, 150, tile=50, per_tile=12, seed=4)
    m = (pts[:, 0] >= -123) & (pts[:, 0] < 77) & (pts[:, 1] >= 211) & (pts[:, 1] < 361)
    ka, kb = np.lexsort(pts[m].T), np.lexsort(sub.T)
    assert np.array_equal(pts[m][ka], sub[kb]) and np.array_equal(ids[m][ka], sub_ids[kb])
    # about per_tile points a tile, none closer than the sampler's seam distance (its tiles drop
    # points nearer than SEAM_DISTANCE / sqrt(PATCH_POINTS) tiles across a seam; across a tile
    # edge both points come from one best-candidate patch)
    assert len(pts) / (700 * 500 / 50**2) == pytest.approx(12, rel=0.1)
    d = np.sqrt(((pts[:, None] - pts[None]) ** 2).sum(-1))
    np.fill_diagonal(d, np.inf)
    assert d.min() >= SEAM_DISTANCE / np.sqrt(PATCH_POINTS) * 50
    assert len(set(ids.tolist())) == len(ids)


def test_scatter_refuses_bad_parameters():
    with pytest.raises(ParameterError, match="points per tile"):
        scatter.scatter_points(0, 0, 10, 10, per_tile=PATCH_POINTS + 1)
    with pytest.raises(LimitError, match="points"):
        scatter.scatter_points(0, 0, 65536, 65536, tile=2, per_tile=64)


# ---------------------------------------------------------------------- examples and bad input


@pytest.mark.parametrize("kind", exemplars.KINDS)
def test_examples_are_repeatable_images(kind):
    a, b, c = (exemplars.example(kind, 64, s) for s in (1, 1, 2))
    assert a.shape == (64, 64, 3) and a.dtype == np.uint8
    assert (a == b).all() and (a != c).any() and a.std() > 5


def test_tiny_or_broken_examples_are_refused(tmp_path):
    ts = get_tileset(EDGE)
    with pytest.raises(ParameterError, match=r"too small for 4 patches of 64 x 64 pixels.*at least 96 x 96"):
        texture.make_texture_tiles(noise_image(90), ts, tile=64)
    with pytest.raises(ParameterError, match="even number of pixels"):
        texture.make_texture_tiles(noise_image(100), ts, tile=33)
    text = tmp_path / "x.png"
    text.write_text("not an image")
    with pytest.raises(ParseError, match="cannot be read as an image"):
        texture.read_image(text)
    with pytest.raises(ParseError, match="not a regular file"):
        texture.read_image(tmp_path)
    with pytest.raises(ParseError, match="cannot be read"):
        texture.read_image(tmp_path / "missing.png")


def test_atlas_limit_counts_every_tile():
    big = from_corners("c4", list(itertools.product(range(4), repeat=4)))  # 256 tiles
    with pytest.raises(LimitError, match="atlas pixels"):
        texture.check_tile_size(1024, big)
    assert texture.check_tile_size(512, big) == 512


def test_missing_pillow_names_the_extra(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "PIL", None)
    with pytest.raises(ParameterError, match=r"tilekit\[texture\]"):
        texture.read_image(Path(__file__))


def run(*args: str):
    from tilekit.cli import cli

    return CliRunner().invoke(cli, list(args))


def one_line_error(result, fragment: str) -> str:
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr
    assert fragment in lines[0], lines[0]
    return lines[0]


def test_cli_example_texture_synth_scatter(tmp_path):
    ex, tiles, out = tmp_path / "ex.png", tmp_path / "tiles.png", tmp_path / "out.png"
    assert run("wang", "example", "pebbles", "--size", "160", "-o", str(ex)).exit_code == 0
    r = run("wang", "texture", str(ex), "--tile", "32", "-o", str(tiles))
    assert r.exit_code == 0, r.output
    assert "8 tiles of 32 x 32 px" in r.stdout and "x the straight seams'" in r.stdout
    r = run("wang", "synth", str(tiles), "--width", "100", "--height", "70", "--stats", "-o", str(out))
    assert r.exit_code == 0, r.output
    assert "scanline fill" in r.stdout and "seam error" in r.stdout and "repetition" in r.stdout
    assert np.asarray(Image.open(out)).shape == (70, 100, 3)
    svg = tmp_path / "s.svg"
    motifs = Path(__file__).parents[2] / "catalogue" / "wang" / "textures" / "scatter-garden.toml"
    r = run("wang", "scatter", "--width", "300", "--height", "200", "--motifs", str(motifs), "-o", str(svg))
    assert r.exit_code == 0, r.output
    assert svg.read_text().count("<use ") == int(r.stdout.split("(")[1].split()[0].replace(",", ""))


@pytest.mark.parametrize("args,fragment", [
    (["texture", "{text}", "-o", "{out}"], "cannot be read as an image"),
    (["texture", "{dir}", "-o", "{out}"], "is a directory"),
    (["texture", "{tiny}", "-o", "{out}"], "too small for 4 patches"),
    (["texture", "{tiny}", "--tile", "4096", "-o", "{out}"], "4096 is out of range 8..1024"),
    (["texture", "{tiny}", "--tile", "33", "-o", "{out}"], "must be even"),
    (["texture", "{tiny}", "--set", "nope", "-o", "{out}"], "unknown Wang tile set 'nope'"),
    (["texture", "{tiny}", "-o", "{dir}/x.svg"], "must end in .png"),
    (["synth", "{text}", "--width", "10", "--height", "10", "-o", "{out}"], "cannot be read as an image"),
    (["synth", "{tiny}", "--width", "10", "--height", "10", "-o", "{out}"], "has no 'tilekit-wang-texture'"),
    (["synth", "{tiny}", "--width", "70000", "--height", "10", "-o", "{out}"], "70000 is out of range 1..65536"),
    (["example", "marble", "-o", "{out}"], "'marble' is not one of"),
    (["scatter", "--per-tile", "65", "-o", "{out}"], "65 is out of range 1..64"),
])
def test_cli_bad_input_is_one_line(tmp_path, args, fragment):
    text = tmp_path / "text.png"
    text.write_text("hello")
    tiny = tmp_path / "tiny.png"
    Image.fromarray(noise_image(40)).save(tiny)
    out = tmp_path / "o.png"
    filled = [a.format(text=text, dir=tmp_path, tiny=tiny, out=out) for a in args]
    one_line_error(run("wang", *filled), fragment)
    assert not out.exists()


def test_cli_synth_over_the_free_disk_is_one_line(tmp_path, corner_tex, monkeypatch):
    class Usage:
        free = 50_000

    tiles = corner_tex.save(tmp_path / "tiles.png")
    monkeypatch.setattr(synth.shutil, "disk_usage", lambda folder: Usage)
    out = tmp_path / "big.png"
    one_line_error(run("wang", "synth", str(tiles), "--width", "30000", "--height", "30000", "-o", str(out)),
                   "free in")
    assert not out.exists()


def test_cli_copies_of_the_library_constants_agree():
    assert wang_cli.SYNTH_METHODS == synth.METHODS
    assert wang_cli.MAX_TEXTURE_SIDE == synth.MAX_SIDE
    assert wang_cli.MAX_TEXTURE_ORIGIN == synth.MAX_ORIGIN
    assert wang_cli.EXAMPLE_KINDS == exemplars.KINDS
    assert (wang_cli.MIN_TEXTURE_TILE, wang_cli.MAX_TEXTURE_TILE) == (texture.MIN_TILE, texture.MAX_TILE)
