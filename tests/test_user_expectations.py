"""What a new user expects to see (issue 14): names, filters, colours, image options, help.

Each test cites the command it covers and runs it on the real built-in catalogue.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from click.testing import CliRunner

from tilekit.cli import cli


@pytest.fixture(scope="module")
def cat(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("user") / "cat.sqlite"
    assert CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{path}", "list", "--limit", "1"]).exit_code == 0
    return path


def run(cat: Path, *args: str):
    return CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{cat}", *args])


def one_line_error(result, fragment: str = "") -> str:
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr
    assert fragment in lines[0], lines[0]
    return lines[0]


@pytest.mark.parametrize("alias,name", [
    ("cairo", "[3^2.4.3.4]"), ("snub square", "3^2.4.3.4"), ("snub hexagonal", "3^4.6l"),
    ("rhombitrihexagonal", "3.4.6.4"), ("truncated square", "4.8^2"), ("kisrhombille", "[4.6.12]"),
    ("floret pentagonal", "[3^4.6]l"), ("prismatic pentagonal", "[3^3.4^2]"), ("tetrille", "[3.4.6.4]"),
    ("Snub-Square", "3^2.4.3.4"), ("kagome", "3.6.3.6"),
])
def test_common_names_are_aliases(cat, tmp_path, alias, name):
    # tilekit show cairo / tilekit render "snub square" -o x.svg / tilekit list --text tetrille
    shown = run(cat, "show", alias)
    assert shown.exit_code == 0, shown.output
    assert shown.stdout.splitlines()[0] == f"name: {name}"
    drawn = run(cat, "render", alias, "-o", str(tmp_path / "x.svg"))
    assert drawn.exit_code == 0, drawn.output
    listed = run(cat, "list", "--text", alias.lower(), "--format", "csv")
    assert name in listed.stdout


def test_symmetry_group_by_either_name(cat):
    # tilekit list --where symmetry_group=p6m (IUC) and =*632 (orbifold) find the same tilings
    iuc = run(cat, "list", "--where", "symmetry_group=p6m", "--format", "csv").stdout
    orb = run(cat, "list", "--where", "symmetry_group=*632", "--format", "csv").stdout
    assert iuc == orb and "4.6.12" in iuc and "3^6" in iuc
    wall = run(cat, "list", "--where", "wallpaper_group=*632", "--format", "csv").stdout
    assert wall.splitlines()[1:] and {r.split(",")[0] for r in wall.splitlines()[1:]} == \
        {r.split(",")[0] for r in iuc.splitlines()[1:]}
    not_iuc = run(cat, "list", "--where", "symmetry_group!=p6m", "--format", "csv").stdout
    assert "4.6.12" not in not_iuc and "3^4.6l" in not_iuc


def test_catalogue_doc_keys_exist(cat):
    # docs/catalogue.md's examples: valence>=5 with symmetry_group!=p6m, expansion_constant=phi
    docs = (Path(__file__).parent.parent / "docs" / "catalogue.md").read_text(encoding="utf-8")
    assert "vertex_degree" not in docs and "polygon_area" not in docs
    assert "3^4.6l" in run(cat, "list", "--where", "valence>=5", "--where", "symmetry_group!=p6m").stdout
    assert "penrose-p2" in run(cat, "list", "--where", "expansion_constant=1.6180339887").stdout


def test_export_unknown_family_is_an_error(cat):
    # tilekit catalogue export --family nope, like tilekit list --family nope
    one_line_error(run(cat, "catalogue", "export", "--family", "nope"), "unknown family 'nope'")
    one_line_error(run(cat, "list", "--family", "nope"), "unknown family 'nope'")


@pytest.mark.parametrize("args,fragment", [
    (["--colours", "notacolour"], "not a CSS colour name"),
    (["--colours", "redd"], "did you mean 'red'"),
    (["--stroke", "notacolour"], "not a CSS colour name"),
    (["--width", "100", "--height", "100"], "not both"),
    (["--width", "99999999"], "--width"),
])
def test_render_image_options_validated(cat, tmp_path, args, fragment):
    # tilekit render 4^4 --colours notacolour: an error, not fill="notacolour"
    out = tmp_path / "x.svg"
    one_line_error(run(cat, "render", "4^4", "-o", str(out), *args), fragment)
    assert not out.exists()


def test_render_width_height_dpi_stroke(cat, tmp_path):
    # tilekit render 4^4 --width 300 --stroke navy --stroke-width 3 -o x.png; --height 200 --dpi 192
    pytest.importorskip("cairosvg")
    from PIL import Image

    a, b = tmp_path / "a.png", tmp_path / "b.png"
    assert run(cat, "render", "4^4", "--width", "300", "--stroke", "navy", "-o", str(a)).exit_code == 0
    assert Image.open(a).size == (300, 300)
    assert run(cat, "render", "4^4", "--height", "200", "--dpi", "192", "-o", str(b)).exit_code == 0
    assert Image.open(b).size == (400, 400)
    svg = tmp_path / "c.svg"
    assert run(cat, "render", "4^4", "--stroke", "navy", "--stroke-width", "3", "--width", "300",
               "-o", str(svg)).exit_code == 0
    g = [e for e in ET.parse(svg).getroot().iter() if e.get("stroke") == "navy"]
    assert g, "the stroke colour is used"


@pytest.mark.parametrize("command", [
    [], ["render"], ["list"], ["show"], ["families"], ["search"], ["search", "vertex-species"], ["runs"],
    ["catalogue"], ["catalogue", "export"], ["catalogue", "path"], ["catalogue", "upgrade"], ["catalogue", "seed"],
    ["wang"], ["wang", "render"], ["wang", "solve"],
    ["wang", "example"], ["wang", "texture"], ["wang", "synth"], ["wang", "scatter"],
])
def test_help_has_an_example(cat, command):
    # tilekit COMMAND --help shows at least one example invocation
    result = run(cat, *command, "--help")
    assert result.exit_code == 0
    assert "tilekit " in result.stdout.split("Options:")[0], result.stdout


def test_cli_doc_covers_every_command(cat):
    # docs/cli.md has a section per command, the wang group included, and --max-tiles
    doc = (Path(__file__).parent.parent / "docs" / "cli.md").read_text(encoding="utf-8")
    for cmd in ("families", "list", "show", "render", "search", "runs", "catalogue", "wang render", "wang solve"):
        assert f"## `tilekit {cmd}" in doc, cmd
    assert "--max-tiles" in doc and "--max-variables" in doc


def test_readme_names_the_png_extra():
    # README: the first PNG example says PNG needs the png extra
    readme = (Path(__file__).parent.parent / "README.md").read_text(encoding="utf-8")
    first_png = readme.index(".png", readme.index("## Command line"))
    assert "[png]" in readme[first_png - 400: first_png + 400]  # tilekit[png] or .[png] from a checkout


@pytest.mark.parametrize("name,ok", [("IH16", True), ("stochastic-2colour", True), ("4^4", False),
                                     ("penrose-p3", False), ("hat", False)])
def test_labels_label_edges_or_say_they_cannot(cat, tmp_path, name, ok):
    # tilekit render IH16 --labels draws the incidence-symbol labels; 4^4 --labels says it can't
    out = tmp_path / "l.svg"
    result = run(cat, "render", name, "--labels", "-o", str(out))
    if ok:
        assert result.exit_code == 0, result.output
        texts = [e.text for e in ET.parse(out).getroot().iter("{http://www.w3.org/2000/svg}text")]
        assert texts
        if name == "IH16":
            assert {"a+", "a-"} <= set(texts)
    else:
        one_line_error(result, "carry no edge labels")


@pytest.mark.parametrize("name,least", [("chair", 4), ("sphinx", 6), ("pinwheel", 4)])
def test_one_prototile_systems_coloured_by_orientation(cat, tmp_path, name, least):
    # tilekit render chair --depth 3: one fill per orientation, not one colour for all
    out = tmp_path / "c.svg"
    assert run(cat, "render", name, "--depth", "3", "-o", str(out)).exit_code == 0
    fills = {e.get("fill") for e in ET.parse(out).getroot().iter("{http://www.w3.org/2000/svg}path")
             if e.get("fill") not in (None, "none")}
    assert len(fills) >= least


def test_render_of_a_wang_set_shows_edge_colours(cat, tmp_path):
    # tilekit render stochastic-2colour draws the triangles of tilekit wang render
    a, b = tmp_path / "a.svg", tmp_path / "b.svg"
    assert run(cat, "render", "stochastic-2colour", "-o", str(a)).exit_code == 0
    assert run(cat, "wang", "render", "stochastic-2colour", "--rows", "8", "--cols", "12", "-o", str(b)).exit_code == 0
    for svg in (a.read_text(), b.read_text()):
        assert "clipN" in svg and "<use" in svg


def test_one_edge_syntax_for_every_family(cat, tmp_path):
    # --edge NAME=x,y:... with or without the end points (0,0) and (1,0), isohedral and substitution
    for name, short, full in (("IH16", "b=0.3,0.2", "b=0,0:0.3,0.2:1,0"),
                              ("penrose-p2", "a=0.3,0.1", "a=0,0:0.3,0.1:1,0")):
        x, y = tmp_path / "x.svg", tmp_path / "y.svg"
        assert run(cat, "render", name, "--edge", short, "-o", str(x)).exit_code == 0
        assert run(cat, "render", name, "--edge", full, "-o", str(y)).exit_code == 0
        assert x.read_text() == y.read_text()


@pytest.mark.parametrize("family,key", [("substitution", "--depth"), ("wang", "method="),
                                        ("isohedral", "colouring="), ("archimedean", "no options")])
def test_show_family_lists_its_options(cat, family, key):
    # tilekit show substitution: the family, its size and the --set keys its tilings take
    result = run(cat, "show", family)
    assert result.exit_code == 0, result.output
    assert result.stdout.startswith(f"family: {family}") and key in result.stdout


def test_clipped_tiles_end_on_a_frame(cat, tmp_path):
    # tilekit render penrose-p3 --region -5,-5,5,5: edges cut by the border end on a drawn frame
    out = tmp_path / "f.svg"
    assert run(cat, "render", "penrose-p3", "--region", "-5,-5,5,5", "-o", str(out)).exit_code == 0
    rects = [e for e in ET.parse(out).getroot().iter("{http://www.w3.org/2000/svg}rect") if e.get("fill") == "none"]
    assert len(rects) == 1 and [float(rects[0].get(k)) for k in ("x", "y", "width", "height")] == [-5, -5, 10, 10]


def test_long_render_shows_progress_on_a_terminal(cat, tmp_path, monkeypatch):
    # tilekit render penrose-p3 --depth 7 on a terminal: what it makes, then what it draws
    import tilekit.cli as cli_module

    monkeypatch.setattr(cli_module.render, "PROGRESS_TILES", 1000)
    out = tmp_path / "p.svg"
    quiet = run(cat, "render", "penrose-p3", "--depth", "6", "-o", str(out))
    assert quiet.exit_code == 0 and quiet.stderr == ""  # not a terminal: no progress lines
    monkeypatch.setattr(cli_module.render, "on_terminal", lambda: True)
    loud = run(cat, "render", "penrose-p3", "--depth", "6", "-o", str(out))
    assert loud.exit_code == 0
    assert "making about" in loud.stderr and "drawing 1,925 tiles" in loud.stderr
