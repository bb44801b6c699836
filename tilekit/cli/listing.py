"""``tilekit families``, ``plugins``, ``list`` and ``show``: what is installed and what the catalogue holds."""

from __future__ import annotations

import json
import sys
from typing import Any

import click

from tilekit.cli.base import (
    State,
    cli,
    pass_state,
)
from tilekit.cli_types import COUNT
from tilekit.text import format_value as _format_value
from tilekit.text import text_table as _table

# --------------------------------------------------------------------------- families


@cli.command()
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table", show_default=True)
@pass_state
def families(state: State, fmt: str) -> None:
    """List the tiling families the installed plugins provide.

    \b
    Examples:
      tilekit families
      tilekit families --format json
    """
    from tilekit.plugins import families as all_families

    fams = all_families(state.pm)
    if fmt == "json":
        data = [{"name": f.name, "summary": f.summary, "reads_files": f.from_file is not None}
                for f in fams.values()]
        click.echo(json.dumps(data, indent=2, ensure_ascii=False))
        return
    if not fams:
        click.echo("no families are installed", err=True)
        return
    click.echo(_table(["family", "summary"], [[f.name, f.summary] for f in sorted(fams.values(), key=lambda f: f.name)]))


@cli.command()
@click.option("--format", "fmt", type=click.Choice(["table", "json"]), default="table", show_default=True)
@pass_state
def plugins(state: State, fmt: str) -> None:
    """List the loaded plugins, where each came from, and the hooks it implements."""
    from tilekit.plugins import plugin_info

    infos = plugin_info(state.pm)
    if fmt == "json":
        click.echo(json.dumps([i.to_dict() for i in infos], indent=2, ensure_ascii=False))
        return
    rows = [[i.name, i.distribution or "built in", ", ".join(h.removeprefix("tilekit_") for h in i.hooks), i.source]
            for i in infos]
    click.echo(_table(["plugin", "from", "hooks", "source"], rows))


# --------------------------------------------------------------------------- list / show


@cli.command(name="list")
@click.option("--family", help="Only tilings of this family (a family with a result table lists its rows).")
@click.option("--where", "where", multiple=True, metavar="EXPR",
              help="Filter KEY=V, KEY!=V, KEY>=N, KEY<=N, KEY>N, KEY<N or KEY~TEXT (repeatable; all must hold).")
@click.option("--text", help="Case-insensitive text in the name, title, an alias or a text property.")
@click.option("--order", "order_by", default="name", show_default=True,
              help="Sort key: name, family, title, a shared column or any property; -KEY descends.")
@click.option("--limit", type=COUNT, help="At most N tilings.")
@click.option("--offset", type=COUNT, default=0, help="Skip the first N tilings.")
@click.option("--count", "count_only", is_flag=True, help="Print only how many match.")
@click.option("--format", "fmt", type=click.Choice(["table", "json", "csv", "jsonl"]), default="table",
              show_default=True)
@pass_state
def list_(state: State, family: str | None, where: tuple[str, ...], text: str | None, order_by: str,
          limit: int | None, offset: int, count_only: bool, fmt: str) -> None:
    """List catalogue tilings matching the filters (Catalogue.iter_query), streamed; a family
    with a result table lists its rows.

    \b
    Examples:
      tilekit list --family archimedean
      tilekit list --where polygons=6 --where symmetry_group=p6m
      tilekit list --text penrose --limit 5 --format json
      tilekit list --family vertex-species --where status=impossible --count
    """
    from tilekit import api
    from tilekit.catalogue.output import write_entries

    matches = api.query(state.reader(family), family, where, text, order_by, limit, offset)
    if count_only:
        click.echo(matches.count())
    elif fmt in ("json", "csv", "jsonl"):
        write_entries(iter(matches), sys.stdout, fmt, keys=matches.csv_keys() if fmt == "csv" else None)
    else:
        _print_entries(matches)


def _print_entries(entries: Any) -> None:
    """The name / family / title table, a thousand rows at a time (streamed)."""
    shown = 0
    batch: list[Any] = []
    for entry in entries:
        batch.append([entry.name, entry.family, entry.title])
        if len(batch) == 1000:
            click.echo(_table(["name", "family", "title"], batch, {2: 60}))
            shown += len(batch)
            batch = []
    if batch:
        click.echo(_table(["name", "family", "title"], batch, {2: 60}))
    elif not shown:
        click.echo("no tilings match", err=True)


@cli.command()
@click.argument("name")
@pass_state
def show(state: State, name: str) -> None:
    """Show a tiling: every catalogue property, then its family's description.

    \b
    Examples:
      tilekit show IH16
      tilekit show cairo
      tilekit show penrose-p3
    """
    from tilekit import api

    summary = api.family_summary(state.catalogue(), name, pm=state.pm)
    if summary is not None:
        _print_family(summary)
    else:
        _print_record(api.record(state.catalogue(), name, pm=state.pm))


def _print_record(rec: Any) -> None:
    """``tilekit show NAME``: the record's columns and properties, then its family's description."""
    entry = rec.entry
    click.echo(f"name: {entry.name}")
    click.echo(f"family: {entry.family}")
    if entry.title:
        click.echo(f"title: {entry.title}")
    if entry.aliases:
        click.echo(f"aliases: {', '.join(entry.aliases)}")
    click.echo("properties:")
    width = max((len(k) for k in entry.properties), default=0)
    for key, value in entry.properties.items():
        click.echo(f"  {key.ljust(width)}  {_format_value(value)}")
    if not rec.installed:
        click.echo(f"({rec.error})", err=True)
        return
    if rec.tiling is None:
        click.echo(f"(no geometry: {rec.error})")
        return
    group = rec.computed_group()
    if group is not None:
        click.echo(f"  {'wallpaper_group'.ljust(width)}  {group.iuc} ({group.orbifold}; computed)")
    text = rec.description()
    if text:
        click.echo("")
        click.echo(text.rstrip("\n"))


def _print_family(summary: Any) -> None:
    """``tilekit show FAMILY``: its summary, description, size and the options its tilings take."""
    fam = summary.family
    click.echo(f"family: {fam.name}")
    click.echo(f"summary: {fam.summary}")
    if getattr(fam, "description", ""):
        click.echo(f"description: {fam.description}")
    click.echo(f"tilings: {summary.tilings} (tilekit list --family {fam.name})")
    if summary.options_help:
        click.echo(f"options of tilekit render (e.g. {summary.example}):")
        for line in summary.options_help.splitlines():
            click.echo(f"  {line}")
