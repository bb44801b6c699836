"""numba's ``njit`` with its on-disk cache kept out of the installed package.

numba's ``cache=True`` writes ``.nbi``/``.nbc`` files beside the source when it can, that is into
``site-packages/tilekit/**/__pycache__`` of a regular install. A later ``pip install -e .`` (or an
uninstall) removes tilekit's files but not those, and the leftover folder becomes an empty
namespace package that shadows the new install. So every compiled loop of tilekit is declared
through :func:`njit` here, which points numba's cache at a per-user cache directory
(platformdirs' ``user_cache_dir("tilekit")/numba``, or ``NUMBA_CACHE_DIR`` when the user set it),
falls back to a per-user folder under the temporary directory when that is not writable, and
compiles without a disk cache when neither is.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

from tilekit.resources import writable


@cache
def cache_dir() -> Path | None:
    """The folder numba's compiled cache goes to, or None when no writable folder exists."""
    chosen = os.environ.get("NUMBA_CACHE_DIR")
    candidates = []
    if chosen:
        candidates.append(Path(chosen))
    else:
        from platformdirs import user_cache_dir

        candidates.append(Path(user_cache_dir("tilekit")) / "numba")
    uid = os.getuid() if hasattr(os, "getuid") else "user"
    candidates.append(Path(tempfile.gettempdir()) / f"tilekit-numba-{uid}")
    for path in candidates:
        if writable(path):
            return path
    return None


def _configure() -> bool:
    """Point numba at :func:`cache_dir`; True when compiled functions may be cached on disk."""
    from numba.core import config

    path = cache_dir()
    if path is None:
        return False
    # numba reads NUMBA_CACHE_DIR once, at its import; its cache locator reads config.CACHE_DIR
    # each time a function is compiled, so setting it here works after numba was imported too.
    config.CACHE_DIR = str(path)
    return True


def njit(*args: Any, **kwargs: Any) -> Any:
    """``numba.njit`` with ``cache=True`` redirected to the per-user cache (see the module)."""
    from numba import njit as numba_njit

    if kwargs.get("cache"):
        kwargs["cache"] = _configure()
    if args and callable(args[0]) and len(args) == 1 and not kwargs:
        return numba_njit(args[0])
    if args and callable(args[0]):
        return numba_njit(*args, **kwargs)

    def decorate(fn: Callable[..., Any]) -> Any:
        return numba_njit(*args, **kwargs)(fn)

    return decorate
