"""Suites: named collections of (problem, start, per-solver settings) cases.

A suite module defines ``SUITE = Suite(...)``; the catalogue (`_catalog.py`) maps suite
names to modules and imports them on demand, so one broken suite cannot break another.
Harness workers rebuild cases from (suite name, case id), so problems built from
closures never need pickling.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from ._problem import Problem

__all__ = ["Case", "Suite"]


@dataclasses.dataclass(frozen=True)
class Case:
    """One problem from one start, with the settings the thesis used for it.

    ``options`` maps a solver id (or ``"*"`` for every solver that has that option) to
    option values, e.g. ``{"*": {"eps_g": 1e-5}, "sqsd": {"rho": 0.3}}``.
    ``problem_id`` is the table's problem label (``"a12"``), ``start`` the start label.
    ``meta["solvers"]``, if given, restricts the case to those solver ids (the harness
    plans no other run for it), e.g. a variant that only changes SQSD's rho.
    """

    problem: Problem
    problem_id: str
    start: str = "x0"
    options: Mapping[str, Mapping[str, Any]] = dataclasses.field(default_factory=dict)
    variant: str = ""  # distinguishes cases with the same problem and start (e.g. "rho=10")
    meta: Mapping[str, Any] = dataclasses.field(default_factory=dict)

    @property
    def n(self) -> int:
        return self.problem.n

    @property
    def case_id(self) -> str:
        """Unique within a suite: problem id, n, start and variant."""
        parts = [self.problem_id, f"n={self.n}", self.start]
        if self.variant:
            parts.append(self.variant)
        return "/".join(parts)

    def options_for(self, solver: str, valid: Sequence[str]) -> dict[str, Any]:
        """Options for ``solver``: ``"*"`` entries it has, then its own entries."""
        general = {k: v for k, v in self.options.get("*", {}).items() if k in valid}
        return {**general, **dict(self.options.get(solver, {}))}


@dataclasses.dataclass(frozen=True)
class Suite:
    """A named benchmark suite.

    Parameters
    ----------
    name : str
        Suite id used on the command line (``appendix-a``, ``hs``, ``rpr2`` ...).
    description : str
    build : callable returning the cases (called once, lazily).
    solvers : default solver ids for ``harness run``.
    build_case : optional ``case_id -> Case`` building one case without the others (large
        libraries: a harness worker rebuilds only the case it runs).
    selector : optional ``expression -> cases``: the cases a selection picks
        (``harness run --select``; see `Suite.select`).
    tables : module of the suite's table plug-in, ``tables(runs[, reference]) -> list[Table]``
        (e.g. ``"harness.tables.rpr2"``); empty: the suite has no tables.
    figures : module of its thesis-figure plug-in, ``figures(runs, outdir) -> list[Path]``
        (e.g. ``"harness.figures.rpr2"``); empty: none.
    """

    name: str
    description: str
    build: Callable[[], Sequence[Case]]
    solvers: tuple[str, ...]
    build_case: Callable[[str], Case] | None = None
    selector: Callable[[str], Sequence[Case]] | None = None
    tables: str = ""
    figures: str = ""

    def select(self, expression: str) -> Suite:
        """The same suite restricted to the cases ``expression`` selects."""
        if self.selector is None:
            raise ValueError(f"suite {self.name} does not support selection expressions: its cases are picked by "
                             "case id ('problem/n=N/start[/variant]', as its cases() list them)")
        selector = self.selector
        return dataclasses.replace(self, build=lambda: selector(expression))

    @functools.cached_property
    def _cases(self) -> tuple[Case, ...]:
        cases = tuple(self.build())
        ids = [c.case_id for c in cases]
        dup = {i for i in ids if ids.count(i) > 1}
        if dup:
            raise ValueError(f"suite {self.name}: duplicate case ids {sorted(dup)}")
        return cases

    def cases(self) -> tuple[Case, ...]:
        return self._cases

    def case(self, case_id: str) -> Case:
        if self.build_case is not None and "_cases" not in self.__dict__:
            return self.build_case(case_id)  # one case only: the others are never built
        for c in self._cases:
            if c.case_id == case_id:
                return c
        raise KeyError(f"suite {self.name} has no case {case_id!r}")

    def problem_ids(self) -> list[str]:
        seen: dict[str, None] = {}
        for c in self._cases:
            seen.setdefault(c.problem_id)
        return list(seen)
