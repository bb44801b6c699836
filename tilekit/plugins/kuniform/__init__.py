"""The k-uniform family plugin: edge-to-edge tilings by regular polygons with k vertex orbits.

Modules: ``dsymbol`` (vertex stars, the D-symbol search, minimality, canonical form),
``realize`` (laying a D-symbol out as regular polygons, its lattice and translational
unit), ``search`` (the ``k-uniform`` search, the tiling class and the catalogue records).
The tilings are stored as search results (``tilekit search k-uniform --k K``), not shipped.
"""

from __future__ import annotations

from tilekit.hookspecs import hookimpl
from tilekit.plugins import Family

FAMILY = "k-uniform"


def _from_spec(spec):
    # measured start-up cost: the layout loads NumPy and the archimedean construction
    # (~0.4 s); naming the families must not pay it
    from tilekit.plugins.kuniform.search import from_spec

    return from_spec(spec)


def _from_file(path):
    # measured start-up cost: as in _from_spec
    from tilekit.plugins.kuniform.search import tiling_from_file

    return tiling_from_file(path)


FAMILIES = [
    Family(
        name=FAMILY,
        summary="k-uniform tilings by regular polygons: k vertex orbits under the symmetry group (§4.1)",
        from_spec=_from_spec,
        description=(
            "Found by `tilekit search k-uniform --k K` from their Delaney-Dress symbols (20 for k = 2, "
            "61 for k = 3); named by their orbit types, e.g. [3^6; 3^4.6] p6, with #i when several share a name. "
            "`tilekit show` also takes a GomJau-Hogg string, a Gavrog <1.1:...> D-symbol or a tes-catalog .tes file."
        ),
        from_file=_from_file,
    )
]


@hookimpl
def tilekit_families():
    return FAMILIES


@hookimpl
def tilekit_searches():
    # measured start-up cost: as in _from_spec
    from tilekit.plugins.kuniform.search import SEARCH

    return [SEARCH]


@hookimpl
def tilekit_normalise(key: str, value: str) -> tuple[str, str] | None:
    """A D-symbol text (``m01/m12/σ0/σ1/σ2``) with its chambers numbered any way, as the
    canonical encoding the tilings' ``dsymbol`` property holds (filters, and ``show``)."""
    if key not in ("dsymbol", "name") or value.count("/") != 4:
        return None
    # measured start-up cost: as in _from_spec; only for a D-symbol
    from tilekit.plugins.kuniform.dsymbol import DSymbol

    try:
        return "dsymbol", DSymbol.decode(value).encode()
    except (ValueError, IndexError):
        return None


@hookimpl
def tilekit_resolve_name(name):
    # measured start-up cost: the notations load NumPy (only when the name is one)
    from tilekit.plugins.kuniform.names import GOMJAU

    if not (name.lstrip().startswith("<") or GOMJAU.match(name) or name.lower().endswith(".tes")):
        return None
    # start-up cost: the notation and search modules (NumPy, shapely) load only when used
    from tilekit.plugins.kuniform.names import resolve

    return resolve(name)


@hookimpl
def tilekit_extra_properties(record):
    if getattr(record, "family", None) != "archimedean":
        return None
    # start-up cost: the notation and search modules (NumPy, shapely) load only when used
    from tilekit.plugins.kuniform.names import archimedean_properties

    return archimedean_properties(record)


@hookimpl
def tilekit_cli_commands(cli):
    # measured start-up cost: cli.py loads only click and the core's cli_types; the reader and
    # the catalogue load when the command runs
    from tilekit.plugins.kuniform.cli import register

    register(cli)


@hookimpl
def tilekit_claim_file(path):
    return FAMILY if str(path).lower().endswith(".tes") else None
