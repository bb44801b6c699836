"""Streamed (chunked) substitution patches: the chunks' union is the unchunked patch, tile for
tile, for every built-in system; halves of a whole tile meet across chunks; a stream's peak
memory is a chunk's, not the patch's."""

from __future__ import annotations

import copy
import json
import shutil
import tracemalloc
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely
from click.testing import CliRunner
from cliutil import assert_one_line_error
from test_substitution import MINIMAL  # tests/plugins is on sys.path (rootdir-relative imports)

from tilekit import export, limits
from tilekit.cli import cli
from tilekit.errors import ParameterError
from tilekit.geometry import Affine
from tilekit.plugins.substitution import builtin_systems, engine, levels, tiling
from tilekit.plugins.substitution.levels import hilbert_order
from tilekit.plugins.substitution.system import system_from_data
from tilekit.plugins.substitution.tiling import KeypointTiling
from tilekit.polygon import centroid
from tilekit.tiling import Patch, PeriodicTiling, Prototile

SYSTEMS = builtin_systems()
#: Similarity systems and a depth whose patch is a few thousand rule tiles.
SIMILARITY = {"penrose-p3": 9, "penrose-p2": 9, "ammann-beenker": 4, "ammann-a3": 8, "chair": 5,
              "kite-domino": 4, "pinwheel": 4, "sphinx": 5}
MONOTILES = {"hat": 3, "spectre": 3}


def test_every_built_in_system_is_covered() -> None:
    assert set(SYSTEMS) == set(SIMILARITY) | set(MONOTILES)


def exact_rows(proto: np.ndarray, transform: np.ndarray) -> np.ndarray:
    """The rule tiles as sorted rows (prototile, map): equal arrays are equal tiles, bit for bit."""
    rows = np.column_stack([proto.astype(float), transform.reshape(len(proto), 9)])
    return rows[np.lexsort(rows.T[::-1])]


