"""Render a suite's tables: find its plug-in, build the tables, write md/csv/LaTeX/HTML.

A suite declares its plug-in: ``Suite(..., tables="harness.tables.rpr2")``, a module
exposing ``tables(runs[, reference]) -> list[Table]`` (see `harness.tables._base`); a user
suite file may define the same ``tables`` function, and without one gets the campaign tables
of `harness.tables._campaign`.  Cells the plug-in flags (``Table.flags``) differ
from the thesis beyond the plug-in's stated tolerance and are marked with ``MARK``.
"""

from __future__ import annotations

import html
import importlib
import inspect
import math
import os
import pathlib
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import pandas as pd

from .._suites import SuiteRef, suite_module
from ._base import Table

__all__ = ["MARK", "MARK_NOTE", "NoTablePlugin", "NoTableRuns", "plugin_for", "build_tables", "to_markdown", "to_csv",
           "to_latex", "to_html", "write_tables", "FORMATS"]

MARK = "⚑"
MARK_NOTE = f"{MARK} marks a cell that differs from the thesis beyond the tolerance stated in the notes."
FORMATS = {"md": "md", "csv": "csv", "latex": "tex"}


class NoTablePlugin(LookupError):
    """The suite has no table plug-in (yet)."""


class NoTableRuns(NoTablePlugin):
    """Runs are stored, but none with the suite's own settings: every one was made with options
    given with the solver id (``sqsd[rho=0.5]``), which the tables leave out."""


def plugin_for(suite: str, ref: SuiteRef | None = None) -> Callable[..., list[Table]]:
    """The ``tables`` function of the suite's plug-in (or of its suite file)."""
    if ref is not None and ref.file:
        fn = getattr(suite_module(ref), "tables", None)
        return fn if callable(fn) else _library_tables(suite)
    from problems import UnknownSuite, get_suite

    try:
        modname = (ref.load() if ref is not None else get_suite(suite)).tables
    except UnknownSuite:
        raise NoTablePlugin(f"suite {suite!r} is not registered: no table plug-in to find") from None
    if not modname:
        raise NoTablePlugin(f"suite {suite!r} declares no table plug-in (Suite(..., tables='module') with "
                            "tables(runs) -> list[Table])")
    module = importlib.import_module(modname)
    fn = getattr(module, "tables", None)
    if not callable(fn):
        raise NoTablePlugin(f"{modname} defines no function tables(runs)")
    return fn


def _library_tables(suite: str) -> Callable[[pd.DataFrame], list[Table]]:
    """The tables of a suite file that defines no ``tables`` of its own: those of the library
    campaigns cutest and hs-all (per-solver summary, every run's N^fg and outcome; a case's
    reference is its ``f_ref`` or else the best feasible f any stored run reached)."""
    from ._campaign import campaign_tables

    def tables(runs: pd.DataFrame) -> list[Table]:
        return campaign_tables(runs, prefix=suite.replace("-", "_"), suite=suite, defaults=False)

    return tables


def build_tables(suite: str, runs: pd.DataFrame, ref: SuiteRef | None = None,
                 reference: Mapping[str, Any] | None = None) -> list[Table]:
    """The plug-in's tables from the runs made with the suite's own settings.

    Runs with command-line options (``sqsd[rho=0.1]``: column ``overrides``) are left out:
    the tables reproduce the thesis's settings, one run per (case, solver).  A plug-in
    ``tables(runs, reference)`` also gets the suite's stored reference (`harness._reference`;
    {} when none is stored): tables never run optimizations themselves.
    """
    plugin = plugin_for(suite, ref)
    if "overrides" in runs.columns:
        mine = runs[runs["overrides"].fillna("") == ""].reset_index(drop=True)
        if mine.empty and not runs.empty:  # a plug-in given no runs draws an empty, malformed table
            from .._profiles import solver_labels

            labels = sorted(set(solver_labels(runs)))
            raise NoTableRuns(
                f"no runs of {suite} with the suite's own settings to tabulate: all {len(runs)} stored runs were "
                f"made with options given with the solver id ({', '.join(labels[:6])}"
                f"{', ...' if len(labels) > 6 else ''}; on the command line or in a suite file's SOLVERS), which "
                "the tables leave out; run the solvers without options for the tables, or see these runs with "
                "python -m harness plot and report")
        runs = mine
    takes_reference = len(inspect.signature(plugin).parameters) >= 2
    tables = list(plugin(runs, dict(reference or {})) if takes_reference else plugin(runs))
    for t in tables:
        if not isinstance(t, Table):
            raise TypeError(f"table plug-in of {suite} returned {type(t).__name__}, expected harness.tables.Table")
    return tables


