"""The isohedral editor on split (dihedral) tilings, issue 33: a spec written by ``tilekit
escherize GOAL_A GOAL_B`` (a tile cut in two by a splitting path, Kaplan and Salesin 2004;
Kaplan 2009, §7.3) opens in the editor with its path editable, a dragged point gives a new
spec, and the exported spec reopens identically on the command line (``render --system``).
Also a Heaven-and-Hell spec (a two-coloured tile), and the split option's text form."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from cliutil import assert_one_line_error
from hypothesis import given
from hypothesis import strategies as st
from test_web_browser import renders, wait_render

from tilekit.cli import cli
from tilekit.edgeshapes import EdgeShape
from tilekit.errors import GeometryError, ParseError
from tilekit.plugins.isohedral.engine import IsohedralTiling
from tilekit.plugins.isohedral.spec import (
    editor_path,
    editor_query,
    tiling_from_file,
    tiling_from_spec,
)
from tilekit.plugins.isohedral.split import SplitTiling, parse_split, split_text

pytest.importorskip("playwright")

#: A split IH1 tile (tests/data/escher/ih1-split.json: the escherize tests' known split).
KNOWN = json.loads((Path(__file__).resolve().parent.parent / "data" / "escher" / "ih1-split.json").read_text())


@pytest.fixture(scope="module")
def cat_url(tmp_path_factory) -> str:
    """One SQLite catalogue for this module's command lines (seeded once, then only read)."""
    return f"sqlite:///{tmp_path_factory.mktemp('cat') / 'c.sqlite'}"


def same_tiling(a, b) -> None:
    """Equal specs and equal patches on the default region (transforms and piece outlines)."""
    assert a.spec() == b.spec()
    region = a.default_region()
    pa, pb = a.patch(region), b.patch(region)
    assert pa.validate(region).ok and len(pa) == len(pb)
    assert np.array_equal(pa.transform, pb.transform) and np.array_equal(pa.prototile, pb.prototile)
    for x, y in zip(pa.prototiles, pb.prototiles, strict=True):
        assert np.array_equal(np.asarray(x.outline), np.asarray(y.outline))


# --------------------------------------------------------------------------- the option


def test_split_option_text_round_trips_and_configures_the_tiling():
    t = tiling_from_spec(KNOWN)
    assert isinstance(t, SplitTiling)
    text = split_text(t.spec()["split"])
    assert text == "0.4,3.6;0,0:0.3,0.15:0.7,-0.1:1,0"
    assert parse_split(text) == t.spec()["split"]
    base = t.base
    same_tiling(base.configure(split=text), t)
    # a split tiling configured keeps its split on the new tile, and split=none removes it
    moved = t.configure(params=[0.13, 0.5, 0.15, 0.6])
    assert isinstance(moved, SplitTiling) and moved.spec()["split"] == t.spec()["split"]
    assert moved.base.params == (0.13, 0.5, 0.15, 0.6)
    assert isinstance(t.configure(split="none"), IsohedralTiling)
    # the editor's URL carries it as set=split=..., and the API's parser reads it back
    assert editor_query(KNOWN).endswith("&set=split=0.4,3.6;0,0:0.3,0.15:0.7,-0.1:1,0")


FINITE = st.floats(allow_nan=False, allow_infinity=False, width=64)


@given(st.tuples(FINITE, FINITE), st.lists(st.tuples(FINITE, FINITE), max_size=5))
def test_split_text_reads_back_as_the_same_numbers(ends, points):
    """split_text -> parse_split is the identity on the numbers (shortest round-trip text)."""
    path = ":".join(f"{x!r},{y!r}" for x, y in [(0.0, 0.0), *points, (1.0, 0.0)])
    table = {"ends": list(ends), "path": path}
    back = parse_split(split_text(table))
    assert back == {"ends": [float(v) for v in ends], "path": path}
    assert parse_split(split_text({"ends": list(ends)})) == {"ends": [float(v) for v in ends]}