def matched(prototiles, a: tuple[np.ndarray, np.ndarray], b: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Assert that two sets of placed tiles are the same tiles and return (i, j) pairs (k, 2)
    of equal tiles: paired by the engine's own key (prototile and placed centroid, as
    ``assemble`` keys whole tiles), then each pair's vertex sets compared (1e-7 of the tile
    size; which map of a whole tile is kept can differ by float noise and by a symmetry)."""
    (pa, ta), (pb, tb) = a, b
    assert len(pa) == len(pb)
    if not len(pa):
        return np.zeros((0, 2), dtype=np.int64)
    centres = np.array([centroid(p.outline) for p in prototiles])
    rep = engine.centre_groups(np.concatenate([pa, pb]), np.concatenate([ta, tb]), centres)
    side = np.r_[np.zeros(len(pa), dtype=np.int64), np.ones(len(pb), dtype=np.int64)]
    ones = np.bincount(rep, weights=side, minlength=len(rep))
    alls = np.bincount(rep, minlength=len(rep))
    groups = np.flatnonzero(alls)
    assert np.all(alls[groups] == 2) and np.all(ones[groups] == 1), "a tile without its equal"
    i = np.flatnonzero(side == 0)
    j = np.empty(len(rep), dtype=np.int64)
    j[rep[len(pa):]] = np.arange(len(pb))
    pairs = np.column_stack([i, j[rep[i]]])
    assert np.array_equal(pa[pairs[:, 0]], pb[pairs[:, 1]])
    for p, shape in enumerate(prototiles):
        at = pairs[pa[pairs[:, 0]] == p]
        va = Affine.apply(ta[at[:, 0]], shape.outline)
        vb = Affine.apply(tb[at[:, 1]], shape.outline)
        gap = np.linalg.norm(va[:, :, None, :] - vb[:, None, :, :], axis=-1).min(axis=2).max(axis=1)
        size = float(np.ptp(shape.outline, axis=0).max()) * np.sqrt(np.abs(np.linalg.det(ta[at[:, 0], :2, :2])))
        assert np.all(gap <= 1e-7 * size), gap.max()
    return pairs


def joined(chunks: list[tuple[np.ndarray, ...]]) -> tuple[np.ndarray, ...]:
    return tuple(np.concatenate([c[k] for c in chunks]) for k in range(len(chunks[0])))


@pytest.mark.parametrize("name", sorted(SIMILARITY))
@pytest.mark.parametrize("boxed", [False, True])
def test_engine_chunks_are_the_unchunked_generation(name: str, boxed: bool) -> None:
    s = SYSTEMS[name]
    depth = SIMILARITY[name]
    seed = Affine.scaling(s.scale**depth)
    box = None
    if boxed:  # a box over part of the seed tile: culling happens in both
        pts = Affine.apply(seed, s.prototiles[s.seed].outline)
        (x0, y0), (x1, y1) = pts.min(axis=0), pts.max(axis=0)
        box = (x0 + 0.2 * (x1 - x0), y0 + 0.3 * (y1 - y0), x0 + 0.7 * (x1 - x0), y0 + 0.6 * (y1 - y0))
    proto, transform = engine.generate(s, depth, seed, box=box)
    chunk = max(8, len(proto) // 40)
    chunks = list(engine.generate_chunks(s, depth, seed, box=box, chunk_tiles=chunk))
    assert len(chunks) >= 10
    assert max(len(c[0]) for c in chunks) <= chunk
    cp, ct = joined(chunks)
    assert np.array_equal(exact_rows(cp, ct), exact_rows(proto, transform))
    # whole tiles: the chunked assembly (halves paired across chunks) is the unchunked one
    whole = engine.assemble(s, proto, transform)
    streamed = list(engine.assemble_chunks(s, iter(chunks)))
    matched(s.tiles, joined(streamed), whole)


@pytest.mark.parametrize("name", sorted(MONOTILES))
@pytest.mark.parametrize("boxed", [False, True])
def test_monotile_chunks_are_the_unchunked_generation(name: str, boxed: bool) -> None:
    s = SYSTEMS[name]
    depth = MONOTILES[name]
    box = (-8.0, -6.0, 9.0, 7.0) if boxed else None
    proto, transform, colour = s.generate(depth, box=box)
    chunk = max(4, len(proto) // 30)
    chunks = list(s.generate_chunks(depth, box=box, chunk_tiles=chunk))
    assert len(chunks) >= 8
    cp, ct, cc = joined(chunks)
    assert np.array_equal(exact_rows(cp, ct), exact_rows(proto, transform))
    # each tile keeps its colour
    key = lambda t, c: sorted(zip(np.round(t[:, :2, 2] * 1e6).astype(np.int64).tolist(), c.tolist()))  # noqa: E731
    assert key(ct, cc) == key(transform, colour)


def region_of(t, depth: int) -> shapely.Polygon:
    """A box inside the depth-N patch, off its centre."""
    keypoint = isinstance(t, KeypointTiling)  # any region: a box cull, then a clip
    whole = t.default_region() if keypoint else t._cluster_polygon(depth)
    c = np.asarray(whole.representative_point().coords[0])
    r = 0.2 * np.sqrt(whole.area)
    while not whole.contains(box := shapely.box(c[0] - r, c[1] - 0.7 * r, c[0] + 1.3 * r, c[1] + r)):
        r *= 0.8
    return box


def assert_same_patch(chunks: list[Patch], patch: Patch) -> None:
    for c in chunks:
        assert c.validate().ok, c.validate().summary()
        assert c.prototiles == patch.prototiles
    union = Patch.concat(chunks)
    pairs = matched(patch.prototiles, (union.prototile, union.transform), (patch.prototile, patch.transform))
    # colours are the tile's own: equal tile for tile
    assert np.array_equal(union.colour[pairs[:, 0]], patch.colour[pairs[:, 1]])


@pytest.mark.parametrize("name", sorted(SIMILARITY) + sorted(MONOTILES))
def test_iter_patches_is_the_patch_at_a_depth_and_in_a_region(name: str) -> None:
    depth = {**SIMILARITY, **MONOTILES}[name] - (1 if name in SIMILARITY else 0)
    t = tiling(name).configure(depth=depth)
    patch = t.patch()
    chunks = list(t.iter_patches(chunk_tiles=max(8, len(patch) // 15)))
    assert len(chunks) >= 5
    assert_same_patch(chunks, patch)
    # the default region (the depth's frame) and a box inside it
    for reg in (t.default_region(), region_of(t, depth)):
        patch = t.patch(reg)
        assert_same_patch(list(t.iter_patches(reg, chunk_tiles=max(8, len(patch) // 10))), patch)


@pytest.mark.parametrize("name", ["penrose-p3", "kite-domino", "chair", "spectre"])
def test_iter_patches_of_a_region_without_a_depth(name: str) -> None:
    t = tiling(name)
    reg = shapely.box(-7.3, -5.1, 6.2, 8.4)
    patch = t.patch(reg)
    chunks = list(t.iter_patches(reg, chunk_tiles=max(8, len(patch) // 12)))
    assert len(chunks) >= 5
    assert_same_patch(chunks, patch)


def test_shaped_tiles_stream_as_the_patch() -> None:
    t = tiling("penrose-p3").configure(params=[0.1, -0.05])
    reg = shapely.box(-4, -4, 4, 4)
    patch = t.patch(reg)
    assert_same_patch(list(t.iter_patches(reg, chunk_tiles=40)), patch)


def test_a_half_waits_for_its_partner_in_a_later_chunk() -> None:
    s = SYSTEMS["penrose-p3"]
    proto, transform = engine.generate(s, 3)
    whole = engine.assemble(s, proto, transform)
    # two halves of one whole tile: a pair of rule tiles giving the same whole tile
    wp, wt = engine.whole_tiles(s, proto, transform)
    rep = engine.centre_groups(wp, wt, np.array([centroid(p.outline) for p in s.tiles]))
    partner = np.flatnonzero(rep != np.arange(len(rep)))[0]
    first = rep[partner]
    a, b = [first], [partner]
    rest = [i for i in range(len(proto)) if i not in (first, partner)]
    chunks = [(proto[a], transform[a]), (proto[rest], transform[rest]), (proto[b], transform[b])]
    out = list(engine.assemble_chunks(s, iter(chunks)))
    assert len(out[0][0]) == 0  # the first half alone: pending, nothing yet
    matched(s.tiles, joined(out), whole)
    # the third chunk (the second half) yields the tile whose halves were split, once
    assert len(out[2][0]) == 1
    matched(s.tiles, out[2], (wp[[first]], wt[[first]]))
    # a half whose partner never comes still gives its whole tile at the end, as assemble does
    lone = list(engine.assemble_chunks(s, iter([(proto[a], transform[a])])))
    assert [len(c[0]) for c in lone] == [0, 1]
    matched(s.tiles, joined(lone), engine.assemble(s, proto[a], transform[a]))


def test_pairing_halves_meet_across_chunks_and_lone_halves_are_dropped() -> None:
    s = SYSTEMS["kite-domino"]
    proto, transform = engine.generate(s, 2)
    whole = engine.assemble(s, proto, transform)
    half = len(proto) // 2
    order = np.argsort(transform[:, 0, 2])  # left half, then right half: pairs straddle the cut
    chunks = [(proto[order[:half]], transform[order[:half]]), (proto[order[half:]], transform[order[half:]])]
    first = engine.assemble(s, *chunks[0])
    out = list(engine.assemble_chunks(s, iter(chunks)))
    assert len(out[0][0]) == len(first[0])  # the first chunk's own pairs
    matched(s.tiles, joined(out), whole)
    assert len(joined(out)[0]) > len(first[0]) + len(engine.assemble(s, *chunks[1])[0])  # pairs across the cut
    # a lone half is dropped at the end, as pair_halves drops it
    assert len(engine.assemble(s, proto[:1], transform[:1])[0]) == 0
    assert sum(len(c[0]) for c in engine.assemble_chunks(s, iter([(proto[:1], transform[:1])]))) == 0


def most_pending(s, chunks: list[tuple[np.ndarray, np.ndarray]]) -> int:
    """The most halves waiting in the assembler's pending buffer after any chunk: a half
    waits from its chunk to its partner's (or to the end, without one)."""
    centres = np.array([centroid(p.outline) for p in s.tiles])
    wp, wt = engine.whole_tiles(s, *joined(chunks))
    rep = engine.centre_groups(wp, wt, centres)
    which = np.repeat(np.arange(len(chunks)), [len(c[0]) for c in chunks])
    last = np.zeros(len(rep), dtype=np.int64)
    np.maximum.at(last, rep, which)
    first = rep == np.arange(len(rep))
    halves = np.bincount(rep, minlength=len(rep))
    lone = first & (halves == 1)
    opened = np.bincount(which[first & ~lone & (last != which)], minlength=len(chunks) + 1)
    closed = np.bincount(last[first & ~lone & (last != which)], minlength=len(chunks) + 1)
    return int(np.cumsum(opened - closed).max() + lone.sum())


