"""``harness list``: solvers (with options), suites, problems.  A solver or suite whose
module fails to import is listed with its error instead of stopping the listing."""

from __future__ import annotations

from collections.abc import Iterator

from problems import suite_names
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
            yield f"{name:12s} {len(s.cases()):4d} cases  solvers: {','.join(s.solvers)}  {s.description}"
        except Exception as exc:  # noqa: BLE001 - one broken suite must not hide the others
            yield f"{name:12s} [unavailable: {type(exc).__name__}: {exc}]"


def list_problems(ref: SuiteRef, select: str | None = None) -> Iterator[str]:
    from ._runner import select_suite

    s = select_suite(ref.load(), select)
    if select:
        yield f"# {len(s.cases())} problems of suite {s.name} selected by {select!r}"
    for c in s.cases():
        form = ",".join(sorted(c.problem.form)) or "unconstrained"
        fref = "" if c.problem.f_ref is None else f"  f_ref={c.problem.f_ref:.10g}"
        yield f"{c.case_id:32s} n={c.n:<7d} {form}{fref}  {c.problem.source}"
