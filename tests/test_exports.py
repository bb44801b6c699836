"""Exports (tilekit.export): adjacency against a brute-force shapely check on every family,
GeoJSON round trips, cut files with each shared edge once, optional dependencies, limits,
notebook pictures and the docs notebook (executed with nbclient)."""

from __future__ import annotations

import json
import os
import re
import sys
from pathlib import Path

import numpy as np
import pytest
import shapely
import shapely.affinity
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit import Affine, Patch, Prototile
from tilekit.cli import cli
from tilekit.errors import ParameterError
from tilekit.export import (
    MissingDependency,
    check_export_size,
    cut_paths,
    cut_segments,
    iter_json,
    output_format,
    tile_edges,
    weld,
)
from tilekit.limits import MAX_DXF_TILES, MAX_REPR_TILES, LimitError

ROOT = Path(__file__).resolve().parent.parent
#: Distance under which the oracle calls two boundaries touching (the tilings are at unit scale).
NEAR = 1e-7
#: Half the side of the square region of the Archimedean edge-count test.
R = 10.0


@pytest.fixture(scope="module")
def cat(tmp_path_factory):
    import tilekit

    path = tmp_path_factory.mktemp("exports") / "cat.sqlite"
    return tilekit.open_catalogue(f"sqlite:///{path}"), path


def kuniform():
    from tilekit.plugins.kuniform.search import tiling_of, tilings_with_types

    return tiling_of(tilings_with_types([(3, 3, 3, 3, 3, 3), (3, 3, 4, 3, 4)])[0])


#: (family, tiling name) with a few hundred tiles in the default region; the last four are not
#: edge-to-edge (tile edges split among several neighbours).
CASES = [
    ("archimedean", "3.4.6.4"),
    ("archimedean", "4.8.8"),
    ("laves", "[3.4.6.4]"),
    ("isohedral", "IH16"),
    ("isohedral", "IH41"),
    ("isohedral", "IH21 shaped"),
    ("k-uniform", None),
    ("substitution", "penrose-p3"),
    ("wang", "checkerboard-2"),
    ("substitution", "chair"),
    ("substitution", "hat"),
    ("polyomino", "pentomino-F"),
    ("polyomino", "pentomino-P"),
]


def patch_of(cat, name):
    if name is None:
        tiling = kuniform()
    elif name == "IH21 shaped":  # S and J edges drawn as polylines: outlines of 10 points
        tiling = cat[0].tiling("IH21").configure(edges=["a=0,0:0.3,0.15:0.7,-0.15:1,0", "b=0,0:0.4,0.2:1,0"])
    else:
        tiling = cat[0].tiling(name)
    region = shapely.affinity.scale(tiling.default_region(), 1.0, 1.0)
    patch = tiling.patch(region)
    while len(patch) < 150:  # a few hundred tiles
        region = shapely.affinity.scale(region, 1.5, 1.5)
        patch = tiling.patch(region)
    return tiling, patch


def brute_force(patch: Patch) -> tuple[set, set]:
    """The oracle: every pair of tiles within NEAR of each other (shapely STRtree), edge
    neighbours when one boundary runs inside the other's NEAR-buffer for a positive length
    (so float noise between shared edges does not hide them), the others vertex neighbours;
    and no pair overlaps."""
    g = patch.to_shapely()
    i, j = shapely.STRtree(g).query(g, predicate="dwithin", distance=NEAR)
    keep = i < j
    i, j = i[keep], j[keep]
    assert shapely.area(shapely.intersection(g[i], g[j], grid_size=1e-9)).max(initial=0) < 1e-6
    run = shapely.length(shapely.intersection(shapely.boundary(g[i]), shapely.buffer(shapely.boundary(g[j]), NEAR)))
    edge = run > 1e-4
    pairs = lambda m: set(zip(i[m].tolist(), j[m].tolist()))  # noqa: E731
    return pairs(edge), pairs(~edge)


def as_set(pairs: np.ndarray) -> set:
    return set(map(tuple, pairs.tolist()))


