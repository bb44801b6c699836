"""The substitution engine, loader and Penrose systems (book chapter 6)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from tilekit.errors import ParameterError, ParseError, TilekitError
from tilekit.geometry import Affine
from tilekit.plugins.substitution import builtin_systems, from_file, from_spec, tiling
from tilekit.plugins.substitution.engine import assemble, generate, unique_tiles
from tilekit.plugins.substitution.expr import evaluate
from tilekit.plugins.substitution.system import load_system, system_from_data
from tilekit.plugins.substitution.tiling import system_properties
from tilekit.tiling import Patch

PHI = (1 + math.sqrt(5)) / 2


def assert_valid(patch: Patch, region=None) -> None:
    """Patch.validate: no overlaps and (with a region) no gaps; the report names offenders."""
    report = patch.validate(region)
    assert report, report.summary()


def fib(n: int) -> int:
    a, b = 0, 1
    for _ in range(n):
        a, b = b, a + b
    return a


# ------------------------------------------------------------------ safe evaluator


@pytest.mark.parametrize(
    "text, value",
    [("phi**-1", 1 / PHI), ("sqrt3/2", math.sqrt(3) / 2), ("-(1+2)*3", -9.0), ("cos(pi/5)", PHI / 2), ("2**-2", 0.25)],
)
def test_evaluator_computes_arithmetic_and_named_constants(text: str, value: float) -> None:
    # cos(pi/5) = phi/2 is the classical identity behind the Penrose geometry
    assert evaluate(text) == pytest.approx(value, abs=1e-15)


@pytest.mark.parametrize(
    "text", ["__import__('os')", "phi.real", "[1]", "lambda: 1", "x", "1 if 1 else 2", "abs(1)", "sqrt(2, 3)"]
)
def test_evaluator_rejects_everything_but_arithmetic(text: str) -> None:
    with pytest.raises(ParseError, match=re.escape(repr(text))):
        evaluate(text)


# ------------------------------------------------------------------ loader

MINIMAL = {
    "name": "square4",
    "scale": 2,
    "prototile": [{"name": "sq", "outline": [[0, 0], [1, 0], [1, 1], [0, 1]]}],
    "rule": [
        {
            "parent": "sq",
            "child": [
                {"tile": "sq", "matrix": [["1/2", 0, 0], [0, "1/2", 0]]},
                {"tile": "sq", "matrix": [["1/2", 0, "1/2"], [0, "1/2", 0]]},
                {"tile": "sq", "matrix": [["1/2", 0, 0], [0, "1/2", "1/2"]]},
                {"tile": "sq", "matrix": [["1/2", 0, "1/2"], [0, "1/2", "1/2"]]},
            ],
        }
    ],
}


def _with_child(child: dict, index: int = 1) -> dict:
    import copy

    data = copy.deepcopy(MINIMAL)
    data["rule"][0]["child"][index] = child
    return data


def test_minimal_square_system_loads_as_a_4_rep_tile() -> None:
    s = system_from_data(MINIMAL, "square4.toml")
    assert s.rep_tile() == 4  # every square is a 4-rep-tile (§6.1)
    assert s.substitution_matrix().tolist() == [[4]]
    assert len(s.symmetries[0]) == 8  # the rule is invariant under all of D4


@pytest.mark.parametrize(
    "child, problem",
    [
        ({"tile": "sq", "matrix": [["1/2", 0, "1/2"], [0, "1/3", 0]]}, "not a similarity"),
        ({"tile": "sq", "matrix": [["1/3", 0, "1/2"], [0, "1/3", 0]]}, "scale 0.333333333, expected 1/scale = 0.5"),
        ({"tile": "triangle", "matrix": [["1/2", 0, "1/2"], [0, "1/2", 0]]}, "unknown tile 'triangle'"),
        ({"tile": 3, "matrix": [["1/2", 0, "1/2"], [0, "1/2", 0]]}, "tile index 3 out of range"),
        ({"tile": "sq", "matrix": [["1/2", 0, 0], [0, "1/2", 0]]}, "leave a gap"),
        ({"tile": "sq", "matrix": [["1/2", 0, "3/4"], [0, "1/2", 0]]}, "extend outside the parent"),
        ({"tile": "sq", "matrix": [["1/2", 0, "open('x')"], [0, "1/2", 0]]}, "contains Call"),
        ({"tile": "sq"}, "give exactly one of 'matrix'"),
    ],
)
def test_loader_rejects_malformed_rules_naming_file_rule_and_problem(child: dict, problem: str) -> None:
    with pytest.raises(ParseError) as err:
        system_from_data(_with_child(child), "broken.toml")
    msg = str(err.value)
    assert "broken.toml" in msg and "\n" not in msg
    assert problem in msg
    if "rule" in problem or "similarity" in problem or "scale" in problem:
        assert "rule for 'sq', child #2" in msg


def test_loader_names_the_file_on_bad_toml_and_missing_pieces(tmp_path: Path) -> None:
    bad = tmp_path / "oops.toml"
    bad.write_text("name = [unclosed\n")
    with pytest.raises(ParseError, match=r"oops\.toml: not valid TOML"):
        load_system(bad)
    bad.write_text('name = "x"\nscale = "phi"\n[[prototile]]\nname="a"\noutline=[[0,0],[1,0],[0,1]]\n')
    with pytest.raises(ParseError, match=r"oops\.toml: no \[\[rule\]\] tables"):
        load_system(bad)
    with pytest.raises(ParseError, match="missing.toml.* does not exist"):
        load_system(tmp_path / "missing.toml")


def test_loader_checks_indented_and_overlapping_kinds() -> None:
    import copy

    # the exact square rule is acceptable as 'overlapping' (children cover the parent)...
    over = copy.deepcopy(MINIMAL)
    over["kind"] = "overlapping"
    assert system_from_data(over, "o.toml").kind == "overlapping"
    # ...but a duplicated child must be declared: as 'indented' it overlaps and is rejected
    dup = _with_child({"tile": "sq", "matrix": [["1/2", 0, 0], [0, "1/2", 0]]})
    dup["rule"][0]["child"].append({"tile": "sq", "matrix": [["1/2", 0, "1/2"], [0, "1/2", 0]]})
    dup["kind"] = "indented"
    with pytest.raises(ParseError, match="children overlap each other"):
        system_from_data(dup, "d.toml")
    dup["kind"] = "overlapping"
    assert len(system_from_data(dup, "d.toml").rules[0].children) == 5


# ------------------------------------------------------------------ duplicates (exercise 6.7)


def test_overlapping_rules_yield_each_tile_once() -> None:
    """A rule placing the same quarter twice, once rotated by a square symmetry, and once more
    reflected: exercise 6.7's symmetric prototile with several matrices placing one tile."""
    import copy

    data = copy.deepcopy(MINIMAL)
    data["kind"] = "overlapping"
    data["rule"][0]["child"] += [
        # quarter (0,0)-(1/2,1/2) rotated by 90 degrees about its centre: the same tile
        {"tile": "sq", "matrix": [[0, "-1/2", "1/2"], ["1/2", 0, 0]]},
        # and reflected in its diagonal: again the same tile
        {"tile": "sq", "matrix": [[0, "1/2", 0], ["1/2", 0, 0]]},
    ]
    s = system_from_data(data, "dup.toml")
    for depth in (1, 2, 3):
        proto, tr = generate(s, depth, Affine.scaling(2**depth))
        assert len(proto) == 4**depth  # each unit square of the 2^d x 2^d grid exactly once
        assert_valid(Patch(s.prototiles, proto, tr), (0, 0, 2**depth, 2**depth))


