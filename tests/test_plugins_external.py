"""A third-party family as a pip package: install tests/data/tilekit-demo-family, find it.

The package (a running-bond brick wall family, the example of docs/plugins.md) is
pip-installed from a temporary copy into a folder of its own that this interpreter and its
subprocesses put on their path (``pip install --target``: not into the shared environment, where
a test in another worker starting ``tilekit serve`` found it half uninstalled), discovered
through the ``tilekit`` entry-point group by ``tilekit families`` and by a fresh catalogue, and
gone again when the test ends.
"""

from __future__ import annotations

import importlib
import importlib.util
import json
import os
import shutil
import subprocess
import sys
from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path

import pytest
from click.testing import CliRunner

from tilekit.catalogue import open_catalogue
from tilekit.cli import cli
from tilekit.plugins import families, make_plugin_manager, reset_plugin_manager

DEMO = Path(__file__).parent / "data" / "tilekit-demo-family"
DIST = "tilekit-demo-family"


def _pip(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "pip", *args], capture_output=True, text=True, timeout=300)


def _build_options() -> list[str]:
    """Build with this environment's setuptools when it can make wheels (setuptools >= 70.1,
    or the ``wheel`` package); otherwise let pip fetch the build requirements."""
    import setuptools

    major, minor = (int(x) for x in setuptools.__version__.split(".")[:2])
    if (major, minor) >= (70, 1) or importlib.util.find_spec("wheel") is not None:
        return ["--no-build-isolation", "--no-index"]
    return []


def _forget() -> None:
    importlib.invalidate_caches()
    for name in [m for m in sys.modules if m.startswith("tilekit_demo_family")]:
        del sys.modules[name]
    reset_plugin_manager()


@pytest.fixture
def demo_installed(tmp_path, monkeypatch):
    """pip-install a copy of the demo package into a folder on this process's and its
    subprocesses' path; take it away afterwards."""
    monkeypatch.delenv("TILEKIT_PLUGINS", raising=False)
    monkeypatch.delenv("TILEKIT_CATALOGUE", raising=False)
    source = tmp_path / "tilekit-demo-family"
    shutil.copytree(DEMO, source, ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__"))
    site = tmp_path / "site"
    done = _pip("install", "--no-deps", "--quiet", "--target", str(site), *_build_options(), str(source))
    assert done.returncode == 0, done.stderr[-2000:]
    assert (site / "tilekit_demo_family" / "static" / "bricks.js").is_file()  # package data installed
    monkeypatch.syspath_prepend(str(site))
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(filter(None, [str(site), os.environ.get("PYTHONPATH")])))
    _forget()
    try:
        yield
    finally:
        monkeypatch.undo()
        shutil.rmtree(site)
        _forget()
        with pytest.raises(PackageNotFoundError):
            distribution(DIST)


def test_installed_family_appears_in_cli_and_catalogue(demo_installed, tmp_path, monkeypatch):
    assert [ep.value for ep in distribution(DIST).entry_points.select(group="tilekit")] == ["tilekit_demo_family"]

    # the default plugin manager (built-ins + entry points) now has the family
    result = CliRunner().invoke(cli, ["families"])
    assert result.exit_code == 0, result.output
    assert any(line.split()[0] == "bricks" for line in result.stdout.splitlines()[1:])

    # a fresh interpreter finds it too
    fresh = subprocess.run([sys.executable, "-m", "tilekit.cli", "families", "--format", "json"],
                           capture_output=True, text=True, timeout=120,
                           env={**os.environ, "TILEKIT_PLUGINS": "demo_bricks"})
    assert fresh.returncode == 0, fresh.stderr
    assert json.loads(fresh.stdout) == [{
        "name": "bricks", "summary": "Brick walls: one a x b rectangle, rows shifted (demo plugin)",
        "reads_files": False}]

    # TILEKIT_PLUGINS restricts loading to the entry point's name; a fresh catalogue is seeded
    monkeypatch.setenv("TILEKIT_PLUGINS", "demo_bricks")
    pm = make_plugin_manager()
    assert set(families(pm)) == {"bricks"}
    url = f"sqlite:///{tmp_path / 'fresh.sqlite'}"
    with open_catalogue(url, pm=pm) as cat:
        assert [e.name for e in cat.query()] == ["running-bond"]
        entry = cat.get("stretcher-bond")
        assert entry.family == "bricks"
        assert entry.properties["symmetry_group"] == "2*22" and entry.properties["wallpaper_group"] == "cmm"
        assert entry.properties["edge_to_edge"] is False
        tiling = cat.tiling("running-bond")
        region = (-3.5, -2.5, 4.0, 3.0)
        assert tiling.patch(region).validate(region)
        # brickwork is the textbook cmm pattern; the stored fact agrees with the geometry
        from tilekit.symmetry import wallpaper_group

        assert wallpaper_group(tiling).iuc == "cmm"

    reset_plugin_manager()
    out = tmp_path / "bricks.svg"
    shown = CliRunner().invoke(cli, ["--catalogue", url, "show", "running-bond"])
    assert shown.exit_code == 0 and "running bond: 2 x 1 bricks" in shown.stdout
    drawn = CliRunner().invoke(cli, ["--catalogue", url, "render", "running-bond", "--param", "3,1", "-o", str(out)])
    assert drawn.exit_code == 0, drawn.output
    assert out.read_text().count("<svg") == 1


