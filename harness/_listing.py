"""``harness list``: solvers (with options), suites, problems.  A solver or suite whose
module fails to import is listed with its error instead of stopping the listing.

Suites with a catalogue (`problems._catalog.case_summaries`: ``cutest``, ``hs-all``) are
listed from it, without building a problem: the same lines, in milliseconds instead of
minutes for a large CUTEst selection."""

from __future__ import annotations

from collections.abc import Iterator

from problems import suite_names
from problems._catalog import case_summaries
from solvers import get_solver_class, solver_names

from ._suites import SuiteRef

__all__ = ["list_solvers", "list_suites", "list_problems"]


def list_solvers(verbose: bool = True) -> Iterator[str]:
    for name in solver_names():
        try:
            cls = get_solver_class(name)
        except Exception as exc:  # noqa: BLE001 - listed, not fatal
            yield f"{name:20s} [unavailable: {type(exc).__name__}: {exc}]"
            continue
        handles = ",".join(sorted(cls.handles)) or "unconstrained"
        yield f"{name:20s} {cls.family:11s} {cls.summary}  (handles: {handles})"
        if verbose:
            for o in cls.options():
                src = f"  [{o['source']}]" if o["source"] else ""
                chk = f"  (valid: {o['check']})" if o.get("check") else ""
                yield f"    {o['name']} = {o['default']!r}: {o['doc']}{chk}{src}"


def list_suites() -> Iterator[str]:
    for name in suite_names():
        try:
            s = SuiteRef(name).load()
            summaries = case_summaries(name)
            count = len(summaries) if summaries is not None else len(s.cases())
            yield f"{name:12s} {count:4d} cases  solvers: {','.join(s.solvers)}  {s.description}"
        except Exception as exc:  # noqa: BLE001 - one broken suite must not hide the others
            yield f"{name:12s} [unavailable: {type(exc).__name__}: {exc}]"


def _summaries(ref: SuiteRef, select: str | None):
    """The catalogue's summaries of a built-in suite's (selected) cases, or None."""
    if ref.file is not None:
        return None
    from ._runner import HarnessArgumentError

    try:
        rows = case_summaries(ref.name, select)
    except ValueError as exc:  # a bad selection: the same argument error as `select_suite`'s
        raise HarnessArgumentError(str(exc)) from None
    if rows is not None and not rows:
        raise HarnessArgumentError(f"the selection {select!r} picks no problem of suite {ref.name}")
    return rows


def list_problems(ref: SuiteRef, select: str | None = None) -> Iterator[str]:
    from ._runner import select_suite

    rows = _summaries(ref, select)
    if rows is None:
        s = select_suite(ref.load(), select)
        rows = [(c.case_id, c.n, c.problem.form, c.problem.f_ref, c.problem.source) for c in s.cases()]
    else:
        rows = [(r.case_id, r.n, r.form, r.f_ref, r.source) for r in rows]
    if select:
        yield f"# {len(rows)} problems of suite {ref.name} selected by {select!r}"
    for case_id, n, form, f_ref, source in rows:
        forms = ",".join(sorted(form)) or "unconstrained"
        fref = "" if f_ref is None else f"  f_ref={f_ref:.10g}"
        yield f"{case_id:32s} n={n:<7d} {forms}{fref}  {source}"