def test_unique_tiles_keeps_distinct_and_merges_symmetric_copies() -> None:
    rot = Affine.rotation(math.pi / 2, (0.5, 0.5))
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    from tilekit.plugins.substitution.system import outline_symmetries

    groups = [outline_symmetries(square)]
    t = np.array([np.eye(3), rot, Affine.translation(1, 0), Affine.translation(1, 0) @ rot, Affine.translation(3e-9, 0)])
    keep = unique_tiles(np.zeros(5, dtype=np.int64), t, groups)
    assert keep.tolist() == [0, 2]


# ------------------------------------------------------------------ Penrose


def test_penrose_p3_counts_are_powers_of_the_matrix_and_fibonacci() -> None:
    """Robinson triangles: acute -> acute + obtuse, obtuse -> acute + 2 obtuse, so from one
    acute triangle generation n holds F(2n-1) acute and F(2n) obtuse triangles, F(2n+1) in
    all (Grunbaum & Shephard, Tilings and Patterns §10.3; the sequences of exercise 6.3)."""
    s = builtin_systems()["penrose-p3"]
    assert s.substitution_matrix().tolist() == [[1, 1], [1, 2]]
    m = s.substitution_matrix()
    for n in range(1, 9):
        proto, _ = generate(s, n, seed_prototile=0)
        counts = np.bincount(proto, minlength=2)
        assert counts.tolist() == (np.linalg.matrix_power(m, n) @ [1, 0]).tolist()
        assert counts.tolist() == [fib(2 * n - 1), fib(2 * n)]
        assert len(proto) == fib(2 * n + 1)