def test_chunks_are_spatially_compact(monkeypatch) -> None:
    """Hilbert order: neighbouring supertiles come in nearby chunks, so a half waits for its
    partner in another chunk only briefly and the pending buffer stays a small boundary; in
    a random order of the same supertiles it grows to a share of the whole patch."""
    s = SYSTEMS["penrose-p3"]
    seed = Affine.scaling(s.scale**12)
    hilbert = list(engine.generate_chunks(s, 12, seed, chunk_tiles=600))
    rng = np.random.default_rng(1)
    monkeypatch.setattr(levels, "hilbert_order", lambda pts: rng.permutation(len(pts)))
    shuffled = list(engine.generate_chunks(s, 12, seed, chunk_tiles=600))
    assert len(hilbert) >= 100 and len(shuffled) >= 100
    ordered, random = most_pending(s, hilbert), most_pending(s, shuffled)
    total = sum(len(c[0]) for c in hilbert)
    assert ordered < 0.05 * total
    assert ordered < 0.5 * random, (ordered, random)


def test_hilbert_order_keeps_neighbours_near() -> None:
    g = np.stack(np.meshgrid(np.arange(64), np.arange(64)), axis=-1).reshape(-1, 2).astype(float)
    order = hilbert_order(g)
    assert sorted(order.tolist()) == list(range(len(g)))
    steps = np.abs(np.diff(g[order], axis=0)).sum(axis=1)
    assert np.all(steps == 1)  # a Hilbert curve through a grid moves one cell at a time


