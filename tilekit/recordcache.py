"""The records a plugin module ships, kept on disk between processes.

Building the shipped records takes seconds of CPU (the curved family's Wythoff enumeration, the
Wang tile sets' checks, ...), and every new catalogue needs them: the first command on a fresh
catalogue paid it each time. A plugin that is a module gets its records cached as JSON under the
user's cache folder (platformdirs' ``user_cache_dir("tilekit")/records``, or
``$TILEKIT_CACHE_DIR/records``; ``TILEKIT_CACHE_DIR=none`` turns the cache off), keyed by a hash
of everything the records can depend on: tilekit's version and every source file of the tilekit
package, the plugin's own source files, the shipped catalogue/ data, and the Python and NumPy
versions. Plugins registered as objects (not modules) are always called, as are all plugins when
no writable folder exists. An unreadable or malformed cache file is recomputed and rewritten;
files are written to a temporary name and renamed, so concurrent processes never read half a file.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import tempfile
import types
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

from tilekit.resources import cache_folder, catalogue_dir

#: Cache files larger than this are not read (a shipped plugin's records are a few MB).
MAX_BYTES = 64 * 2**20
FIELDS = ("family", "name", "spec", "title", "properties", "aliases")


def _hash_files(digest: Any, paths: list[Path]) -> None:
    for path in sorted(paths):
        digest.update(str(path.name).encode())
        try:
            digest.update(path.read_bytes())
        except OSError:
            digest.update(b"?")


@cache
def _base_key() -> str:
    """The part of every key that does not depend on the plugin (computed once per process)."""
    import numpy  # start-up cost: NumPy is loaded only when records are built

    # tilekit's version is in tilekit/__init__.py, one of the hashed sources
    digest = hashlib.sha256(f"{sys.version}|{numpy.__version__}".encode())
    package = Path(__file__).resolve().parent
    _hash_files(digest, [p for p in package.rglob("*.py") if "__pycache__" not in p.parts])
    data = catalogue_dir()
    if data.is_dir():
        _hash_files(digest, [f for f in data.rglob("*") if f.is_file() and "__pycache__" not in f.parts])
    return digest.hexdigest()


def _plugin_key(name: str, module: types.ModuleType) -> str | None:
    source = getattr(module, "__file__", None)
    if not source:
        return None
    src = Path(source).resolve()
    digest = hashlib.sha256(f"{_base_key()}|{name}|{module.__name__}|{src}".encode())
    _hash_files(digest, list(src.parent.rglob("*.py")) if src.name == "__init__.py" else [src])
    return digest.hexdigest()[:40]


def _safe(name: str) -> str:
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in name)[:80] or "plugin"


def _read(path: Path, record: Callable[..., Any]) -> list[Any] | None:
    try:
        if not path.is_file() or path.stat().st_size > MAX_BYTES:
            return None
        rows = json.loads(path.read_text(encoding="utf-8"))
        if not isinstance(rows, list):
            return None
        out = []
        for row in rows:
            if not (isinstance(row, list) and len(row) == len(FIELDS)):
                return None
            family, name, spec, title, properties, aliases = row
            if not (isinstance(family, str) and isinstance(name, str) and isinstance(spec, dict)
                    and isinstance(title, str) and isinstance(properties, dict) and isinstance(aliases, list)):
                return None
            out.append(record(family=family, name=name, spec=spec, title=title, properties=properties,
                              aliases=aliases))
        return out
    except (OSError, ValueError, TypeError, RecursionError):
        return None


def _write(folder: Path, path: Path, records: list[Any]) -> None:
    try:
        text = json.dumps([[getattr(r, f) for f in FIELDS] for r in records], allow_nan=True)
    except (TypeError, ValueError):
        return  # not JSON (a plugin's own objects in a spec): computed each time
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=path.name, suffix=".tmp")
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.replace(tmp, path)
        stem = path.name.rsplit("-", 1)[0]
        for old in folder.glob(f"{stem}-*.json"):  # earlier versions of this plugin's records
            if old != path and old.name.rsplit("-", 1)[0] == stem:
                old.unlink(missing_ok=True)
    except OSError:
        pass


def cached_records(name: str, plugin: Any, compute: Callable[[], Any], record: Callable[..., Any]) -> Any:
    """The records ``compute()`` gives for the plugin registered as ``name``: from the cache
    when ``plugin`` is a module and a cache entry for its current key exists, else computed
    (and stored for the next process). ``record`` builds one record from its fields."""
    folder = cache_folder("records") if isinstance(plugin, types.ModuleType) else None
    key = _plugin_key(name, plugin) if folder is not None else None
    if folder is None or key is None:
        return compute()
    path = folder / f"{_safe(name)}-{key}.json"
    found = _read(path, record)
    if found is not None:
        return found
    records = compute()
    if isinstance(records, list | tuple) and all(isinstance(r, record) for r in records):
        _write(folder, path, list(records))
    return records