def test_penrose_p2_counts_are_fibonacci() -> None:
    """Half-kite -> 2 half-kites + half-dart, half-dart -> half-kite + half-dart: from one
    half-kite, generation n has F(2n+1) half-kites and F(2n) half-darts."""
    s = builtin_systems()["penrose-p2"]
    assert s.substitution_matrix().tolist() == [[2, 1], [1, 1]]
    for n in range(1, 9):
        proto, _ = generate(s, n, seed_prototile=0)
        assert np.bincount(proto, minlength=2).tolist() == [fib(2 * n + 1), fib(2 * n)]


@pytest.mark.parametrize("name", ["penrose-p2", "penrose-p3"])
def test_penrose_whole_tile_ratio_converges_to_phi(name: str) -> None:
    """Kites:darts and thick:thin rhombs tend to the golden ratio (Grunbaum & Shephard §10.3)."""
    s = builtin_systems()[name]
    eig, freq = s.perron_frobenius()
    assert eig == pytest.approx(PHI**2)  # self-similar: the eigenvalue is s^2
    assert max(freq) / min(freq) == pytest.approx(PHI)
    proto, tr = generate(s, 14, Affine.scaling(PHI**14), 0)
    whole, _ = assemble(s, proto, tr)
    counts = np.bincount(whole, minlength=2)
    assert max(counts) / min(counts) == pytest.approx(PHI, rel=2e-3)


@pytest.mark.parametrize("name", ["penrose-p2", "penrose-p3"])
@pytest.mark.parametrize("depth", [2, 5, 8])
def test_penrose_half_and_whole_tiles_validate(name: str, depth: int) -> None:
    s = builtin_systems()[name]
    for seed in (0, 1):
        proto, tr = generate(s, depth, Affine.scaling(PHI**depth), seed)
        halves = Patch(s.prototiles, proto, tr)
        scaled = Affine.apply(Affine.scaling(PHI**depth), s.prototiles[seed].outline)
        import shapely

        assert_valid(halves, shapely.Polygon(scaled))  # the halves tile the inflated seed exactly
        whole, wt = assemble(s, proto, tr)
        patch = Patch(s.tiles, whole, wt)
        assert_valid(patch, shapely.Polygon(scaled))
        # every whole tile is made of two halves, so no whole tile appears twice
        assert len(whole) == len(unique_tiles(whole, wt, s.output_symmetries))
        assert len(whole) * 2 >= len(proto)


def test_penrose_p3_whole_rhombs_pair_every_interior_half() -> None:
    """Exercise 6.10: after assembly each interior half-tile is matched with its mirror half,
    so the number of rhombs is (halves + unpaired boundary halves) / 2."""
    s = builtin_systems()["penrose-p3"]
    proto, tr = generate(s, 7, Affine.scaling(PHI**7), 1)
    whole, _ = assemble(s, proto, tr)
    # each rhomb accounts for two halves if both lie in the patch, one if its partner is outside
    assert len(proto) / 2 <= len(whole) < len(proto)


