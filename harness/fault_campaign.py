"""Fault-injection campaign: does the store come out of every fault equal to a clean run's?

    python -m harness.fault_campaign --out /tmp/faults            # hs sample, ~5 minutes on 2 cores
    python -m harness.fault_campaign --out /tmp/faults --suite appendix-a --problems a01,a04,a11

A clean run of the selection is made first.  Then each scenario starts from an empty
results directory (or a copy of the clean one), injects its fault into a real
``python -m harness run`` process, and runs the same command again, plainly, as a user
would.  The store must then equal the clean run's: the same run keys, the same N^fg, nf,
ng and status, bitwise the same f, every (case, solver) once, nothing left pending.

Scenarios (docs/harness.md, "Fault campaign"):

* ``kill-harness``: SIGKILL of the harness process at a random moment (3 times);
* ``kill-worker``: SIGKILL of one worker process at a random moment (3 times);
* ``sigint``: Ctrl-C of the harness;
* ``concurrent``: two harness processes on one ``--out`` at once;
* ``truncated``: ``runs.parquet`` cut in half, then ``harness repair``;
* ``kill-dask-worker``: SIGKILL of one Dask worker process of a LocalCluster mid-suite.

``--scenarios kill-harness,truncated`` runs only those.  A kill that finds no process to kill
(the run ended first) is reported as "no fault injected": its store is still checked, but the
scenario tested nothing.

Exit status 0 when every scenario ends equal to the clean run, 1 otherwise, 2 on bad input.
"""

from __future__ import annotations

import argparse
import functools
import os
import pathlib
import random
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Callable

import numpy as np
import pandas as pd

from ._store import IDENTITY, Store

DEFAULT_PROBLEMS = "hs010,hs014,hs022,hs024,hs029,hs031,hs045,hs065,hs071,hs076"
COUNTS = ["nfg", "nf", "ng", "status"]
SCENARIOS = ("kill-harness", "kill-worker", "sigint", "concurrent", "truncated", "kill-dask-worker")
#: a fault: interrupts the harness process given, returns (injected, what it did)
Fault = Callable[[subprocess.Popen[bytes]], tuple[bool, str]]


def _harness(*args: str) -> list[str]:
    return [sys.executable, "-m", "harness", *args]


def _descendants(pid: int) -> list[int]:
    """Process ids below ``pid`` (Linux /proc; no third-party dependency)."""
    children: dict[int, list[int]] = {}
    for d in pathlib.Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            ppid = int((d / "stat").read_text().rsplit(")", 1)[1].split()[1])
        except (OSError, IndexError, ValueError):
            continue
        children.setdefault(ppid, []).append(int(d.name))
    out, stack = [], [pid]
    while stack:
        for c in children.get(stack.pop(), []):
            out.append(c)
            stack.append(c)
    return out


def _cmdline(pid: int) -> str:
    try:
        return pathlib.Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
    except OSError:
        return ""


