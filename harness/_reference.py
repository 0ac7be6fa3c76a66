"""Stored references: expensive analyses that a suite's tables read but never compute.

Some tables set the runs beside what an independent, exact model allows (Table 4.7's
exact E problem, Tables 5.3-5.5's exact-model optima).  Those are optimizations in their
own right (SciPy SLSQP, differential evolution; about 75 s for rpr3), so they are not run
when a table is rendered.  A suite's analysis module (`REFERENCE_MODULES`) defines
``reference(runs, stored) -> dict``; `update_reference` calls it and writes the result to
``<out>/<suite>/reference.json`` with the analysis module's code version.  ``harness run``
updates it after the runs (only what is missing: the polish of a new end, or everything
when the analysis code changed), ``python -m harness reference --suite S`` does it alone,
and ``harness table`` only reads it.  Docs: docs/harness.md, "Stored references".

A module that sets ``PERSISTENT = True`` stores data that outlives changes of its code: the
campaigns' best-known points (`harness._best_known`) are points runs reached, not analyses
to redo, so only ``fresh`` rebuilds them.
"""

from __future__ import annotations

import importlib
import json
import os
import pathlib
from typing import Any

import pandas as pd

from ._codeversion import code_version

__all__ = ["REFERENCE_MODULES", "has_reference", "reference_path", "load_reference", "update_reference"]

#: suite -> module defining ``reference(runs, stored) -> dict``
REFERENCE_MODULES: dict[str, str] = {
    "rpr2": "manipulators.synthesis.rpr2_exact",
    "rpr2-exact": "manipulators.synthesis.rpr2_exact_suite",
    "rpr3": "manipulators.synthesis.rpr3_exact",
    "rpr3-exact": "manipulators.synthesis.rpr3_exact",
    "rpr3-spread": "manipulators.synthesis.rpr3_exact",
    "cutest": "harness._best_known",
    "hs-all": "harness._best_known",
}

FILENAME = "reference.json"


def has_reference(suite: str) -> bool:
    return suite in REFERENCE_MODULES


def reference_path(out: str | os.PathLike[str], suite: str) -> pathlib.Path:
    return pathlib.Path(out) / suite / FILENAME


def load_reference(out: str | os.PathLike[str], suite: str) -> dict[str, Any]:
    """The stored reference of ``suite`` under ``out`` ({} if none or unreadable)."""
    path = reference_path(out, suite)
    try:
        return dict(json.loads(path.read_text()).get("data") or {})
    except (OSError, ValueError, AttributeError):
        return {}


def update_reference(out: str | os.PathLike[str], suite: str, runs: pd.DataFrame | None,
                     fresh: bool = False) -> pathlib.Path | None:
    """Compute what is missing from ``suite``'s stored reference and write it; None if the
    suite has none.  ``fresh`` (or a changed analysis module, unless it is ``PERSISTENT``)
    recomputes everything."""
    if suite not in REFERENCE_MODULES:
        return None
    modname = REFERENCE_MODULES[suite]
    module = importlib.import_module(modname)
    keep = bool(getattr(module, "PERSISTENT", False))
    version = code_version((modname,))
    path = reference_path(out, suite)
    stored: dict[str, Any] = {}
    if not fresh and path.exists():
        try:
            doc = json.loads(path.read_text())
            if keep or doc.get("code_version") == version:
                stored = dict(doc.get("data") or {})
        except (OSError, ValueError):
            stored = {}
    data = module.reference(runs, stored)
    if data == stored and path.exists():
        return path
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(f".{os.getpid()}.tmp")
    tmp.write_text(json.dumps({"suite": suite, "module": modname, "code_version": version, "data": data},
                              indent=1, sort_keys=True) + "\n")
    os.replace(tmp, path)
    return path
