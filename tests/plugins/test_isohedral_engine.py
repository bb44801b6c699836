"""The hop engine against Tactile, patch validity with shaped edges, edge model, validation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tilekit.errors import GeometryError, NotFoundError, ParameterError, ParseError
from tilekit.geometry import Affine
from tilekit.plugins.isohedral import EdgeShape, IsohedralTiling, isohedral_tiling
from tilekit.plugins.isohedral.engine import shape_classes
from tilekit.plugins.isohedral.spec import tiling_from_spec
from tilekit.plugins.isohedral.templates import load_parameterizations, load_templates

UNMARKED = sorted(ih for ih, t in load_templates().items() if not t.marked)

J_SHAPE = EdgeShape(np.array([[0.0, 0.0], [0.3, 0.12], [0.62, -0.08], [1.0, 0.0]]))
HALF_SHAPE = EdgeShape(np.array([[0.0, 0.0], [0.4, 0.14], [1.0, 0.0]]))  # first half of U and S edges


def shaped_edges(ih: int) -> dict[str, EdgeShape]:
    t = load_templates()[ih]
    return {c: (J_SHAPE if t.symbol.label_kind(c) == "J" else HALF_SHAPE) for c in shape_classes(t.symbol)}


def random_valid_params(ih: int, seed: int) -> list[float]:
    """Defaults perturbed at random, keeping only vectors that give a valid shaped tiling."""
    tv = load_parameterizations()[load_templates()[ih].parameterization]
    rng = np.random.default_rng(seed)
    d = np.array(tv.default)
    for spread in (0.12, 0.08, 0.05, 0.03, 0.02):
        for _ in range(10):
            p = d + rng.uniform(-spread, spread, len(d))
            try:
                IsohedralTiling(ih, p, shaped_edges(ih))
            except (ParameterError, GeometryError):
                continue
            return p.tolist()
    return d.tolist()


def _tactile(ih: int, params: list[float]):
    from tactile import IsohedralTiling as TactileTiling

    tt = TactileTiling(ih)
    if params:
        tt.parameters = list(params)
    verts = np.array([[p.x, p.y] for p in tt.vertices])
    aspects = np.array([[[m[0], m[1], m[2]], [m[3], m[4], m[5]], [0, 0, 1]] for m in tt.aspects])
    return verts, aspects, np.array(tt.t1), np.array(tt.t2)


def _same_lattice(a: np.ndarray, b: np.ndarray) -> bool:
    m = np.linalg.solve(a, b)
    return bool(np.allclose(m, np.round(m), atol=1e-6) and abs(abs(round(np.linalg.det(np.round(m)))) - 1) == 0)


def _same_tiles_mod_lattice(ours: list[np.ndarray], theirs: list[np.ndarray], basis: np.ndarray) -> bool:
    """Each placed tile (vertex array) equals one of the others up to a lattice translation."""
    if len(ours) != len(theirs):
        return False
    used = set()
    for p in ours:
        hit = None
        for k, q in enumerate(theirs):
            if k in used:
                continue
            shift = np.linalg.solve(basis, q.mean(axis=0) - p.mean(axis=0))
            if not np.allclose(shift, np.round(shift), atol=1e-6):
                continue
            moved = p + basis @ np.round(shift)
            # the same point set (tiles may differ by an internal symmetry: vertex order)
            d = np.linalg.norm(moved[:, None, :] - q[None, :, :], axis=2)
            if np.all(d.min(axis=1) < 1e-6) and np.all(d.min(axis=0) < 1e-6):
                hit = k
                break
        if hit is None:
            return False
        used.add(hit)
    return True


def _compare_with_tactile(ih: int, params: list[float]) -> None:
    t = load_templates()[ih]
    ours = IsohedralTiling(ih, params, check=False)
    verts, aspects, t1, t2 = _tactile(ih, params)
    # tiling vertices (IH43 and IH58: Tactile starts from another edge, see FACTS.md)
    assert np.allclose(np.roll(ours.tiling_vertices(), t.edge_offset, axis=0), verts, atol=1e-9)
    basis = np.column_stack([t1, t2])
    assert _same_lattice(basis, ours.basis)
    ov = ours.tiling_vertices()
    placed = [Affine.apply(m, ov) for m in ours.unit_transform]
    theirs = [Affine.apply(m, verts) for m in aspects]
    assert _same_tiles_mod_lattice(placed, theirs, basis)


@pytest.mark.parametrize("ih", UNMARKED)
def test_agrees_with_tactile_at_default_parameters(ih):
    """Tiling vertices, aspect transforms (mod lattice) and lattice equal Tactile's (Laves defaults)."""
    _compare_with_tactile(ih, list(load_parameterizations()[load_templates()[ih].parameterization].default))