def test_installed_plugin_owns_a_result_table(demo_installed, tmp_path, monkeypatch):
    """A plugin's result table is created by its own Alembic branch on open, written by its
    search in the chunk's transaction, queried with typed filters, and migrated down and up
    again with data present (the other tables keep theirs)."""
    import sqlalchemy as sa

    from tilekit.search import run_search

    monkeypatch.setenv("TILEKIT_PLUGINS", "demo_bricks")
    pm = make_plugin_manager()
    url = f"sqlite:///{tmp_path / 'rows.sqlite'}"
    with open_catalogue(url, pm=pm) as cat:
        assert "brick_sizes" in sa.inspect(cat.engine).get_table_names()
        current, heads = cat.revisions()
        assert current == heads and "d0001" in current
        run_id = run_search(cat, "brick-sizes", {"max_area": 24}, pm=pm)
        info = cat.run(run_id)
        # bricks a x b with a >= b, a*b = n: A038548(n) of them; sum for n <= 24 is 44
        assert info.status == "done" and info.rows == 44 and info.summary["bricks"] == 44
        assert cat.count_matching(family="brick-sizes") == 44
        assert cat.count_matching(family="brick-sizes", where=["square=true"]) == 4  # 1, 4, 9, 16
        assert [e.name for e in cat.query(family="brick-sizes", where=["area>=20", "b>=4"], order_by="area")] == [
            "bricks-5x4-0.5", "bricks-6x4-0.5"]
        with pytest.raises(Exception, match="no column 'colour'|column 'colour'"):
            cat.query(family="brick-sizes", where=["colour=red"])
        # a second run writing the same keys updates them: nothing doubled
        run_search(cat, "brick-sizes", {"max_area": 24}, pm=pm)
        assert cat.count_matching(family="brick-sizes") == 44
        # a row renders through the family's from_spec
        tiling = cat.tiling("bricks-6x4-0.5")
        assert tiling.patch((0, 0, 20, 20)).validate((0, 0, 20, 20))
        cat.downgrade("demo_bricks@base")
        assert "brick_sizes" not in sa.inspect(cat.engine).get_table_names()
        assert cat.count() == 1  # the tilings table kept the shipped running-bond
        cat.upgrade()
        assert "brick_sizes" in sa.inspect(cat.engine).get_table_names()
        assert cat.count_matching(family="brick-sizes") == 0
    out = tmp_path / "sizes.jsonl"
    reset_plugin_manager()
    done = CliRunner().invoke(cli, ["--catalogue", url, "search", "brick-sizes", "--max-area", "6"])
    assert done.exit_code == 0, done.output
    done = CliRunner().invoke(cli, ["--catalogue", url, "catalogue", "export", "--family", "brick-sizes",
                                    "--format", "jsonl", "-o", str(out)])
    assert done.exit_code == 0, done.output
    rows = [json.loads(line) for line in out.read_text().splitlines()]
    assert sorted(r["name"] for r in rows) == ["bricks-1x1-0.5", "bricks-2x1-0.5", "bricks-2x2-0.5",
                                               "bricks-3x1-0.5", "bricks-3x2-0.5", "bricks-4x1-0.5",
                                               "bricks-5x1-0.5", "bricks-6x1-0.5"]
    bad = CliRunner().invoke(cli, ["--catalogue", url, "search", "brick-sizes", "--max-area", "0"])
    assert bad.exit_code == 2 and "from 1 to 10000" in bad.stderr