class Campaign:
    def __init__(self, out: pathlib.Path, suite: str, problems: str, jobs: int, seed: int):
        self.out, self.suite, self.problems, self.jobs = out, suite, problems, jobs
        self.rng = random.Random(seed)
        self.clean_time = 0.0
        self.results: list[dict[str, object]] = []

    def run_args(self, out: pathlib.Path, *extra: str) -> list[str]:
        return _harness("run", "--suite", self.suite, "--problems", self.problems, "--out", str(out),
                        "--quiet", "--no-table", "--jobs", str(self.jobs), *extra)

    def plain_run(self, out: pathlib.Path) -> None:
        subprocess.run(self.run_args(out), check=False, capture_output=True)

    def clean(self) -> pd.DataFrame:
        """The reference run; a selection the harness refuses (exit 2: unknown suite or problem)
        raises ValueError with its message."""
        t0 = time.perf_counter()
        done = subprocess.run(self.run_args(self.out / "clean", "--fresh"), capture_output=True, text=True)
        self.clean_time = time.perf_counter() - t0
        if done.returncode != 0:
            last = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else f"exit {done.returncode}"
            raise ValueError(f"the clean run failed: {last}")
        return Store(self.out / "clean", self.suite).load()

    def moment(self) -> float:
        return self.rng.uniform(0.1, 0.9) * self.clean_time

    # ------------------------------------------------------------------ scenarios
    def _interrupted(self, name: str, fault: Fault, *extra: str) -> None:
        out = self.out / name
        shutil.rmtree(out, ignore_errors=True)
        proc = subprocess.Popen(self.run_args(out, *extra), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        at = self.moment()
        time.sleep(at)
        # a run that has already ended leaves nothing to interrupt
        injected, what = fault(proc) if proc.poll() is None else (False, "no fault: the run had ended")
        proc.wait(timeout=600)
        before = len(Store(out, self.suite).load()) if Store(out, self.suite).exists() else 0
        self.plain_run(out)
        self.check(name, out, f"{what} at {at:.1f} s; {before} runs stored before the re-run", injected)

    def kill_harness(self, i: int) -> None:
        def fault(proc: subprocess.Popen[bytes]) -> tuple[bool, str]:
            proc.send_signal(signal.SIGKILL)
            return True, "SIGKILL of the harness"
        self._interrupted(f"kill-harness-{i}", fault)

    def _kill_one(self, proc: subprocess.Popen[bytes], pick: Callable[[list[int]], list[int]], what: str,
                  tries: int, pause: float) -> tuple[bool, str]:
        """SIGKILL one process, chosen at random among ``pick(descendants of proc)``, polling until there is one."""
        for _ in range(tries):
            victims = pick(_descendants(proc.pid))
            if victims:
                victim = self.rng.choice(victims)
                os.kill(victim, signal.SIGKILL)
                return True, f"SIGKILL of {what} {victim}"
            time.sleep(pause)
        return False, f"no {what} found to kill"

    def kill_worker(self, i: int) -> None:
        def workers(kids: list[int]) -> list[int]:
            return [p for p in kids if "multiprocessing" in _cmdline(p) or "harness" in _cmdline(p)]
        self._interrupted(f"kill-worker-{i}", lambda proc: self._kill_one(proc, workers, "worker", 50, 0.05))

    def sigint(self) -> None:
        def fault(proc: subprocess.Popen[bytes]) -> tuple[bool, str]:
            proc.send_signal(signal.SIGINT)
            return True, "SIGINT of the harness"
        self._interrupted("sigint", fault)

    def kill_dask_worker(self) -> None:
        def workers(kids: list[int]) -> list[int]:
            # Dask worker processes: spawned children of the nannies that run children of their own
            return [p for p in kids if "spawn_main" in _cmdline(p) and _descendants(p)]
        self._interrupted("kill-dask-worker", lambda proc: self._kill_one(proc, workers, "Dask worker", 100, 0.1),
                          "--executor", "dask", "--scheduler", "local:2")

    def concurrent(self) -> None:
        out = self.out / "concurrent"
        shutil.rmtree(out, ignore_errors=True)
        procs = [subprocess.Popen(self.run_args(out), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                 for _ in range(2)]
        for p in procs:
            p.wait(timeout=900)
        self.plain_run(out)
        self.check("concurrent", out, "two harness processes on one --out, then a plain re-run")

    def truncated(self) -> None:
        out = self.out / "truncated"
        shutil.rmtree(out, ignore_errors=True)
        # two merges, so that a previous generation exists, as after any real campaign
        half = ",".join(self.problems.split(",")[: max(1, len(self.problems.split(",")) // 2)])
        subprocess.run(_harness("run", "--suite", self.suite, "--problems", half, "--out", str(out), "--quiet",
                                "--no-table", "--jobs", str(self.jobs)), check=True, capture_output=True)
        self.plain_run(out)
        parquet = Store(out, self.suite).parquet
        data = parquet.read_bytes()
        parquet.write_bytes(data[: len(data) // 2])
        broken = subprocess.run(self.run_args(out), capture_output=True, text=True)
        subprocess.run(_harness("repair", "--suite", self.suite, "--out", str(out)), check=True, capture_output=True)
        self.plain_run(out)
        self.check("truncated", out, f"runs.parquet cut to {len(data) // 2} of {len(data)} bytes; run exited "
                   f"{broken.returncode} ({broken.stderr.strip().splitlines()[-1][:80] if broken.stderr else ''}); "
                   "repair; re-run")

    # ------------------------------------------------------------------ verdict
    def check(self, name: str, out: pathlib.Path, what: str, injected: bool = True) -> None:
        clean = Store(self.out / "clean", self.suite).load()
        store = Store(out, self.suite)
        got = store.load()
        pending = len(store._pending_files())
        dup = int(got.duplicated(IDENTITY).sum())
        a = clean.set_index(IDENTITY).sort_index()
        b = got.set_index(IDENTITY).sort_index()
        same_keys = a.index.equals(b.index) and set(clean["run_key"]) == set(got["run_key"])
        same_counts = same_keys and all(a[c].equals(b[c]) for c in COUNTS)
        same_f = same_keys and bool(np.array_equal(a["f"].to_numpy(), b["f"].to_numpy(), equal_nan=True))
        ok = same_keys and same_counts and same_f and dup == 0 and pending == 0
        self.results.append({"scenario": name, "fault": what, "fault injected": injected,
                             "runs": len(got), "clean runs": len(clean),
                             "same keys": same_keys, "same counts": same_counts, "bitwise f": same_f,
                             "duplicates": dup, "pending files": pending, "ok": ok})
        verdict = ("ok" if ok else "DIFFERS") + ("" if injected else " (no fault injected: nothing was tested)")
        print(f"{name}: {verdict} - {what}", flush=True)


def _markdown(df: pd.DataFrame) -> str:
    lines = ["| " + " | ".join(df.columns) + " |", "|" + "---|" * len(df.columns)]
    lines += ["| " + " | ".join(str(v) for v in row) + " |" for row in df.itertuples(index=False)]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m harness.fault_campaign", description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="scratch directory (one sub-directory per scenario)")
    ap.add_argument("--suite", default="hs", help="suite to sample (default: hs)")
    ap.add_argument("--problems", default=DEFAULT_PROBLEMS, help="comma-separated problem ids of the suite")
    ap.add_argument("--jobs", type=int, default=2, help="worker processes of each harness run (default: 2)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the random fault moments")
    ap.add_argument("--scenarios", default=",".join(SCENARIOS),
                    help=f"comma-separated scenarios to run (default: all of {', '.join(SCENARIOS)})")
    ap.add_argument("--no-dask", action="store_true", help="skip the Dask scenario")
    a = ap.parse_args(argv)
    chosen = [x.strip() for x in a.scenarios.split(",") if x.strip()]
    unknown = [x for x in chosen if x not in SCENARIOS]
    if unknown or not chosen:
        ap.error(f"unknown scenario(s) {', '.join(unknown) or '(none given)'}; valid: {', '.join(SCENARIOS)}")
    if a.no_dask and "kill-dask-worker" in chosen:
        chosen.remove("kill-dask-worker")
    c = Campaign(pathlib.Path(a.out), a.suite, a.problems, a.jobs, a.seed)
    t0 = time.perf_counter()
    try:
        runs = c.clean()
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(f"clean run: {len(runs)} runs in {c.clean_time:.1f} s", flush=True)
    # the kills of the harness and of a worker at three random moments each; the others once
    scenarios: dict[str, list[Callable[[], None]]] = {
        "kill-harness": [functools.partial(c.kill_harness, i) for i in range(1, 4)],
        "kill-worker": [functools.partial(c.kill_worker, i) for i in range(1, 4)],
        "sigint": [c.sigint], "concurrent": [c.concurrent], "truncated": [c.truncated],
        "kill-dask-worker": [c.kill_dask_worker],
    }
    assert tuple(scenarios) == SCENARIOS
    for name in SCENARIOS:  # in this order, whatever the order given
        if name in chosen:
            for run in scenarios[name]:
                run()
    table = pd.DataFrame(c.results)
    report = pathlib.Path(a.out) / "fault_campaign.md"
    report.write_text(f"Fault campaign on suite {a.suite}, problems {a.problems} (clean run {len(runs)} runs, "
                      f"{c.clean_time:.1f} s; campaign {time.perf_counter() - t0:.0f} s)\n\n"
                      + _markdown(table) + "\n")
    print(f"\n{report}")
    return 0 if bool(table["ok"].all()) else 1


if __name__ == "__main__":
    sys.exit(main())  # the runs pin their numerical environment themselves (python -m harness)