@pytest.mark.parametrize("family,name", CASES)
def test_adjacency_equals_the_brute_force_check(cat, family, name):
    tiling, patch = patch_of(cat, name)
    assert 100 <= len(patch) <= 3000, len(patch)
    adj = patch.adjacency()
    edge, vertex = brute_force(patch)
    assert as_set(adj.edge) == edge
    assert as_set(adj.vertex) == vertex
    assert as_set(adj.touching) == edge | vertex
    assert (adj.edge[:, 0] < adj.edge[:, 1]).all() and (adj.vertex[:, 0] < adj.vertex[:, 1]).all()
    if name in ("chair", "hat", "pentomino-F", "pentomino-P"):
        assert adj.split > 0  # not edge-to-edge: the split found vertices inside edges
    if family in ("archimedean", "laves", "substitution") and name in ("3.4.6.4", "4.8.8", "[3.4.6.4]", "penrose-p3"):
        assert adj.split == 0


@pytest.mark.parametrize("name", ["3.4.6.4", "4.8.8", "3.12.12", "3.3.3.4.4", "3.3.4.3.4", "4.6.12", "3.6.3.6"])
def test_interior_tiles_of_archimedean_tilings_have_an_edge_neighbour_per_side(cat, name):
    tiling = cat[0].tiling(name)
    region = (-R, -R, R, R)
    patch = tiling.patch(region)
    degree = patch.adjacency().degree("edge")
    sides = np.array([len(p.outline) for p in patch.prototiles])[patch.prototile]
    b = patch.tile_bounds()
    diam = float((b[:, 2:] - b[:, :2]).max())
    inner = (b[:, 0] > -R + diam) & (b[:, 1] > -R + diam) & (b[:, 2] < R - diam) & (b[:, 3] < R - diam)
    assert inner.sum() > 10
    assert (degree[inner] == sides[inner]).all()
    assert (degree <= sides).all()


@pytest.mark.parametrize("name", ["3.4.6.4", "chair", "IH21 shaped"])
def test_adjacency_does_not_change_under_a_rigid_motion(cat, name):
    # a rotation by an irrational angle and a far translation put float noise everywhere
    _, patch = patch_of(cat, name)
    adj = patch.adjacency()
    moved = patch.transformed(Affine.translation(1234.5678, -987.654) @ Affine.rotation(1.0))
    again = moved.adjacency()
    assert np.array_equal(adj.edge, again.edge) and np.array_equal(adj.vertex, again.vertex)
    assert adj.split == again.split


def test_an_empty_patch_exports_empty():
    patch = Patch.empty([Prototile(np.array([[0, 0], [1, 0], [0, 1.0]]))])
    adj = patch.adjacency()
    assert adj.edge.shape == adj.vertex.shape == adj.touching.shape == (0, 2)
    assert json.loads(patch.to_geojson())["features"] == []
    assert json.loads("".join(iter_json(patch)))["tiles"] == []
    assert segments_in_svg(patch.to_cut_svg()) == {"cut": 0}


def test_weld_joins_points_a_hair_apart_across_any_grid_line():
    # copies of a vertex 1e-12 apart on either side of every rounding boundary still weld
    base = np.array([[0.5, 0.25], [1.0, 1.0], [0.5, 0.75], [1e-6 * 7.5, 2.0]])
    pts = np.concatenate([base, base + 1e-12, base - 1e-12])
    ids, reps = weld(pts, 1e-9)
    assert len(reps) == 4 and (ids[:4] == ids[4:8]).all() and (ids[:4] == ids[8:]).all()


def test_geojson_round_trips_through_shapely(cat):
    for name in ("3.4.6.4", "hat", "pentomino-F"):
        _, patch = patch_of(cat, name)
        data = json.loads(patch.to_geojson())
        assert data["type"] == "FeatureCollection" and len(data["features"]) == len(patch)
        back = np.array([shapely.geometry.shape(f["geometry"]) for f in data["features"]])
        ours = patch.geometries()
        assert np.abs(shapely.area(back) - shapely.area(ours)).max() < 1e-9
        assert shapely.hausdorff_distance(back, ours).max() < 1e-9
        assert all(shapely.is_ccw(shapely.get_exterior_ring(back)))  # RFC 7946 ring order
        props = data["features"][7]["properties"]
        assert props == {"prototile": int(patch.prototile[7]), "name": patch.prototiles[patch.prototile[7]].name,
                         "colour": int(patch.colour[7]), "aspect": int(patch.aspect[7])}


