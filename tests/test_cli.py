"""The tilekit command line through click's CliRunner: each command's happy and bad-input paths.

Bad input must give exit status 2 and exactly one line ``error: ...`` on stderr, no traceback.
The catalogue data are the test family of tests/data/testkit.py (Grünbaum & Shephard §2.1).
"""

from __future__ import annotations

import csv
import io
import json
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

sys.path.insert(0, str(Path(__file__).parent / "data"))
sys.path.insert(0, str(Path(__file__).parent))

import test_search  # noqa: E402
import testkit  # noqa: E402
from cliutil import assert_one_line_error

import tilekit.cli as cli_module  # noqa: E402
from tilekit.cli import cli  # noqa: E402


@pytest.fixture
def pm(monkeypatch):
    pm = testkit.isolated_pm(monkeypatch, testkit.GridPlugin(), test_search.RectPlugin())
    monkeypatch.setattr(cli_module.base, "plugin_manager", lambda: pm)
    return pm


@pytest.fixture
def db(tmp_path, monkeypatch):
    path = tmp_path / "cli.sqlite"
    monkeypatch.delenv("TILEKIT_CATALOGUE", raising=False)
    return path


def run(db: Path, *args: str):
    return CliRunner().invoke(cli, ["--catalogue", f"sqlite:///{db}", *args], catch_exceptions=False)


# --------------------------------------------------------------------------- families / list / show


def test_families(pm, db):
    result = run(db, "families")
    assert result.exit_code == 0
    assert result.stdout.splitlines()[1].startswith("testgrid")
    data = json.loads(run(db, "families", "--format", "json").stdout)
    assert data == [{"name": "testgrid", "summary": "Archimedean tilings for tests (regular ones with geometry)",
                     "reads_files": True}]


def test_list_table_json_csv(pm, db):
    table = run(db, "list")
    assert table.exit_code == 0
    lines = table.stdout.splitlines()
    assert lines[0].split() == ["NAME", "FAMILY", "TITLE"]
    assert len(lines) == 12 and lines[1].split()[0] == "3.4.6.4"  # natural order: 3.4 before 3.12

    data = json.loads(run(db, "list", "--where", "polygons=6", "--format", "json").stdout)
    assert {d["name"] for d in data} == {"6^3", "3^4.6", "3.4.6.4", "3.6.3.6", "4.6.12"}
    hexagonal = next(d for d in data if d["name"] == "6^3")
    assert hexagonal["family"] == "testgrid" and hexagonal["title"] == "regular hexagonal tiling"
    assert hexagonal["sides"] == [6] and hexagonal["vertex_degree"] == 3 and hexagonal["periodic"] is True

    out = run(db, "list", "--where", "vertex_degree>=5", "--where", "symmetry_group!=p6m", "--format", "csv").stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [r["name"] for r in rows] == ["3^2.4.3.4", "3^3.4^2", "3^4.6"]
    assert rows[0]["symmetry_group"] == "p4g"


def test_list_family_text_paging(pm, db):
    names = lambda r: [line.split()[0] for line in r.stdout.splitlines()[1:]]  # noqa: E731
    assert names(run(db, "list", "--text", "snub")) == ["3^2.4.3.4", "3^4.6"]
    assert names(run(db, "list", "--family", "testgrid", "--limit", "2", "--offset", "1")) == ["3.6.3.6", "3.12^2"]  # natural order
    assert names(run(db, "list", "--order", "-vertex_degree", "--limit", "1")) == ["3^6"]
    empty = run(db, "list", "--where", "polygons=5")
    assert empty.exit_code == 0 and empty.stdout == "" and "no tilings match" in empty.stderr


@pytest.mark.parametrize(
    "args, fragment",
    [
        (["list", "--where", "polygons"], "is not of the form"),
        # what bash passes for an unquoted `--where heesch>=2` (stdout goes to a file '=2')
        (["list", "--where", "heesch"], "quote the filter, e.g. --where 'heesch>=2'"),
        (["list", "--where", "polygon=3"], "did you mean 'polygons'"),
        (["list", "--where", "k_hedral>=many"], "needs a number"),
        (["list", "--family", "testgrd"], "did you mean 'testgrid'"),
        (["list", "--limit", "-3"], "--limit"),
        (["list", "--format", "xml"], "'xml' is not one of"),
        (["list", "--order", "colour"], "unknown order key 'colour'"),
    ],
)
def test_list_bad_input(pm, db, args, fragment):
    assert_one_line_error(run(db, *args), fragment)


def test_show(pm, db):
    result = run(db, "show", "4.4.4.4")
    assert result.exit_code == 0
    out = result.stdout
    assert "name: 4^4" in out and "family: testgrid" in out and "aliases: 4.4.4.4, (4^4)" in out
    assert "symmetry_group" in out and "p4m" in out
    assert "sides" in out and "vertex_degree" in out
    assert out.rstrip().endswith("regular tiling 4^4: one 4-gon shape")  # tiling.describe()


