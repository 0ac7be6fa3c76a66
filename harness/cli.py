"""Command line: ``python -m harness run|table|list|plot|report|repair|prune|compare|export|reference|baseline``.

A thin layer over the Python API (`harness.run_suite`, `harness.load_results`,
`harness.render_tables`, ...).  Exit status (docs/harness.md): 0 the harness worked
(whatever the solvers did), 1 ``compare`` found regressions, 2 bad input (unknown names
list the valid ones; nothing stored where asked), 3 harness failure (an unreadable store,
a broken plug-in, an unwritable output directory), 130 interrupted.  Errors are one line;
``HAYBENCH_TRACEBACK=1`` prints the traceback of a harness failure too.
"""


from __future__ import annotations

import argparse
import difflib
import os
import pathlib
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from ._plan import HarnessArgumentError, name_list

if TYPE_CHECKING:
    from ._suites import SuiteRef

__all__ = ["main"]
EXIT_OK, EXIT_REGRESSIONS, EXIT_BAD_INPUT, EXIT_HARNESS_FAILURE, EXIT_INTERRUPTED = 0, 1, 2, 3, 130


def _csv(s: str | None, what: str) -> list[str] | None:
    """A comma-separated option (brackets kept together); an empty one is refused, not "all"."""
    return None if s is None else name_list(s, what)


class _Parser(argparse.ArgumentParser):
    """Bad command lines end like every other bad input (docs/harness.md, "Exit status"): one line
    ``error: ...`` naming the command and where its help is, exit 2."""

    def error(self, message: str) -> None:  # type: ignore[override]  # never returns
        self.exit(EXIT_BAD_INPUT, f"error: {self.prog}: {message}; see `{self.prog} --help`\n")

    def unrecognized(self, extra: list[str]) -> None:
        """Refuse arguments the command does not take, suggesting the option probably meant."""
        known = [o for a in self._actions for o in a.option_strings]
        hints = [m[0] for x in extra if x.startswith("-")
                 for m in [difflib.get_close_matches(x.split("=")[0], known, n=1)] if m]
        self.error(f"unrecognized arguments: {' '.join(extra)}" + (f" (did you mean {', '.join(hints)}?)"
                                                                   if hints else ""))


def _typed(convert: type, needs: str) -> Any:
    """An argparse ``type=``: ``convert(s)``, or a one-line error saying what the option ``needs``."""
    def parse(s: str) -> Any:
        try:
            return convert(s)
        except ValueError:
            raise argparse.ArgumentTypeError(f"needs {needs}, got {s!r}") from None
    return parse


_seconds = _typed(float, "a number of seconds (0 or inf: no limit)")
_whole_number = _typed(int, "a whole number")
_number = _typed(float, "a number")


def _suite_name(s: str) -> str:
    """A ``--suite`` argument: a suite name is a directory of results, so '../hs' is bad input, not a path."""
    from problems._catalog import is_suite_name

    if not is_suite_name(s):
        raise argparse.ArgumentTypeError(f"suite name {s!r} must be kebab-case (lower-case letters, digits, '-'); "
                                         "see `python -m harness list suites`")
    return s


def _path_arg(s: str) -> str:
    """A directory or file argument: an empty one would silently mean the current directory."""
    if not s.strip():
        raise argparse.ArgumentTypeError("needs a path, got an empty string")
    return s


def _writable_target(path: str, what: str) -> None:
    """Refuse, as bad input, a target whose parent is missing or is a file (before any work)."""
    p = pathlib.Path(path)
    parent = p.parent if p.suffix else p
    for q in [parent, *parent.parents]:
        if q.exists():
            if not q.is_dir():
                raise HarnessArgumentError(f"{what} {path}: {q} is a file, not a directory")
            break
    if p.suffix and not p.parent.is_dir():
        raise HarnessArgumentError(f"{what} {path}: directory {p.parent} does not exist")


OUT_HELP = "results directory, holding <suite>/runs.parquet (default: results)"


