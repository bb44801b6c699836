"""A non-editable install must carry the catalogue data and the Alembic migrations."""

from __future__ import annotations

import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


@pytest.mark.slow
def test_wheel_ships_catalogue_data_and_migrations(tmp_path) -> None:
    # built from a copy of the tracked files: a checkout's stale build/ folder would hide a
    # file that a fresh clone's wheel lacks
    source = tmp_path / "source"
    tracked = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    for name in tracked:
        if (ROOT / name).is_file():
            (source / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, source / name)
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
         "-w", str(tmp_path), str(source)],
        check=True,
        capture_output=True,
    )
    (wheel,) = tmp_path.glob("tilekit-*.whl")
    names = set(zipfile.ZipFile(wheel).namelist())
    shipped_data = {n for n in names if n.startswith("tilekit/_catalogue/")}
    repo_data = {
        "tilekit/_catalogue/" + p.relative_to(ROOT / "catalogue").as_posix()
        for p in (ROOT / "catalogue").rglob("*")
        if p.is_file() and "__pycache__" not in p.parts
    }
    assert repo_data <= shipped_data
    assert "tilekit/_migrations/env.py" in names
    versions = {p.name for p in (ROOT / "migrations" / "versions").glob("*.py")}
    assert versions and all(f"tilekit/_migrations/versions/{v}" in names for v in versions)
    # the built-in plugins' own Alembic branches (their result tables) ship too
    plugin_versions = {p.relative_to(ROOT).as_posix() for p in (ROOT / "tilekit" / "plugins").glob("*/migrations/*.py")}
    assert {"tilekit/plugins/archimedean/migrations/a0001_vertex_species.py",
            "tilekit/plugins/polyomino/migrations/p0001_polyominoes.py"} <= plugin_versions <= names
    # every data file a module reads from its own folder ships beside it (a regular install
    # once lacked the k-uniform plugin's notation table, so every command failed)
    tracked = subprocess.run(["git", "ls-files", "tilekit"], cwd=ROOT, capture_output=True, text=True).stdout.split()
    module_data = {n for n in tracked if not n.endswith(".py") and "/migrations/" not in n}
    assert module_data and module_data <= names, sorted(module_data - names)
