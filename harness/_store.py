"""The results store of one suite: ``DIR/<suite>/runs.parquet`` plus pending run files.

Durability (docs/harness.md, "Results store and resume"): every finished run is written at once to its own file
``DIR/<suite>/runs/<time>-<run_key>.json`` through a temporary file and `os.replace`
(atomic on POSIX and Windows), so a killed process (SIGINT or SIGKILL) leaves either the
whole file or none.  `consolidate` merges the pending files into ``runs.parquet`` — again
via a temporary file and `os.replace` — and only then deletes them; if it is killed in
between, the next load sees the rows twice and keeps one.  Rows are unique on
(case_id, solver, overrides): a newer run of the same case and solver with the same
command-line options (``--fresh``, new code, new solver defaults) replaces the older one.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import pathlib
import re
import signal
import subprocess
import tempfile
import time
from collections.abc import Iterator
from typing import Any

import pandas as pd

from problems._catalog import check_suite_name

from ._record import ROW_COLUMNS
from ._worker import COUNT_COLUMNS, EXTRA_COLUMNS

__all__ = ["Store", "COLUMNS", "IDENTITY", "normalize", "failure_kind", "retry_keys", "CorruptStore"]


class CorruptStore(RuntimeError):
    """``runs.parquet`` cannot be read (truncated, overwritten): CLI exit status 3, with the
    command that restores the previous generation."""

    def __init__(self, path: pathlib.Path, suite: str, out: pathlib.Path, cause: BaseException):
        self.path, self.suite = path, suite
        hint = f"python -m harness repair --suite {suite}" + ("" if str(out) == "results" else f" --out {out}")
        super().__init__(f"{path} is unreadable ({type(cause).__name__}: {str(cause).splitlines()[0][:120]}); "
                         f"restore the previous generation with: {hint}")

#: written by the runner beside the worker's row: the run's wall-clock limit (s; 0 = none).
#: Store metadata, not part of a run's numbers, so not part of its code version.
STORE_COLUMNS = ["timeout_s"]
COLUMNS = ROW_COLUMNS + EXTRA_COLUMNS + STORE_COLUMNS
IDENTITY = ["case_id", "solver", "overrides"]
FLOAT_COLUMNS = ["f", "f_ref", "rel_error", "inf_error", "max_violation", "wall_time_s", "time_in_evals_s",
                 "timeout_s"]
#: messages of runs that failed for reasons outside the solver: the worker was killed from outside
#: (e.g. SIGKILL from the kernel's OOM killer) or died while starting, was lost with its Dask
#: worker, or the run ran out of memory (MemoryError)
INFRASTRUCTURE = re.compile(r"^(worker process died while starting|dask task failed|MemoryError\b)")
_DIED = re.compile(r"^worker process died \(exit code (-?\d+|None)\)")
#: signals a run's own code raises (segmentation fault, abort, bus error, floating-point trap,
#: illegal instruction): deterministic, so a result of the solver or problem, not retried
_CRASH_SIGNALS = {int(getattr(signal, n)) for n in ("SIGSEGV", "SIGABRT", "SIGBUS", "SIGFPE", "SIGILL")
                  if hasattr(signal, n)}


def failure_kind(status: str, message: str) -> str:
    """"" for a run that produced a result, else "timeout", "infrastructure" or "solver".

    Solver errors (an exception in the solver or the problem) are results and stay stored;
    infrastructure failures say nothing about the solver and are re-run (docs/harness.md).
    """
    if status == "timeout":
        return "timeout"
    if status != "error":
        return ""
    message = str(message)
    if INFRASTRUCTURE.match(message):
        return "infrastructure"
    died = _DIED.match(message)
    if died:  # killed by a signal from outside: infrastructure; exited or crashed by itself: the run's own
        code = died.group(1)
        return "infrastructure" if code == "None" or (int(code) < 0 and -int(code) not in _CRASH_SIGNALS) else "solver"
    return "solver"


def _stored_limit(row: pd.Series) -> float:
    """The wall-clock limit a stored time-out ran under (older rows: read from the message)."""
    v = row.get("timeout_s")
    if v is not None and v == v:
        return float(v)
    m = re.search(r"limit of ([0-9.eE+-]+) s", str(row.get("message", "")))
    return float(m.group(1)) if m else 0.0


def retry_keys(runs: pd.DataFrame, timeout: float, retry_failed: bool = False) -> set[str]:
    """Run keys of stored failures to run again under the retry policy (docs/harness.md):

    * infrastructure failures (worker killed, Dask worker lost, out of memory): always;
    * time-outs: when the new limit is larger than the stored one (0 = no limit);
    * every error and time-out row with ``retry_failed``.
    Solver errors otherwise stay stored as results.
    """
    keys: set[str] = set()
    new_limit = math.inf if timeout <= 0 else timeout
    for _, r in runs[runs["status"].isin(["error", "timeout"])].iterrows():
        kind = failure_kind(str(r["status"]), str(r["message"]))
        old = _stored_limit(r)
        if retry_failed or kind == "infrastructure" or (
                kind == "timeout" and new_limit > (math.inf if old <= 0 else old)):
            keys.add(str(r["run_key"]))
    return keys


def normalize(df: pd.DataFrame) -> pd.DataFrame:
    """Fixed column order and dtypes (counts nullable: unknown for time-outs)."""
    for c in COLUMNS:
        if c not in df.columns:
            df[c] = None
    df = df[COLUMNS + [c for c in df.columns if c not in COLUMNS]].copy()
    for c in COUNT_COLUMNS + ["n"]:
        df[c] = pd.to_numeric(df[c], errors="coerce").astype("Int64")
    for c in FLOAT_COLUMNS:
        df[c] = pd.to_numeric(df[c], errors="coerce").astype("float64")
    df["success"] = df["success"].fillna(False).astype(bool)
    for c in ("suite", "problem", "start", "variant", "case_id", "solver", "settings", "settings_hash",
              "status", "message", "history", "extra", "overrides", "run_key", "code_version", "finished_at"):
        df[c] = df[c].astype(object).where(df[c].notna(), "").astype(str)
    df["x"] = [list(v) if v is not None and not isinstance(v, float) else [] for v in df["x"]]
    return df.reset_index(drop=True)


@contextlib.contextmanager
def _locked(path: pathlib.Path) -> Iterator[None]:
    """Exclusive lock so two harness processes never consolidate at once (POSIX)."""
    try:
        import fcntl
    except ImportError:  # Windows: single writer assumed
        yield
        return
    with open(path, "a+") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


_MODE = 0o666 & ~_umask()  # mkstemp creates 0600 files; results are meant to be shared


def _atomic_write_bytes(path: pathlib.Path, data: bytes) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.chmod(tmp, _MODE)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


class Store:
    """Read and write the runs of one suite under ``out``."""

    def __init__(self, out: str | os.PathLike[str], suite: str):
        check_suite_name(suite, "the store's suite")  # the store is a directory under out: never outside it
        self.out = pathlib.Path(out)
        self.root = self.out / suite
        self.parquet = self.root / "runs.parquet"
        self.previous = self.root / "runs.prev.parquet"  # the generation before the last merge
        self.pending_dir = self.root / "runs"
        self.suite = suite

    def _read(self, columns: list[str] | None = None, path: pathlib.Path | None = None) -> pd.DataFrame:
        path = path or self.parquet
        try:
            return pd.read_parquet(path, columns=columns)
        except FileNotFoundError:
            raise
        except Exception as exc:  # noqa: BLE001 - pyarrow raises several types for a damaged file
            raise CorruptStore(path, self.suite, self.out, exc) from None

    # ------------------------------------------------------------------ writing
    def write_run(self, row: dict[str, Any]) -> pathlib.Path:
        """Persist one finished run at once, atomically."""
        self.pending_dir.mkdir(parents=True, exist_ok=True)
        path = self.pending_dir / f"{time.time_ns()}-{row['run_key']}.json"
        _atomic_write_bytes(path, json.dumps(row, separators=(",", ":")).encode())
        return path

    def _pending_files(self) -> list[pathlib.Path]:
        if not self.pending_dir.is_dir():
            return []
        return sorted(p for p in self.pending_dir.glob("*.json") if not p.name.startswith("."))

    def _read_pending(self, files: list[pathlib.Path]) -> list[dict[str, Any]]:
        rows = []
        for p in files:
            try:
                rows.append(json.loads(p.read_text()))
            except (OSError, ValueError):  # vanished (consolidated meanwhile): it is in the parquet
                continue
        return rows

    def consolidate(self) -> int:
        """Merge pending run files into runs.parquet atomically; returns the row count."""
        self.root.mkdir(parents=True, exist_ok=True)
        with _locked(self.root / ".lock"):
            files = self._pending_files()
            if not files and self.parquet.exists():
                return len(self._read(["run_key"]))
            df = self._merged(files)
            self._replace(df, files)
            return len(df)

    def _replace(self, df: pd.DataFrame, files: list[pathlib.Path]) -> None:
        """Write ``df`` as runs.parquet atomically, keeping the replaced generation, and delete
        the merged pending files (the caller holds the lock)."""
        buf = df.to_parquet(index=False, compression="zstd")
        if self.parquet.exists():  # keep the generation being replaced (a hard link: no copy)
            tmp = self.root / f".{self.previous.name}.tmp"
            with contextlib.suppress(OSError):
                tmp.unlink()
            try:
                os.link(self.parquet, tmp)
            except OSError:  # no hard links here (some network file systems): copy
                _atomic_write_bytes(tmp, self.parquet.read_bytes())
            os.replace(tmp, self.previous)
        _atomic_write_bytes(self.parquet, buf)
        for p in files:
            with contextlib.suppress(OSError):
                p.unlink()

    def keep_only(self, keys: set[str], dry_run: bool = False) -> dict[str, int]:
        """Keep the rows whose run key is in ``keys`` (pending run files merged); rows removed
        per solver (``dry_run``: that would be removed; nothing is written).  Atomic like
        `consolidate`, which keeps the replaced generation."""
        with _locked(self.root / ".lock"):
            files = self._pending_files()
            df = self._merged(files)
            drop = ~df["run_key"].astype(str).isin(keys)
            removed = {str(k): int(v) for k, v in df.loc[drop, "solver"].value_counts().items()}
            if dry_run or (not drop.any() and not files):
                return removed
            self._replace(df[~drop], files)
            return removed

    # ------------------------------------------------------------------ reading
    def _merged(self, files: list[pathlib.Path]) -> pd.DataFrame:
        parts = []
        if self.parquet.exists():
            parts.append(self._read())
        rows = self._read_pending(files)
        if rows:
            parts.append(pd.DataFrame(rows))
        if not parts:
            return normalize(pd.DataFrame(columns=COLUMNS))
        df = normalize(pd.concat([normalize(p) for p in parts], ignore_index=True))
        df = df.sort_values("finished_at", kind="stable").drop_duplicates(IDENTITY, keep="last")
        return df.reset_index(drop=True)

    def exists(self) -> bool:
        return self.parquet.exists() or bool(self._pending_files())

    def load(self) -> pd.DataFrame:
        """All stored runs (runs.parquet merged with runs not yet consolidated)."""
        return self._merged(self._pending_files())

    def stored_keys(self) -> set[str]:
        """Run keys already stored (for resume): from the parquet and the file names."""
        keys: set[str] = set()
        if self.parquet.exists():
            keys |= set(self._read(["run_key"])["run_key"])
        keys |= {p.stem.split("-", 1)[1] for p in self._pending_files() if "-" in p.stem}
        return keys

    # ------------------------------------------------------------------ repair
    def repair(self) -> str:
        """Make ``runs.parquet`` readable again; returns what was done.

        A readable store is left alone.  An unreadable one is moved aside (``.corrupt``) and
        replaced by the previous generation merged with the pending run files, so at most
        the runs of the last merge are lost; a re-run of the suite redoes them.
        """
        if not self.parquet.exists() and not self.previous.exists():
            return f"{self.root}: nothing stored"
        if self.parquet.exists():
            try:
                n = len(self._read(["run_key"]))
                return f"{self.parquet}: readable, {n} runs; nothing to repair"
            except CorruptStore:
                pass
        with _locked(self.root / ".lock"):
            kept = 0
            if self.previous.exists():
                prev = self._read(path=self.previous)  # raises CorruptStore if both are damaged
                kept = len(prev)
            aside = self.root / "runs.parquet"
            if self.parquet.exists():
                aside = self.root / f"runs.parquet.corrupt-{time.strftime('%Y%m%dT%H%M%S')}"
                os.replace(self.parquet, aside)
            if self.previous.exists():
                _atomic_write_bytes(self.parquet, self.previous.read_bytes())
        had_previous = self.parquet.exists()  # the previous generation was copied into place
        n = self.consolidate() if self.parquet.exists() or self._pending_files() else 0
        if had_previous:
            return (f"{self.parquet}: restored the previous generation ({kept} runs) and merged pending runs: "
                    f"{n} runs stored; re-run the suite to redo the runs of the lost merge")
        # e.g. a fresh clone: runs.prev.parquet is a local copy, never committed
        hint = (f"; the committed store is intact in git: git checkout -- {self.parquet}"
                if _tracked_by_git(self.parquet) else "; re-run the suite to redo its runs")
        return (f"{self.parquet}: no previous generation kept, damaged file moved aside ({aside.name}); "
                f"{n} pending runs stored{hint}")


def _tracked_by_git(path: pathlib.Path) -> bool:
    """True if ``path`` is committed in a git work tree (so ``git checkout`` can restore it)."""
    try:
        done = subprocess.run(["git", "ls-files", "--error-unmatch", path.name], cwd=path.parent,
                              capture_output=True, timeout=10, check=False)
    except (OSError, subprocess.SubprocessError):
        return False
    return done.returncode == 0