@pytest.mark.parametrize("name", ["penrose-p2", "penrose-p3"])
def test_patch_covers_requested_regions(name: str) -> None:
    t = tiling(name)
    for region in [(-5, -5, 5, 5), (100, -40, 130, -10), (-3, 2, 20, 4)]:
        assert_valid(t.patch(region), region)


def test_region_targeted_expansion_only_expands_near_the_region() -> None:
    s = builtin_systems()["penrose-p3"]
    t = tiling("penrose-p3")
    region = (-3, -3, 3, 3)
    import shapely

    seed, tr, depth = t.seed_placement(shapely.box(*region))
    culled, _ = generate(s, depth + 6, tr @ Affine.scaling(PHI**6), seed, box=region)
    full_count = sum(s.counts(depth + 6, seed)[-1])
    assert len(culled) < full_count / 50


def test_fixed_depth_configuration_and_spec_round_trip() -> None:
    t = tiling("penrose-p3").configure(depth=5)
    patch = t.patch()
    s = builtin_systems()["penrose-p3"]
    # thick seed (obtuse half) at depth 5: F(12) halves
    assert len(generate(s, 5, seed_prototile=s.seed)[0]) == fib(12)
    assert_valid(patch)
    back = from_spec(t.spec())
    assert back.spec() == {"system": "penrose-p3", "depth": 5}
    assert len(back.patch()) == len(patch)
    with pytest.raises(ParameterError, match="does not take option"):
        t.configure(colour="red")
    with pytest.raises(ParameterError, match="seed 'kite' is not a prototile"):
        t.configure(seed="kite")
    with pytest.raises(TilekitError, match="unknown substitution system 'penrose-p4'"):
        from_spec({"system": "penrose-p4"})


def test_custom_system_from_file_round_trips_through_its_spec(tmp_path: Path) -> None:
    src = Path(__file__).resolve().parents[2] / "catalogue" / "substitution" / "penrose-p3.toml"
    mine = tmp_path / "my.toml"
    mine.write_text(src.read_text().replace('name = "penrose-p3"', 'name = "my-rhombs"'))
    t = from_file(str(mine))
    assert t.name == "my-rhombs"
    back = from_spec(t.spec())
    region = (-4, -4, 4, 4)
    assert len(back.patch(region)) == len(t.patch(region)) > 50


def test_cli_renders_builtin_and_custom_systems(tmp_path: Path) -> None:
    """`tilekit render penrose-p3 --depth 6 -o p3.svg` and `tilekit render --system my.toml`."""
    from click.testing import CliRunner

    from tilekit.cli import cli

    db = f"sqlite:///{tmp_path / 'cat.db'}"
    out = tmp_path / "p3.svg"
    res = CliRunner().invoke(cli, ["--catalogue", db, "render", "penrose-p3", "--depth", "6", "-o", str(out)])
    assert res.exit_code == 0, res.output
    s = builtin_systems()["penrose-p3"]
    whole = system_properties(s)["tiles_per_generation"][6]  # the star of five thick rhombs, 6 times
    assert f"({whole} tiles)" in res.output  # the whole depth-6 patch, not a window
    assert out.read_text().startswith("<svg") or "<svg" in out.read_text()[:200]
    src = Path(__file__).resolve().parents[2] / "catalogue" / "substitution" / "chair.toml"
    mine = tmp_path / "mine.toml"
    mine.write_text(src.read_text().replace('name = "chair"', 'name = "my-chair"', 1))
    res = CliRunner().invoke(
        cli, ["--catalogue", db, "render", "--system", str(mine), "--depth", "3", "-o", str(tmp_path / "c.svg")]
    )
    assert res.exit_code == 0, res.output
    assert "(64 tiles)" in res.output  # 4^3 chairs
    broken = tmp_path / "broken.toml"
    broken.write_text(src.read_text().replace('vertices = [[2, 0], [2, 1], ["3/2", 1]]', 'vertices = [[2, 0], [2, 1], [2, 1]]'))
    res = CliRunner().invoke(cli, ["--catalogue", db, "render", "--system", str(broken), "-o", str(tmp_path / "b.svg")])
    assert res.exit_code != 0
    assert "broken.toml" in res.output and "rule for 'chair', child #3" in res.output