def _timeout_defaults() -> str:
    """The per-suite defaults of ``--timeout`` as text, from `_runner.SUITE_TIMEOUTS` and `DEFAULT_TIMEOUT`:
    "10 for cutest and hs-all, 1800 for spatial, rpr3 and rpr3-spread, 600 otherwise"."""
    from ._runner import DEFAULT_TIMEOUT, SUITE_TIMEOUTS

    by_value: dict[float, list[str]] = {}
    for suite, limit in SUITE_TIMEOUTS.items():
        by_value.setdefault(limit, []).append(suite)
    parts = [f"{limit:g} for " + (", ".join(names[:-1]) + " and " + names[-1] if len(names) > 1 else names[0])
             for limit, names in by_value.items()]
    return ", ".join([*parts, f"{DEFAULT_TIMEOUT:g} otherwise and for --suite-file"])


def _directory_target(path: str, what: str) -> None:
    """Refuse, as bad input, a directory target that is, or lies under, a file (creates nothing)."""
    p = pathlib.Path(path)
    for q in [p, *p.parents]:
        if q.exists():
            if not q.is_dir():
                raise HarnessArgumentError(f"{what} {path}: {q} is a file, not a directory")
            return


def _stored_suite_file_runs(ref: SuiteRef, a: argparse.Namespace) -> None:
    """Before reading the runs of a ``--suite-file``: none stored is bad input naming the command that
    stores them (`load_results`'s message is about names, listing the built-in suites)."""
    from ._store import Store

    if a.suite_file and not Store(a.out, ref.name).exists():
        raise HarnessArgumentError(f"no results of suite file {a.suite_file} (suite {ref.name!r}) under {a.out}; "
                                   f"run `python -m harness run --suite-file {a.suite_file} --out {a.out}` first")


def _suite_args(p: argparse.ArgumentParser, required: bool = True) -> None:
    g = p.add_mutually_exclusive_group(required=required)
    g.add_argument("--suite", metavar="NAME", help="suite name (see `list suites`)")
    g.add_argument("--suite-file", metavar="FILE.py",
                   help="a Python file defining SUITE or PROBLEMS (your own problems)")


