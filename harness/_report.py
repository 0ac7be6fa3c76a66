"""``harness report``: one static, offline HTML page of every suite under ``DIR``.

``DIR/report/index.html`` shows, per suite: the tables of its plug-in (ours beside the
thesis's, differing cells marked), a per-solver summary, the stored figures (linked by
relative path, so the directory can be copied or served as is; inlined with ``--embed``,
so the page is one self-contained file) and the environment of the latest run.  Nothing
is re-run: everything comes from the stored results.
"""

from __future__ import annotations

import html
import json
import os
import pathlib
import time
from typing import TextIO

import pandas as pd

from problems._catalog import is_suite_name

from ._api import load_results
from ._plan import HarnessArgumentError
from ._profiles import solver_labels
from ._store import Store

__all__ = ["write_report", "solver_summary"]

CSS = """body{font-family:system-ui,sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;color:#222}
table{border-collapse:collapse;margin:.5em 0;font-size:.85em}
th,td{border:1px solid #ccc;padding:2px 6px;text-align:right}
th{background:#f0f0f0}td.flag{background:#ffe3c2;font-weight:bold}figcaption{font-weight:bold;margin-top:1em}
.notes{font-size:.8em;color:#555}img{max-width:48%;margin:4px;border:1px solid #ddd}nav a{margin-right:1em}
.err{color:#a00}code{font-size:.85em}"""


def suites_under(out: str | os.PathLike[str]) -> list[str]:
    root = pathlib.Path(out)
    if not root.is_dir():
        return []
    # other directories (a user's notes, __pycache__) are not suites: their names are not suite names
    return sorted(d.name for d in root.iterdir()
                  if d.is_dir() and is_suite_name(d.name) and Store(root, d.name).exists())


def solver_summary(runs: pd.DataFrame) -> pd.DataFrame:
    """Per solver: runs, successes, failures, median N^fg of successful runs, total wall time."""
    df = runs.assign(label=solver_labels(runs))
    g = df.groupby("label")
    out = pd.DataFrame({
        "runs": g.size(),
        "solved": g["success"].sum(),
        "error/timeout": g["status"].apply(lambda s: int(s.isin(["error", "timeout"]).sum())),
        "not applicable": g["status"].apply(lambda s: int((s == "not_applicable").sum())),
        "median N^fg (solved)": g.apply(lambda x: x.loc[x["success"], "nfg"].astype(float).median(),
                                        include_groups=False),
        "wall time [s]": g["wall_time_s"].sum().round(2),
    })
    out.index.name = "solver"
    return out


def _frame_html(df: pd.DataFrame) -> str:
    return df.to_html(na_rep="—", float_format=lambda v: f"{v:.6g}", border=0)


def _suite_section(out: pathlib.Path, suite: str, report_dir: pathlib.Path, runs: pd.DataFrame) -> str:
    from .tables._render import NoTablePlugin, build_tables, to_html

    manifest = out / suite / "manifest.json"
    latest = json.loads(manifest.read_text()).get("latest", {}) if manifest.exists() else {}
    ref = None
    if latest.get("suite_file") and pathlib.Path(latest["suite_file"]).exists():
        from ._suites import SuiteRef  # a user's suite file may carry its own tables()

        ref = SuiteRef(suite, latest["suite_file"])
    parts = [f'<h2 id="{html.escape(suite)}">{html.escape(suite)}</h2>',
             f"<p>{len(runs)} stored runs, {int(runs['success'].sum())} successful.</p>"]
    try:
        from ._reference import load_reference

        for t in build_tables(suite, runs, ref, reference=load_reference(out, suite)):
            parts.append(to_html(t))
    except NoTablePlugin as exc:
        parts.append(f"<p>{html.escape(str(exc))}</p>")
    except Exception as exc:  # noqa: BLE001 - a broken plug-in must not hide the other suites
        parts.append(f'<p class="err">table plug-in failed: {html.escape(type(exc).__name__)}: '
                     f"{html.escape(str(exc))}</p>")
    parts += ["<h3>Solvers</h3>", _frame_html(solver_summary(runs))]
    figdir = out / suite / "figures"
    figs = sorted(figdir.glob("*.png")) if figdir.is_dir() else []
    if figs:
        parts.append("<h3>Figures</h3>")
        for f in figs:
            rel = os.path.relpath(f, report_dir)
            parts.append(f'<a href="{html.escape(rel)}"><img src="{html.escape(rel)}" alt="{html.escape(f.stem)}"></a>')
    else:
        parts.append(f"<p>No figures yet: <code>python -m harness plot --suite {html.escape(suite)} "
                     "--kind profile</code>.</p>")
    if latest:
        parts.append(f'<p class="notes">Latest run: {html.escape(str(latest.get("end")))}, git '
                     f'{html.escape(str(latest.get("git_commit")))[:12]}{" (dirty)" if latest.get("git_dirty") else ""}'
                     f', Python {html.escape(str(latest.get("python")))}, '
                     f'{html.escape(str(latest.get("machine", {}).get("platform")))}.</p>')
    return "\n".join(parts)