def test_stream_peak_memory_is_a_chunk_not_the_patch() -> None:
    t = tiling("penrose-p3").configure(depth=12)
    full = t._full_count(12)  # rule tiles (halves) of the depth-12 patch
    chunk = full // 20
    patch_bytes = full * 80  # the rule tiles' (3, 3) maps and labels alone
    tiles = 0
    list(t.iter_patches(chunk_tiles=64))  # compile and cache everything first
    tracemalloc.start()
    try:
        for p in t.iter_patches(chunk_tiles=chunk):
            tiles += len(p)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert tiles == len(t.patch())
    assert full >= 10 * chunk
    assert peak < 0.4 * patch_bytes, (peak, patch_bytes)
    tracemalloc.start()
    try:
        t.patch()
        _, unchunked = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < unchunked / 3, (peak, unchunked)


@pytest.mark.parametrize("bad", [0, -5, 2.5, True, "100", None])
def test_bad_chunk_sizes_are_one_line_errors(bad) -> None:
    t = tiling("penrose-p3").configure(depth=3)
    with pytest.raises(ParameterError, match="chunk size .* must be a positive whole number") as info:
        next(t.iter_patches(chunk_tiles=bad))
    assert "\n" not in str(info.value)
    with pytest.raises(ParameterError, match="chunk size"):
        next(engine.generate_chunks(SYSTEMS["chair"], 3, chunk_tiles=bad))
    with pytest.raises(ParameterError, match="chunk size"):
        next(SYSTEMS["hat"].generate_chunks(2, chunk_tiles=bad))
    with pytest.raises(ParameterError, match="chunk size"):  # the base class checks it too
        next(square_grid().iter_patches(chunk_tiles=bad))


