"""A PNG written row by row: memory independent of the image's height (and of its width beyond
one block of rows), for pictures too large to hold (a 64k x 64k texture is 12 GB of RGB).

The format is the PNG specification's (ISO/IEC 15948): the signature, an IHDR chunk, tEXt
chunks, IDAT chunks holding one zlib stream of the filtered rows, and IEND. Each row is
filtered on its own (type 0 None, 1 Sub, 2 Up, 3 Average or 4 Paeth, or ``"adaptive"``: per row
the type whose bytes have the least sum of absolute values as signed numbers, the heuristic
the specification suggests), vectorised over a block of rows with NumPy, and the block is fed
to one ``zlib.compressobj``; compressed bytes leave in IDAT chunks of about
:data:`IDAT_BYTES`. The writer never seeks, so it can write to a pipe.

Compression is the slow part, and zlib releases the GIL: with ``threads`` > 1 each block is
deflated on its own in a thread pool, primed with the last 32 KiB of the block before it (so
matches still reach back across blocks) and ended with a sync flush, which byte-aligns it; the
pieces in order form one deflate stream, closed by an empty final block and the Adler-32 of
all the bytes (the method of Mark Adler's pigz). Any zlib decoder reads it as usual.
"""

from __future__ import annotations

import os
import struct
import zlib
from collections import deque
from concurrent.futures import Future, ThreadPoolExecutor
from pathlib import Path
from types import TracebackType
from typing import BinaryIO

import numpy as np

from tilekit.errors import ParameterError, TilekitError

SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: Compressed bytes gathered before an IDAT chunk is written.
IDAT_BYTES = 1 << 20
#: PNG colour types by channels: grey, grey + alpha, RGB, RGBA.
COLOUR_TYPES = {1: 0, 2: 4, 3: 2, 4: 6}
#: The filter types by name (the numbers are the PNG specification's).
FILTERS = {"none": 0, "sub": 1, "up": 2, "average": 3, "paeth": 4, "adaptive": -1}
#: Largest width or height (the specification's limit is 2^31 - 1).
MAX_SIDE = 2**31 - 1
#: Most compression threads.
MAX_THREADS = 64
#: The deflate window: a block is primed with this many bytes of the one before.
WINDOW = 1 << 15


def _zlib_header(level: int) -> bytes:
    """The two zlib header bytes (deflate, 32 KiB window, no preset dictionary), FLEVEL from
    the level; (CMF * 256 + FLG) is a multiple of 31 as RFC 1950 requires."""
    flevel = 0 if level in (0, 1) else 1 if level in (2, 3, 4, 5) else 2 if level in (6, -1) else 3
    cmf = 0x78
    flg = flevel << 6
    flg += 31 - (cmf * 256 + flg) % 31
    return bytes([cmf, flg])


def _deflate_piece(data: bytes, prime: bytes, level: int) -> bytes:
    """Raw deflate of ``data`` primed with ``prime``, ending byte-aligned (sync flush)."""
    c = zlib.compressobj(level, zlib.DEFLATED, -zlib.MAX_WBITS, 9, zdict=prime) if prime else \
        zlib.compressobj(level, zlib.DEFLATED, -zlib.MAX_WBITS, 9)
    return c.compress(data) + c.flush(zlib.Z_SYNC_FLUSH)


def chunk(kind: bytes, data: bytes) -> bytes:
    """One PNG chunk: length, type, data and the CRC-32 of type and data."""
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(data, zlib.crc32(kind)))