def test_geojson_from_the_command_line_carries_transitivity_classes(cat, tmp_path):
    out = tmp_path / "p.geojson"
    r = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{cat[1]}", "render", "3.4.6.4", "-o", str(out)])
    assert r.exit_code == 0, r.output
    feats = json.loads(out.read_text())["features"]
    # 3.4.6.4 is 3-isohedral: triangles, squares and hexagons each form one class
    by_proto = {}
    for f in feats:
        by_proto.setdefault(f["properties"]["name"], set()).add(f["properties"]["transitivity_class"])
    assert sorted(len(v) for v in by_proto.values()) == [1, 1, 1]
    assert len(set().union(*by_proto.values())) == 3


def test_json_from_the_command_line_has_neighbours_and_classes(cat, tmp_path):
    out = tmp_path / "p.json"
    r = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{cat[1]}", "render", "4.8.8", "-o", str(out)])
    assert r.exit_code == 0, r.output
    tiles = json.loads(out.read_text())["tiles"]
    # 4.8.8 is 2-isohedral (squares, octagons); a square's edge neighbours are octagons
    kinds = {len(t["outline"]): {t["transitivity_class"]} for t in tiles}
    for t in tiles:
        kinds[len(t["outline"])].add(t["transitivity_class"])
    assert sorted(kinds) == [4, 8] and all(len(v) == 1 for v in kinds.values()) and len(set().union(*kinds.values())) == 2
    assert all(len(tiles[n]["outline"]) == 8 for t in tiles if len(t["outline"]) == 4 for n in t["neighbours"])


def test_json_lists_each_tiles_neighbours(cat, tmp_path):
    _, patch = patch_of(cat, "chair")
    data = json.loads("".join(iter_json(patch)))
    adj = patch.adjacency()
    pairs = {(t, n) for t, tile in enumerate(data["tiles"]) for n in tile["neighbours"]}
    assert pairs == as_set(adj.edge) | {(j, i) for i, j in as_set(adj.edge)}
    corners = {(t, n) for t, tile in enumerate(data["tiles"]) for n in tile["vertex_neighbours"]}
    assert corners == as_set(adj.vertex) | {(j, i) for i, j in as_set(adj.vertex)} and corners
    tile = data["tiles"][3]
    assert len(tile["outline"]) == len(patch.prototiles[tile["prototile"]].outline)
    assert np.allclose(sorted(map(tuple, tile["outline"])), sorted(map(tuple, patch.polygons()[3])))


def svg_paths(d: str) -> list[np.ndarray]:
    """The paths of SVG path data written as M x y (L x y)* [Z], each as its points (y up,
    a closed path ending at its first point again)."""
    out = []
    for piece in re.findall(r"M[^M]*", d):
        pts = np.array(re.findall(r"-?\d+(?:\.\d*)?(?:e[-+]?\d+)?", piece), dtype=float).reshape(-1, 2) * [1, -1]
        out.append(np.vstack([pts, pts[:1]]) if piece.rstrip().endswith("Z") else pts)
    return out


def layers_in_svg(text: str) -> dict[str, list[np.ndarray]]:
    return {m.group(1): svg_paths(m.group(2)) for m in re.finditer(r'<g id="([^"]+)"[^>]*>\s*<path d="([^"]*)"', text)}


def segments_in_svg(text: str) -> dict[str, int]:
    """Elementary segments drawn per layer (a path of k points draws k - 1)."""
    return {name: sum(len(p) - 1 for p in paths) for name, paths in layers_in_svg(text).items()}


def segment_set(paths: list[np.ndarray], reference: np.ndarray) -> list[tuple[int, int]]:
    """The unordered segments of paths (consecutive points) as sorted pairs of indices of
    their nearest ``reference`` points (every point must lie within 1e-7 of one)."""
    from scipy.spatial import cKDTree

    tree = cKDTree(reference)
    out = []
    for p in paths:
        dist, idx = tree.query(p)
        assert dist.max(initial=0.0) < 1e-7
        out += [tuple(sorted(ab)) for ab in zip(idx[:-1].tolist(), idx[1:].tolist(), strict=True)]
    return sorted(out)


def dxf_paths(path) -> dict[str, list[np.ndarray]]:
    ezdxf = pytest.importorskip("ezdxf")
    out: dict[str, list[np.ndarray]] = {}
    for e in ezdxf.readfile(path).modelspace():
        assert e.dxftype() == "LWPOLYLINE"
        pts = np.array([(x, y) for x, y, *_ in e.get_points()])
        out.setdefault(e.dxf.layer, []).append(np.vstack([pts, pts[:1]]) if e.closed else pts)
    return out


