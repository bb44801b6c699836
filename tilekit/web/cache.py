"""The render cache: least recently used entries dropped to keep it under a byte bound.

An entry counts the memory of its value as Python holds it (``sys.getsizeof`` of the SVG
string), so ``max_bytes`` bounds what the cache itself keeps alive, whatever the mix of
160-px thumbnails and 3 MB renders; a value over a quarter of the bound is not kept.
"""

from __future__ import annotations

import sys
import threading
from collections import OrderedDict
from typing import Any

#: The render cache's bound (``tilekit serve --cache-mb``).
DEFAULT_CACHE_BYTES = 128 << 20


class ByteLRU:
    """A thread-safe mapping of keys to values whose summed sizes stay <= ``max_bytes``."""

    def __init__(self, max_bytes: int = DEFAULT_CACHE_BYTES) -> None:
        if max_bytes < 0:
            raise ValueError(f"max_bytes {max_bytes} must be >= 0")
        self.max_bytes = int(max_bytes)
        self.bytes = 0
        self._items: OrderedDict[str, tuple[Any, int]] = OrderedDict()
        self._lock = threading.Lock()

    def __len__(self) -> int:
        return len(self._items)

    def get(self, key: str) -> Any:
        """The value (now the most recently used), or None."""
        with self._lock:
            hit = self._items.get(key)
            if hit is None:
                return None
            self._items.move_to_end(key)
            return hit[0]

    def put(self, key: str, value: Any) -> bool:
        """Keep ``value`` under ``key``, dropping the least recently used entries to fit;
        False (nothing kept) when the value alone is over a quarter of the bound."""
        size = sys.getsizeof(value)
        if size * 4 > self.max_bytes:
            return False
        with self._lock:
            old = self._items.pop(key, None)
            if old is not None:
                self.bytes -= old[1]
            self._items[key] = (value, size)
            self.bytes += size
            while self.bytes > self.max_bytes:
                _, (_, dropped) = self._items.popitem(last=False)
                self.bytes -= dropped
        return True

    def clear(self) -> None:
        with self._lock:
            self._items.clear()
            self.bytes = 0
