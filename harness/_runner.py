"""`run_suite`: plan the runs of a suite, skip stored ones, execute the rest, store rows.

The harness's own failures (unknown names, bad values) raise `HarnessArgumentError`;
whatever the solvers do is recorded as rows and never stops the suite (docs/harness.md,
"Fault isolation").
"""

from __future__ import annotations

import dataclasses
import numbers
import os
import pathlib
import re
import sys
import time
from collections.abc import Iterator, Sequence
from typing import Any, TextIO

import numpy as np
import pandas as pd

from problems import UnknownSuite

from . import _manifest
from ._history import thin_history
from ._plan import HarnessArgumentError, RunSpec, name_list, plan_runs
from ._pool import LocalPool
from ._preflight import check_problems
from ._progress import Progress
from ._store import Store, retry_keys
from ._suites import SolverModuleError, SuiteRef, import_modules, ref_for

__all__ = ["run_suite", "RunSummary", "resolve_suite", "default_timeout", "check_run_options"]

CONSOLIDATE_EVERY = 60.0  # seconds between merges of pending run files into runs.parquet
HEARTBEAT = 5.0  # seconds: progress is redrawn even while no run finishes


@dataclasses.dataclass
class RunSummary:
    """What one ``run`` did."""

    suite: str
    planned: int
    skipped: int
    executed: int
    failed: int
    not_applicable: int
    store: pathlib.Path
    elapsed: float
    retried: int = 0  # stored failures run again under the retry policy

    def __str__(self) -> str:
        if self.executed == 0:
            return (f"{self.suite}: all {self.planned} runs already stored in {self.store} (resume) - "
                    f"no solver work done; use --fresh to run them again")
        again = f", {self.retried} of them stored failures run again" if self.retried else ""
        return (f"{self.suite}: {self.executed} runs executed ({self.failed} error/timeout, "
                f"{self.not_applicable} not applicable{again}), {self.skipped} already stored, "
                f"{self.elapsed:.1f} s -> {self.store}")


def _clock_decided(store: Store) -> int:
    """Stored runs whose outcome the wall clock decided (`tables._campaign.clock_decided`)."""
    from .tables._campaign import clock_decided

    if not store.exists():
        return 0
    runs = store.load()
    return int(clock_decided(runs).sum()) if len(runs) else 0


def _machine_note(store: Store, timeout: float) -> str:
    """`_manifest.machine_note` for runs about to be added to ``store``."""
    return _manifest.machine_note(store.root, timeout, lambda: _clock_decided(store))


def _cores() -> int:
    """Cores this process may use (CPU affinity, e.g. under a batch system), else all."""
    try:
        return len(os.sched_getaffinity(0)) or 1
    except AttributeError:  # macOS, Windows
        return os.cpu_count() or 1


def _check_writable(directory: pathlib.Path) -> None:
    """Fail before any solver work when the results cannot be written."""
    import tempfile

    try:
        directory.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=directory, prefix=".write-test-"):
            pass
    except OSError as exc:
        raise HarnessArgumentError(f"cannot write results to {directory}: {exc.strerror or exc}; "
                                   "choose another --out") from None


def select_suite(s: Any, select: str | None) -> Any:
    """``s`` restricted to ``select`` (None: unchanged); bad selections are argument errors."""
    if not select:
        return s
    try:
        chosen = s.select(select)
        n = len(chosen.cases())
    except ValueError as exc:  # SelectionError, or a suite without selections
        raise HarnessArgumentError(str(exc)) from None
    if n == 0:
        raise HarnessArgumentError(f"the selection {select!r} picks no problem of suite {s.name}")
    return chosen


def resolve_suite(suite: str | None = None, suite_file: str | os.PathLike[str] | None = None) -> SuiteRef:
    """A `SuiteRef`; unknown names raise `HarnessArgumentError` listing the valid ones."""
    try:
        ref = ref_for(suite, suite_file)
        ref.load()
    except UnknownSuite as exc:
        raise HarnessArgumentError(str(exc)) from None
    except (FileNotFoundError, ValueError, ImportError, SyntaxError) as exc:
        if suite_file is None and not isinstance(exc, ValueError):
            raise
        raise HarnessArgumentError(str(exc)) from None
    return ref


