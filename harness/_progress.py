"""Progress: a bar on a terminal, plain periodic lines otherwise (CI logs)."""

from __future__ import annotations

import sys
import time
from typing import Any, TextIO

__all__ = ["Progress"]


def _fmt(seconds: float) -> str:
    if seconds != seconds or seconds == float("inf"):
        return "--:--"
    s = int(round(seconds))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60:02d}:{s % 60:02d}"


class Progress:
    """done/total, failures and ETA for one suite.

    ``stream=None`` disables output.  On a tty the bar is redrawn at most 10 times a
    second; otherwise a line is printed every ``interval`` seconds and at the end.
    """

    def __init__(self, label: str, total: int, stream: TextIO | None = sys.stderr, interval: float = 10.0):
        self.label, self.total, self.stream = label, total, stream
        self.tty = bool(stream is not None and getattr(stream, "isatty", lambda: False)())
        self.interval = 0.1 if self.tty else interval
        self.done = self.failed = 0
        self.t0 = time.perf_counter()
        self._last = self.t0

    def update(self, row: dict[str, Any]) -> None:
        self.done += 1
        if row.get("status") in ("error", "timeout"):
            self.failed += 1
        now = time.perf_counter()
        if self.stream is not None and (now - self._last >= self.interval or self.done == self.total):
            self._last = now
            self._draw(now, final=False)

    def tick(self) -> None:
        """Redraw if due although no run finished (long runs: show the clock moving)."""
        now = time.perf_counter()
        if self.stream is not None and now - self._last >= max(self.interval, 1.0 if self.tty else 60.0):
            self._last = now
            self._draw(now, final=False)

    def _line(self, now: float) -> str:
        el = now - self.t0
        eta = el / self.done * (self.total - self.done) if self.done else float("nan")
        return (f"{self.label}: {self.done}/{self.total} runs, {self.failed} failed, "
                f"elapsed {_fmt(el)}, ETA {_fmt(eta)}")

    def _draw(self, now: float, final: bool) -> None:
        assert self.stream is not None
        if self.tty:
            width = 28
            filled = int(width * self.done / self.total) if self.total else width
            bar = "#" * filled + "-" * (width - filled)
            self.stream.write(f"\r[{bar}] {self._line(now)}" + ("\n" if final else ""))
        else:
            self.stream.write(self._line(now) + "\n")
        self.stream.flush()

    def close(self) -> None:
        if self.stream is not None and self.total:
            if self.tty:
                self._draw(time.perf_counter(), final=True)
            elif self.done != self.total:
                self._draw(time.perf_counter(), final=False)
