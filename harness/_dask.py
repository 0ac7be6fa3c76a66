"""Dask executor: the same runs on a `dask.distributed` cluster (issue 4, Section 3).

Each Dask task runs its `RunSpec` in a child process of the Dask worker (one persistent
child per worker thread), so the per-run time limit is enforced by killing the child
exactly as the local pool does, and a crashing solver cannot take the Dask worker down.
Children come from a ``forkserver`` (Dask workers are multi-threaded; forking them is
unsafe).  Workers need the project installed and, for ``--suite-file``, the file at the
same path.  ``scheduler="local"`` (or ``"local:N"``) starts an in-process LocalCluster.
"""

from __future__ import annotations

import multiprocessing as mp
import threading
from collections.abc import Iterator
from typing import Any

from ._plan import RunSpec
from ._pool import Slot
from ._worker import spec_row

__all__ = ["dask_map", "run_isolated"]

_LOCAL = threading.local()


def _context() -> Any:
    import os

    for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")  # run children share the Dask worker's cores
    try:
        ctx = mp.get_context("forkserver")
        ctx.set_forkserver_preload(["harness._worker"])
    except ValueError:  # no forkserver (Windows)
        ctx = mp.get_context("spawn")
    return ctx


def _new_slot() -> Slot:
    proc = mp.current_process()
    daemon = proc._config.get("daemon")  # type: ignore[attr-defined]
    # Dask's worker processes are daemonic and multiprocessing refuses children of daemons;
    # our child ends by itself when its pipe closes, so the rule's purpose is kept.
    proc._config["daemon"] = False  # type: ignore[attr-defined]
    try:
        return Slot(_context(), die_with_parent=False)  # forkserver is the parent
    finally:
        proc._config["daemon"] = daemon  # type: ignore[attr-defined]


def run_isolated(spec: RunSpec) -> dict[str, Any]:
    """The Dask task: run ``spec`` in this thread's child process, with its time limit."""
    slot = getattr(_LOCAL, "slot", None)
    if slot is None or not slot.alive:
        slot = _LOCAL.slot = _new_slot()
    row, usable = slot.run_one(spec)
    if not usable:
        _LOCAL.slot = None
    return row


def dask_map(specs: list[RunSpec], scheduler: str | None) -> Iterator[dict[str, Any]]:
    """Submit every run to the cluster at ``scheduler``; yield rows as they finish."""
    from distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler and scheduler.startswith("local"):
        n = int(scheduler.split(":", 1)[1]) if ":" in scheduler else None
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    else:
        client = Client(scheduler, timeout="30s")
    try:
        futures = {client.submit(run_isolated, sp, pure=False, key=f"run-{sp.run_key}-{i}"): sp
                   for i, sp in enumerate(specs)}
        for fut in as_completed(futures):
            sp = futures[fut]
            try:
                yield fut.result()
            except Exception as exc:  # noqa: BLE001 - lost worker etc.: recorded, suite goes on
                yield spec_row(sp, "error", f"dask task failed: {type(exc).__name__}: {exc}")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
