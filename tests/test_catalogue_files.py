"""Catalogue files tilekit must not damage: another program's SQLite database, and a
catalogue on a read-only file system (SQLite only: these are facts about files)."""

from __future__ import annotations

import hashlib
import sqlite3
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

sys.path.insert(0, str(Path(__file__).parent / "data"))

import testkit  # noqa: E402

from tilekit.catalogue import open_catalogue  # noqa: E402
from tilekit.cli import cli  # noqa: E402
from tilekit.errors import CatalogueError  # noqa: E402


@pytest.fixture
def pm(monkeypatch):
    return testkit.isolated_pm(monkeypatch, testkit.GridPlugin())


def digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_a_foreign_sqlite_database_is_refused_before_anything_is_written(tmp_path, pm):
    path = tmp_path / "shop.db"
    conn = sqlite3.connect(path)
    conn.execute("CREATE TABLE customers (id INTEGER PRIMARY KEY, name TEXT)")
    conn.execute("INSERT INTO customers (name) VALUES ('Escher')")
    conn.commit()
    conn.close()
    before = digest(path)
    with pytest.raises(CatalogueError) as info:
        open_catalogue(f"sqlite:///{path}", pm=pm)
    message = str(info.value)
    assert "did not create" in message and "customers" in message and "\n" not in message
    assert digest(path) == before  # no tables added, journal mode unchanged
    assert not (tmp_path / "shop.db-wal").exists()
    result = CliRunner().invoke(cli, ["--catalogue", str(path), "list"])
    assert result.exit_code == 2 and result.stderr.startswith("error: ") and "did not create" in result.stderr


def test_an_empty_sqlite_file_becomes_a_catalogue(tmp_path, pm):
    path = tmp_path / "empty.db"
    sqlite3.connect(path).close()  # a database with no tables (0 bytes)
    with open_catalogue(f"sqlite:///{path}", pm=pm) as cat:
        assert cat.count() == 11


@pytest.fixture
def read_only_dir(tmp_path):
    """A tmpfs to remount read-only (mounting needs root, which the test machines are)."""
    mount = tmp_path / "ro"
    mount.mkdir()
    done = subprocess.run(["mount", "-t", "tmpfs", "none", str(mount)], capture_output=True, text=True)
    assert done.returncode == 0, f"the read-only test mounts a tmpfs (the test machines run as root): {done.stderr}"
    try:
        yield mount
    finally:
        subprocess.run(["umount", str(mount)], capture_output=True)


def test_a_catalogue_on_a_read_only_file_system_is_read_and_says_so_when_asked_to_write(read_only_dir, pm,
                                                                                          monkeypatch):
    import tilekit.cli.base

    monkeypatch.setattr(tilekit.cli.base, "plugin_manager", lambda: pm)
    path = read_only_dir / "cat.sqlite"
    open_catalogue(f"sqlite:///{path}", pm=pm).close()
    assert subprocess.run(["mount", "-o", "remount,ro", str(read_only_dir)]).returncode == 0
    before = digest(path)
    with open_catalogue(f"sqlite:///{path}", pm=pm) as cat:
        assert cat.read_only
        assert cat.count() == 11 and cat.get("4^4").family == testkit.FAMILY
        assert cat.tiling("4^4").patch((0, 0, 3, 3)).validate((0, 0, 3, 3))
        with pytest.raises(CatalogueError, match="read-only") as info:
            cat.seed(replace=True)
        assert "\n" not in str(info.value)
    runner = CliRunner()
    shown = runner.invoke(cli, ["--catalogue", str(path), "show", "4^4"])
    assert shown.exit_code == 0, shown.output
    listed = runner.invoke(cli, ["--catalogue", str(path), "list", "--count"])
    assert listed.exit_code == 0 and listed.stdout.strip() == "11"
    seeded = runner.invoke(cli, ["--catalogue", str(path), "catalogue", "seed", "--replace"])
    assert seeded.exit_code == 2 and len(seeded.stderr.splitlines()) == 1 and "read-only" in seeded.stderr
    assert digest(path) == before