def test_show_computes_the_wallpaper_group_when_not_stored(pm, db, tmp_path):
    from tilekit.catalogue import open_catalogue
    from tilekit.plugins import CatalogueRecord

    with open_catalogue(f"sqlite:///{db}", pm=pm) as cat:
        spec = testkit.regular_tiling("4^4").spec()
        cat.upsert([CatalogueRecord("testgrid", "plain-squares", spec, properties={"periodic": True})])
    out = run(db, "show", "plain-squares").stdout
    # the square tiling's group is p4m, orbifold *442 (Kaplan §3.2)
    assert "wallpaper_group" in out and "p4m (*442; computed)" in out


def test_show_unknown_name_suggests(pm, db):
    assert_one_line_error(run(db, "show", "4.4.4.5"), "did you mean '4.4.4.4'")


# --------------------------------------------------------------------------- render


def test_render_svg_and_png(pm, db, tmp_path):
    svg = tmp_path / "squares.svg"
    result = run(db, "render", "4^4", "-o", str(svg), "--region", "0,0,3,2", "--colours", "red,#00ff00",
                 "--vectors")
    assert result.exit_code == 0, result.output
    assert result.stdout.strip() == f"wrote {svg} (6 tiles)"  # a 3 x 2 box of unit squares
    text = svg.read_text()
    assert text.lstrip().startswith("<") and "<svg" in text and "red" in text
    png = tmp_path / "hexagons.png"
    assert run(db, "render", "6^3", "-o", str(png)).exit_code == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_render_from_a_system_file(pm, db, tmp_path):
    spec_file = tmp_path / "tri.json"
    spec_file.write_text(json.dumps(testkit.regular_tiling("3^6").spec()))
    out = tmp_path / "tri.svg"
    result = run(db, "render", "--system", str(spec_file), "--family", "testgrid", "-o", str(out),
                 "--region", "0,0,1,0.8660254")
    assert result.exit_code == 0, result.output
    # the box [0,1] x [0, sqrt(3)/2] holds one up triangle and halves of its two down neighbours
    assert out.exists() and "(3 tiles)" in result.stdout


@pytest.mark.parametrize(
    "args, fragment",
    [
        (["render", "4^4", "-o", "X.svg", "--region", "0,0,1"], "needs four numbers"),
        (["render", "4^4", "-o", "X.svg", "--region", "2,0,1,1"], "x0 < x1"),
        (["render", "4^4", "-o", "X.svg", "--param", "0.1,abc"], "'abc' is not a number"),
        (["render", "4^4", "-o", "X.svg", "--param", "0.1,0.2"], "takes no options (params given)"),
        (["render", "4^4", "-o", "X.svg", "--set", "colour"], "is not KEY=VALUE"),
        (["render", "4^4", "-o", "X.gif"], "must end in one of .svg, .png, .geojson, .json, .cut.svg, .dxf"),
        (["render", "4^4", "-o", "X.svg", "--colours", "not a colour!"], "is not a CSS colour name"),
        (["render", "-o", "X.svg"], "needs a tiling NAME"),
        (["render", "4^4", "-o", "X.svg", "--family", "testgrid"], "--family only goes with --system"),
        (["render", "squares", "-o", "X.svg"], "unknown tiling 'squares'"),
        (["render", "4^4"], "Missing option '-o'"),
        (["render", "4^4", "-o", "X.svg", "--depth", "-1"], "--depth"),
    ],
)
def test_render_bad_input(pm, db, tmp_path, args, fragment):
    args = [a.replace("X.svg", str(tmp_path / "x.svg")) for a in args]
    assert_one_line_error(run(db, *args), fragment)
    assert not (tmp_path / "x.svg").exists()


def test_render_system_with_unknown_family(pm, db, tmp_path):
    spec_file = tmp_path / "s.json"
    spec_file.write_text("{}")
    # the core names no family: with no plugin claiming .json files, the user must name one
    assert_one_line_error(run(db, "render", "--system", str(spec_file), "-o", str(tmp_path / "o.svg")),
                          "no installed family claims the file 's.json'; name one with --family")
    assert_one_line_error(run(db, "render", "--system", str(spec_file), "--family", "substitution",
                              "-o", str(tmp_path / "o.svg")), "unknown family 'substitution'")


# --------------------------------------------------------------------------- search / runs


def test_search_and_runs(pm, db):
    help_text = run(db, "search", "rects", "--help").stdout
    assert "--max-area" in help_text and "--store / --no-store" in help_text and "--executor" in help_text
    listing = run(db, "search").stdout
    assert "rects" in listing

    result = run(db, "search", "rects", "--max-area", "12", "--no-store")
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert lines[0].startswith("run 1: rects done (12/12 chunks")
    assert "  rectangles: 19" in lines and "  squares: 3" in lines  # sum of A038548(1..12) = 19

    table = run(db, "runs").stdout.splitlines()
    assert table[0].split()[:5] == ["ID", "KIND", "STATUS", "PROGRESS", "SECONDS"]
    assert table[1].split()[:4] == ["1", "rects", "done", "12/12"]
    detail = run(db, "runs", "1").stdout
    assert "results: 19" in detail and '"max_area": 12' in detail
    data = json.loads(run(db, "runs", "1", "--format", "json").stdout)
    assert data[0]["status"] == "done" and len(data[0]["results"]) == 19


