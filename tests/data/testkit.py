"""A small in-process test plugin for the catalogue, search and CLI tests.

Family ``testgrid``: the 11 Archimedean tilings as catalogue records, with facts from
Grünbaum & Shephard, *Tilings and Patterns* §2.1 (vertex types, symmetry groups; the snub
hexagonal 3^4.6 is the only chiral one), and real geometry for the three regular tilings
(§2.1 of Kaplan's book: 3^6, 4^4, 6^3 with unit edges).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import Any

import click
import numpy as np

import tilekit
from tilekit.errors import ParameterError
from tilekit.geometry import Affine
from tilekit.plugins import CatalogueRecord, Family, make_plugin_manager
from tilekit.tiling import PeriodicTiling, Prototile

FAMILY = "testgrid"
S3 = math.sqrt(3.0)

#: name -> (vertex type, symmetry group, title, aliases)
ARCHIMEDEAN: dict[str, tuple[tuple[int, ...], str, str, list[str]]] = {
    "3^6": ((3, 3, 3, 3, 3, 3), "p6m", "regular triangular tiling", ["3.3.3.3.3.3", "(3^6)"]),
    "4^4": ((4, 4, 4, 4), "p4m", "regular square tiling", ["4.4.4.4", "(4^4)"]),
    "6^3": ((6, 6, 6), "p6m", "regular hexagonal tiling", ["6.6.6", "(6^3)"]),
    "3^4.6": ((3, 3, 3, 3, 6), "p6", "snub hexagonal tiling", ["3.3.3.3.6"]),
    "3^3.4^2": ((3, 3, 3, 4, 4), "cmm", "elongated triangular tiling", ["3.3.3.4.4"]),
    "3^2.4.3.4": ((3, 3, 4, 3, 4), "p4g", "snub square tiling", ["3.3.4.3.4"]),
    "3.4.6.4": ((3, 4, 6, 4), "p6m", "rhombitrihexagonal tiling", []),
    "3.6.3.6": ((3, 6, 3, 6), "p6m", "trihexagonal tiling", []),
    "3.12^2": ((3, 12, 12), "p6m", "truncated hexagonal tiling", ["3.12.12"]),
    "4.6.12": ((4, 6, 12), "p6m", "truncated trihexagonal tiling", []),
    "4.8^2": ((4, 8, 8), "p4m", "truncated square tiling", ["4.8.8"]),
}

#: Area of the regular n-gon with unit edge, n / (4 tan(pi/n)), in closed form.
POLYGON_AREA = {3: S3 / 4, 4: 1.0, 6: 1.5 * S3}


class GridTiling(PeriodicTiling):
    """A PeriodicTiling that describes itself (to test ``tilekit show``)."""

    def describe(self) -> str:
        return f"regular tiling {self.name}: one {len(self._prototiles[0].outline)}-gon shape"


def regular_tiling(name: str) -> GridTiling:
    """Unit-edge regular tilings 3^6, 4^4, 6^3 (translation units by hand)."""
    if name == "4^4":
        square = Prototile(np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float), name="square")
        return GridTiling([square], [0], np.eye(3)[None], (1, 0), (0, 1), family=FAMILY, name=name)
    if name == "3^6":
        tri = Prototile(np.array([[0, 0], [1, 0], [0.5, S3 / 2]]), name="triangle")
        half_turn = Affine.rotation(math.pi, (0.75, S3 / 4))
        return GridTiling([tri], [0, 0], np.stack([np.eye(3), half_turn]), (1, 0), (0.5, S3 / 2),
                          unit_aspect=[0, 1], family=FAMILY, name=name)
    if name == "6^3":
        angles = np.arange(6) * math.pi / 3
        hexagon = Prototile(np.column_stack([np.cos(angles), np.sin(angles)]), name="hexagon")
        return GridTiling([hexagon], [0], np.eye(3)[None], (1.5, S3 / 2), (0, S3), family=FAMILY, name=name)
    raise ParameterError(f"no geometry for {name!r} in the test family")


def from_spec(spec: Mapping[str, Any]) -> PeriodicTiling:
    if spec.get("kind") == "periodic":
        tiling = GridTiling.from_spec(spec)
        return tiling
    return regular_tiling(spec["vertex_type"])


def from_file(path: str) -> PeriodicTiling:
    with open(path, encoding="utf-8") as fh:
        return from_spec(json.load(fh))


def records() -> list[CatalogueRecord]:
    out = []
    for name, (vt, group, title, aliases) in ARCHIMEDEAN.items():
        props: dict[str, Any] = {
            "periodic": True,
            "k_hedral": len(set(vt)),
            "edge_to_edge": True,
            "symmetry_group": group,
            "vertex_type": ".".join(map(str, vt)),
            "polygons": sorted(set(vt)),
            "vertex_degree": len(vt),
            "regular": len(set(vt)) == 1,
            "chiral": group == "p6",
        }
        if len(set(vt)) == 1:
            props["polygon_area"] = POLYGON_AREA[vt[0]]
        out.append(CatalogueRecord(FAMILY, name, {"vertex_type": name}, title=title,
                                   properties=props, aliases=aliases))
    return out


class GridPlugin:
    """The plugin object registered through ``make_plugin_manager(extra_plugins=[...])``."""

    @tilekit.hookimpl
    def tilekit_families(self):
        return [Family(FAMILY, "Archimedean tilings for tests (regular ones with geometry)",
                       from_spec, from_file=from_file)]

    @tilekit.hookimpl
    def tilekit_catalogue_records(self):
        return records()

    @tilekit.hookimpl
    def tilekit_cli_commands(self, cli):
        @cli.command(name="grid-count")
        def grid_count() -> None:
            """Print how many Archimedean tilings the test family ships."""
            click.echo(str(len(ARCHIMEDEAN)))


def isolated_pm(monkeypatch: Any, *plugins: object) -> Any:
    """A plugin manager with only ``plugins`` (built-ins and entry points switched off)."""
    monkeypatch.setenv("TILEKIT_PLUGINS", "no-such-plugin")
    pm = make_plugin_manager(extra_plugins=plugins)
    monkeypatch.delenv("TILEKIT_PLUGINS")
    return pm
