"""``tilekit import tes-catalog DIR``: attach the tessellation catalogue's identifiers
(zenorogue/tes-catalog) to the k-uniform records of a catalogue, matched by D-symbol
(:mod:`.tescatalog`). A thin command: the library call is
:func:`tilekit.plugins.kuniform.tescatalog.attach`.
"""

from __future__ import annotations

from typing import Any

import click

from tilekit.cli_types import BoundedInt


@click.command(name="tes-catalog")
@click.argument("directory", type=click.Path(exists=True, file_okay=False, dir_okay=True))
@click.option("--max-k", type=BoundedInt(1, 12, "--max-k"), default=None,
              help="Read the files of k <= N only (the catalogue's tree goes to k = 12).")
@click.pass_context
def tes_catalog_command(ctx: click.Context, directory: str, max_k: int | None) -> None:
    """Read a tes-catalog checkout's k-uniform .tes files and set the property tes_catalog
    (the file's path under files/tessellations) on each k-uniform record they draw.

    \b
    Examples:
      tilekit import tes-catalog ~/src/tes-catalog --max-k 4
      tilekit list --family k-uniform --where tes_catalog='k-uniform/02/2/eu 5a 6d 1'

    A malformed file or one that draws no record is reported on one line each; files of a k
    that was not searched are counted. Exit status 2 when a file was malformed.
    """
    # measured start-up cost: the reader and the catalogue load only when the command runs
    from tilekit.errors import ParameterError
    from tilekit.plugins.kuniform.tescatalog import attach

    cat = ctx.find_root().obj.catalogue()
    report = attach(cat, directory, max_k)
    for path, why in report["refused"]:
        click.echo(f"refused: {path}: {why}", err=True)
    click.echo(f"{report['attached']} records got a tes_catalog identifier; {report['unmatched']} files draw no record "
               f"in this catalogue (k searched: {', '.join(map(str, report['ks'])) or 'none'}); "
               f"{len(report['refused'])} files refused")
    if report["refused"]:
        raise ParameterError(f"{len(report['refused'])} .tes files were refused (listed above)")


def register(cli: Any) -> None:
    """Add ``import tes-catalog`` to the ``import`` group, making the group if no plugin has."""
    group = cli.commands.get("import")
    if group is None:
        group = click.Group(name="import", help="Import data from other people's catalogues into this one.")
        cli.add_command(group)
    group.add_command(tes_catalog_command)