def _parser() -> _Parser:
    from ._reference import REFERENCE_MODULES

    ap = _Parser(
        prog="python -m harness",
        description="Run benchmark suites, store one row per run, and render tables, figures, a report and "
                    "comparisons from the stored runs (docs/harness.md).",
        epilog="Exit status: 0 harness worked (whatever the solvers did), 1 compare found regressions, "
               "2 bad input, 3 harness failure, 130 interrupted.")
    sub = ap.add_subparsers(dest="command", required=True, metavar="COMMAND")

    r = sub.add_parser("run", help="run a suite and store one row per run")
    _suite_args(r)
    r.add_argument("--solvers", metavar="IDS", help="comma-separated solver ids, options as id[k=v] "
                                                    "(default: the suite's; see `list solvers`)")
    r.add_argument("--problems", metavar="IDS", help="comma-separated problem ids or case ids (default: all; "
                                                     "see `list problems`)")
    r.add_argument("--select", metavar="EXPR",
                   help="pick problems by their properties, e.g. \"type=u,n<=100\" (suites cutest, hs-all; "
                        "docs/cutest.md)")
    r.add_argument("--out", default="results", type=_path_arg, metavar="DIR", help=OUT_HELP)
    r.add_argument("--jobs", type=_whole_number, default=None, metavar="N",
                   help="worker processes, local executor (default: all cores)")
    r.add_argument("--timeout", type=_seconds, default=None, metavar="SEC",
                   help=f"per-run wall-clock limit, s (default {_timeout_defaults()}; 0 or inf: none). Stored "
                        "time-outs with a smaller limit are run again")
    r.add_argument("--history-points", type=_whole_number, default=None, metavar="N",
                   help="store histories longer than N evaluations thinned to about N (campaigns; "
                        "docs/harness.md, \"Histories\"); default: every evaluation")
    r.add_argument("--fresh", action="store_true", help="re-run runs already stored under the same key")
    r.add_argument("--dry-run", action="store_true",
                   help="plan only: per solver, the runs done and to run (and how many replace a stored "
                        "row), with a run-time estimate")
    r.add_argument("--retry-failed", action="store_true",
                   help="re-run every stored error and time-out row (failures of the infrastructure - a killed "
                        "worker, a lost Dask worker, out of memory - are re-run without it)")
    r.add_argument("--executor", choices=["local", "dask"], default="local",
                   help="local worker processes (default) or a Dask cluster (needs --scheduler)")
    r.add_argument("--scheduler", metavar="ADDR",
                   help="Dask scheduler address for --executor dask (tcp://host:8786, or local:N for a throw-away "
                        "LocalCluster of N workers)")
    r.add_argument("--solver-module", action="append", default=[], dest="modules", metavar="M",
                   help="module name or .py file to import first (e.g. one that registers solvers); repeatable")
    r.add_argument("--quiet", action="store_true", help="no progress display")
    r.add_argument("--no-table", action="store_true",
                   help="do not regenerate the suite's tables after the run")
    t = sub.add_parser("table", help="render a suite's tables from stored results")
    _suite_args(t)
    t.add_argument("--format", choices=["md", "csv", "latex"], default="md", help="format printed (all are written)")
    t.add_argument("--out", default="results", type=_path_arg, metavar="DIR", help=OUT_HELP)

    ls = sub.add_parser("list", help="list solvers, suites or a suite's problems")
    ls.add_argument("what", choices=["solvers", "suites", "problems"],
                    help="solvers: every solver and its options; suites: every suite, its cases and solvers; "
                         "problems: the cases of --suite or --suite-file")
    _suite_args(ls, required=False)
    ls.add_argument("--brief", action="store_true", help="with `list solvers`: without their options")
    ls.add_argument("--select", metavar="EXPR",
                    help="with `list problems`: only the problems a selection picks (docs/cutest.md)")
    ls.add_argument("--solver-module", action="append", default=[], dest="modules", metavar="M",
                    help="module name or .py file to import first (e.g. one that registers solvers); repeatable")

    pl = sub.add_parser("plot", help="figures from stored results (PNG and SVG)")
    _suite_args(pl)
    pl.add_argument("--kind", required=True, choices=["profile", "data-profile", "history", "thesis", "log-ratio"],
                    help="performance profiles, data profiles, convergence histories, the suite's thesis "
                         "figures, or log-ratio profiles of thesis vs established solvers")
    pl.add_argument("--problem", metavar="ID", help="with --kind history: one problem id or case id (default: "
                                                    "every case)")
    pl.add_argument("--out", default="results", type=_path_arg, metavar="DIR",
                    help=OUT_HELP + "; figures go to DIR/<suite>/figures/")
    pl.add_argument("--quiet", action="store_true", help="no progress lines")

    rp = sub.add_parser("report", help="static HTML report of every suite under --out")
    rp.add_argument("--out", default="results", type=_path_arg, metavar="DIR",
                    help=OUT_HELP + "; the report goes to DIR/report/index.html")
    rp.add_argument("--embed", action="store_true",
                    help="inline the figures: one self-contained HTML file (to mail or attach to a CI run)")
    rp.add_argument("--quiet", action="store_true", help="no progress lines")

    rr = sub.add_parser("repair", help="make a suite's unreadable runs.parquet readable again "
                                        "(restores the previous generation, merges pending runs)")
    rr.add_argument("--suite", required=True, metavar="NAME", type=_suite_name, help="the suite whose store to repair")
    rr.add_argument("--out", default="results", type=_path_arg, metavar="DIR", help=OUT_HELP)

    pr = sub.add_parser("prune", help="remove stored rows a run would not produce now (older code or "
                                      "settings, cases or solvers outside the selection)")
    _suite_args(pr)
    pr.add_argument("--dry-run", action="store_true", help="list what would be removed; change nothing")
    pr.add_argument("--select", metavar="EXPR", help="the selection the store should hold (suites cutest, hs-all)")
    pr.add_argument("--solvers", metavar="IDS", help="comma-separated solver ids to keep (default: the suite's)")
    pr.add_argument("--out", default="results", type=_path_arg, metavar="DIR", help=OUT_HELP)

    cp = sub.add_parser("compare", help="per-run changes between two result directories")
    cp.add_argument("old", help="the earlier results directory (holding <suite>/runs.parquet, e.g. results)")
    cp.add_argument("new", help="the later results directory")
    cp.add_argument("--suite", metavar="NAME", type=_suite_name, help="only this suite (default: every suite in both)")
    cp.add_argument("--nfg-tol", type=_number, default=0.10, metavar="TOL",
                    help="relative N^fg increase that is a regression (default: 0.10, i.e. 10%%)")
    cp.add_argument("--rel-error-factor", type=_number, default=None, metavar="F",
                    help="E^r growing by more than this factor (above 1e-12) is a regression (default: off)")
    cp.add_argument("--all", action="store_true", help="list unchanged runs too")

    ex = sub.add_parser("export", help="write a suite's runs for OptiProfiler: an HDF5 archive, or an experiment "
                        "directory its benchmark(load=...) draws profiles from (docs/cutest.md)")
    ex.add_argument("--suite", required=True, metavar="NAME", type=_suite_name,
                    help="the suite whose stored runs to export")
    ex.add_argument("--out", default="results", type=_path_arg, metavar="DIR", help=OUT_HELP)
    ex.add_argument("--to", required=True, type=_path_arg, metavar="PATH",
                    help="a path ending in .h5: the archive alone; otherwise a directory "
                    "in OptiProfiler's experiment layout")

    rf = sub.add_parser("reference", help="compute and store what a suite's tables read from exact models "
                        "(rpr2, rpr3) or its best-known points (cutest, hs-all; docs/harness.md)")
    rf.add_argument("--suite", required=True, metavar="NAME", type=_suite_name,
                    help=f"a suite with a stored reference: {', '.join(REFERENCE_MODULES)}")
    rf.add_argument("--out", default="results", type=_path_arg, metavar="DIR", help=OUT_HELP)
    rf.add_argument("--fresh", action="store_true", help="recompute every entry, not only the missing ones "
                    "(best-known points: rebuild from the stored runs alone)")
    rf.add_argument("--verify", action="store_true", help="cutest, hs-all: re-evaluate every stored best-known "
                    "point through the problem's own functions; exit 1 if any f or feasibility disagrees")

    b = sub.add_parser("baseline", help="save the deterministic counts of stored runs as a baseline")
    b.add_argument("--suite", required=True, metavar="NAME", type=_suite_name,
                   help="the suite whose stored runs to save")
    b.add_argument("--out", default="results", type=_path_arg, metavar="DIR", help=OUT_HELP)
    b.add_argument("--to", default=os.path.join("results", "baseline"), type=_path_arg, metavar="DIR",
                   help="baseline directory: writes DIR/<suite>/counts.csv (default: results/baseline)")
    b.add_argument("--solvers", default=None, metavar="IDS",
                   help="comma-separated: replace only these solvers' rows, keep the baseline's others")
    return ap


