"""Cross-references to Čtrnáct and Kopczyński's tessellation catalogue (zenorogue/tes-catalog):
which of its ``.tes`` files draws each k-uniform record.

The catalogue keeps k-uniform tilings as ``files/tessellations/k-uniform/<k>/<m> (...)/<name>.tes``
(k two digits, m the number of vertex types). A file's identifier here is its path from
``files/tessellations`` without ``.tes``, e.g. ``k-uniform/02/2/eu 3a 4b 1``. The match is
computed, never typed in: each file is read by :func:`.tes.read_tes` to its minimal D-symbol,
and a record matches the file whose symbol has the record's canonical encoding (two tilings
are congruent exactly when their minimal symbols are isomorphic).

:data:`TABLE` ships the result for k <= :data:`TABLE_MAX_K` as ``{key: identifier}``, the key
being :func:`symbol_key` of the file's symbol (a hash, so the table stays small); records
get the ``tes_catalog`` property from it when a run stores them. It is rebuilt from a
checkout by ``python -m tilekit.plugins.kuniform.tescatalog DIR [COMMIT]`` (DIR: the checkout, or any
folder holding its ``k-uniform`` tree), and ``tilekit import tes-catalog DIR`` attaches the
identifiers of a checkout to the records already in a catalogue.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import sys
from collections.abc import Iterator
from functools import cache
from pathlib import Path
from typing import Any

from tilekit.errors import ParameterError, TilekitError

#: The shipped cross-reference table and the largest k it covers.
TABLE = Path(__file__).parent / "tes_catalog.json"
TABLE_MAX_K = 7
#: The most .tes files a folder walk reads (the whole catalogue's k-uniform tree has 97,649).
MAX_FILES = 200_000
FAMILY = "k-uniform"
_K_DIR = re.compile(r"^\d{2}$")


def symbol_key(encoding: str) -> str:
    """The table's key of a canonical D-symbol encoding (:meth:`.DSymbol.encode`): 16 hex
    digits of its SHA-256."""
    return hashlib.sha256(encoding.encode()).hexdigest()[:16]


def _kuniform_root(root: Path) -> Path:
    for candidate in (root / "files" / "tessellations" / "k-uniform", root / "k-uniform", root):
        if candidate.is_dir() and any(_K_DIR.match(p.name) for p in candidate.iterdir() if p.is_dir()):
            return candidate
    raise ParameterError(f"{root}: no tes-catalog k-uniform tree here (expected files/tessellations/k-uniform/01, "
                         "02, ... or k-uniform/01, ... or the folders 01, 02, ... themselves)")


def catalogue_files(root: str | os.PathLike[str], max_k: int | None = None) -> Iterator[tuple[int, str, Path]]:
    """(k, identifier, path) of every ``.tes`` file of a tes-catalog k-uniform tree, k <= max_k,
    in sorted order; ParameterError for a folder that holds no such tree or too many files."""
    base = _kuniform_root(Path(root))
    seen = 0
    for kdir in sorted(p for p in base.iterdir() if p.is_dir() and _K_DIR.match(p.name)):
        k = int(kdir.name)
        if max_k is not None and k > max_k:
            continue
        for dirpath, dirnames, filenames in os.walk(kdir):
            dirnames.sort()
            for name in sorted(filenames):
                if not name.endswith(".tes"):
                    continue
                seen += 1
                if seen > MAX_FILES:
                    raise ParameterError(f"{base}: more than {MAX_FILES} .tes files; pass --max-k to read fewer")
                path = Path(dirpath) / name
                ident = "k-uniform/" + path.relative_to(base).as_posix()[: -len(".tes")]
                yield k, ident, path


def match_files(root: str | os.PathLike[str], max_k: int | None = None
                ) -> tuple[dict[str, tuple[int, str]], list[tuple[str, str]]]:
    """Read every file (:func:`catalogue_files`): ``{encoding: (k, identifier)}`` and the
    refused files as (path, one-line reason). Two files of one tiling refuse the second."""
    # start-up cost: the reader (NumPy, the D-symbol code) loads only for an import
    from tilekit.plugins.kuniform.tes import read_tes

    found: dict[str, tuple[int, str]] = {}
    refused: list[tuple[str, str]] = []
    for k, ident, path in catalogue_files(root, max_k):
        try:
            sym = read_tes(path)[1]
        except TilekitError as exc:
            why = str(exc).splitlines()[0]
            refused.append((str(path), why.removeprefix(f"{path}: ")))
            continue
        orbits = len(sym.vertex_orbits())
        if orbits != k:
            refused.append((str(path), f"its tiling has {orbits} vertex orbits, but it is filed under k = {k}"))
            continue
        enc = sym.encode()
        if enc in found:
            refused.append((str(path), f"draws the same tiling as {found[enc][1]}"))
            continue
        found[enc] = (k, ident)
    return found, refused


@cache
def shipped() -> dict[str, str]:
    """The shipped table ``{symbol_key: identifier}`` (empty if it is absent)."""
    if not TABLE.is_file():
        return {}
    return json.loads(TABLE.read_text())["ids"]


def tes_catalog_id(encoding: str) -> str | None:
    """The tes-catalog identifier of the tiling with this canonical encoding, from the shipped
    table (None beyond its k or where no file matched)."""
    return shipped().get(symbol_key(encoding))


def build_table(root: str | os.PathLike[str], max_k: int = TABLE_MAX_K, commit: str = "") -> dict:
    """The table :data:`TABLE` holds, from a checkout (raises on any refused file)."""
    found, refused = match_files(root, max_k)
    if refused:
        path, why = refused[0]
        raise ParameterError(f"{path}: {why} ({len(refused)} files refused)")
    ids = {symbol_key(enc): ident for enc, (_k, ident) in found.items()}
    if len(ids) != len(found):
        raise ParameterError("two encodings share a table key; lengthen symbol_key")
    counts: dict[int, int] = {}
    for k, _ident in found.values():
        counts[k] = counts.get(k, 0) + 1
    return {"source": "zenorogue/tes-catalog, files/tessellations/k-uniform", "commit": commit,
            "regenerate": "python -m tilekit.plugins.kuniform.tescatalog DIR [COMMIT]",
            "max_k": max_k, "count_by_k": {str(k): counts[k] for k in sorted(counts)}, "ids": dict(sorted(ids.items()))}


if __name__ == "__main__":  # pragma: no cover - regenerates the shipped table
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: python -m tilekit.plugins.kuniform.tescatalog TES_CATALOG_CHECKOUT [COMMIT]")
    TABLE.write_text(json.dumps(build_table(sys.argv[1], commit=sys.argv[2] if len(sys.argv) > 2 else ""),
                                indent=0) + "\n")


def attach(cat: Any, root: str | os.PathLike[str], max_k: int | None = None) -> dict[str, Any]:
    """Set ``tes_catalog`` on every k-uniform record of catalogue ``cat`` that a file of the
    checkout at ``root`` draws (k <= max_k); returns counts: ``attached``, ``unmatched`` (files
    of a searched k that draw no record: 0 when the search is complete), ``refused`` ((path,
    reason) of malformed files), ``ks`` (the k values the catalogue holds)."""
    # start-up cost: the plugin manager loads only for an import
    from tilekit.plugins import CatalogueRecord

    records = {e.properties.get("dsymbol"): e for e in cat.iter_query(family=FAMILY)}
    ks = sorted({int(e.properties["k"]) for e in records.values() if "k" in e.properties})
    found, refused = match_files(root, max_k)
    updated, unmatched = [], 0
    for enc, (k, ident) in found.items():
        entry = records.get(enc)
        if entry is None:
            unmatched += k in ks
            continue
        props = {**entry.properties, "tes_catalog": ident}
        updated.append(CatalogueRecord(entry.family, entry.name, entry.spec, title=entry.title, properties=props,
                                       aliases=list(entry.aliases)))
    if updated:
        cat.upsert(updated, replace=True)
    return {"attached": len(updated), "unmatched": unmatched, "refused": refused, "ks": ks}
