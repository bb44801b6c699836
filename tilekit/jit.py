"""numba's ``njit`` with its on-disk cache kept out of the installed package.

numba's ``cache=True`` writes ``.nbi``/``.nbc`` files beside the source when it can, that is into
``site-packages/tilekit/**/__pycache__`` of a regular install. A later ``pip install -e .`` (or an
uninstall) removes tilekit's files but not those, and the leftover folder becomes an empty
namespace package that shadows the new install. So every compiled loop of tilekit is declared
through :func:`njit` here, which points numba's cache at a per-user cache directory
(platformdirs' ``user_cache_dir("tilekit")/numba``, or ``NUMBA_CACHE_DIR`` when the user set it),
falls back to a per-user folder under the temporary directory when that is not writable, and
compiles without a disk cache when neither is.

numba checks a cached function against its own source file only, not against the modules it calls:
after ``lattice._empty_components`` changed its arguments, the cached ``heesch._least_holes``
(which calls it) still held the old callee's code and failed to type on the next compile. So the
cache goes to a subfolder named by a fingerprint of tilekit's sources (each module's path, size and
modification time): any change to tilekit starts a fresh cache, and fingerprints unused for a week
are removed when a new one is made.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import tempfile
import time
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
    here = fingerprint(Path(__file__).resolve().parent)
    for path in candidates:
        if writable(path / f"src-{here}"):
            _prune(path, keep=f"src-{here}")
            try:
                os.utime(path / f"src-{here}")  # marks it in use for _prune
            except OSError:
                pass
            return path / f"src-{here}"
    return None


def fingerprint(root: Path) -> str:
    """A short hash of every ``.py`` file under ``root``: relative path, size, modification time."""
    h = hashlib.sha1()
    for p in sorted(root.rglob("*.py")):
        st = p.stat()
        h.update(f"{p.relative_to(root).as_posix()}\0{st.st_size}\0{st.st_mtime_ns}\n".encode())
    return h.hexdigest()[:16]


STALE_SECONDS = 7 * 24 * 3600


def _prune(base: Path, keep: str) -> None:
    """Remove the fingerprint folders beside ``keep`` that nothing wrote to for a week."""
    now = time.time()
    try:
        others = [p for p in base.iterdir() if p.name.startswith("src-") and p.name != keep and p.is_dir()]
    except OSError:
        return
    for p in others:
        try:
            if now - p.stat().st_mtime > STALE_SECONDS:
                shutil.rmtree(p, ignore_errors=True)
        except OSError:
            continue


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