def test_cut_files_draw_each_shared_edge_once_edge_to_edge(cat, tmp_path):
    pytest.importorskip("ezdxf")
    _, patch = patch_of(cat, "3.4.6.4")
    adj = patch.adjacency()
    total = sum(len(patch.prototiles[p].outline) for p in patch.prototile.tolist())
    # edge-to-edge: one line per tile edge, minus one per shared edge (one per edge pair)
    assert segments_in_svg(patch.to_cut_svg()) == {"cut": total - len(adj.edge)}
    path = tmp_path / "p.dxf"
    assert patch.to_dxf(path) == total - len(adj.edge)
    assert sum(len(p) - 1 for p in dxf_paths(path)["cut"]) == total - len(adj.edge)
    # a layer per colour: that colour's tile edges, minus edges shared by two tiles of it
    got = segments_in_svg(patch.to_cut_svg(layers="colour"))
    patch.to_dxf(path, layers="colour")
    assert {k: sum(len(p) - 1 for p in v) for k, v in dxf_paths(path).items()} == got
    same = patch.colour[adj.edge[:, 0]] == patch.colour[adj.edge[:, 1]]
    for c in np.unique(patch.colour).tolist():
        mine = patch.colour == c
        edges_c = sum(len(patch.prototiles[p].outline) for p in patch.prototile[mine].tolist())
        assert got[f"colour-{c}"] == edges_c - int((same & (patch.colour[adj.edge[:, 0]] == c)).sum())


@pytest.mark.parametrize("name", ["chair", "pentomino-F", "penrose-p3"])
def test_cut_lines_of_non_edge_to_edge_patches_cover_every_boundary_once(cat, name):
    # Counted: elementary segments (tile edges split at every vertex inside them). The file
    # holds every elementary segment once: all of them minus the shared ones; and, counted
    # without the split, its length is the tiles' perimeters minus each shared boundary
    # length once (shapely on the edge-neighbour pairs).
    _, patch = patch_of(cat, name)
    e = tile_edges(patch)
    (layer, _, segs), = cut_segments(patch, edges=e)
    o = np.lexsort((e.tile, e.key))
    shared = int((e.key[o][1:] == e.key[o][:-1]).sum())
    assert len(segs) == len(e.key) - shared
    g = patch.to_shapely()
    i, j = patch.adjacency().edge.T
    common = shapely.length(shapely.intersection(shapely.boundary(g[i]), shapely.buffer(shapely.boundary(g[j]), NEAR)))
    length = np.hypot(*(segs[:, 1] - segs[:, 0]).T).sum()
    assert abs(length - (shapely.length(g).sum() - common.sum())) < 1e-5 * length
    svg = patch.to_cut_svg()
    assert segments_in_svg(svg) == {"cut": len(segs)}
    # the paths draw exactly the elementary segments, each once (the SVG's y axis points down)
    ends = np.unique(segs.reshape(-1, 2), axis=0)
    assert segment_set(layers_in_svg(svg)["cut"], ends) == segment_set(list(segs), ends)


@pytest.mark.parametrize("name", ["4^4", "3.4.6.4", "chair", "penrose-p3"])
def test_cut_paths_chain_the_segments_into_the_fewest_open_paths(cat, name, tmp_path):
    """A walk that uses every segment once and starts at a vertex of odd degree ends at
    another: the cut lines become exactly (odd-degree vertices) / 2 open paths, then closed
    ones (a graph with 2k odd vertices needs at least k paths; Euler)."""
    _, patch = patch_of(cat, name)
    (layer, _, segs), = cut_segments(patch)
    (paths,) = cut_paths(patch)
    assert paths.segments == len(segs) and len(paths) < len(segs) / 2
    drawn = [paths.points[a:b] for a, b in zip(paths.starts[:-1], paths.starts[1:], strict=True)]
    ends = np.unique(segs.reshape(-1, 2), axis=0)
    assert segment_set(drawn, ends) == segment_set(list(segs), ends)
    _, degree = np.unique(segs.reshape(-1, 2), axis=0, return_counts=True)  # welded: equal ends are equal
    odd = int((degree % 2).sum())
    open_paths = sum(not np.array_equal(p[0], p[-1]) for p in drawn)
    assert open_paths == odd // 2
    # the files draw the same paths
    svg = layers_in_svg(patch.to_cut_svg())["cut"]
    assert len(svg) == len(paths) and segment_set(svg, ends) == segment_set(drawn, ends)
    pytest.importorskip("ezdxf")
    patch.to_dxf(tmp_path / "p.dxf", mm_per_unit=1.0)
    dxf = dxf_paths(tmp_path / "p.dxf")["cut"]
    assert len(dxf) == len(paths) and segment_set(dxf, ends) == segment_set(drawn, ends)


