"""The library layer under the commands and the web API (tilekit.api, docs/api.md; issue 29,
item 4): each command is option parsing, one library call and printing, and the command line
and the web server draw through the same calls."""

from __future__ import annotations

import ast
import inspect
import textwrap

import click
import pytest
from click.testing import CliRunner

from tilekit import api
from tilekit.errors import NotFoundError
from tilekit.limits import LimitError

#: Lines a command function's body may take (its docstring left out).
MAX_COMMAND_LINES = 25

#: Commands that are not yet a few lines over one call, each with its reason: none now (the core's
#: commands and the plugins' alike fit); a command added here must say why it cannot.
LONG_COMMANDS: dict[str, str] = {}


def body_lines(fn) -> int:
    """Lines of a function's body, from its first statement after the docstring to its last."""
    while hasattr(fn, "__wrapped__"):  # click.pass_obj / make_pass_decorator keep the callback here
        fn = fn.__wrapped__
    node = ast.parse(textwrap.dedent(inspect.getsource(fn))).body[0]
    body = node.body
    if body and isinstance(body[0], ast.Expr) and isinstance(getattr(body[0], "value", None), ast.Constant):
        body = body[1:]
    return body[-1].end_lineno - body[0].lineno + 1 if body else 0


def all_commands():
    """(name, command) of every command `tilekit` has: the core's, its groups', the plugins'
    (tilekit_cli_commands) and one per registered search."""
    from tilekit.cli import cli

    def walk(group, prefix):
        ctx = click.Context(group)
        for name in group.list_commands(ctx):
            cmd = group.get_command(ctx, name)
            yield prefix + name, cmd
            if isinstance(cmd, click.Group):
                yield from walk(cmd, f"{prefix}{name} ")

    return list(walk(cli, ""))


def test_the_line_count_sees_a_long_body():
    def long() -> None:
        """A docstring is not counted."""
        a = 1
        a += 1
        if a:
            a = (a
                 + 1)
        return None

    assert body_lines(long) == 6


def test_every_command_is_a_few_lines_over_the_library():
    commands = all_commands()
    names = {name for name, _ in commands}
    assert {"render", "list", "show", "keys", "runs", "catalogue export", "search vertex-species"} <= names
    long = {name: body_lines(cmd.callback) for name, cmd in commands
            if cmd.callback is not None and body_lines(cmd.callback) > MAX_COMMAND_LINES}
    assert set(long) <= set(LONG_COMMANDS), long
    # the allow-list holds no command that has become thin (or gone)
    assert set(LONG_COMMANDS) <= set(long), set(LONG_COMMANDS) - set(long)


@pytest.fixture(scope="module")
def catalogue(tmp_path_factory):
    from tilekit import open_catalogue

    path = tmp_path_factory.mktemp("api") / "catalogue.sqlite"
    cat = open_catalogue(str(path))
    yield cat
    cat.close()


def test_the_web_api_and_tilekit_render_draw_the_same_picture(catalogue, tmp_path):
    """One pipeline: GET /api/render/NAME and `tilekit render NAME -o x.svg` with the same
    region and size give the same SVG, byte for byte, of the tiles api.render_svg makes."""
    pytest.importorskip("starlette")
    from starlette.testclient import TestClient

    from tilekit.web import create_app

    region = "-3,-3,3,3"
    out = tmp_path / "cli.svg"
    result = CliRunner().invoke(__import__("tilekit.cli", fromlist=["cli"]).cli,
                                ["--catalogue", catalogue.url, "render", "3.4.6.4", "--region", region,
                                 "-o", str(out)])
    assert result.exit_code == 0, result.output
    with TestClient(create_app(catalogue=catalogue)) as client:
        got = client.get("/api/render/3.4.6.4", params={"region": region, "size": 800})
    assert got.status_code == 200, got.text
    assert got.text == out.read_text()
    tiling = catalogue.tiling("3.4.6.4")
    picture = api.render_svg(tiling, region, size=800)
    assert picture.svg == got.text
    assert f"({picture.tiles} tiles)" in result.output
    # the picture's tiles are a patch with no gap and no overlap over the region
    patch = tiling.patch(picture.region)
    assert len(patch) == picture.tiles
    assert patch.validate(picture.region).ok


