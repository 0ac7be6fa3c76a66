"""Local executor: persistent worker processes with a hard per-run time limit.

`concurrent.futures` cannot stop one hung task, so each worker is a process of our own
with a pipe; the parent waits on all pipes at once (`multiprocessing.connection.wait`)
up to the nearest deadline, kills a worker whose run overstays its limit (a solver that
sleeps forever or a C extension stuck in a loop) and starts a fresh one.  A worker that
dies (segfault, out of memory) yields an ``error`` row and is replaced.

On Linux workers are forked: start-up is cheap (the parent's imports are inherited) and
solvers registered at run time in the parent (tests, notebooks) exist in the workers.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import signal
import sys
import time
from collections import deque
from collections.abc import Iterable, Iterator
from multiprocessing.connection import Connection, wait
from typing import Any

from solvers._deadline import set_run_deadline

from ._plan import RunSpec
from ._worker import execute, spec_row

__all__ = ["LocalPool", "default_start_method", "Slot"]


def default_start_method() -> str:
    return "fork" if sys.platform.startswith("linux") else "spawn"


READY = "ready"
BOOT_LIMIT = 300.0  # seconds a new worker may take to import everything (spawn on a busy machine)


def _die_with_parent(parent: int) -> None:
    """Linux: the kernel kills this worker when the harness dies (even by SIGKILL), so no
    orphan goes on computing a run nobody will store."""
    if not sys.platform.startswith("linux"):
        return
    try:
        import ctypes

        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:  # the parent died before prctl took effect
        os._exit(1)


def _worker_main(conn: Connection, parent: int | None = None) -> None:
    """Worker loop: announce readiness, then receive a RunSpec and send back its row."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's business
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # not the parent's KeyboardInterrupt handler
    if parent is not None:
        _die_with_parent(parent)
    conn.send(READY)
    while True:
        try:
            spec = conn.recv()
        except (EOFError, OSError):
            return
        if spec is None:
            return
        set_run_deadline(spec.timeout)  # solvers that can stop early with an answer read it (multistart)
        conn.send(execute(spec))


class Slot:
    """One worker process and its pipe.

    A run's time limit starts when the worker holds the spec *and* has finished booting
    (the READY message), so slow imports in a fresh worker never count against a run.
    """

    def __init__(self, ctx: Any, die_with_parent: bool = True):
        self.ctx = ctx
        self.conn, child = ctx.Pipe(duplex=True)
        parent = os.getpid() if die_with_parent else None
        self.proc = ctx.Process(target=_worker_main, args=(child, parent), daemon=True, name="harness-worker")
        self.proc.start()
        child.close()
        self.ready = False
        self.spec: RunSpec | None = None
        self.started = time.perf_counter()
        self.deadline = self.started + BOOT_LIMIT

    def _start_clock(self) -> None:
        self.started = time.perf_counter()
        timeout = self.spec.timeout if self.spec is not None else 0.0
        self.deadline = self.started + timeout if timeout > 0 else float("inf")

    def submit(self, spec: RunSpec) -> None:
        self.spec = spec
        if self.ready:
            self._start_clock()
        self.conn.send(spec)

    def receive(self) -> dict[str, Any] | None:
        """The finished row; None for the READY message (the run's clock starts now)."""
        try:
            msg = self.conn.recv()
        except (EOFError, OSError):
            spec, self.spec = self.spec, None
            self.proc.join(1.0)
            code = self.proc.exitcode
            self.kill()
            if code == -signal.SIGTERM:  # the campaign is being stopped, not a solver failure:
                raise KeyboardInterrupt from None  # store nothing for this run, so a re-run redoes it
            if spec is None:
                return None
            return spec_row(spec, "error", f"worker process died (exit code {code})",
                            time.perf_counter() - self.started)
        if isinstance(msg, str) and msg == READY:
            self.ready = True
            self._start_clock()
            return None
        self.spec = None
        return msg

    def timeout_row(self) -> dict[str, Any]:
        """Kill an overdue worker; the row of the run it was doing (or of its failed boot)."""
        spec, self.spec = self.spec, None
        self.kill()
        assert spec is not None
        if not self.ready:
            return spec_row(spec, "error", f"worker process did not start within {BOOT_LIMIT:g} s")
        return spec_row(spec, "timeout", f"wall-clock limit of {spec.timeout:g} s exceeded",
                        time.perf_counter() - self.started)

    def kill(self) -> None:
        if self.proc.is_alive():
            self.proc.kill()
        self.proc.join()
        self.conn.close()

    def close(self) -> None:
        try:
            self.conn.send(None)
        except (OSError, BrokenPipeError):
            pass
        self.proc.join(2.0)
        self.kill()

    @property
    def alive(self) -> bool:
        return self.proc.is_alive()

    def run_one(self, spec: RunSpec) -> tuple[dict[str, Any], bool]:
        """Run one spec synchronously; returns (row, worker still usable)."""
        self.submit(spec)
        while True:
            remaining = None if self.deadline == float("inf") else max(0.0, self.deadline - time.perf_counter())
            if not self.conn.poll(remaining):
                return self.timeout_row(), False
            row = self.receive()
            if row is not None:
                return row, self.alive
            if self.spec is None:  # died while booting
                return spec_row(spec, "error", "worker process died while starting"), False


class LocalPool:
    """A pool of ``jobs`` worker processes (context manager)."""

    def __init__(self, jobs: int, start_method: str | None = None):
        self.jobs = max(1, int(jobs))
        self.ctx = mp.get_context(start_method or default_start_method())
        self.slots: list[Slot] = []

    def __enter__(self) -> LocalPool:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def close(self) -> None:
        for s in self.slots:
            if s.spec is not None:
                s.kill()  # interrupted: in-flight runs are lost, never half-written
            else:
                s.close()
        self.slots = []

    def map(self, specs: Iterable[RunSpec], heartbeat: float | None = None) -> Iterator[dict[str, Any] | None]:
        """Yield one row per spec, in completion order (and None every ``heartbeat``
        seconds without a finished run, so the caller can report progress)."""
        queue = deque(specs)
        while len(self.slots) < min(self.jobs, len(queue)):
            self.slots.append(Slot(self.ctx))
        busy: dict[Connection, Slot] = {}
        while queue or busy:
            for i, s in enumerate(self.slots):
                if s.spec is None and queue:
                    if not s.alive:
                        s = self.slots[i] = Slot(self.ctx)
                    s.submit(queue.popleft())
                    busy[s.conn] = s
            now = time.perf_counter()
            nearest = min(s.deadline for s in busy.values())
            limit = None if nearest == float("inf") else max(0.0, nearest - now)
            if heartbeat is not None:
                limit = heartbeat if limit is None else min(limit, heartbeat)
            ready = wait(list(busy), timeout=limit)
            if not ready and heartbeat is not None and time.perf_counter() < nearest:
                yield None
            for conn in ready:
                slot = busy[conn]  # type: ignore[index]  # wait() returns the keys it was given
                row = slot.receive()  # a dead worker is replaced at the next submit
                if row is not None:
                    del busy[conn]  # type: ignore[arg-type]  # as above
                    yield row
            now = time.perf_counter()
            for conn, slot in list(busy.items()):
                if now >= slot.deadline:
                    del busy[conn]
                    yield slot.timeout_row()
