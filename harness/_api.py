"""The Python API behind the CLI: load stored results, render tables."""

from __future__ import annotations

import os
import pathlib
from collections.abc import Sequence

import pandas as pd

from ._plan import HarnessArgumentError
from ._store import Store
from ._suites import SuiteRef

__all__ = ["load_results", "render_tables", "NoResults"]


class NoResults(FileNotFoundError):
    """Nothing stored yet for a suite."""


def _suite_name(suite: str | SuiteRef) -> str:
    return suite.name if isinstance(suite, SuiteRef) else suite


def load_results(suite: str | SuiteRef, out: str | os.PathLike[str] = "results") -> pd.DataFrame:
    """The stored runs of ``suite`` under ``out`` as a DataFrame (one row per run).

    Columns: `harness._record.ROW_COLUMNS` plus overrides (the command-line options of the
    run, canonical JSON, "" for none), run_key, code_version, finished_at and timeout_s (the
    wall-clock limit the run ran under; 0 = none). Counts are nullable integers (unknown for
    runs that timed out).
    """
    name = _suite_name(suite)
    store = Store(out, name)
    if not store.exists():
        from problems import suite_names

        where = pathlib.Path(out).resolve()
        if name not in suite_names():
            stored = sorted(p.parent.name for p in where.glob("*/runs.parquet"))
            raise NoResults(f"no results for suite {name!r} under {where}: it is not a built-in suite (built-in: "
                            f"{', '.join(suite_names())}) and nothing is stored under that name there (stored: "
                            f"{', '.join(stored) or 'none'})")
        raise NoResults(f"no results for suite {name!r} under {where}; "
                        f"run `python -m harness run --suite {name} --out {out}` first")
    return store.load()


def render_tables(suite: str | SuiteRef, out: str | os.PathLike[str] = "results",
                  formats: Sequence[str] = ("md", "csv", "latex")) -> tuple[list, list[pathlib.Path]]:
    """Build the suite's tables from stored runs and write them to ``out/<suite>/``.

    Returns (tables, written paths). Raises `harness.tables.NoTablePlugin` when the suite
    has no plug-in, `NoResults` when nothing is stored.
    """
    from .tables._render import FORMATS, build_tables, write_tables

    bad = [f for f in formats if f not in FORMATS]
    if bad:
        raise HarnessArgumentError(f"unknown format(s) {', '.join(bad)}; valid formats: {', '.join(FORMATS)}")
    name = _suite_name(suite)
    ref = suite if isinstance(suite, SuiteRef) else None
    from ._reference import load_reference

    runs = load_results(name, out)
    tables = build_tables(name, runs, ref, reference=load_reference(out, name))
    return tables, write_tables(tables, pathlib.Path(out) / name, formats)