@pytest.mark.parametrize("name", ["spectre", "penrose-p3"])
def test_a_stream_that_would_not_fit_is_refused_before_it_starts(name) -> None:
    """A stream holds one chunk and the supertiles the chunks are cut from: a chunk as large
    as a patch far beyond memory, or chunks so small that the supertiles are nearly every
    tile, are refused (LimitError, one line) before anything is generated."""
    t = tiling(name).configure(depth=12 if name == "spectre" else 40)
    for chunk in (10**15, 1):
        with pytest.raises(limits.LimitError, match="tiles held at once by the stream") as info:
            next(t.iter_patches(chunk_tiles=chunk))
        assert "\n" not in str(info.value)


def test_overlapping_systems_refuse_to_stream_in_one_line() -> None:
    over = copy.deepcopy(MINIMAL)
    over["kind"] = "overlapping"
    s = system_from_data(over, "o.toml")
    with pytest.raises(ParameterError, match="overlapping system.*cannot be generated in chunks") as info:
        next(engine.generate_chunks(s, 3, chunk_tiles=4))
    assert "\n" not in str(info.value)


def square_grid() -> PeriodicTiling:
    return PeriodicTiling([Prototile(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]))], [0],
                          np.eye(3)[None], (1, 0), (0, 1))


def test_other_families_stream_their_one_patch() -> None:
    t = square_grid()
    assert not t.streams
    reg = (-3, -3, 3, 3)
    (only,) = list(t.iter_patches(reg))
    assert len(only) == len(t.patch(reg))


# ------------------------------------------------------------------ tilekit render, streamed

#: Bytes of memory the CLI tests pretend are available: a depth-8 P3 (25,840 rule tiles at
#: 400-900 bytes each to generate and write) does not fit, so it must stream.
SMALL_MEMORY = 3e6


@pytest.fixture
def render(tmp_path, monkeypatch):
    monkeypatch.delenv("TILEKIT_CATALOGUE", raising=False)
    db = f"sqlite:///{tmp_path / 'c.sqlite'}"

    def run(*args: str):
        return CliRunner().invoke(cli, ["--catalogue", db, "render", *args], catch_exceptions=False)

    # the catalogue is built (its tile counts generated) with the machine's real memory
    assert run("chair", "--depth", "1", "-o", str(tmp_path / "warm.svg")).exit_code == 0
    return run


def little_memory(monkeypatch) -> None:
    monkeypatch.setattr(limits, "available_memory", lambda: SMALL_MEMORY)


@pytest.mark.parametrize(("name", "extra"), [("penrose-p3", ["--depth", "8"]),
                                             ("penrose-p3", ["--region", "-80,-70,80,75"]),
                                             ("kite-domino", ["--depth", "6"]),
                                             ("spectre", ["--depth", "5"])])
def test_render_streams_a_geojson_larger_than_memory(render, tmp_path, monkeypatch, name, extra) -> None:
    t = tiling(name).configure(depth=int(extra[1])) if "--depth" in extra else tiling(name)
    reg = shapely.box(*map(float, extra[1].split(","))) if "--region" in extra else t.default_region()
    expect = t.patch(reg)  # made with the machine's real memory
    out = tmp_path / "p.geojson"
    little_memory(monkeypatch)
    with pytest.raises(limits.LimitError, match="memory available"):  # the whole patch no longer fits
        t.patch(reg)
    result = render(name, *extra, "-o", str(out))
    assert result.exit_code == 0, result.output
    assert f"({len(expect)} tiles, streamed in chunks" in result.output
    data = json.loads(out.read_text())
    features = data["features"]
    assert len(features) == len(expect)
    assert [f["id"] for f in features] == list(range(len(expect)))
    polys = shapely.polygons([np.array(f["geometry"]["coordinates"][0]) for f in features])
    assert shapely.area(polys).sum() == pytest.approx(float(shapely.area(expect.geometries()).sum()), rel=1e-9)