@pytest.mark.parametrize(
    ("split", "error", "fragment"),
    [
        ("0.4", ParseError, "give two ends 'S,T'"),
        ("0.4,x", ParseError, "are not two numbers"),
        ("0.4,3.6;0,0:0.5,3:1,0", GeometryError, "crosses itself"),  # the path leaves the tile
        ("0.4,0.6", GeometryError, "fewer than 3 distinct vertices"),  # both ends on one straight run
    ],
)
def test_bad_split_options_are_one_line_errors(split, error, fragment, tmp_path, cat_url):
    base = tiling_from_spec({k: v for k, v in KNOWN.items() if k != "split"})
    with pytest.raises(error, match=re.escape(fragment)):
        base.configure(split=split)
    result = CliRunner().invoke(cli, ["--catalogue", cat_url, "render", "IH1",
                                      "--set", f"split={split}", "-o", str(tmp_path / "x.svg")])
    assert_one_line_error(result, fragment)


def test_the_api_reads_a_split_and_refuses_a_path_outside_the_tile(client):
    spec = client.get(f"/api/tiling/IH1/spec?{editor_query(KNOWN)}").json()
    assert spec["spec"] == tiling_from_spec(KNOWN).spec()
    info = client.get(f"/api/tiling/IH1/editor?{editor_query(KNOWN)}").json()
    assert info["split"]["ends"] == [0.4, 3.6] and len(info["split"]["points"]) == 4
    assert info["tile"]["counts"] == [5, 5, 5, 5, 5, 5]  # five segments on each J edge of the shaped IH1
    page = client.get(editor_path(KNOWN))
    assert page.status_code == 200 and "data-notice" not in page.text
    bad = client.get("/api/render/IH1?set=split=0.4,3.6;0,0:0.5,3:1,0")
    assert bad.status_code == 400 and "crosses itself" in bad.json()["error"]


# --------------------------------------------------------------------------- the browser


def drag(page, selector: str, dx: float, dy: float, panel: str = "#split-svg") -> None:
    """Drag the handle ``selector`` by (dx, dy) pixels, its panel scrolled into view first."""
    page.locator(panel).scroll_into_view_if_needed()
    box = page.locator(selector).bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + dx, y + dy, steps=5)
    page.mouse.up()


def open_spec(page, spec: dict) -> None:
    page.goto(editor_path(spec))
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    assert json.loads(page.get_attribute("#editor", "data-spec")) == tiling_from_spec(spec).spec()


def export_and_reopen(page, tmp_path: Path, cat_url: str) -> dict:
    """The exported spec file, reopened by ``render --system``: the same tiling as the editor's."""
    with page.expect_download() as dl:
        page.click("#export-spec")
    path = tmp_path / "edited.isohedral.json"
    dl.value.save_as(path)
    data = json.loads(path.read_text())
    shown = json.loads(page.get_attribute("#editor", "data-spec"))
    assert data["spec"] == shown
    same_tiling(tiling_from_file(str(path)), tiling_from_spec(shown))
    result = CliRunner().invoke(cli, ["--catalogue", cat_url, "render", "--system",
                                      str(path), "-o", str(tmp_path / "reopened.svg")])
    assert result.exit_code == 0, result.output
    return data["spec"]


def check_split_editing(page, spec: dict, tmp_path: Path, cat_url: str) -> None:
    open_spec(page, spec)
    # the two pieces in two colours, in the panel and in the tiling
    fills = page.eval_on_selector_all("#split-svg .piece", "els => els.map(e => e.getAttribute('fill'))")
    assert len(fills) == 2 and fills[0] != fills[1]
    view_fills = set(page.eval_on_selector_all("#view svg path[fill]", "els => els.map(e => e.getAttribute('fill'))"))
    assert set(fills) <= view_fills
    before = json.loads(page.get_attribute("#editor", "data-spec"))["split"]

    n = renders(page)
    drag(page, ".split-point >> nth=0", 12, 8)
    wait_render(page, n)
    assert page.get_attribute("#editor", "data-state") == "ok"
    after = json.loads(page.get_attribute("#editor", "data-spec"))["split"]
    assert after["ends"] == before["ends"] and after["path"] != before["path"]
    # the dragged point has at most 4 decimals (no float32 noise), the others are untouched
    moved = [p for p in after["path"].split(":") if p not in before["path"].split(":")]
    assert len(moved) == 1 and all(len(v.split(".")[-1]) <= 4 for v in moved[0].split(","))

    n = renders(page)
    drag(page, ".split-end[data-index='0']", 6, 6)
    wait_render(page, n)
    moved_end = json.loads(page.get_attribute("#editor", "data-spec"))["split"]
    if page.get_attribute("#editor", "data-state") == "ok":
        assert moved_end["ends"][0] != after["ends"][0] and moved_end["ends"][1] == after["ends"][1]

    # a path dragged out of the tile is refused with the reason; the export keeps the last tiling
    last = json.loads(page.get_attribute("#editor", "data-spec"))
    n = renders(page)
    drag(page, ".split-point >> nth=0", 0, 400)
    wait_render(page, n)
    assert page.get_attribute("#editor", "data-state") == "refused"
    assert "split" in page.inner_text("#error") and "last tiling drawn" in page.inner_text("#error")
    assert export_and_reopen(page, tmp_path, cat_url) == last
    assert not page.js_errors


