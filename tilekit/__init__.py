"""tilekit: computational tiling theory after Kaplan's *Introductory Tiling Theory for Computer Graphics*.

The public face: the core vocabulary (Affine, Prototile, Patch, Tiling, PeriodicTiling,
Colouring), the plugin marker ``hookimpl``, and the catalogue entry point ``open_catalogue``.
"""

from typing import TYPE_CHECKING

from tilekit.errors import (
    CatalogueError,
    GeometryError,
    NotFoundError,
    ParameterError,
    ParseError,
    PluginError,
    SearchError,
    TilekitError,
)
from tilekit.hookspecs import hookimpl
from tilekit.lazy import lazy_exports

if TYPE_CHECKING:  # pragma: no cover
    from tilekit.colouring import Colouring
    from tilekit.geometry import Affine, Isometry
    from tilekit.tiling import Patch, PeriodicTiling, Prototile, Tiling, ValidationReport

__version__ = "0.1.0"

#: The core vocabulary, imported on first use (PEP 562): measured start-up cost, NumPy and
#: shapely take most of a second to import, which `tilekit --help` and a plugin that only
#: needs `tilekit.hookimpl` should not pay.
_LAZY = {
    "Colouring": "tilekit.colouring",
    "Affine": "tilekit.geometry",
    "Isometry": "tilekit.geometry",
    "Patch": "tilekit.tiling",
    "PeriodicTiling": "tilekit.tiling",
    "Prototile": "tilekit.tiling",
    "Tiling": "tilekit.tiling",
    "ValidationReport": "tilekit.tiling",
}


__getattr__, __dir__ = lazy_exports(__name__, _LAZY)


def open_catalogue(url: str | None = None, **kwargs):
    """Open (migrating and seeding on first use) the catalogue at ``url`` or the default."""
    # measured start-up cost: the catalogue pulls in sqlalchemy and alembic (~0.4-1 s by
    # `python -X importtime -c "import tilekit.catalogue"` on the 2-core dev box), which
    # a library user who never opens a catalogue should not pay
    from tilekit.catalogue import open_catalogue as _open

    return _open(url, **kwargs)


def polyomino(spec):
    """A polyomino from a usual name (``pentomino-F``), a code (``.xx/xx./.x.``) or (column, row) cells.

    The polyomino family's, reached through the plugin manager (``tilekit_public_names``): the
    core imports no family."""
    # start-up cost: the plugin manager loads the plugins, the polyomino family numba and NumPy
    from tilekit.plugins import public_name

    return public_name("polyomino")(spec)


__all__ = [
    "Affine",
    "CatalogueError",
    "Colouring",
    "GeometryError",
    "Isometry",
    "NotFoundError",
    "ParameterError",
    "ParseError",
    "Patch",
    "PeriodicTiling",
    "PluginError",
    "Prototile",
    "SearchError",
    "Tiling",
    "TilekitError",
    "ValidationReport",
    "hookimpl",
    "open_catalogue",
    "polyomino",
]