@pytest.mark.parametrize("name", ["hat", "3.4.6.4"])  # one outline length; three
def test_plot_is_one_poly_collection(cat, name):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    _, patch = patch_of(cat, name)
    ax = patch.plot(colours="red,blue,green,black")
    assert len(ax.collections) == 1 and len(ax.patches) == 0
    coll = ax.collections[0]
    assert len(coll.get_paths()) == len(patch)
    rgba = np.array(matplotlib.colors.to_rgba_array(["red", "blue", "green", "black"]))
    assert np.allclose(coll.get_facecolor(), rgba[patch.colour % 4])
    area = np.abs([shapely.Polygon(p.vertices).area for p in coll.get_paths()])
    assert np.allclose(area, shapely.area(patch.geometries()))


def test_networkx_and_geopandas(cat):
    pytest.importorskip("networkx")
    gpd = pytest.importorskip("geopandas")
    _, patch = patch_of(cat, "penrose-p3")
    g = patch.to_networkx()
    adj = patch.adjacency()
    assert g.number_of_nodes() == len(patch) and set(map(tuple, map(sorted, g.edges))) == as_set(adj.edge)
    assert g.nodes[5]["prototile"] == patch.prototile[5]
    df = patch.to_geopandas()
    assert isinstance(df, gpd.GeoDataFrame) and len(df) == len(patch)
    assert (df["colour"].to_numpy() == patch.colour).all()
    assert np.allclose(df.geometry.area.to_numpy(), shapely.area(patch.geometries()))


@pytest.mark.parametrize("module,extra,call", [
    ("matplotlib", "plot", lambda p, tmp: p.plot()),
    ("geopandas", "geo", lambda p, tmp: p.to_geopandas()),
    ("networkx", "graph", lambda p, tmp: p.to_networkx()),
    ("ezdxf", "dxf", lambda p, tmp: p.to_dxf(tmp / "x.dxf")),
])
def test_a_missing_optional_dependency_names_its_extra(cat, tmp_path, monkeypatch, module, extra, call):
    _, patch = patch_of(cat, "4.8.8")
    monkeypatch.setitem(sys.modules, module, None)  # `import module` now raises ImportError
    with pytest.raises(MissingDependency) as err:
        call(patch, tmp_path)
    msg = str(err.value)
    assert "\n" not in msg and f"pip install 'tilekit[{extra}]'" in msg