def test_render_streams_an_svg_picture(render, tmp_path, monkeypatch) -> None:
    t = tiling("penrose-p3").configure(depth=8)
    expect = t.patch(t.default_region())
    out = tmp_path / "p.svg"
    little_memory(monkeypatch)
    result = render("penrose-p3", "--depth", "8", "-o", str(out))
    assert result.exit_code == 0, result.output
    root = ET.parse(out).getroot()
    fills = [e for e in root.iter("{http://www.w3.org/2000/svg}path") if e.get("fill") not in (None, "none")]
    assert len(fills) > 2  # a path per colour per chunk
    assert sum(e.get("d").count("M") for e in fills) == len(expect)
    x0, y0, x1, y1 = t.default_region().bounds
    pad = 0.02 * max(x1 - x0, y1 - y0)
    assert root.get("viewBox") == f"{x0 - pad:.6g} {-(y1 + pad):.6g} {x1 - x0 + 2 * pad:.6g} {y1 - y0 + 2 * pad:.6g}"


@pytest.mark.parametrize("suffix", [".json", ".png", ".cut.svg", ".dxf"])
def test_formats_that_need_the_whole_patch_still_refuse(render, tmp_path, monkeypatch, suffix) -> None:
    little_memory(monkeypatch)
    out = tmp_path / f"p{suffix}"
    assert_one_line_error(render("penrose-p3", "--depth", "8", "-o", str(out)), "memory available")
    assert not out.exists()


def test_labels_and_max_tiles_still_refuse_a_stream(render, tmp_path, monkeypatch) -> None:
    little_memory(monkeypatch)
    out = tmp_path / "p.svg"
    assert_one_line_error(render("penrose-p3", "--depth", "8", "--labels", "-o", str(out)), "memory available")
    # --max-tiles still bounds the count, streamed or not
    assert_one_line_error(render("penrose-p3", "--depth", "8", "--max-tiles", "1000", "-o", str(out)),
                          "over the limit of 1,000")
    assert not out.exists()


def test_a_file_larger_than_the_free_disk_is_refused(render, tmp_path, monkeypatch) -> None:
    usage = shutil.disk_usage(tmp_path)
    monkeypatch.setattr(export.shutil, "disk_usage", lambda path: usage._replace(free=1_000_000))
    out = tmp_path / "p.geojson"
    # ~26,000 rule tiles at ~300 bytes: about 8 MB, over the 1 MB free
    result = render("penrose-p3", "--depth", "8", "-o", str(out))
    assert_one_line_error(result, "p.geojson would take about")
    assert "GiB free in" in result.stderr and "tiles as .geojson" in result.stderr
    assert not out.exists()
    little_memory(monkeypatch)  # and when streaming
    assert_one_line_error(render("penrose-p3", "--depth", "8", "-o", str(out)), "would take about")
    # a small patch fits
    assert render("penrose-p3", "--depth", "4", "-o", str(out)).exit_code == 0


def test_file_size_estimates_bound_the_written_sizes(tmp_path) -> None:
    """FILE_BYTES_PER_TILE bounds what each format writes per tile, within a factor 4 (the
    chair's integer coordinates are short)."""
    for name, depth in (("penrose-p3", 7), ("hat", 3), ("spectre", 3), ("chair", 4)):
        t = tiling(name).configure(depth=depth)
        patch = t.patch(t.default_region())
        for suffix in (".geojson", ".svg", ".json", ".cut.svg"):
            out = tmp_path / f"x{suffix}"
            if suffix == ".svg":
                out.write_text(t.render_svg(patch, region=t.default_region()))
            else:
                export.write_patch(patch, out)
            size = out.stat().st_size
            bound = export.file_size_estimate(len(patch), suffix, t.prototiles)
            assert size <= bound <= 4 * size, (name, suffix, size, bound)


def test_a_stream_on_a_terminal_shows_progress(render, tmp_path, monkeypatch) -> None:
    import tilekit.cli as cli_module

    little_memory(monkeypatch)
    monkeypatch.setattr(cli_module.render, "on_terminal", lambda: True)
    monkeypatch.setattr(cli_module.render, "PROGRESS_TILES", 1000)
    result = render("penrose-p3", "--depth", "8", "-o", str(tmp_path / "p.geojson"))
    assert result.exit_code == 0
    assert "streaming" in result.stderr