#: per-run wall-clock limit (s) when none is given: 10 s for the library campaigns (their protocol,
#: docs/cutest.md; the campaign tables judge every run under one limit), 600 s elsewhere, where it
#: is only a guard against hangs (the solvers' caps end the runs, so the rows do not depend on the
#: machine).  ``spatial`` gets 1800 s: its SLSQP run on spatial-cable-13 (257 evaluations of ~1.7 s)
#: took 436 s on the machine that made the campaigns and over 600 s on a slower one.  ``rpr3`` and
#: ``rpr3-spread`` get 1800 s too: Dynamic-Q+ on D P1 took 286 s on an idle 2-core Xeon and 454 s
#: with a test job beside it, too close to 600 s for a limit that is only a guard.
DEFAULT_TIMEOUT = 600.0
SUITE_TIMEOUTS = {"cutest": 10.0, "hs-all": 10.0, "spatial": 1800.0, "rpr3": 1800.0, "rpr3-spread": 1800.0}


def default_timeout(suite: str | None, suite_file: str | os.PathLike[str] | None = None) -> float:
    """The wall-clock limit a run of the suite gets when ``--timeout`` is not given."""
    return DEFAULT_TIMEOUT if suite_file is not None else SUITE_TIMEOUTS.get(str(suite), DEFAULT_TIMEOUT)


def _execute(specs: list[RunSpec], executor: str, jobs: int, scheduler: str | None,
             start_method: str | None, info: dict[str, Any]) -> Iterator[dict[str, Any] | None]:
    if executor == "local":
        with LocalPool(jobs, start_method) as pool:
            yield from pool.map(specs, heartbeat=HEARTBEAT)
    elif executor == "dask":
        from ._dask import dask_map

        yield from dask_map(specs, scheduler, info)
    else:
        raise HarnessArgumentError(f"unknown executor {executor!r}; valid executors: local, dask")


def plan_table(specs: list[RunSpec], todo: list[RunSpec], store: Store) -> pd.DataFrame:
    """Per solver (with its command-line options, ``sqsd[rho=0.5]``, a solver of its own as in
    the store): planned runs, runs already stored under the current code, runs to do (and how
    many of them replace a stored row of the same case, solver and command-line options: from
    other code or settings, a time-out under a smaller limit, or any with ``fresh``), and an
    estimate of their run time: the stored wall time of the same case, solver and options
    where there is one, else the solver's mean stored wall time per run (the mean, not the
    median: time-outs make the distribution heavy-tailed).  Sums of run times; divide by the
    workers for the wall time.  Not-applicable pairs count as done.
    """
    from ._profiles import solver_labels

    runs = store.load() if store.exists() else pd.DataFrame(columns=["case_id", "solver", "wall_time_s"])
    wall = pd.to_numeric(runs["wall_time_s"], errors="coerce")
    over = runs["overrides"].fillna("") if "overrides" in runs else pd.Series("", index=runs.index)
    last = dict(zip(zip(runs["case_id"], runs["solver"], over), wall))
    mean = wall.groupby(runs["solver"]).mean().to_dict()
    todo_keys = {sp.run_key for sp in todo}
    labels = list(solver_labels(pd.DataFrame({"solver": [sp.solver for sp in specs],
                                              "overrides": [sp.overrides for sp in specs]})))
    rows = []
    for label in dict.fromkeys(labels):
        mine = [sp for sp, lab in zip(specs, labels) if lab == label]
        pending = [sp for sp in mine if sp.run_key in todo_keys and sp.not_applicable is None]
        stale = [sp for sp in pending if (sp.case_id, sp.solver, sp.overrides) in last]
        est = sum(last.get((sp.case_id, sp.solver, sp.overrides), mean.get(sp.solver, float("nan")))
                  for sp in pending)
        rows.append({"solver": label, "planned": len(mine), "done": len(mine) - len(pending),
                     "to run": len(pending), "replace a stored row": len(stale),
                     "estimated run time [s]": round(float(est), 1)})
    table = pd.DataFrame(rows)
    # an estimate unknown for one solver (no stored wall times) leaves the total unknown, not 0
    total = {"solver": "all", **{c: table[c].sum(skipna=c != "estimated run time [s]")
                                 for c in table.columns if c != "solver"}}
    return pd.concat([table, pd.DataFrame([total])], ignore_index=True)


