"""A third-party family as a pip package: install tests/data/tilekit-demo-family, find it.

The package (a running-bond brick wall family, the example of docs/plugins.md) is
pip-installed into this interpreter's environment from a temporary copy, discovered through
the ``tilekit`` entry-point group by ``tilekit families`` and by a fresh catalogue, and
uninstalled again when the test ends.
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
    """pip-install a copy of the demo package; uninstall it afterwards."""
    monkeypatch.delenv("TILEKIT_PLUGINS", raising=False)
    monkeypatch.delenv("TILEKIT_CATALOGUE", raising=False)
    source = tmp_path / "tilekit-demo-family"
    shutil.copytree(DEMO, source, ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__"))
    done = _pip("install", "--no-deps", "--quiet", *_build_options(), str(source))
    assert done.returncode == 0, done.stderr[-2000:]
    _forget()
    try:
        yield
    finally:
        gone = _pip("uninstall", "--yes", DIST)
        _forget()
        assert gone.returncode == 0, gone.stderr[-2000:]
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