def test_editor_edits_a_split_spec_and_its_export_reopens_identically(page, tmp_path, cat_url):
    check_split_editing(page, KNOWN, tmp_path, cat_url)


def test_editor_adds_and_removes_a_split(page):
    page.goto("/editor/IH41")
    page.wait_for_selector("#editor[data-state=ok]", timeout=20000)
    n = renders(page)
    page.click("#split-add")
    wait_render(page, n)
    spec = json.loads(page.get_attribute("#editor", "data-spec"))
    assert spec["split"]["ends"] == [0.5, 2.5]
    assert page.is_disabled("#colouring")  # coloured by piece while split
    assert "set=split=0.5,2.5;0,0:1,0" in page.evaluate("location.search")
    n = renders(page)
    page.click("#split-point")
    wait_render(page, n)
    assert json.loads(page.get_attribute("#editor", "data-spec"))["split"]["path"] == "0,0:0.5,0.1:1,0"
    n = renders(page)
    page.click("#split-remove")
    wait_render(page, n)
    assert "split" not in json.loads(page.get_attribute("#editor", "data-spec"))
    assert not page.is_disabled("#colouring")
    assert not page.js_errors


@pytest.fixture(scope="module")
def escherized(tmp_path_factory):
    """Specs written by ``tilekit escherize``: a dihedral split (the two pieces of the known
    IH1 split as goals, fitted on IH41) and a Heaven-and-Hell tile (an IH41 tile and its mirror)."""
    out = tmp_path_factory.mktemp("escherize")
    t = tiling_from_spec(KNOWN)
    a, b = (np.asarray(p.outline).tolist() for p in t.prototiles)
    (out / "a.json").write_text(json.dumps(a))
    (out / "b.json").write_text(json.dumps(b))
    tile = IsohedralTiling("IH41", None, {"a": EdgeShape.parse("0.3,0.15:0.6,-0.1")}, check=True)
    c = np.asarray(tile.prototile.outline)
    (out / "c.json").write_text(json.dumps(c.tolist()))
    (out / "d.json").write_text(json.dumps((c * [-1, 1]).tolist()))
    runner = CliRunner()
    common = ["--types", "IH41", "--starts", "1", "--samples", "64"]
    split = runner.invoke(cli, ["escherize", str(out / "a.json"), str(out / "b.json"), *common, "-o", str(out / "split")])
    assert split.exit_code == 0, split.output
    hh = runner.invoke(cli, ["escherize", str(out / "c.json"), str(out / "d.json"), "--heaven-hell", *common,
                             "-o", str(out / "hh")])
    assert hh.exit_code == 0, hh.output
    return {"split": json.loads((out / "split" / "01-IH41-split.isohedral.json").read_text())["spec"],
            "hh": json.loads((out / "hh" / "01-IH41-hh.isohedral.json").read_text())["spec"]}


@pytest.mark.slow
def test_editor_on_an_escherize_dihedral_spec(page, escherized, tmp_path, cat_url):
    assert "split" in escherized["split"]
    check_split_editing(page, escherized["split"], tmp_path, cat_url)


@pytest.mark.slow
def test_editor_on_an_escherize_heaven_and_hell_spec(page, escherized, tmp_path, cat_url):
    """The Heaven-and-Hell tile opens with its two-colouring (neighbours differ); an edge
    handle dragged gives a spec that reopens identically, colouring kept."""
    spec = escherized["hh"]
    open_spec(page, spec)
    assert page.input_value("#colouring") == spec["colouring"]
    n = renders(page)
    drag(page, "#edge-a .handle >> nth=0", 8, -6, panel="#edge-a")
    wait_render(page, n)
    edited = export_and_reopen(page, tmp_path, cat_url)
    # the two-colouring stays (escherize writes it out; a spec leaves out the type's default)
    assert str(tiling_from_spec(edited).colouring) == spec["colouring"] and edited["edges"] != spec["edges"]
    assert not page.js_errors