def _import_solver_modules(modules: Sequence[str]) -> None:
    try:
        import_modules(tuple(modules))
    except SolverModuleError as exc:  # bad input: exit 2, naming the module
        raise HarnessArgumentError(str(exc)) from None


def _whole(v: Any) -> bool:
    return isinstance(v, numbers.Integral) and not isinstance(v, bool)


def _check_timeout(timeout: Any) -> None:
    if isinstance(timeout, bool) or not isinstance(timeout, (int, float, np.integer, np.floating)) \
            or not (timeout >= 0):  # NaN too
        raise HarnessArgumentError(f"--timeout must be a number of seconds >= 0 (0 or inf: no limit), got {timeout!r}")


def check_run_options(*, jobs: Any = None, history_points: Any = None, executor: str = "local",
                      scheduler: str | None = None) -> None:
    """`HarnessArgumentError` for run options `run_suite` cannot use (``run --dry-run`` checks them too)."""
    if history_points is not None and not (_whole(history_points) and history_points >= 2):
        raise HarnessArgumentError(f"--history-points must be a whole number >= 2, got {history_points!r}")
    if jobs is not None and not (_whole(jobs) and jobs >= 1):
        raise HarnessArgumentError(f"--jobs must be a whole number >= 1, got {jobs!r}")
    if executor not in ("local", "dask"):
        raise HarnessArgumentError(f"unknown executor {executor!r}; valid executors: local, dask")
    if executor == "dask" and not scheduler:
        raise HarnessArgumentError("--executor dask needs --scheduler ADDRESS (e.g. tcp://127.0.0.1:8786)")
    if executor != "dask" and scheduler:  # it would be ignored: the runs would go to local workers
        raise HarnessArgumentError(f"--scheduler {scheduler!r} is for --executor dask; add --executor dask to run "
                                   f"on that cluster, or leave --scheduler out to run locally")
    if executor == "dask" and str(scheduler).startswith("local") and not re.fullmatch(r"local(:[1-9][0-9]*)?",
                                                                                    str(scheduler)):
        raise HarnessArgumentError(f"--scheduler {scheduler!r}: an in-process cluster is 'local' or 'local:N' with N "
                                   "workers >= 1; a running scheduler is an address such as tcp://127.0.0.1:8786")


def _plan(suite: str | None, suite_file: str | os.PathLike[str] | None, solvers: Sequence[str] | None,
          problems: Sequence[str] | None, select: str | None, timeout: float,
          modules: Sequence[str]) -> tuple[SuiteRef, list[RunSpec]]:
    """The suite and every run it plans (keys computed), as `run_suite` would run them."""
    solvers, problems = name_list(solvers, "solvers"), name_list(problems, "problems")
    ref = resolve_suite(suite, suite_file)
    s = select_suite(ref.load(), select)
    solver_specs = list(solvers) if solvers else list(s.solvers)
    every_solver = not solver_specs  # a suite without defaults: every registered solver that handles it
    if every_solver:
        from solvers import solver_names

        solver_specs = solver_names()
    specs = plan_runs(ref, s, solver_specs, list(problems) if problems else None, timeout, tuple(modules))
    if every_solver:  # only the solvers that handle each problem; a bad plan would be ours, not the user's
        specs = [sp for sp in specs if sp.not_applicable is None and sp.plan_error is None]
    if ref.file:  # a user's problems: wrong shapes are bad input before any run, doubtful derivatives a warning
        ids = {sp.case_id for sp in specs}
        for note in check_problems(c.problem for c in s.cases() if c.case_id in ids):
            print(f"warning: {note}", file=sys.stderr, flush=True)
    return ref, specs


