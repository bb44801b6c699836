"""One error hierarchy for tilekit: every message names the bad input and what is valid."""

from __future__ import annotations

import difflib
import importlib
from collections.abc import Iterable
from typing import Any


class TilekitError(Exception):
    """Base class of every error tilekit raises on purpose (the CLI prints it on one line)."""


class ParseError(TilekitError, ValueError):
    """Malformed text: a vertex type, an incidence symbol, a data file, a CLI value."""


class GeometryError(TilekitError, ValueError):
    """Degenerate or invalid geometry: a self-intersecting tile, overlapping tiles, a gap."""


class ParameterError(TilekitError, ValueError):
    """A parameter value, option or edge shape that a tiling cannot take."""


class NotFoundError(TilekitError, LookupError):
    """An unknown name: tiling, family, search, run. Suggests the closest valid names."""

    def __init__(self, what: str, name: str, candidates: Iterable[str] = ()) -> None:
        self.what = what
        self.name = name
        cands = list(candidates)
        close = difflib.get_close_matches(name, cands, n=3, cutoff=0.5)
        if not close:
            low = name.lower()
            close = [c for c in cands if low and low in c.lower()][:3]
        msg = f"unknown {what} {name!r}"
        if close:
            msg += "; did you mean " + ", ".join(repr(c) for c in close) + "?"
        elif cands and len(cands) <= 12:
            msg += "; valid: " + ", ".join(sorted(cands))
        super().__init__(msg)


class CatalogueError(TilekitError):
    """The catalogue database cannot be opened, migrated or written."""


class PluginError(TilekitError):
    """A plugin is broken: a hook raised, returned the wrong type, or clashes with another."""


class SearchError(TilekitError):
    """A search run cannot start, resume or finish."""


class SolverLimit(TilekitError):
    """A bounded search stopped at its node or time limit without an answer."""


class MissingDependency(TilekitError, ImportError):
    """An optional library is not installed; the message names the extra that installs it."""


def optional(module: str, extra: str, what: str) -> Any:
    """``import module``, or MissingDependency naming the extra: one line, no traceback. A guard
    imports every module its feature will import later (``scipy.optimize``, not just the
    feature's own module), so a missing one is found before the work starts."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        missing = (getattr(exc, "name", None) or module).split(".")[0]
        raise MissingDependency(
            f"{what} needs {missing}, which is not installed; install it with: pip install 'tilekit[{extra}]'"
        ) from None
