"""The public API (``tiling(name).patch``, ``--depth N``, ``--region``) gives exactly the
engine's tiles at the same size, and the compiled kernels agree with plain NumPy."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from tilekit import limits
from tilekit.cli import cli
from tilekit.geometry import Affine
from tilekit.plugins.substitution import builtin_systems, engine, kernels, tiling
from tilekit.plugins.substitution.engine import assemble, generate, unique_centres, unique_tiles
from tilekit.polygon import centroid
from tilekit.tiling import Patch


def tile_keys(prototiles, proto: np.ndarray, transform: np.ndarray) -> set[tuple]:
    """Each tile as (prototile, centroid, first vertex) rounded at 1e-6: equal sets mean the
    same tiles (a vertex as well as the centroid, so a wrongly mirrored tile differs)."""
    out = set()
    for p, shape in enumerate(prototiles):
        idx = np.flatnonzero(proto == p)
        pts = np.round(Affine.apply(transform[idx], np.vstack([centroid(shape.outline), shape.outline])) * 1e6)
        for tile in pts.astype(np.int64).tolist():
            # the vertex set, sorted: independent of which symmetry of the tile the map carries
            out.add((p, *tile[0], tuple(sorted(map(tuple, tile[1:])))))
    return out


def engine_depth_patch(name: str, depth: int) -> tuple[np.ndarray, np.ndarray]:
    """The depth-N patch straight from the engine: the seed cluster scaled by s**N, each
    member substituted N times, halves assembled."""
    t = tiling(name)
    s = t.system
    lam = Affine.scaling(s.scale**depth)
    protos, maps = [], []
    for p, m in zip(*t.seed_cluster()):
        a, b = generate(s, depth, lam @ m, int(p))
        protos.append(a)
        maps.append(b)
    return assemble(s, np.concatenate(protos), np.concatenate(maps))


@pytest.mark.parametrize(("name", "depth"), [("penrose-p3", 7), ("penrose-p2", 7), ("ammann-beenker", 3), ("chair", 4)])
def test_depth_patch_is_the_engines(name: str, depth: int) -> None:
    t = tiling(name).configure(depth=depth)
    patch = t.patch()
    proto, transform = engine_depth_patch(name, depth)
    assert len(patch) == len(proto)
    assert tile_keys(patch.prototiles, patch.prototile, patch.transform) == tile_keys(t.prototiles, proto, transform)


@pytest.mark.parametrize("name", ["penrose-p3", "penrose-p2", "ammann-beenker"])
def test_region_patch_is_the_engines_patch_clipped(name: str) -> None:
    """patch(region) culls supertiles by their discs; the result must be exactly the tiles
    of the whole (unculled) patch at the same depth and seed that meet the region."""
    t = tiling(name)
    s = t.system
    region = shapely.box(-7.3, -2.1, 9.4, 6.2)
    patch = t.patch(region)
    # raw() widens the box only for systems paired along an edge (none of these)
    assert s.pairing_edge is None
    margin = 0.0
    x0, y0, x1, y1 = region.bounds
    seed, seed_t, depth = t.seed_placement(shapely.box(x0 - margin, y0 - margin, x1 + margin, y1 + margin))
    proto, transform = assemble(s, *generate(s, depth, seed_t, seed))
    full = Patch(t.prototiles, proto, transform).clip(region)
    assert len(patch) == len(full)
    assert tile_keys(t.prototiles, patch.prototile, patch.transform) == tile_keys(t.prototiles, full.prototile, full.transform)
    assert patch.validate(region)


def test_cli_depth_and_region_match_the_api(tmp_path, monkeypatch) -> None:
    """``tilekit render penrose-p3 --depth N`` and ``--region`` draw the API's patches."""
    monkeypatch.delenv("TILEKIT_CATALOGUE", raising=False)
    db = f"sqlite:///{tmp_path / 'c.sqlite'}"
    for extra, expect in [(["--depth", "5"], tiling("penrose-p3").configure(depth=5).patch()),
                          (["--region", "-3,-2,4,3"], tiling("penrose-p3").patch((-3, -2, 4, 3)))]:
        out = tmp_path / "p.svg"
        result = CliRunner().invoke(cli, ["--catalogue", db, "render", "penrose-p3", *extra, "-o", str(out)],
                                    catch_exceptions=False)
        assert result.exit_code == 0, result.output
        assert f"({len(expect)} tiles)" in result.output


def test_kernel_expand_matches_numpy_matmul() -> None:
    rng = np.random.default_rng(1)
    maps = np.tile(np.eye(3), (50, 1, 1))
    maps[:, :2, :] = rng.normal(size=(50, 2, 3))
    label = rng.integers(0, 3, 50)
    children = [np.array([0, 1]), np.array([2]), np.array([0, 2, 1])]
    mats = [np.tile(np.eye(3), (len(c), 1, 1)) for c in children]
    for m in mats:
        m[:, :2, :] = rng.normal(size=(len(m), 2, 3))
    kids, out = kernels.expand(label, maps, children, mats)
    ref_k = np.concatenate([children[j] for j in label])
    ref = np.concatenate([maps[i] @ mats[j] for i, j in enumerate(label)])
    assert np.array_equal(kids, ref_k)
    assert np.allclose(out, ref, rtol=0, atol=1e-12)
    # integer lattice maps stay exact integers
    ik, iout = kernels.expand(label, np.round(maps * 3).astype(np.int64), children,
                              [np.round(m * 3).astype(np.int64) for m in mats])
    assert iout.dtype == np.int64


def test_centroid_dedupe_agrees_with_the_symmetric_key() -> None:
    s = builtin_systems()["penrose-p3"]
    proto, transform = generate(s, 9, Affine.scaling(s.scale**9), s.seed)
    n = len(s.prototiles)
    whole_p = s.assemble_tile[proto]
    whole_t = np.matmul(transform, s.assemble_matrix[proto])
    centres = np.array([centroid(p.outline) for p in s.output_prototiles])
    a = unique_centres(whole_p, whole_t, centres)
    b = unique_tiles(whole_p, whole_t, s.output_symmetries)
    assert n == 2 and len(a) == len(b)
    assert tile_keys(s.output_prototiles, whole_p[a], whole_t[a]) == tile_keys(s.output_prototiles, whole_p[b], whole_t[b])


@pytest.mark.parametrize(("name", "depth"), [("penrose-p3", 12), ("hat", 5), ("spectre", 5)])
def test_patches_that_would_not_fit_in_memory_are_refused_first(monkeypatch, name: str, depth: int) -> None:
    """With 1 MB available, a patch of ~10^5 tiles (~20 MB to generate) is refused before
    anything is generated; the estimate uses the measured per-tile cost."""
    monkeypatch.setattr(limits, "available_memory", lambda: 1e6)
    called = []
    real = engine.generate

    def generate(system, depth, *args, **kwargs):  # small patches (the seed cluster's) pass
        if depth >= 8:
            called.append(depth)
        return real(system, depth, *args, **kwargs)

    monkeypatch.setattr(engine, "generate", generate)
    with pytest.raises(limits.LimitError, match="memory available"):
        tiling(name).configure(depth=depth).patch()
    with pytest.raises(limits.LimitError, match="memory available"):
        tiling(name).patch((-300, -300, 300, 300))
    assert not called
    monkeypatch.undo()
    assert len(tiling(name).configure(depth=2).patch())
