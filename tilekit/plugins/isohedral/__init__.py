"""The isohedral family plugin: the 93 isohedral tiling types (Kaplan 2009, chapter 5).

Templates and tiling vertex parameterizations are data (catalogue/isohedral/); the hop
engine (:mod:`.engine`) turns a template, a parameter vector and edge shapes into a
:class:`tilekit.PeriodicTiling`. Public names: :class:`IsohedralTiling`,
:class:`IncidenceSymbol`, :class:`EdgeShape`, :func:`lookup`, :func:`isohedral_tiling`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from tilekit.hookspecs import hookimpl
from tilekit.lazy import lazy_exports
from tilekit.plugins import Family, web_pages

if TYPE_CHECKING:  # pragma: no cover
    from tilekit.plugins.isohedral.engine import IsohedralTiling

__all__ = ["EdgeShape", "IncidenceSymbol", "IsohedralTiling", "isohedral_tiling", "lookup"]

#: Public names, imported on first use (PEP 562): measured start-up cost, the engine loads
#: NumPy, shapely and the symmetry package (about 0.5 s of `python -X importtime` on the
#: 2-core dev box), which every `tilekit` command would pay when pluggy loads this plugin.
_LAZY = {
    "IsohedralTiling": "tilekit.plugins.isohedral.engine",
    "lookup": "tilekit.plugins.isohedral.lookup",
    "EdgeShape": "tilekit.edgeshapes",
    "IncidenceSymbol": "tilekit.incidence",
}
__getattr__, __dir__ = lazy_exports(__name__, _LAZY, pinned=("lookup",))


DESCRIPTION = """\
The 93 isohedral tiling types IH1..IH93 of Grünbaum and Shephard, after Kaplan's chapter 5
and Appendix A. Each unmarked type has a template (topological type, incidence symbol,
tiling vertex parameterization, default colouring, aspects and rules); a tiling of the type
is given by parameters (--param) and fundamental edge shapes (--edge LABEL=x,y:...:1,0,
polylines from (0,0) to (1,0), or 'bezier:' control points). The 12 marked types are drawn
as the Laves tile of their topology with a marking."""


def isohedral_tiling(name: str | int, **options) -> IsohedralTiling:
    """IsohedralTiling('IH16', params=[0.3], edges=['b=0,0:0.3,0.2:1,0'])-style convenience."""
    # measured start-up cost: the engine (NumPy, shapely, symmetry; ~0.5 s), loaded on use
    from tilekit.edgeshapes import parse_edge_option  # start-up cost: as above
    from tilekit.plugins.isohedral.engine import IsohedralTiling

    edges = options.pop("edges", None) or []
    shapes = dict(parse_edge_option(e) if isinstance(e, str) else e for e in edges)
    return IsohedralTiling(name, options.pop("params", None), shapes, options.pop("colouring", None), **options)


def _from_spec(spec: Any) -> IsohedralTiling:
    # measured start-up cost: the engine (NumPy, shapely, symmetry; ~0.5 s), loaded when a
    # tiling is built rather than when pluggy loads the plugin
    from tilekit.plugins.isohedral.spec import tiling_from_spec

    return tiling_from_spec(spec)


#: Spec files this family claims for ``tilekit render --system FILE`` (what escherize writes).
SPEC_SUFFIX = ".isohedral.json"


def _from_file(path: str) -> Any:
    """A tiling from a spec file (:func:`tilekit.plugins.isohedral.spec.tiling_from_file`)."""
    # measured start-up cost: as in _from_spec
    from tilekit.plugins.isohedral.spec import tiling_from_file

    return tiling_from_file(path)


@hookimpl
def tilekit_families():
    return [
        Family(
            name="isohedral",
            summary="The 93 isohedral tiling types (templates, incidence symbols, edge shapes)",
            from_spec=_from_spec,
            description=DESCRIPTION,
            from_file=_from_file,
        )
    ]


@hookimpl(tryfirst=True)
def tilekit_claim_file(path: str) -> str | None:
    """Spec files named ``*.isohedral.json`` (tryfirst: the substitution family claims every
    other ``.json``)."""
    return "isohedral" if str(path).lower().endswith(SPEC_SUFFIX) else None


@hookimpl
def tilekit_cli_commands(cli: Any) -> None:
    # measured start-up cost: cli.py loads only click, the core's cheap cli_types and the
    # import-free escher limits (a few ms); its command imports NumPy/scipy when it runs
    from tilekit.plugins.isohedral.cli import escherize_command, metamorphosis_command

    cli.add_command(escherize_command)
    cli.add_command(metamorphosis_command)


@hookimpl
def tilekit_catalogue_records():
    # measured start-up cost: the records build tilings (the engine, ~0.5 s); seeding only
    from tilekit.plugins.isohedral.records import records

    return records()


@hookimpl
def tilekit_normalise(key: str, value: str) -> tuple[str, str] | None:
    """Incidence symbols in any equivalent form (filters on them, and ``show SYMBOL``)."""
    if key not in ("incidence_symbol", "canonical_symbol", "name") or "[" not in value or ";" not in value:
        return None
    # measured start-up cost: lookup reads the templates (data files); only for a symbol
    from tilekit.plugins.isohedral.lookup import normalised

    return normalised(key, value)


# the web app (tilekit serve): the pages are this plugin's (web.py), the web layer names none
(tilekit_web_routes, tilekit_web_menu_links, tilekit_web_tiling_links,
 tilekit_web_static) = web_pages("tilekit.plugins.isohedral.web", [("/editor", "isohedral editor")])
