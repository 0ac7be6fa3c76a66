"""Dask executor: the same runs on a `dask.distributed` cluster (docs/harness.md).

Each Dask task runs its `RunSpec` in a child process of the Dask worker (one persistent
child per worker thread), so the per-run time limit is enforced by killing the child
exactly as the local pool does, and a crashing solver cannot take the Dask worker down.

Same numbers as the local executor: a Dask worker was started by someone else, with its
own environment and NumPy already loaded, so the harness's BLAS kernel pin and thread
counts (`harness._blas`) cannot act on it.  They act on its children instead: every task
carries the harness process's numerical environment, which is applied to the worker's
``os.environ`` before a child is *spawned* (a fresh interpreter that loads OpenBLAS under
it; a forked or forkserver child would inherit already-loaded kernels).  The environment
each worker applied is recorded in the run's manifest.  Workers need the project
installed and, for ``--suite-file``, the file at the same path.  ``scheduler="local"``
(or ``"local:N"``) starts an in-process LocalCluster.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import threading
from collections.abc import Iterator
from typing import Any

from ._blas import KERNEL_ENV, THREAD_ENV
from ._plan import HarnessArgumentError, RunSpec
from ._pool import Slot
from ._worker import spec_row

__all__ = ["dask_map", "run_isolated"]

_LOCAL = threading.local()


NUMERIC_ENV = KERNEL_ENV + THREAD_ENV
_ENV_LOCK = threading.Lock()
_DAEMON_LOCK = threading.Lock()  # guards the toggle of the process's daemon flag in `_new_slot`


def numeric_env() -> dict[str, str | None]:
    """This process's numerical environment: BLAS and NumPy kernels, thread counts (None: unset)."""
    return {v: os.environ.get(v) for v in NUMERIC_ENV}


def apply_numeric_env(env: dict[str, str | None]) -> dict[str, str | None]:
    """Make ``env`` this process's numerical environment for the children it spawns next."""
    with _ENV_LOCK:
        for k, v in env.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
        return numeric_env()


def _new_slot(env: dict[str, str | None]) -> Slot:
    apply_numeric_env(env)
    ctx = mp.get_context("spawn")  # a fresh interpreter: OpenBLAS loads under ``env``
    proc = mp.current_process()
    # Dask's worker processes are daemonic and multiprocessing refuses children of daemons;
    # our child ends by itself when its pipe closes, so the rule's purpose is kept.  The flag
    # is process-wide and a worker runs several threads: without the lock one thread could
    # restore it while another starts its child ("daemonic processes are not allowed to have
    # children", seen with threads_per_worker=2 under load).
    with _DAEMON_LOCK:
        daemon = proc._config.get("daemon")  # type: ignore[attr-defined]  # private, no stub
        proc._config["daemon"] = False  # type: ignore[attr-defined]  # private, no stub
        try:
            return Slot(ctx, die_with_parent=False)  # the child ends when its pipe closes
        finally:
            proc._config["daemon"] = daemon  # type: ignore[attr-defined]  # private, no stub


def run_isolated(spec: RunSpec, env: dict[str, str | None] | None = None) -> dict[str, Any]:
    """The Dask task: run ``spec`` in this thread's child process, with its time limit,
    under the harness's numerical environment ``env``."""
    env = env if env is not None else numeric_env()
    slot = getattr(_LOCAL, "slot", None)
    if slot is None or not slot.alive or getattr(_LOCAL, "env", None) != env:
        if slot is not None:
            slot.close()
        slot = _LOCAL.slot = _new_slot(env)
        _LOCAL.env = env
    row, usable = slot.run_one(spec)
    if not usable:
        _LOCAL.slot = None
    return row


def dask_map(specs: list[RunSpec], scheduler: str | None,
             info: dict[str, Any] | None = None) -> Iterator[dict[str, Any]]:
    """Submit every run to the cluster at ``scheduler``; yield rows as they finish.

    ``info`` (if given) receives ``workers``: the numerical environment each worker applied.
    """
    from problems._registry import MissingExtra, require

    try:
        distributed = require("distributed", "--executor dask")
    except MissingExtra as exc:
        raise HarnessArgumentError(str(exc)) from None
    Client, LocalCluster, as_completed = distributed.Client, distributed.LocalCluster, distributed.as_completed

    cluster = None
    if scheduler and scheduler.startswith("local"):
        n = int(scheduler.split(":", 1)[1]) if ":" in scheduler else None
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    else:
        client = Client(scheduler, timeout="30s")
    try:
        env = numeric_env()
        applied = client.run(apply_numeric_env, env)  # every worker now; late joiners per task
        if info is not None:
            info["workers"] = applied
        futures = {client.submit(run_isolated, sp, env, pure=False, key=f"run-{sp.run_key}-{i}"): sp
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