def _cmd_run(a: argparse.Namespace) -> int:
    from ._runner import check_run_options, plan_suite, run_suite

    solvers, problems = _csv(a.solvers, "--solvers"), _csv(a.problems, "--problems")
    if a.dry_run:  # refuse what the run would refuse, before planning (and write nothing)
        check_run_options(jobs=a.jobs, history_points=a.history_points, executor=a.executor, scheduler=a.scheduler)
        _directory_target(a.out, "--out")
        plan = plan_suite(a.suite, suite_file=a.suite_file, solvers=solvers, problems=problems, select=a.select,
                          out=a.out, timeout=a.timeout, fresh=a.fresh,
                          retry_failed=a.retry_failed, modules=a.modules)
        print(plan.to_string(index=False))
        print("\nestimated run time: stored wall times of the same runs where there are any, else the solver's "
              "mean (NaN: none stored); divide the sum by the workers (--jobs) for the wall time. Nothing was run.")
        if plan.attrs.get("note"):
            print(plan.attrs["note"])
        return 0
    summary = run_suite(a.suite, suite_file=a.suite_file, solvers=solvers, problems=problems, select=a.select,
                        out=a.out, jobs=a.jobs, timeout=a.timeout, history_points=a.history_points, fresh=a.fresh,
                        retry_failed=a.retry_failed,
                        executor=a.executor,
                        scheduler=a.scheduler, modules=a.modules, progress=None if a.quiet else sys.stderr,
                        argv=sys.argv)
    print(summary)
    if not a.no_table:
        _tables_after_run(a)
    return 0