@pytest.mark.parametrize("ih", UNMARKED)
def test_agrees_with_tactile_at_random_parameters(ih):
    _compare_with_tactile(ih, random_valid_params(ih, seed=ih))


def _validate_shaped(ih: int, params: list[float] | None) -> None:
    tiling = IsohedralTiling(ih, params, shaped_edges(ih))
    side = math.sqrt(abs(tiling.prototile.area) * 260)
    region = (0.0, 0.0, side, side)
    patch = tiling.patch(region)
    assert len(patch) >= 200
    report = patch.validate(region)
    assert report, report.summary()


@pytest.mark.parametrize("ih", UNMARKED)
def test_patch_valid_with_shaped_edges_default_parameters(ih):
    """Patch.validate over >= 200 tiles with non-trivial J, U and S edges."""
    _validate_shaped(ih, None)


@pytest.mark.parametrize("ih", UNMARKED)
def test_patch_valid_with_shaped_edges_random_parameters(ih):
    _validate_shaped(ih, random_valid_params(ih, seed=1000 + ih))


def test_every_kind_of_edge_is_exercised():
    kinds = set()
    for ih in UNMARKED:
        kinds |= set(load_templates()[ih].symbol.edge_kinds())
    assert kinds == {"J", "U", "S", "I"}


def test_shaped_outline_keeps_its_edge_symmetries():
    """U edges are mirror-symmetric, S edges centrally symmetric, I edges straight (§5.3.1)."""
    for ih in UNMARKED:
        tiling = IsohedralTiling(ih, None, shaped_edges(ih))
        kinds = tiling.symbol.edge_kinds()
        for i, path in enumerate(tiling.edge_paths):
            frame = Affine.segment_map((0, 0), (1, 0), path[0], path[-1])
            local = Affine.apply(frame, path)
            if kinds[i] == "I":
                assert np.allclose(local[:, 1], 0.0)
            elif kinds[i] == "S":
                assert np.allclose(local[::-1], np.column_stack([1 - local[:, 0], -local[:, 1]]), atol=1e-9)
            elif kinds[i] == "U":
                assert np.allclose(local[::-1], np.column_stack([1 - local[:, 0], local[:, 1]]), atol=1e-9)


def test_one_fundamental_shape_drives_every_dependent_edge():
    """Editing IH16's b changes edges b+, c+, c-, b- (2..5) and leaves the I edges a (1, 6) straight."""
    plain = IsohedralTiling(16)
    shaped = IsohedralTiling(16, edges={"b": J_SHAPE})
    for i in range(6):
        changed = len(shaped.edge_paths[i]) != len(plain.edge_paths[i])
        assert changed == (i in (1, 2, 3, 4))
    # the c edges are the b curve moved by the hop between them: congruent paths
    b, c = shaped.edge_paths[1], shaped.edge_paths[2]
    lb = np.linalg.norm(np.diff(b, axis=0), axis=1)
    lc = np.linalg.norm(np.diff(c, axis=0), axis=1)
    assert np.allclose(sorted(lb), sorted(lc))


def test_shape_given_for_the_partner_label_is_accepted():
    by_b = IsohedralTiling(16, edges={"b": J_SHAPE})
    frame = Affine.segment_map((0, 0), (1, 0), by_b.edge_paths[2][0], by_b.edge_paths[2][-1])
    c_shape = EdgeShape(Affine.apply(frame, by_b.edge_paths[2]))
    by_c = IsohedralTiling(16, edges={"c": c_shape})
    assert np.allclose(by_c.prototile.outline, by_b.prototile.outline, atol=1e-9)


def test_smooth_bezier_shapes_are_flattened_and_tile():
    smooth = EdgeShape.parse("bezier:0,0:0.3,0.3:0.7,-0.3:1,0")
    assert smooth.smooth and len(smooth.path()) > 4
    path = smooth.path()
    assert np.allclose(path[0], (0, 0)) and np.allclose(path[-1], (1, 0))
    tiling = IsohedralTiling(41, edges={"a": smooth, "b": smooth})
    region = (0, 0, 12, 12)
    assert tiling.patch(region).validate(region)