def _paeth(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The Paeth predictor of every byte from its left (a), upper (b) and upper-left (c)."""
    a16, b16, c16 = a.astype(np.int16), b.astype(np.int16), c.astype(np.int16)
    pa = np.abs(b16 - c16)
    pb = np.abs(a16 - c16)
    pc = np.abs(a16 + b16 - 2 * c16)
    return np.where((pa <= pb) & (pa <= pc), a, np.where(pb <= pc, b, c))


def filter_rows(rows: np.ndarray, prior: np.ndarray, bpp: int, kind: str) -> np.ndarray:
    """``rows`` (k, stride) uint8 filtered, with the filter-type byte in front of each row:
    (k, stride + 1). ``prior`` is the row above the first (zeros above the image's top).
    Bytes wrap modulo 256, as the specification's differences do."""
    k, stride = rows.shape
    code = FILTERS[kind]
    out = np.empty((k, stride + 1), dtype=np.uint8)
    body = out[:, 1:]
    if code == 0:
        out[:, 0] = 0
        body[...] = rows
        return out
    if code == 1:  # Sub: minus the byte bpp to the left
        out[:, 0] = 1
        body[:, :bpp] = rows[:, :bpp]
        np.subtract(rows[:, bpp:], rows[:, :-bpp], out=body[:, bpp:])
        return out
    if code == 2:  # Up: minus the byte above
        out[:, 0] = 2
        np.subtract(rows[0], prior, out=body[0])
        np.subtract(rows[1:], rows[:-1], out=body[1:])
        return out
    up = np.empty_like(rows)
    up[0] = prior
    up[1:] = rows[:-1]
    left = np.zeros_like(rows)
    left[:, bpp:] = rows[:, :-bpp]
    upleft = np.zeros_like(rows)
    upleft[:, bpp:] = up[:, :-bpp]
    average = rows - ((left.astype(np.uint16) + up) >> 1).astype(np.uint8)
    paeth = rows - _paeth(left, up, upleft)
    if code == 3:
        out[:, 0], body[...] = 3, average
        return out
    if code == 4:
        out[:, 0], body[...] = 4, paeth
        return out
    candidates = np.stack([rows, rows - left, rows - up, average, paeth])  # (5, k, stride)
    cost = np.abs(candidates.view(np.int8).astype(np.int16)).sum(axis=2, dtype=np.int64)  # (5, k)
    best = np.argmin(cost, axis=0)
    out[:, 0] = best
    body[...] = candidates[best, np.arange(k)]
    return out


class PngWriter:
    """Write a PNG of ``width`` x ``height`` pixels of ``channels`` 8-bit channels, block by
    block of rows from the top (:meth:`write`); ``text`` becomes tEXt chunks (Latin-1 keys
    and values). Closing checks that every row was written; a writer left by an exception
    removes its unfinished file.

    >>> import io
    >>> buf = io.BytesIO()
    >>> with PngWriter(buf, 2, 1, channels=1) as png:
    ...     png.write(np.array([[0, 255]], dtype=np.uint8))
    >>> buf.getvalue()[:8] == SIGNATURE
    True
    """

    def __init__(self, target: str | Path | BinaryIO, width: int, height: int, channels: int = 3,
                 level: int = 6, filter: str = "up", text: dict[str, str] | None = None,
                 threads: int = 1) -> None:
        if channels not in COLOUR_TYPES:
            raise ParameterError(f"a PNG has 1, 2, 3 or 4 channels, not {channels}")
        for name, side in (("width", width), ("height", height)):
            if not (isinstance(side, int | np.integer) and 1 <= side <= MAX_SIDE):
                raise ParameterError(f"PNG {name} {side!r} must be a whole number from 1 to {MAX_SIDE}")
        if not (isinstance(level, int) and -1 <= level <= 9):
            raise ParameterError(f"compression level {level!r} must be -1 (zlib's default) or 0..9")
        if filter not in FILTERS:
            raise ParameterError(f"PNG filter {filter!r} is not one of {', '.join(FILTERS)}")
        if isinstance(threads, bool) or not isinstance(threads, int) or not 0 <= threads <= MAX_THREADS:
            raise ParameterError(f"threads {threads!r} must be a whole number from 0 (one per core) to {MAX_THREADS}")
        if threads == 0:
            threads = max(1, min(MAX_THREADS, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
                                 else os.cpu_count() or 1))
        self.width, self.height, self.channels = int(width), int(height), channels
        self.filter = filter
        self.rows_written = 0
        self.bytes_written = 0
        self._prior = np.zeros(self.width * channels, dtype=np.uint8)
        self.level = level
        self.threads = threads
        self._compress = zlib.compressobj(level, zlib.DEFLATED, zlib.MAX_WBITS, 9)
        self._pool: ThreadPoolExecutor | None = None
        self._inflight: deque[Future[bytes]] = deque()
        self._tail = b""
        self._adler = 1
        if threads > 1:
            self._pool = ThreadPoolExecutor(max_workers=threads, thread_name_prefix="png-deflate")
        self._pending: list[bytes] = []
        self._pending_bytes = 0
        self._path: Path | None = None
        if isinstance(target, str | Path):
            self._path = Path(target)
            try:
                self._fh: BinaryIO = open(self._path, "wb")  # noqa: SIM115 - closed by close()
            except OSError as exc:
                raise TilekitError(f"cannot write {str(target)!r}: {exc.strerror or exc}") from None
        else:
            self._fh = target
        self._closed = False
        header = struct.pack(">IIBBBBB", self.width, self.height, 8, COLOUR_TYPES[channels], 0, 0, 0)
        out = SIGNATURE + chunk(b"IHDR", header)
        for key, value in (text or {}).items():
            if not (1 <= len(key) <= 79):
                raise ParameterError(f"PNG text key {key!r} must have 1 to 79 characters")
            out += chunk(b"tEXt", key.encode("latin-1") + b"\0" + value.encode("latin-1"))
        self._emit(out)

    def _emit(self, data: bytes) -> None:
        try:
            self._fh.write(data)
        except OSError as exc:
            self._abandon()
            where = f" {str(self._path)!r}" if self._path else ""
            raise TilekitError(f"cannot write{where}: {exc.strerror or exc}") from None
        self.bytes_written += len(data)

    def _flush_idat(self, force: bool = False) -> None:
        if self._pending and (force or self._pending_bytes >= IDAT_BYTES):
            self._emit(chunk(b"IDAT", b"".join(self._pending)))
            self._pending, self._pending_bytes = [], 0

    def write(self, rows: np.ndarray) -> None:
        """Append a block of rows: a (k, width, channels) (or (k, width) for one channel)
        uint8 array, top row first."""
        a = np.asarray(rows)
        if a.ndim == 2 and self.channels == 1:
            a = a[:, :, None]
        if a.dtype != np.uint8 or a.ndim != 3 or a.shape[1:] != (self.width, self.channels):
            raise ParameterError(f"rows must be a (k, {self.width}, {self.channels}) uint8 array, "
                                 f"got {a.dtype} {a.shape}")
        if self.rows_written + len(a) > self.height:
            raise ParameterError(f"{self.rows_written + len(a)} rows written to a PNG {self.height} rows high")
        if len(a) == 0:
            return
        flat = np.ascontiguousarray(a).reshape(len(a), -1)
        filtered = filter_rows(flat, self._prior, self.channels, self.filter)
        self._prior = flat[-1].copy()
        if self._pool is None:
            self._add(self._compress.compress(filtered.data))
        else:
            raw = filtered.tobytes()
            if self.rows_written == 0:
                self._add(_zlib_header(self.level))
            self._adler = zlib.adler32(raw, self._adler)
            self._inflight.append(self._pool.submit(_deflate_piece, raw, self._tail, self.level))
            self._tail = raw[-WINDOW:]
            while len(self._inflight) > 2 * self.threads:
                self._add(self._inflight.popleft().result())
        self.rows_written += len(a)
        self._flush_idat()

    def _add(self, data: bytes) -> None:
        if data:
            self._pending.append(data)
            self._pending_bytes += len(data)

    def close(self) -> None:
        """Finish the zlib stream, write IEND and close the file (if the writer opened it)."""
        if self._closed:
            return
        if self.rows_written != self.height:
            self._abandon()
            raise ParameterError(f"a PNG {self.height} rows high was closed after {self.rows_written} rows")
        if self._pool is None:
            self._add(self._compress.flush())
        else:
            while self._inflight:
                self._add(self._inflight.popleft().result())
                self._flush_idat()
            self._pool.shutdown()
            self._pool = None
            final = zlib.compressobj(self.level, zlib.DEFLATED, -zlib.MAX_WBITS, 9)
            self._add(final.flush(zlib.Z_FINISH) + struct.pack(">I", self._adler & 0xFFFFFFFF))
        self._flush_idat(force=True)
        self._emit(chunk(b"IEND", b""))
        self._closed = True
        if self._path is not None:
            try:
                self._fh.close()
            except OSError as exc:
                self._abandon()
                raise TilekitError(f"cannot write {str(self._path)!r}: {exc.strerror or exc}") from None

    def _abandon(self) -> None:
        """Close and remove an unfinished file the writer opened."""
        if self._closed:
            return
        self._closed = True
        if self._pool is not None:
            for f in self._inflight:
                f.cancel()
            self._pool.shutdown()
            self._pool = None
        if self._path is not None:
            try:
                self._fh.close()
            except OSError:
                pass
            try:
                os.unlink(self._path)
            except OSError:
                pass

    def __enter__(self) -> PngWriter:
        return self

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None) -> None:
        if kind is None:
            self.close()
        else:
            self._abandon()


def write_png(path: str | Path | BinaryIO, image: np.ndarray, level: int = 6, filter: str = "up",
              text: dict[str, str] | None = None, threads: int = 1) -> None:
    """Write a whole (h, w[, channels]) uint8 array as a PNG (one block)."""
    a = np.asarray(image)
    if a.ndim == 2:
        a = a[:, :, None]
    if a.ndim != 3:
        raise ParameterError(f"an image is a (h, w) or (h, w, channels) array, got shape {a.shape}")
    with PngWriter(path, a.shape[1], a.shape[0], a.shape[2], level=level, filter=filter, text=text,
                   threads=threads) as png:
        png.write(a)
