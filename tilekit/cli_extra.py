"""Commands about the catalogue's vocabulary and single shapes, kept out of cli.py so that they
merge cleanly: ``tilekit keys [FAMILY]`` (every queryable key with its type, families and an
example) and ``tilekit prototile NAME`` (one prototile of any tiling as SVG, DXF or GeoJSON).
cli.py registers them on the ``tilekit`` group."""

from __future__ import annotations

import json
from typing import Any

import click

from tilekit.cli_types import OUTPUT, BoundedInt
from tilekit.errors import ParameterError


def _cli() -> Any:
    """tilekit.cli, which registers these commands (a module-level import would be a cycle)."""
    from tilekit import cli  # cycle: cli imports this module to register its commands

    return cli


def _result_table_keys(cat: Any, rt: Any, family: str) -> list[Any]:
    """KeyInfos for the columns of a result table (what ``--where`` filters on for its family)."""
    from tilekit.catalogue.results import column_kind
    from tilekit.catalogue.vocabulary import KeyInfo

    rows = cat.count_result_rows(rt)
    examples = {"bool": "{}=true", "int": "{}>=1", "float": "{}>=0.5", "json": "{}~TEXT", "text": "{}=TEXT"}
    out = []
    for column in rt.table.c:
        kind = column_kind(column.type)
        out.append(KeyInfo(key=column.name, type=kind, families=(family,), tilings=rows,
                           example=examples.get(kind, "{}=VALUE").format(column.name)))
    return out


@click.command(name="keys")
@click.argument("family", required=False)
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table", show_default=True)
@click.pass_obj
def keys_command(state: Any, family: str | None, fmt: str) -> None:
    """List every key `tilekit list --where` takes: its type, the families whose tilings have it,
    how many tilings do, an example filter and its older names (aliases). The shared vocabulary
    (sides, aperiodic, periodic, wallpaper_group ...) comes first; docs/catalogue.md explains it.

    \b
    Examples:
      tilekit keys
      tilekit keys isohedral
      tilekit keys --format json
    """
    from tilekit.catalogue.entry import TEXT_COLUMNS
    from tilekit.catalogue.vocabulary import KeyInfo

    cat = state.reader(family)
    cat.check_family(family)
    rt = cat.family_table(family)
    if rt is not None:
        infos = _result_table_keys(cat, rt, family or "")
    else:
        infos = cat.key_table(family)
        everyone = tuple(sorted({f for info in infos for f in info.families}))
        total = cat.count(family)
        first = cat.query(family=family, limit=1)
        if first:
            shown = {"name": first[0].name, "family": first[0].family,
                     "title": (first[0].title.split() or ["a"])[0].lower()}
            infos = [KeyInfo(key=c, type="text", families=everyone, tilings=total,
                             example=f"{c}{'~' if c == 'title' else '='}{shown[c]}")
                     for c in TEXT_COLUMNS] + infos
    if fmt == "json":
        click.echo(json.dumps([i.to_dict() for i in infos], indent=2, ensure_ascii=False))
        return
    if not infos:
        click.echo("no keys: the catalogue has no tilings" + (f" of family {family!r}" if family else ""), err=True)
        return
    rows = [[i.key, i.type, ", ".join(i.families), str(i.tilings), i.example, ", ".join(i.aliases)] for i in infos]
    click.echo(_cli()._table(["key", "type", "families", "tilings", "example", "aliases"], rows, {2: 48}))


def register(group: click.Group) -> None:
    """Add this module's commands to the ``tilekit`` group."""
    group.add_command(keys_command)


__all__ = ["register", "keys_command", "OUTPUT", "BoundedInt", "ParameterError"]
