"""The hooks that serve: claiming data files, adding properties to another family's records,
and `tilekit plugins`."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

import tilekit
from tilekit.cli import cli
from tilekit.plugins import catalogue_records, family_for_file, make_plugin_manager, plugin_info
from tilekit.resources import catalogue_dir


def test_families_claim_their_files_by_suffix():
    pm = make_plugin_manager()
    assert family_for_file("mine.toml", pm) == "substitution"
    assert family_for_file("sets/mine.wang", pm) == "wang"
    assert family_for_file("notes.txt", pm) is None


def test_render_a_wang_file_without_naming_the_family(tmp_path):
    out = tmp_path / "w.svg"
    source = catalogue_dir() / "wang" / "checkerboard-2.wang"
    db = f"sqlite:///{tmp_path / 'c.db'}"
    res = CliRunner().invoke(cli, ["--catalogue", db, "render", "--system", str(source), "-o", str(out)])
    assert res.exit_code == 0, res.output
    assert out.read_text().lstrip().startswith("<")


class Annotator:
    """A plugin that adds a property to another family's records."""

    @tilekit.hookimpl
    def tilekit_extra_properties(self, record):
        if record.family == "isohedral":
            return {"annotated": True, "ih": -1}  # "ih" is the record's own: kept
        return None


def test_one_plugin_adds_properties_to_another_familys_records(monkeypatch):
    monkeypatch.setenv("TILEKIT_PLUGINS", "isohedral")
    pm = make_plugin_manager(extra_plugins=[Annotator()])
    records = catalogue_records(pm)
    assert len(records) == 93
    assert all(r.properties["annotated"] is True for r in records)
    assert [r.properties["ih"] for r in records] == list(range(1, 94))


def test_an_extra_plugin_already_loaded_is_registered_once(monkeypatch):
    """A plugin's tests pass its module as an extra plugin; when the package is also installed,
    its entry point has loaded the same module already (docs/plugins.md)."""
    import tilekit.plugins.archimedean as archimedean

    monkeypatch.setenv("TILEKIT_PLUGINS", "archimedean")
    annotator = Annotator()
    pm = make_plugin_manager(extra_plugins=[archimedean, annotator, annotator])
    assert pm.get_plugins() == {archimedean, annotator}
    names = [r.name for r in catalogue_records(pm)]
    assert names and len(names) == len(set(names))  # each record once


def test_tilekit_plugins_lists_plugins_hooks_and_sources():
    pm = make_plugin_manager()
    infos = {i.name: i for i in plugin_info(pm)}
    assert {"tilekit.plugins.archimedean", "tilekit.plugins.isohedral", "tilekit.plugins.substitution",
            "tilekit.plugins.wang"} <= set(infos)
    wang = infos["tilekit.plugins.wang"]
    assert "tilekit_cli_commands" in wang.hooks and "tilekit_claim_file" in wang.hooks
    assert wang.source.endswith("wang/__init__.py") and wang.distribution is None
    res = CliRunner().invoke(cli, ["plugins", "--format", "json"])
    assert res.exit_code == 0, res.output
    names = {row["name"] for row in json.loads(res.output)}
    assert "tilekit.plugins.isohedral" in names
    table = CliRunner().invoke(cli, ["plugins"])
    assert table.exit_code == 0 and "claim_file" in table.output


def test_a_family_adds_a_public_name_to_the_tilekit_package():
    """tilekit.polyomino is the polyomino family's (tilekit_public_names): the core names no family."""
    import tilekit
    from tilekit.errors import PluginError
    from tilekit.plugins import public_name

    assert tilekit.polyomino("pentomino-F").name == "pentomino-F"
    pm = make_plugin_manager()
    assert public_name("polyomino", pm)(".xx/xx./.x.").name == "pentomino-F"
    with pytest.raises(PluginError, match=r"no loaded plugin offers tilekit\.no_such_name"):
        public_name("no_such_name", pm)

    class Twin:
        @tilekit.hookimpl
        def tilekit_public_names(self):
            return {"polyomino": len}

    with pytest.raises(PluginError, match="two plugins define the public name tilekit.polyomino"):
        public_name("polyomino", make_plugin_manager(extra_plugins=[Twin()]))