def test_cli_style_configure_and_spec_round_trip():
    base = IsohedralTiling("IH16")
    t = base.configure(params=[0.3], edges=["b=0,0:0.3,0.2:1,0"])
    assert t.params == (0.3,)
    assert t.spec() == {"ih": 16, "params": [0.3], "edges": {"b": "0,0:0.3,0.2:1,0"}}
    again = tiling_from_spec(t.spec())
    assert np.allclose(again.prototile.outline, t.prototile.outline)
    assert np.allclose(again.unit_transform, t.unit_transform)
    assert isohedral_tiling("ih016", params=[0.3], edges=["b=0,0:0.3,0.2:1,0"]).spec() == t.spec()
    coloured = base.configure(colouring="(1 2 3)(2 3 1)(1 2 3)")
    assert str(coloured.colouring) == "(1 2 3)(2 3 1)(1 2 3)"
    assert coloured.spec()["colouring"] == "(1 2 3)(2 3 1)(1 2 3)"


def test_describe_prints_the_template():
    text = IsohedralTiling(16).describe()
    assert "IH16 3^6 [a+b+c+c-b-a-; a-c+b+]" in text
    assert "parameterization TV14" in text and "3 <- 1; 6" in text and "b (J)" in text


@pytest.mark.parametrize(
    "kwargs, error, words",
    [
        ({"params": [0.1, 0.2]}, ParameterError, "IH16 takes 1 parameter(s)"),
        ({"edges": ["q=0,0:1,0"]}, ParameterError, "no edge label 'q'"),
        ({"edges": ["a=0,0:0.5,0.1:1,0"]}, ParameterError, "I edges and must stay straight"),
        ({"edges": ["b=0,0:1,1"]}, ParameterError, "must run from (0, 0) to (1, 0)"),
        ({"edges": ["b 0,0:1,0"]}, ParseError, "is not 'LABEL=x,y:x,y:...'"),
        ({"depth": 3}, ParameterError, "does not take option 'depth'"),
    ],
)
def test_bad_options_are_named(kwargs, error, words):
    with pytest.raises(error) as info:
        IsohedralTiling(16).configure(**kwargs)
    assert words in str(info.value)


def test_unknown_type_suggests_names():
    with pytest.raises(NotFoundError):
        IsohedralTiling("IH94")
    with pytest.raises(ParameterError, match="marked"):
        IsohedralTiling("IH19")


def test_figure_5_14_degenerate_edge_names_the_parameters():
    """IH9: as the book's v0 (Tactile's 3.9 v0 + 0.1) reaches zero, edges 1 and 4 vanish (Figure 5.14)."""
    with pytest.raises(ParameterError) as info:
        IsohedralTiling(9, [-0.1 / 3.9, 0.5, 0.225])
    msg = str(info.value)
    assert "tiling edge 1 degenerate" in msg and "v0=" in msg


def test_self_intersecting_edge_and_tile_are_rejected():
    with pytest.raises(ParameterError, match="edge 1 .label 'a'. crosses itself"):
        IsohedralTiling(41, edges={"a": EdgeShape(np.array([[0, 0], [0.6, 0.3], [0.4, -0.3], [0.5, 0.4], [1, 0]]))})
    with pytest.raises(ParameterError, match="cross - the tile would be self-intersecting"):
        IsohedralTiling(41, edges={"a": EdgeShape(np.array([[0, 0], [1.3, 0.3], [1, 0]]))})
    with pytest.raises(ParameterError, match="self-intersecting or inside out"):
        IsohedralTiling(9, [0.122, 0.5, 0.0])


def test_overlap_check_catches_a_broken_unit():
    tiling = IsohedralTiling(16)
    tiling.unit_transform = tiling.unit_transform.copy()
    tiling.unit_transform[1, :2, 2] += 0.3 * tiling.v1  # move aspect 2 into its neighbours
    with pytest.raises(GeometryError, match="neighbouring tiles overlap"):
        tiling.check_overlaps()


def test_prototile_corners_are_the_tiling_vertices():
    t = IsohedralTiling(16, edges={"b": J_SHAPE})
    corners = t.prototile.outline[list(t.prototile.corners)]
    assert np.allclose(corners, t.tiling_vertices())


def test_translation_vectors_by_the_centroid_rule():
    """v1, v2 map the tile onto a tile: the translated outline is a placed tile of the patch."""
    for ih in (16, 21, 77, 81):
        t = IsohedralTiling(ih)
        for v in (t.v1, t.v2):
            moved = Affine.apply(Affine.translation(*v), t.tiling_vertices())
            unit_tiles = [Affine.apply(m, t.tiling_vertices()) for m in t.unit_transform]
            assert any(
                np.allclose(np.sort(moved - v, axis=0), np.sort(u, axis=0)) for u in unit_tiles
            )


def test_properties_follow_a_user_colouring():
    t = IsohedralTiling(28)
    assert t.properties()["perfect_colouring"] is False  # exercise 5.10(a)
    single = t.configure(colouring="(1 1 1 1)(1)(1)")
    assert single.properties()["colours"] == 1 and single.properties()["perfect_colouring"] is True