def test_search_interrupt_then_resume_from_the_cli(pm, db):
    test_search.INTERRUPT_AT.add(4)
    try:
        result = run(db, "search", "rects", "--max-area", "6")
    finally:
        test_search.INTERRUPT_AT.clear()
    assert result.exit_code == 130
    assert "run 1 interrupted after 3/6 chunks" in result.stderr and "--resume 1" in result.stderr
    assert "interrupted" in run(db, "runs").stdout
    resumed = run(db, "search", "rects", "--resume", "1")
    assert resumed.exit_code == 0, resumed.output
    assert resumed.stdout.startswith("run 1: rects done (6/6 chunks")


@pytest.mark.parametrize(
    "args, fragment",
    [
        (["search", "rect"], "unknown search 'rect'; did you mean 'rects'"),
        (["search", "rects"], "needs the parameter 'max_area'"),
        (["search", "rects", "--max-area", "many"], "'many' is not a valid integer"),
        (["search", "rects", "--max-area", "3", "--executor", "gpu"], "'gpu' is not one of"),
        (["search", "rects", "--resume", "9"], "unknown run '9'"),
        (["search", "rects", "--resume", "1", "--max-area", "3"], "drop --max-area"),
        (["runs", "5"], "unknown run '5'"),
    ],
)
def test_search_bad_input(pm, db, args, fragment):
    assert_one_line_error(run(db, *args), fragment)


# --------------------------------------------------------------------------- catalogue


def test_catalogue_commands(pm, db, tmp_path):
    assert run(db, "catalogue", "path").stdout.strip() == str(db)
    assert not db.exists()  # path does not create the catalogue
    upgrade = run(db, "catalogue", "upgrade")
    assert upgrade.exit_code == 0 and "at revision 0003" in upgrade.stdout
    seeded = run(db, "catalogue", "seed")
    assert seeded.stdout.strip() == "added 11, replaced 0 tilings (11 in the catalogue)"
    assert run(db, "catalogue", "seed", "--replace").stdout.startswith("added 0, replaced 11")

    out = tmp_path / "export.json"
    result = run(db, "catalogue", "export", "-o", str(out))
    assert result.exit_code == 0 and "wrote 11 tilings" in result.stderr
    assert {d["name"] for d in json.loads(out.read_text())} == set(testkit.ARCHIMEDEAN)
    rows = list(csv.DictReader(io.StringIO(run(db, "catalogue", "export", "--format", "csv",
                                                "--where", "regular=true").stdout)))
    assert [r["name"] for r in rows] == ["3^6", "4^4", "6^3"] and json.loads(rows[1]["spec"]) == {"vertex_type": "4^4"}


def test_catalogue_option_from_environment(pm, db, monkeypatch):
    monkeypatch.setenv("TILEKIT_CATALOGUE", str(db))
    result = CliRunner().invoke(cli, ["catalogue", "path"])
    assert result.stdout.strip() == str(db)


def test_corrupt_catalogue_is_one_line_error(pm, tmp_path):
    bad = tmp_path / "bad.sqlite"
    bad.write_text("not a database")
    assert_one_line_error(run(bad, "list"), "is not a SQLite database")
    assert bad.read_text() == "not a database"


# --------------------------------------------------------------------------- plugins and generic errors


def test_plugin_commands_are_added(pm, db):
    result = run(db, "grid-count")
    assert result.exit_code == 0 and result.stdout.strip() == "11"
    assert "grid-count" in run(db, "--help").stdout


def test_unknown_command_and_help(pm, db):
    assert_one_line_error(run(db, "lst"), "unknown command 'lst'; did you mean 'list'")
    assert_one_line_error(run(db, "show"), "Missing argument 'NAME'")
    assert run(db, "--help").exit_code == 0


def test_main_exits_2_with_one_line(pm, db, capsys):
    with pytest.raises(SystemExit) as info:
        cli_module.main(["--catalogue", f"sqlite:///{db}", "show", "nope"])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("error: unknown tiling 'nope'") and err.count("\n") == 1


@pytest.mark.parametrize(
    "args, fragment",
    [
        (["families", "--format", "xml"], "'xml' is not one of"),
        (["catalogue", "export", "--format", "xml"], "'xml' is not one of"),
        (["catalogue", "export", "-o", "/no/such/dir/out.json"], "cannot write /no/such/dir/out.json"),
        (["catalogue", "export", "--where", "k_hedral>>1"], "needs a number"),
        (["catalogue", "exprt"], "unknown command 'exprt'; did you mean 'export'"),
        (["runs", "--format", "yaml"], "'yaml' is not one of"),
    ],
)
def test_other_bad_input(pm, db, args, fragment):
    assert_one_line_error(run(db, *args), fragment)