def test_the_cli_without_ezdxf_says_which_extra_in_one_line(cat, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    r = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{cat[1]}", "render", "4.8.8", "-o", str(tmp_path / "x.dxf")])
    assert r.exit_code == 2
    assert r.output.strip().count("\n") == 0 and "Traceback" not in r.output
    assert r.output.startswith("error: DXF output needs ezdxf") and "tilekit[dxf]" in r.output


@pytest.mark.parametrize("args,fragment", [
    (["-o", "x.txt"], "must end in one of .svg, .png, .geojson, .json, .cut.svg, .dxf"),
    (["-o", "x.geojson", "--layers", "colour"], "--layers applies to .cut.svg and .dxf output, not .geojson"),
    (["-o", "x.json", "--width", "300"], "--width applies to .svg and .png output, not .json"),
    (["-o", "x.dxf", "--layers", "rainbow"], "'rainbow' is not one of 'one', 'colour'"),
    (["-o", "x.svg", "--mm-per-unit", "5"], "--mm-per-unit applies to .cut.svg and .dxf output, not .svg"),
    (["--depth", "40", "-o", "x.geojson"], "over the limit of 2,000,000 (raise it with --max-tiles N"),
])
def test_bad_export_arguments_are_one_line_errors(cat, tmp_path, args, fragment):
    args = [a if not a.startswith("x.") else str(tmp_path / a) for a in args]
    r = CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{cat[1]}", "render", "penrose-p3", *args])
    assert r.exit_code == 2, r.output
    assert r.output.startswith("error: ") and r.output.strip().count("\n") == 0
    assert fragment in r.output
    assert not list(tmp_path.iterdir())  # refused before anything was written


def test_exports_refuse_over_the_named_limits():
    with pytest.raises(LimitError, match="MAX_DXF_TILES"):
        check_export_size(MAX_DXF_TILES + 1, ".dxf")
    check_export_size(MAX_DXF_TILES + 1, ".geojson")  # streamed: only --max-tiles and memory bound it
    with pytest.raises(LimitError, match="--max-tiles"):
        check_export_size(3e6, ".geojson")
    assert output_format("a/b.CUT.svg") == ".cut.svg" and output_format("x.svg") == ".svg"
    with pytest.raises(ParameterError):
        output_format(".dxf")


def test_notebook_pictures_and_their_size_cap(cat, monkeypatch):
    tiling, patch = patch_of(cat, "3.4.6.4")
    bundle = patch._repr_mimebundle_()
    assert bundle["image/svg+xml"].startswith("<svg") and patch._repr_svg_() == bundle["image/svg+xml"]
    assert patch.prototiles[0]._repr_svg_().count("<path") == 1
    big = tiling.patch((-40, -40, 40, 40))
    assert len(big) > MAX_REPR_TILES
    text = big._repr_mimebundle_()
    assert set(text) == {"text/plain"} and "MAX_REPR_TILES" in text["text/plain"] and big._repr_svg_() is None
    entry = cat[0].get("penrose-p3")
    html = entry._repr_mimebundle_()["text/html"]
    assert "<b>penrose-p3</b>" in html and "<svg" in html
    assert entry._repr_svg_().startswith("<svg") and tiling._repr_svg_().startswith("<svg")
    # a tiling checks its estimate before making any patch
    monkeypatch.setattr(type(tiling), "estimate_tiles", lambda self, region=None: MAX_REPR_TILES + 1)
    monkeypatch.setattr(type(tiling), "patch", lambda self, region: pytest.fail("made a patch over the cap"))
    assert "MAX_REPR_TILES" in tiling._repr_mimebundle_()["text/plain"]


def test_the_docs_notebook_runs_and_draws(cat):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    path = ROOT / "docs" / "examples" / "exports.ipynb"
    nb = nbformat.read(path, as_version=4)
    env = {"TILEKIT_CATALOGUE": f"sqlite:///{cat[1]}"}
    old = {k: os.environ.get(k) for k in env}
    os.environ.update(env)  # the kernel inherits the environment: the test's own catalogue
    try:
        nbclient.NotebookClient(nb, timeout=240, kernel_name="python3",
                                resources={"metadata": {"path": str(path.parent)}}).execute()
    finally:
        for k, v in old.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.get("output_type") == "error"]
    svgs = [o["data"]["image/svg+xml"] for o in outputs if "image/svg+xml" in o.get("data", {})]
    assert len(svgs) >= 2 and all("<svg" in s and "<path" in s for s in svgs)
    assert any("image/png" in o.get("data", {}) for o in outputs)  # the matplotlib figure
    assert any("MAX_REPR_TILES" in o.get("data", {}).get("text/plain", "") for o in outputs)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 11), st.integers(0, 11)).filter(lambda e: e[0] != e[1]), max_size=60))
def test_trails_use_every_edge_once_with_the_fewest_open_walks(edges):
    """Any multigraph: the walks step along its edges, use each exactly once, and the open
    ones number half its odd-degree vertices (Euler: no fewer walks can cover the edges)."""
    from tilekit.kernels import trails

    u = np.array([a for a, _ in edges], dtype=np.int64)
    v = np.array([b for _, b in edges], dtype=np.int64)
    vertices, starts = trails(u, v, 12)
    walked = []
    open_walks = 0
    for a, b in zip(starts[:-1].tolist(), starts[1:].tolist(), strict=True):
        walk = vertices[a:b].tolist()
        assert len(walk) >= 2
        walked += [tuple(sorted(p)) for p in zip(walk[:-1], walk[1:], strict=True)]
        open_walks += walk[0] != walk[-1]
    assert sorted(walked) == sorted(tuple(sorted(e)) for e in edges)
    degree = np.bincount(np.concatenate([u, v]), minlength=12)
    assert open_walks == int((degree % 2).sum()) // 2
