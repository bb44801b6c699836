"""Users' files read and written without surprises: every read is of a regular file whose size
is bounded before and during reading, and no output path can block or write into a device.

A FIFO, a socket, a character device such as ``/dev/zero`` (or a symlink to one) given where a
data file is expected would otherwise block forever or be read until memory runs out; a file
that grows while it is read is cut off at the limit. Every loader of a user's file (TOML
systems and textures, ``.wang`` tile sets, JSON specs and goals, PNG densities) reads through
:func:`read_bytes` / :func:`read_text`, and the JSON and TOML it parses go through
:func:`tilekit.schema.parse_json` / :func:`tilekit.schema.parse_toml` (bounded nesting). The
CLI's output options check their path with :func:`check_output` before any work.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path
from typing import Any

from tilekit.errors import ParameterError, ParseError
from tilekit.limits import MAX_FILE_BYTES
from tilekit.schema import parse_json, parse_toml

__all__ = ["check_output", "read_bytes", "read_json", "read_text", "read_toml"]

#: Bytes read per system call.
_CHUNK = 1 << 20


def _kind(mode: int) -> str:
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISSOCK(mode):
        return "a socket"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    return "not a regular file"


def _show(path: str | os.PathLike[str]) -> str:
    text = os.fspath(path)
    return repr(text if len(text) <= 120 else text[:117] + "...")


def read_bytes(path: str | os.PathLike[str], what: str, limit: int = MAX_FILE_BYTES) -> bytes:
    """The bytes of the regular file ``path`` (a ``what``, e.g. "tile set file"), or a one-line
    ParseError: not there, not a regular file (FIFO, device, socket, directory: refused without
    blocking), larger than ``limit`` bytes (checked on the size the file reports and again
    while reading, so a file that grows is cut off), or unreadable."""
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_NOCTTY", 0)
    try:
        fd = os.open(os.fspath(path), flags)
    except FileNotFoundError:
        raise ParseError(f"{what} {_show(path)} does not exist") from None
    except (OSError, ValueError) as exc:  # ValueError: a NUL byte in the path
        reason = getattr(exc, "strerror", None) or str(exc)
        raise ParseError(f"{what} {_show(path)} cannot be read: {reason}") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise ParseError(f"{what} {_show(path)} is {_kind(info.st_mode)}; give a regular file")
        if info.st_size > limit:
            raise ParseError(f"{what} {_show(path)} is {info.st_size:,} bytes, over the limit of {limit:,}")
        os.set_blocking(fd, True)
        parts: list[bytes] = []
        size = 0
        while True:
            block = os.read(fd, min(_CHUNK, limit + 1 - size))
            if not block:
                break
            parts.append(block)
            size += len(block)
            if size > limit:
                raise ParseError(f"{what} {_show(path)} grew past the limit of {limit:,} bytes while it was read")
        return b"".join(parts)
    except OSError as exc:
        raise ParseError(f"{what} {_show(path)} cannot be read: {exc.strerror or exc}") from None
    finally:
        os.close(fd)


def read_text(path: str | os.PathLike[str], what: str, limit: int = MAX_FILE_BYTES) -> str:
    """The UTF-8 text of the regular file ``path`` (:func:`read_bytes`), or a one-line
    ParseError naming the first byte that is not UTF-8."""
    data = read_bytes(path, what, limit)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ParseError(f"{what} {Path(path).name}: not UTF-8 text (byte {exc.start}); save it as UTF-8") from None


def read_toml(path: str | os.PathLike[str], what: str, limit: int = MAX_FILE_BYTES) -> dict[str, Any]:
    """A TOML file's table: bounded reading (:func:`read_text`) and bounded nesting
    (:func:`tilekit.schema.parse_toml`), every failure one ParseError naming the file."""
    return parse_toml(read_text(path, what, limit), f"{what} {Path(path).name}")


def read_json(path: str | os.PathLike[str], what: str, limit: int = MAX_FILE_BYTES) -> Any:
    """A JSON file's value: bounded reading and bounded nesting (:func:`tilekit.schema.parse_json`)."""
    return parse_json(read_text(path, what, limit), f"{what} {Path(path).name}")


def check_output(path: str | os.PathLike[str], what: str = "output") -> None:
    """Refuse (ParameterError, one line) an output path that exists and is not a regular file
    (a FIFO would block the writer until someone reads it; a device or socket is no file to
    write a picture into), before any work is done. A path that does not exist yet is fine."""
    try:
        info = os.stat(os.fspath(path))
    except FileNotFoundError:
        return
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise ParameterError(f"{what} {_show(path)} cannot be written: {reason}") from None
    if not stat.S_ISREG(info.st_mode):
        raise ParameterError(f"{what} {_show(path)} is {_kind(info.st_mode)}; give a regular file path to write")
