"""Suite ``appendix-a``: the 14 test problems of thesis Appendix A (Tables 2.1-2.2).

Cases: a01 ... a14, problem 5 as a05a / a05b (its two starts), problem 12 at
n = 20 ... 50000, 13 at n = 10 ... 1000, 14 at n = 20 ... 200. Each case carries the
thesis settings as options (see `_settings`): eps_g/eps_x for every solver ("*"), SQSD's
rho, and the N^fg caps of the comparison solvers.

Problem 14 is run twice by SQSD (rho = 1 and rho = 10, Table 2.1). The second case has
``variant="rho=10"`` and ``meta["solvers"] = ("sqsd",)``: only SQSD's settings differ,
so the harness runs the other solvers once per n (on the rho = 1 case).

>>> from problems import get_suite
>>> [c.case_id for c in get_suite("appendix-a").cases()][:2]
['a01/n=3/x0', 'a02/n=2/x0']
"""

from __future__ import annotations

from .._suite import Case, Suite
from ._classic import CLASSIC_BUILDERS as CLASSIC_BUILDERS
from ._classic import FREUDENSTEIN_LOCAL_F
from ._extended import EXTENDED_BUILDERS as EXTENDED_BUILDERS
from ._extended import extended_rosenbrock as extended_rosenbrock
from ._extended import homogeneous_quadratic as homogeneous_quadratic
from ._extended import manevich as manevich
from ._settings import DIMENSIONS, cap_for, rho_for, thesis_label, tolerances_for

__all__ = ["SUITE", "SOLVERS", "COMPARISON_SOLVERS", "build_cases", "make_case"]

#: the comparison methods of Tables 2.1-2.2 (capped as the tables show)
COMPARISON_SOLVERS = ("sd", "fletcher-reeves", "polak-ribiere")
#: established solvers run beside them (third table)
SCIPY_SOLVERS = ("scipy-cg", "scipy-bfgs", "scipy-lbfgsb")
SOLVERS = ("sqsd", *COMPARISON_SOLVERS, *SCIPY_SOLVERS)

# Thesis table markers kept with the case: SD, FR and PR reach the local minimum
# f = 48.98 of problem 8 (Tables 2.1-2.2, "*").
_META = {"a08": {"local_minimum_f": FREUDENSTEIN_LOCAL_F,
                 "thesis_local_minimum_solvers": COMPARISON_SOLVERS}}


def make_case(problem_id: str, n: int | None = None, *, rho: float | None = None, variant: str = "") -> Case:
    """One Appendix A case with the thesis settings (n only for problems 12-14)."""
    if problem_id in CLASSIC_BUILDERS:
        problem = CLASSIC_BUILDERS[problem_id]()
    elif problem_id in EXTENDED_BUILDERS:
        if n is None:
            raise ValueError(f"{problem_id} needs n (thesis dimensions: {DIMENSIONS[problem_id]})")
        problem = EXTENDED_BUILDERS[problem_id](n)
    else:
        valid = [*CLASSIC_BUILDERS, *EXTENDED_BUILDERS]
        raise ValueError(f"unknown Appendix A problem {problem_id!r}; valid: {', '.join(valid)}")
    n = problem.n
    cap = cap_for(problem_id, n)
    options = {
        "*": tolerances_for(problem_id, n),
        "sqsd": {"rho": rho_for(problem_id, n) if rho is None else rho},
        **{s: {"max_fg": cap, "max_iter": cap} for s in COMPARISON_SOLVERS},
        **{s: {"max_fg": cap, "max_iter": cap} for s in SCIPY_SOLVERS},
    }
    meta = {"thesis_problem": thesis_label(problem_id), "cap": cap, **_META.get(problem_id, {})}
    if variant:
        meta["solvers"] = ("sqsd",)  # only SQSD's settings differ in this variant
    return Case(problem=problem, problem_id=problem_id, start="x0", options=options,  # type: ignore[arg-type]
                variant=variant, meta=meta)  # (options: solver -> settings, typed loosely above)


def build_cases() -> list[Case]:
    """All cases in the order of Tables 2.1-2.2."""
    cases = [make_case(pid) for pid in CLASSIC_BUILDERS]
    for pid in ("a12", "a13", "a14"):
        for n in DIMENSIONS[pid]:
            cases.append(make_case(pid, n))
            if pid == "a14":  # Table 2.1 also reports SQSD with rho = 10
                cases.append(make_case(pid, n, rho=10.0, variant="rho=10"))
    return cases


SUITE = Suite(
    name="appendix-a",
    description="Thesis Appendix A: 14 unconstrained test problems (Tables 2.1-2.2: SQSD vs SD, FR, PR)",
    build=build_cases,
    solvers=SOLVERS,
    tables="harness.tables.appendix_a",
)
