"""``tilekit catalogue path | upgrade | export | seed``."""

from __future__ import annotations

import sys

import click

from tilekit.cli.base import (
    State,
    SuggestingGroup,
    cli,
    pass_state,
)
from tilekit.cli_types import OUTPUT

# --------------------------------------------------------------------------- catalogue


@cli.group(name="catalogue", cls=SuggestingGroup)
def catalogue_group() -> None:
    """The catalogue database: where it is, migrate, export, seed.

    \b
    Examples:
      tilekit catalogue path
      tilekit catalogue export --format csv -o all.csv
    """


@catalogue_group.command(name="path")
@pass_state
def catalogue_path(state: State) -> None:
    """Print the catalogue's file (SQLite) or URL (password hidden), without opening it.

    \b
    Example:
      tilekit --catalogue shared.sqlite catalogue path
    """
    from sqlalchemy.engine import make_url

    from tilekit.catalogue import resolve_url

    url = make_url(resolve_url(state.url))
    if url.get_backend_name() == "sqlite" and url.database and url.database != ":memory:":
        click.echo(url.database)
    else:
        click.echo(url.render_as_string(hide_password=True))


@catalogue_group.command(name="upgrade")
@pass_state
def catalogue_upgrade(state: State) -> None:
    """Run the Alembic migrations (core and plugins) to head.

    \b
    Example:
      tilekit catalogue upgrade
    """
    cat = state.catalogue(seed=False)
    current, heads = cat.revisions()
    click.echo(f"catalogue {cat.url} at revision {', '.join(sorted(current)) or 'base'} (heads: {', '.join(sorted(heads))})")


@catalogue_group.command(name="export")
@click.option("--format", "fmt", type=click.Choice(["json", "jsonl", "csv"]), default="json", show_default=True,
              help="A JSON array, JSON Lines (one object a line) or CSV; all streamed.")
@click.option("-o", "--output", "out", type=OUTPUT, help="Output file (default: stdout).")
@click.option("--family", help="Only tilings of this family.")
@click.option("--where", "where", multiple=True, metavar="EXPR", help="Filter, as for tilekit list.")
@pass_state
def catalogue_export(state: State, fmt: str, out: str | None, family: str | None, where: tuple[str, ...]) -> None:
    """Export tilings (name, family, title, aliases, properties, spec) as JSON, JSON Lines or
    CSV, streamed in constant memory (a family with a result table exports its rows).

    \b
    Examples:
      tilekit catalogue export -o all.json
      tilekit catalogue export --format csv --family archimedean -o arch.csv
      tilekit catalogue export --family vertex-species --format jsonl -o species.jsonl
    """
    cat = state.catalogue()
    if out is None:
        cat.export(sys.stdout, fmt, family=family, where=list(where))
        return
    count = cat.export(out, fmt, family=family, where=list(where))
    click.echo(f"wrote {count} tilings to {out}", err=True)


@catalogue_group.command(name="seed")
@click.option("--replace", is_flag=True, help="Overwrite tilings the plugins ship (keeps others).")
@pass_state
def catalogue_seed(state: State, replace: bool) -> None:
    """Load the tilings the installed plugins ship (new names; all with --replace).

    \b
    Examples:
      tilekit catalogue seed
      tilekit catalogue seed --replace
    """
    cat = state.catalogue(seed=False)
    added, replaced = cat.seed(replace=replace)
    click.echo(f"added {added}, replaced {replaced} tilings ({cat.count()} in the catalogue)")
