"""Cases of the S2MPJ suites: one case per instance, from its x0; case ids ``NAME/n=N/x0``."""

from __future__ import annotations

from collections.abc import Callable

from .._suite import Case
from ._adapter import s2mpj_problem

__all__ = ["case_for", "instance_of"]


def instance_of(case_id: str) -> str:
    return case_id.split("/", 1)[0]


def case_for(instance: str, reference: Callable[[str], tuple[float | None, object]] | None = None) -> Case:
    """The case of ``instance``; ``reference(instance) -> (f_ref, x_ref)`` gives known optima."""
    f_ref, x_ref = reference(instance) if reference is not None else (None, None)
    problem = s2mpj_problem(instance, f_ref=f_ref, x_ref=x_ref)  # type: ignore[arg-type]  # x_ref: array or None
    return Case(problem=problem, problem_id=instance, meta={"type": problem.meta["type"]})