def _tables_after_run(a: argparse.Namespace) -> None:
    """Regenerate the suite's tables from the store, so one command gives the thesis tables."""
    from ._api import render_tables
    from ._reference import has_reference, update_reference
    from ._runner import resolve_suite
    from .tables._render import RENDERERS, NoTablePlugin, NoTableRuns

    if a.suite and has_reference(a.suite):  # the exact-model analyses the tables read (never computed by them)
        try:
            from ._api import load_results

            update_reference(a.out, a.suite, load_results(a.suite, a.out))
        except Exception as exc:  # noqa: BLE001 - the runs are stored; say why the reference is not
            print(f"reference not updated: {type(exc).__name__}: {exc}", file=sys.stderr)
    try:
        tables, paths = render_tables(resolve_suite(a.suite, a.suite_file), a.out)
    except NoTableRuns as exc:  # the runs are stored; say why there is no table
        print(f"tables not rendered: {exc}", file=sys.stderr)
        return
    except NoTablePlugin:
        return
    except Exception as exc:  # noqa: BLE001 - the runs are stored; say why the tables are not
        print(f"tables not rendered: {type(exc).__name__}: {exc}", file=sys.stderr)
        return
    for t in tables:
        if "summary" in t.name:
            print(RENDERERS["md"](t))
    md = [str(p) for p in paths if str(p).endswith(".md")]
    print("tables: " + ", ".join(md))  # a user's suite, cutest and hs-all have no thesis column


def _cmd_table(a: argparse.Namespace) -> int:
    from ._api import render_tables
    from ._runner import resolve_suite
    from .tables._render import RENDERERS, NoTablePlugin

    ref = resolve_suite(a.suite, a.suite_file)
    _stored_suite_file_runs(ref, a)
    try:
        tables, paths = render_tables(ref, a.out)
    except NoTablePlugin as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    for t in tables:
        print(RENDERERS[a.format](t))
    print(f"wrote {len(paths)} files under {os.path.join(a.out, ref.name)}", file=sys.stderr)
    return 0


def _cmd_list(a: argparse.Namespace) -> int:
    from . import _listing
    from ._runner import resolve_suite

    if a.modules:  # solvers registered there are listed too
        from ._suites import SolverModuleError, import_modules

        try:
            import_modules(tuple(a.modules))
        except SolverModuleError as exc:
            raise HarnessArgumentError(str(exc)) from None
    if a.what != "problems":  # options that would be ignored
        given = [o for o, v in (("--suite", a.suite), ("--suite-file", a.suite_file), ("--select", a.select)) if v]
        if given:
            raise HarnessArgumentError(f"{', '.join(given)} applies to `list problems` only, not `list {a.what}` "
                                       "(`list suites` shows each suite's solvers)")
    if a.brief and a.what != "solvers":
        raise HarnessArgumentError(f"--brief applies to `list solvers` only, not `list {a.what}`")
    if a.what == "solvers":
        lines = _listing.list_solvers(verbose=not a.brief)
    elif a.what == "suites":
        lines = _listing.list_suites()
    else:
        if not (a.suite or a.suite_file):
            raise HarnessArgumentError("list problems needs --suite or --suite-file")
        lines = _listing.list_problems(resolve_suite(a.suite, a.suite_file), a.select)
    for line in lines:
        print(line)
    return 0


def _cmd_plot(a: argparse.Namespace) -> int:
    from ._plots import plot
    from ._runner import resolve_suite
    from .figures import NoFigurePlugin

    if a.problem is not None and a.kind != "history":
        raise HarnessArgumentError(f"--problem applies to --kind history only; --kind {a.kind} draws every case "
                                   f"(leave --problem out, or use --kind history --problem {a.problem})")
    ref = resolve_suite(a.suite, a.suite_file)
    _stored_suite_file_runs(ref, a)
    _writable_target(os.path.join(a.out, ref.name, "figures"), "--out")  # before any drawing
    try:
        if a.kind in ("thesis", "history") and not a.quiet:
            print(f"plot: drawing {a.kind} figures of {ref.name} ...", file=sys.stderr, flush=True)
        paths = plot(ref.name, a.kind, out=a.out, problem=a.problem, progress=None if a.quiet else sys.stderr)
    except NoFigurePlugin as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    for p in paths:
        print(p)
    return 0


