"""Start-up: `tilekit --help` and a warm `tilekit list` do not import the heavy libraries.

A timing test would be flaky on a shared machine, so these check what a fresh interpreter has
imported after the command ran (``sys.modules``); docs/benchmarks.md has the timings.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

#: ``sqlalchemy.dialects.postgresql`` (21 ms): only a PostgreSQL catalogue compiles models.JSONType to JSONB.
HEAVY = ("numpy", "shapely", "numba", "sqlalchemy", "sqlalchemy.orm", "sqlalchemy.dialects.postgresql", "alembic")
#: The exports' optional libraries: imported only by the export that needs them.
OPTIONAL = ("matplotlib", "geopandas", "networkx", "ezdxf")

#: Runs the command line in-process and prints which of HEAVY it imported, as JSON.
PROBE = """
import json, sys
from tilekit.cli import main
try:
    main(sys.argv[1:])
except SystemExit as exc:
    code = exc.code
else:
    code = 0
print(json.dumps({"code": code, "heavy": sorted(m for m in HEAVY if m in sys.modules)}))
""".replace("HEAVY", repr(HEAVY + OPTIONAL))


def run_probe(args: list[str], tmp_path, plugins: str | None = None) -> dict:
    env = dict(os.environ)
    env["TILEKIT_CATALOGUE"] = f"sqlite:///{tmp_path / 'catalogue.sqlite'}"
    env.pop("TILEKIT_PLUGINS", None)
    if plugins is not None:
        env["TILEKIT_PLUGINS"] = plugins
    out = subprocess.run([sys.executable, "-c", PROBE, *args], env=env, capture_output=True, text=True,
                         timeout=300, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_help_imports_no_array_geometry_or_compiler_library(tmp_path):
    got = run_probe(["--help"], tmp_path)
    assert got["code"] == 0
    assert [m for m in got["heavy"] if m in ("numpy", "shapely", "numba")] == []


def test_help_imports_nothing_heavy_with_the_four_families(tmp_path):
    # the archimedean, isohedral, substitution and wang plugins load without NumPy, shapely
    # or SQLAlchemy; the wang plugin's `tilekit wang` group is listed
    got = run_probe(["--help"], tmp_path, plugins="archimedean,isohedral,substitution,wang")
    assert got == {"code": 0, "heavy": []}


def test_help_imports_no_sqlalchemy_with_every_plugin(tmp_path):
    got = run_probe(["--help"], tmp_path)
    assert got["heavy"] == []


def test_python_m_tilekit_runs_the_command_line(tmp_path):
    out = subprocess.run([sys.executable, "-m", "tilekit", "--help"], capture_output=True, text=True,
                         timeout=120, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("Usage: ")
    assert "  wang " in out.stdout


def test_warm_list_imports_nothing_heavy(tmp_path):
    plugins = "archimedean,wang"
    first = run_probe(["list", "--count"], tmp_path, plugins=plugins)  # migrates and seeds
    assert first["code"] == 0 and "sqlalchemy" in first["heavy"]
    # a current SQLite catalogue is read through sqlite3 (tilekit.catalogue.reading):
    # no SQLAlchemy, and the families' array code stays unloaded
    for args in (["list", "--where", "polygons=6", "--count"], ["list", "--where", "polygons=6"],
                 ["list", "--text", "snub", "--order", "-polygons", "--format", "csv"]):
        assert run_probe(args, tmp_path, plugins=plugins) == {"code": 0, "heavy": []}, args


def test_warm_list_of_one_family_imports_no_family_code_or_orm(tmp_path):
    """``--family`` checks the name against every installed family: naming them loads no
    construction code (the archimedean records pull in NumPy and the builder). A family of
    the tilings table is read without SQLAlchemy; one whose rows are in a plugin's result
    table (polyomino) through SQLAlchemy Core, without the ORM."""
    first = run_probe(["list", "--count"], tmp_path)  # migrates and seeds, every plugin
    assert first["code"] == 0
    for family, where, heavy in (("archimedean", "polygons=6", []), ("polyomino", "cells=8", ["sqlalchemy"]),
                                 ("laves", "periodic=true", [])):
        got = run_probe(["list", "--family", family, "--where", where, "--count"], tmp_path)
        assert got == {"code": 0, "heavy": heavy}, family


def test_a_changed_installation_is_read_the_full_way_once(tmp_path):
    """A catalogue whose stored fingerprint is not the installation's (an upgrade, a plugin
    added or removed) is opened through SQLAlchemy, which re-seeds it; the next list is fast."""
    assert run_probe(["list", "--count"], tmp_path, plugins="archimedean")["code"] == 0
    assert run_probe(["list", "--count"], tmp_path, plugins="archimedean")["heavy"] == []
    assert "sqlalchemy" in run_probe(["list", "--count"], tmp_path, plugins="archimedean,wang")["heavy"]
    assert run_probe(["list", "--count"], tmp_path, plugins="archimedean,wang")["heavy"] == []


def test_the_cheap_copies_of_wang_names_equal_their_sources():
    import importlib

    from tilekit.plugins import wang
    from tilekit.plugins.wang import cli

    tiling = importlib.import_module("tilekit.plugins.wang.tiling")
    solve = importlib.import_module("tilekit.plugins.wang.solve")
    assert wang.FAMILY == tiling.FAMILY == "wang"
    assert cli.FILL_CHOICES == tiling.FILL_METHODS
    assert cli.SOLVE_CHOICES == solve.METHODS


@pytest.mark.parametrize("package, name, module", [
    ("wang", "solve", "solve"),  # a function named like its submodule
    ("wang", "WangTiling", "tiling"),
    ("isohedral", "lookup", "lookup"),
    ("substitution", "tiling", None),  # defined in the package, named like a submodule
    ("substitution", "SubstitutionTiling", "tiling"),
    ("archimedean", "archimedean_tiling", "construct"),
])
def test_lazy_re_exports_are_the_library_objects(package, name, module):
    import importlib
    import types

    pkg = importlib.import_module(f"tilekit.plugins.{package}")
    # import the submodule first: the import system then sets the package attribute of that name
    sub = importlib.import_module(f"tilekit.plugins.{package}.{module or name}")
    value = getattr(pkg, name)
    assert not isinstance(value, types.ModuleType)
    assert callable(value)
    if module is not None:
        assert value is getattr(sub, name)
    assert name in dir(pkg) and name in pkg.__all__
    exec(f"from tilekit.plugins.{package} import {name} as imported", ns := {})
    assert ns["imported"] is value
    with pytest.raises(AttributeError, match="has no attribute 'nope'"):
        pkg.nope  # noqa: B018


def test_help_and_a_geojson_export_import_no_optional_library(tmp_path):
    assert [m for m in run_probe(["--help"], tmp_path)["heavy"] if m in OPTIONAL] == []
    got = run_probe(["render", "4.8.8", "-o", "p.geojson"], tmp_path)
    assert got["code"] == 0 and (tmp_path / "p.geojson").exists()
    assert [m for m in got["heavy"] if m in OPTIONAL] == []