def test_render_svg_refuses_over_the_limit_before_making_anything(catalogue):
    tiling = catalogue.tiling("4^4")
    estimate = tiling.estimate_tiles(api.tiling_region(tiling, "0,0,10,10")[0])
    assert estimate >= 100  # a 10 x 10 square of unit squares

    def no_patch(region):
        raise AssertionError("a patch was made over the limit")

    tiling.patch = no_patch  # an instance attribute: this tiling object only
    seen = []

    def refuse(count, limit, name):
        seen.append((count, limit, name))
        raise LimitError("refused")

    with pytest.raises(LimitError, match="refused"):
        api.render_svg(tiling, "0,0,10,10", max_tiles=50, too_large=refuse)
    assert seen == [(int(estimate), 50, "4^4")]
    with pytest.raises(LimitError, match="--max-tiles"):  # the default refusal names the option
        api.render_svg(tiling, "0,0,10,10", max_tiles=50)


def test_configure_merges_the_webs_settings_and_checks_the_geometry(catalogue):
    from tilekit.errors import ParameterError

    base = catalogue.tiling("penrose-p3")
    assert api.configure(base, {}) is base
    deeper = api.configure(base, {"settings": {"depth": 2}})
    assert deeper.spec() == base.configure(depth=2).spec()
    with pytest.raises(ParameterError, match="Euclidean plane"):
        api.configure(base, {}, geometry="sphere")


def test_query_is_what_list_prints(catalogue):
    """The 11 Archimedean tilings (Kaplan §4.1; Grünbaum and Shephard 2.1), 3^4.6 in both
    hands: 12 records."""
    matches = api.query(catalogue, "archimedean")
    assert matches.count() == 12
    names = [e.name for e in matches]
    assert len(names) == 12 and "3^4.6l" in names and "3^4.6r" in names
    page = api.query(catalogue, "archimedean", where=["sides=3"], limit=2, offset=1)
    everyone = [e.name for e in api.query(catalogue, "archimedean", where=["sides=3"])]
    assert [e.name for e in page] == everyone[1:3] and page.count() == len(everyone)
    result = CliRunner().invoke(__import__("tilekit.cli", fromlist=["cli"]).cli,
                                ["--catalogue", catalogue.url, "list", "--family", "archimedean", "--format", "csv"])
    assert result.exit_code == 0
    assert [line.split(",")[0] for line in result.output.splitlines()[1:]] == names
    with pytest.raises(NotFoundError, match="archimedean"):
        api.query(catalogue, "archimedian")  # a typo: the close name is suggested


def test_record_builds_the_geometry_or_says_why_not(catalogue):
    rec = api.record(catalogue, "4.8^2")
    assert rec.installed and rec.error is None
    assert rec.tiling.spec() == catalogue.tiling("4.8^2").spec()
    assert rec.description() == rec.tiling.describe()
    built = []
    api.record(catalogue, "4.8^2", build=lambda entry: built.append(entry.name) or rec.tiling)
    assert built == ["4.8^2"]
    assert api.family_summary(catalogue, "4.8^2") is None
    summary = api.family_summary(catalogue, "archimedean")
    assert summary.tilings == 12 and summary.family.name == "archimedean"


def test_run_report_and_run_data(catalogue):
    from tilekit.plugins import ChunkResult

    run_id = catalogue.create_run("demo", {"n": 4}, [{"i": i} for i in range(4)])
    owner = catalogue.start_worker(run_id, "api-tests")
    for index, _spec in catalogue.claim(run_id, owner, 3):
        rows = [{"chunk": index, "k": k} for k in range(5)]
        catalogue.record_chunk(run_id, index, ChunkResult(results=rows, counts={"found": 5}), 0.01, owner=owner)
    catalogue.finish_worker(owner)
    report = api.run_report(catalogue, run_id)
    assert report.pending == [3]  # three of four chunks claimed and recorded
    assert report.results == 15
    assert report.info.chunks_done == 3
    [item] = api.run_data(catalogue, run_id)
    assert item["id"] == run_id and len(item["results"]) == 15 and item["counts"]["found"] == 15
    assert "results" not in api.run_data(catalogue, run_id, results=False)[0]
    assert run_id in [r["id"] for r in api.run_data(catalogue)]
    with pytest.raises(NotFoundError):
        api.run_report(catalogue, 10**9)