def _cmd_report(a: argparse.Namespace) -> int:
    from ._report import suites_under, write_report

    out = pathlib.Path(a.out)
    if out.exists() and not out.is_dir():
        raise HarnessArgumentError(f"--out {out} is a file, not a results directory")
    if out.is_dir() and not suites_under(out):
        raise HarnessArgumentError(f"no stored results under {out}; run a suite first "
                                   f"(python -m harness run --suite hs --out {out})")
    _writable_target(str(out / "report"), "--out")
    print(write_report(a.out, embed=a.embed, progress=None if a.quiet else sys.stderr))
    return 0


def _cmd_prune(a: argparse.Namespace) -> int:
    from ._runner import prune_suite

    removed = prune_suite(a.suite, suite_file=a.suite_file, solvers=_csv(a.solvers, "--solvers"), select=a.select,
                          out=a.out, dry_run=a.dry_run)
    total = sum(removed.values())
    detail = ", ".join(f"{k} {v}" for k, v in sorted(removed.items()))
    name = a.suite or a.suite_file
    if a.dry_run:
        print(f"{name}: would remove {total} stored rows" + (f" ({detail})" if detail else "") + "; nothing changed")
    else:
        print(f"{name}: removed {total} stored rows" + (f" ({detail})" if detail else "")
              + "; the previous generation is runs.prev.parquet")
    return 0


def _cmd_repair(a: argparse.Namespace) -> int:
    from ._store import Store

    if not (pathlib.Path(a.out) / a.suite).is_dir():
        raise HarnessArgumentError(
            f"no directory {pathlib.Path(a.out) / a.suite}: nothing stored for suite {a.suite!r}"
        )
    print(Store(a.out, a.suite).repair())
    return 0


def _cmd_compare(a: argparse.Namespace) -> int:
    from ._compare import compare_dirs, format_changes

    for d in (a.old, a.new):  # a suite's own directory instead of the results directory holding it
        if (pathlib.Path(d) / "runs.parquet").is_file():
            p = pathlib.Path(d)
            raise HarnessArgumentError(f"{d} is the directory of suite {p.name!r}; compare takes results "
                                       f"directories holding <suite>/runs.parquet: compare {p.parent} ... "
                                       f"--suite {p.name}")
    res = compare_dirs(a.old, a.new, suite=a.suite, nfg_tol=a.nfg_tol, rel_error_factor=a.rel_error_factor)
    print(format_changes(res, show_all=a.all))
    return EXIT_REGRESSIONS if len(res.regressions) else EXIT_OK


def _cmd_export(a: argparse.Namespace) -> int:
    from ._api import load_results
    from ._optiprofiler import export_optiprofiler

    runs = load_results(a.suite, a.out)
    _writable_target(a.to, "--to")
    print(export_optiprofiler(runs, a.to, plib=a.suite))
    return EXIT_OK


def _cmd_reference(a: argparse.Namespace) -> int:
    from ._api import NoResults, load_results
    from ._reference import REFERENCE_MODULES, update_reference

    if a.suite not in REFERENCE_MODULES:
        from problems import suite_names

        if a.suite not in suite_names():
            raise HarnessArgumentError(f"unknown suite {a.suite!r}; suites with a stored reference: "
                                       f"{', '.join(REFERENCE_MODULES)}")
        raise HarnessArgumentError(f"suite {a.suite!r} has no stored reference; suites with one: "
                                   f"{', '.join(REFERENCE_MODULES)}")
    if a.verify:
        return _verify_best_known(a)
    from . import _best_known

    try:
        runs = load_results(a.suite, a.out)
    except NoResults:
        if REFERENCE_MODULES[a.suite] == _best_known.__name__:  # made from the runs alone
            raise HarnessArgumentError(f"no stored runs of {a.suite} under {a.out}: its best-known points come "
                                       f"from them (python -m harness run --suite {a.suite} --out {a.out})") from None
        runs = None  # the run-independent part (exact optima) is still useful
    print(update_reference(a.out, a.suite, runs, fresh=a.fresh))
    return 0