def _todo(specs: list[RunSpec], store: Store, timeout: float, fresh: bool,
          retry_failed: bool) -> tuple[list[RunSpec], set[str]]:
    """The planned runs not stored yet (or to run again), and the stored keys run again."""
    stored = set() if fresh else store.stored_keys()
    again = set() if fresh or not stored else retry_keys(store.load(), timeout, retry_failed) & stored
    return [sp for sp in specs if sp.run_key not in stored or sp.run_key in again], again


def plan_suite(suite: str | None = None, *, suite_file: str | os.PathLike[str] | None = None,
               solvers: Sequence[str] | None = None, problems: Sequence[str] | None = None,
               select: str | None = None, out: str | os.PathLike[str] = "results", timeout: float | None = None,
               fresh: bool = False, retry_failed: bool = False, modules: Sequence[str] = ()) -> pd.DataFrame:
    """What `run_suite` with the same arguments would do, per solver (`plan_table`); runs nothing."""
    if timeout is None:
        timeout = default_timeout(suite, suite_file)
    _check_timeout(timeout)
    if modules:
        _import_solver_modules(modules)
    ref, specs = _plan(suite, suite_file, solvers, problems, select, timeout, modules)
    store = Store(out, ref.name)
    todo = _todo(specs, store, timeout, fresh, retry_failed)[0]
    table = plan_table(specs, todo, store)
    # the note `run_suite` would print (`_manifest.machine_note`): stored wall times, which the
    # estimate uses, are another machine's too
    table.attrs["note"] = _machine_note(store, timeout) if todo else ""
    return table


def prune_suite(suite: str | None = None, *, suite_file: str | os.PathLike[str] | None = None,
                solvers: Sequence[str] | None = None, select: str | None = None,
                out: str | os.PathLike[str] = "results", modules: Sequence[str] = (),
                dry_run: bool = False) -> dict[str, int]:
    """Remove the stored rows a run of the suite would not produce now; rows removed per solver
    (``dry_run``: the rows that would be removed; nothing is changed).

    Those are rows from older code or settings (their key is no longer planned) and rows of
    cases or solvers outside the selection.  After a change of a solver or of a campaign's
    selection, the tables then show the current code only.  The previous generation stays
    in ``runs.prev.parquet`` (`harness repair` restores it); the committed store is in git.
    """
    if modules:
        _import_solver_modules(modules)
    ref, specs = _plan(suite, suite_file, solvers, None, select, 0.0, modules)
    store = Store(out, ref.name)
    if not store.exists():
        return {}
    return store.keep_only({sp.run_key for sp in specs}, dry_run=dry_run)