# --------------------------------------------------------------------- cells
def _cell(v: Any) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)) or v is pd.NA:
        return "—"
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def _grid(table: Table, mark: Callable[[str], str]) -> tuple[list[str], list[list[str]]]:
    """Header and body cells (index included when it carries labels), flagged cells marked."""
    frame = table.frame
    show_index = not isinstance(frame.index, pd.RangeIndex)
    header = ([str(frame.index.name or "")] if show_index else []) + [str(c) for c in frame.columns]
    flags = None
    if table.flags is not None:
        flags = table.flags.reindex(index=frame.index, columns=frame.columns).fillna(False).astype(bool).to_numpy()
    body = []
    for i, (idx, row) in enumerate(frame.iterrows()):
        cells = [_cell(v) for v in row.tolist()]
        if flags is not None:
            cells = [mark(c) if flags[i, j] else c for j, c in enumerate(cells)]
        body.append(([_cell(idx)] if show_index else []) + cells)
    return header, body


def _has_flags(table: Table) -> bool:
    return table.flags is not None and bool(table.flags.fillna(False).astype(bool).to_numpy().any())


def _notes(table: Table) -> list[str]:
    return list(table.notes) + ([MARK_NOTE] if _has_flags(table) else [])


def to_markdown(table: Table) -> str:
    header, body = _grid(table, lambda c: f"{c} {MARK}")
    esc = lambda s: s.replace("|", "\\|")
    lines = [f"**{table.title}**", "", "| " + " | ".join(map(esc, header)) + " |",
             "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(map(esc, r)) + " |" for r in body]
    notes = _notes(table)
    if notes:
        lines += [""] + [f"- {n}" for n in notes]
    return "\n".join(lines) + "\n"


def to_csv(table: Table) -> str:
    header, body = _grid(table, lambda c: f"{c} {MARK}")
    return pd.DataFrame(body, columns=header).to_csv(index=False)


_TEX = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
        "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}", "—": "--"}


def _tex(s: str) -> str:
    return "".join(_TEX.get(ch, ch) for ch in s)


def to_latex(table: Table) -> str:
    header, body = _grid(table, lambda c: "\x00" + c)
    cell = lambda c: (r"\textbf{" + _tex(c[1:]) + r"}$^\dagger$") if c.startswith("\x00") else _tex(c)
    lines = [r"\begin{table}[htbp]", r"\centering", r"\caption{" + _tex(table.title) + "}",
             r"\begin{tabular}{" + "l" * len(header) + "}", r"\toprule",
             " & ".join(_tex(h) for h in header) + r" \\", r"\midrule"]
    lines += [" & ".join(cell(c) for c in r) + r" \\" for r in body]
    lines += [r"\bottomrule", r"\end{tabular}"]
    notes = list(table.notes) + ([r"$^\dagger$ differs from the thesis beyond the stated tolerance."]
                                 if _has_flags(table) else [])
    for n in notes:
        lines.append(r"\par\footnotesize " + (n if n.startswith("$^") else _tex(n)))
    lines.append(r"\end{table}")
    return "\n".join(lines) + "\n"


def to_html(table: Table) -> str:
    header, body = _grid(table, lambda c: "\x00" + c)
    td = lambda c: (f'<td class="flag">{html.escape(c[1:])} {MARK}</td>' if c.startswith("\x00")
                    else f"<td>{html.escape(c)}</td>")
    rows = "\n".join("<tr>" + "".join(td(c) for c in r) + "</tr>" for r in body)
    head = "<tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in header) + "</tr>"
    notes = "".join(f"<li>{html.escape(n)}</li>" for n in _notes(table))
    return (f'<figure class="table"><figcaption>{html.escape(table.title)}</figcaption>'
            f"<table><thead>{head}</thead><tbody>{rows}</tbody></table>"
            + (f'<ul class="notes">{notes}</ul>' if notes else "") + "</figure>")


RENDERERS = {"md": to_markdown, "csv": to_csv, "latex": to_latex}


def write_tables(tables: Sequence[Table], outdir: str | os.PathLike[str],
                 formats: Sequence[str] = ("md", "csv", "latex")) -> list[pathlib.Path]:
    """Write every table in every format to ``outdir/<table.name>.<ext>``."""
    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    paths = []
    for t in tables:
        for fmt in formats:
            p = outdir / f"{t.name}.{FORMATS[fmt]}"
            p.write_text(RENDERERS[fmt](t), encoding="utf-8")
            paths.append(p)
    return paths