def _verify_best_known(a: argparse.Namespace) -> int:
    from . import _best_known
    from ._reference import REFERENCE_MODULES, load_reference
    from ._runner import resolve_suite
    from ._suites import load_suite

    if REFERENCE_MODULES[a.suite] != _best_known.__name__:
        raise HarnessArgumentError(f"--verify checks best-known points; suite {a.suite!r} stores an exact-model "
                                   "analysis instead")
    stored = load_reference(a.out, a.suite)
    if not stored.get("best_known"):
        raise HarnessArgumentError(f"no stored best-known points of {a.suite} under {a.out} to verify "
                                   f"(python -m harness reference --suite {a.suite} --out {a.out})")
    report = _best_known.verify(load_suite(resolve_suite(a.suite)), stored)
    bad = report[~report["ok"]]
    for r in bad.itertuples():
        print(f"{r.case_id}: {r.why}")
    print(f"{a.suite}: {len(report) - len(bad)} of {len(report)} stored best-known points verified"
          + (f", {len(bad)} not" if len(bad) else ""))
    return 1 if len(bad) else 0


def _cmd_baseline(a: argparse.Namespace) -> int:
    from ._compare import save_baseline

    _writable_target(a.to, "--to")
    print(save_baseline(a.suite, a.out, a.to, _csv(a.solvers, "--solvers")))
    return 0


COMMANDS = {"run": _cmd_run, "table": _cmd_table, "list": _cmd_list, "plot": _cmd_plot,
            "report": _cmd_report, "compare": _cmd_compare, "baseline": _cmd_baseline,
            "export": _cmd_export, "repair": _cmd_repair, "prune": _cmd_prune, "reference": _cmd_reference}


def _terminate_as_interrupt() -> object:
    """SIGTERM (e.g. a batch system's kill) ends a run like Ctrl-C: in-flight runs are
    dropped, finished ones consolidated; SIGKILL loses nothing stored either."""
    import signal
    import threading

    def handler(signum: int, frame: object) -> None:
        raise KeyboardInterrupt

    if threading.current_thread() is threading.main_thread():
        return signal.signal(signal.SIGTERM, handler)
    return None


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    from ._api import NoResults

    ap = _parser()
    args, extra = ap.parse_known_args(argv)
    if extra:
        given = list(sys.argv[1:] if argv is None else argv)
        early = [x for x in extra if x in given[:given.index(args.command)]]
        if early:  # `python -m harness --quiet run ...`
            ap.error(f"unrecognized arguments: {' '.join(early)} (a command's options go after it: "
                     f"python -m harness {args.command} {' '.join(early)} ...)")
        # refused by the command's own parser, which knows the options meant
        commands = next(a for a in ap._actions if isinstance(a, argparse._SubParsersAction))
        command_parser = commands.choices[args.command]
        assert isinstance(command_parser, _Parser)  # every subparser is made by _parser() as a _Parser
        command_parser.unrecognized(extra)
    previous = _terminate_as_interrupt()
    try:
        return COMMANDS[args.command](args)
    except HarnessArgumentError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except NoResults as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except BrokenPipeError:  # output piped into `head`
        sys.stderr.close()
        return EXIT_OK
    except KeyboardInterrupt:
        print("interrupted: finished runs are stored; run again to resume" if args.command == "run"
              else f"interrupted: {args.command} did not finish", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception as exc:  # noqa: BLE001 - one line, not a traceback; exit 3 tells CI it was the harness
        if os.environ.get("HAYBENCH_TRACEBACK"):
            import traceback

            traceback.print_exc()
        print(f"error: harness failure: {type(exc).__name__}: {exc}", file=sys.stderr)
        return EXIT_HARNESS_FAILURE
    finally:
        if previous is not None:
            import signal

            signal.signal(signal.SIGTERM, previous)  # type: ignore[arg-type]  # the handler signal() returned