def run_suite(
    suite: str | None = None,
    *,
    suite_file: str | os.PathLike[str] | None = None,
    solvers: Sequence[str] | None = None,
    problems: Sequence[str] | None = None,
    select: str | None = None,
    out: str | os.PathLike[str] = "results",
    jobs: int | None = None,
    timeout: float | None = None,
    fresh: bool = False,
    retry_failed: bool = False,
    executor: str = "local",
    scheduler: str | None = None,
    modules: Sequence[str] = (),
    start_method: str | None = None,
    progress: TextIO | None = sys.stderr,
    argv: Sequence[str] | None = None,
    history_points: int | None = None,
) -> RunSummary:
    """Run a suite's (case x solver) runs and store one row per run.

    Parameters
    ----------
    suite, suite_file : catalogue name, or a Python file defining SUITE or PROBLEMS.
    solvers : solver ids, optionally with options (``"sqsd[rho=0.5]"``); default the suite's, or,
        for a suite that names none (a user's ``PROBLEMS`` file without ``SOLVERS``), every
        registered solver that handles the problem.
    problems : problem ids (or case ids) to run; default all.
    select : a selection of the suite's problems by their properties, for suites that
        support it (``cutest``, ``hs-all``: ``"type=u,n<=100"``; docs/cutest.md).
    out : results directory; rows go to ``out/<suite>/runs.parquet``.
    jobs : worker processes (local executor); default all cores.
    timeout : per-run wall-clock limit in seconds (0 or inf: none; negative or NaN is an error);
        default `default_timeout`: the suite's entry of `SUITE_TIMEOUTS` (the campaigns ``cutest``
        and ``hs-all``, and the suites with runs of several minutes), else `DEFAULT_TIMEOUT`.
    fresh : run again even the runs already stored under the same key.
    retry_failed : run again every stored error and time-out row. Without it, stored failures
        of the infrastructure (worker killed, Dask worker lost, out of memory) are run again,
        and time-outs when ``timeout`` is larger than the limit they ran under.
    executor, scheduler : ``"local"`` or ``"dask"`` with a scheduler address.
    modules : modules (names or .py paths) workers import first, e.g. to register solvers.
    progress : stream for the progress display (None: quiet).
    history_points : store long histories thinned to about this many evaluations
        (`harness._history.thin_history`: exact for best-so-far curves, first-hitting
        counts rounded up by a bounded factor); None keeps every evaluation.
    """
    t0 = time.perf_counter()
    started = _manifest.now()
    if modules:
        _import_solver_modules(modules)
    if timeout is None:
        timeout = default_timeout(suite, suite_file)
    _check_timeout(timeout)
    check_run_options(jobs=jobs, history_points=history_points, executor=executor, scheduler=scheduler)
    ref, specs = _plan(suite, suite_file, solvers, problems, select, timeout, modules)
    store = Store(out, ref.name)
    _check_writable(store.root)
    todo, again = _todo(specs, store, timeout, fresh, retry_failed)
    existed = store.exists()
    by_key = {sp.run_key: sp for sp in todo}
    summary = RunSummary(ref.name, len(specs), len(specs) - len(todo), 0, 0, 0, store.parquet, 0.0,
                         retried=sum(sp.run_key in again for sp in todo))
    if todo:
        note = _machine_note(store, timeout)
        if note:  # before the work, and whether or not progress is shown: it qualifies the results
            print(note, file=sys.stderr, flush=True)
        bar = Progress(ref.name, len(todo), progress)
        last = time.perf_counter()
        info: dict[str, Any] = {}
        try:
            for row in _execute(todo, executor, jobs or _cores(), scheduler, start_method, info):
                if row is None:  # heartbeat: nothing finished lately
                    bar.tick()
                    continue
                sp = by_key.get(str(row.get("run_key")))
                row["timeout_s"] = sp.timeout if sp is not None else float("nan")
                if history_points and isinstance(row.get("history"), str):
                    row["history"] = thin_history(row["history"], history_points)
                store.write_run(row)
                summary.executed += 1
                summary.failed += row["status"] in ("error", "timeout")
                summary.not_applicable += row["status"] == "not_applicable"
                bar.update(row)
                if time.perf_counter() - last > CONSOLIDATE_EVERY:
                    store.consolidate()
                    last = time.perf_counter()
        finally:
            bar.close()
            summary.elapsed = time.perf_counter() - t0
            if summary.executed or existed:  # nothing ran (e.g. no Dask scheduler): leave no empty store
                store.consolidate()
                _manifest.record_session(store.root, {
                    **_manifest.environment(), "suite": ref.name, "suite_file": ref.file, "start": started,
                    "end": _manifest.now(), "argv": list(argv) if argv is not None else sys.argv,
                    "planned": summary.planned, "executed": summary.executed, "skipped": summary.skipped,
                    "failed": summary.failed, "executor": executor, "jobs": jobs, "timeout": timeout,
                    "history_points": history_points,
                    **({"dask_workers": info["workers"]} if "workers" in info else {})})
    elif not store.parquet.exists() and store.exists():
        store.consolidate()
    summary.elapsed = time.perf_counter() - t0
    return summary