def _solver_catalogue(names: set[str]) -> str:
    from solvers import get_solver_class

    rows = []
    for n in sorted(names):
        try:
            cls = get_solver_class(n)
            rows.append({"solver": n, "family": cls.family, "summary": cls.summary})
        except Exception as exc:  # noqa: BLE001 - test-only or unavailable solvers
            rows.append({"solver": n, "family": "?", "summary": f"(not loadable: {exc})"})
    return _frame_html(pd.DataFrame(rows).set_index("solver")) if rows else ""


def _inline_images(page: str, report_dir: pathlib.Path) -> str:
    """Replace every ``src``/``href`` pointing at a PNG by a data URI: one self-contained file."""
    import base64
    import re

    cache: dict[str, str] = {}

    def data_uri(m: re.Match[str]) -> str:
        rel = html.unescape(m.group(2))
        if rel not in cache:
            path = (report_dir / rel).resolve()
            try:
                cache[rel] = "data:image/png;base64," + base64.b64encode(path.read_bytes()).decode("ascii")
            except OSError:
                cache[rel] = rel
        return f'{m.group(1)}="{cache[rel]}"'

    page = re.sub(r'<a href="[^"]+\.png">(<img [^>]*>)</a>', r"\1", page)  # no links to inlined figures
    return re.sub(r'(src)="([^"]+\.png)"', data_uri, page)


def write_report(out: str | os.PathLike[str] = "results", embed: bool = False,
                 progress: TextIO | None = None) -> pathlib.Path:
    """Write ``out/report/index.html`` from the stored results; returns its path.

    embed : inline the figures, so the page is one self-contained file (to mail or attach to
        a CI run); otherwise it links to the PNG files under ``out``.
    progress : stream for one line per suite (None: quiet).
    A suite whose store cannot be read gets a section saying why; the others are unaffected.
    """
    out = pathlib.Path(out)
    if not out.is_dir():
        raise HarnessArgumentError(f"results directory {out} does not exist; run a suite first "
                                   f"(python -m harness run --suite hs --out {out})")
    report_dir = out / "report"
    report_dir.mkdir(parents=True, exist_ok=True)
    suites = suites_under(out)
    sections, solver_ids = [], set()
    for i, s in enumerate(suites, 1):
        t0 = time.perf_counter()
        if progress is not None:
            print(f"report: [{i}/{len(suites)}] {s} ...", file=progress, flush=True)
        try:
            runs = load_results(s, out)
        except Exception as exc:  # noqa: BLE001 - a broken store must not hide the other suites
            sections.append(f'<h2 id="{html.escape(s)}">{html.escape(s)}</h2>'
                            f'<p class="err">results not readable: {html.escape(str(exc))}</p>')
            continue
        sections.append(_suite_section(out, s, report_dir, runs))
        solver_ids |= set(runs["solver"])
        if progress is not None:
            print(f"report: [{i}/{len(suites)}] {s}: {len(runs)} runs, {time.perf_counter() - t0:.1f} s",
                  file=progress, flush=True)
    nav = " ".join(f'<a href="#{html.escape(s)}">{html.escape(s)}</a>' for s in suites)
    body = (f"<h1>haybench results</h1><nav>{nav}</nav>"
            + ("<h2>Solvers</h2>" + _solver_catalogue(solver_ids) if solver_ids else "<p>No stored results.</p>")
            + "\n".join(sections))
    page = (f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>haybench results</title>'
            f"<style>{CSS}</style></head><body>{body}</body></html>")
    if embed:
        page = _inline_images(page, report_dir)
    path = report_dir / "index.html"
    path.write_text(page, encoding="utf-8")
    return path
