"""A small LRU memo keyed by the exact design vector.

The objective and the constraints of a synthesis problem at one design share one
workspace computation. The counting Oracle sits in front of the problem's callables, so
this cache changes no count; it only avoids tracing the same workspace twice.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable
from typing import Generic, TypeVar

import numpy as np

__all__ = ["DesignCache"]

T = TypeVar("T")


class DesignCache(Generic[T]):
    """``cache.get(d, compute)`` returns ``compute(d)``, memoized for the last ``size`` designs."""

    def __init__(self, size: int = 16):
        self.size = size
        self._items: OrderedDict[bytes, T] = OrderedDict()

    def get(self, d, compute: Callable[[np.ndarray], T]) -> T:
        d = np.asarray(d, dtype=float)
        key = d.tobytes()
        if key in self._items:
            self._items.move_to_end(key)
            return self._items[key]
        value = compute(d)
        self._items[key] = value
        if len(self._items) > self.size:
            self._items.popitem(last=False)
        return value
