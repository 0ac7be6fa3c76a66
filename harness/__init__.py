"""The benchmark harness: run suites, store results, render tables, plots and reports.

>>> import harness
>>> summary = harness.run_suite("appendix-a", solvers=["sqsd"], out="results")
>>> runs = harness.load_results("appendix-a")
>>> tables, paths = harness.render_tables("appendix-a")

``harness.check_problem(problem)`` evaluates a problem's callables once at x0 and names any
wrong shape (what ``run --suite-file`` checks before running).  ``harness.pin_blas()``,
called before NumPy is imported, loads the same numerical kernels as
the harness's runs (their counts then match the stored ones; docs/harness.md).

Command line: ``python -m harness --help``.  Names are imported lazily so that worker
processes (which only need `harness._worker`) start without pandas or matplotlib.
"""

from __future__ import annotations

import importlib
from typing import Any

_EXPORTS = {
    "run_suite": "._runner", "plan_suite": "._runner", "prune_suite": "._runner", "RunSummary": "._runner",
    "load_results": "._api", "render_tables": "._api",
    "NoResults": "._api", "HarnessArgumentError": "._plan", "plot": "._plots", "write_report": "._report",
    "compare_dirs": "._compare", "pin_blas": "._blas", "check_problem": "._preflight",
    "ProblemInputError": "._preflight",
}

__all__ = list(_EXPORTS)


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name], __name__), name)
    raise AttributeError(f"module 'harness' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
