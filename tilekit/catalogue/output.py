"""Writing entries as JSON, JSON Lines or CSV, streamed: one entry in memory at a time."""

from __future__ import annotations

import csv
import io
import json
from collections.abc import Iterable, Sequence
from typing import IO, Any

from tilekit.catalogue.entry import Entry
from tilekit.errors import ParameterError

FORMATS: tuple[str, ...] = ("json", "csv", "jsonl")


def csv_cell(value: Any) -> str:
    """A property value as one CSV cell: empty for None, true/false, JSON for lists and tables."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, list | dict):
        return json.dumps(value, ensure_ascii=False, default=str)
    return str(value)


def write_entries(
    entries: Iterable[Entry],
    stream: IO[str],
    format: str = "json",
    *,
    full: bool = False,
    keys: Sequence[str] | None = None,
) -> int:
    """Write entries as a JSON array, JSON Lines or CSV (``full`` adds aliases and spec);
    return how many were written.

    Entries are consumed one at a time. CSV needs its columns first: give ``keys`` (the
    property keys, in order) to stream; without them the entries are read once to find the
    keys, which holds them all in memory.
    """
    if format not in FORMATS:
        raise ParameterError(f"format {format!r} is not one of: {', '.join(FORMATS)}")
    count = 0
    if format == "json":
        stream.write("[")
        for e in entries:
            stream.write(",\n  " if count else "\n  ")
            stream.write(json.dumps(e.full() if full else e.flat(), ensure_ascii=False))
            count += 1
        stream.write("\n]\n" if count else "]\n")
        return count
    if format == "jsonl":
        for e in entries:
            stream.write(json.dumps(e.full() if full else e.flat(), ensure_ascii=False))
            stream.write("\n")
            count += 1
        return count
    if keys is None:
        entries = list(entries)
        found: dict[str, None] = {}
        for e in entries:
            found.update(dict.fromkeys(e.properties))
        keys = list(found)
    header = ["name", "family", "title", *(["aliases"] if full else []), *keys, *(["spec"] if full else [])]
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow(header)
    for e in entries:
        row = [e.name, e.family, e.title]
        if full:
            row.append("; ".join(e.aliases))
        row.extend(csv_cell(e.properties.get(k)) for k in keys)
        if full:
            row.append(json.dumps(e.spec, ensure_ascii=False))
        writer.writerow(row)
        count += 1
    return count


def entries_text(entries: Iterable[Entry], format: str = "json", *, full: bool = False) -> str:
    """:func:`write_entries` into a string."""
    buf = io.StringIO()
    write_entries(entries, buf, format, full=full)
    return buf.getvalue()
