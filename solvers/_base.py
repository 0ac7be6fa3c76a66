"""The abstract solver: every solver is a frozen dataclass whose fields are its options.

Solvers are composed, not subclassed (Equinox's abstract-or-final rule): Dynamic-Q holds
an LFOPC instance as its subproblem solver.
"""

from __future__ import annotations

import abc
import dataclasses
from typing import Any, ClassVar

from problems import Oracle, Problem

from ._result import SolverOutput

__all__ = ["AbstractSolver", "option", "NotApplicable"]


class NotApplicable(ValueError):
    """The solver cannot handle this problem's form (e.g. constraints for SQSD)."""


def option(default: Any, doc: str, source: str = "") -> Any:
    """A solver option: its default, its meaning and where it comes from in the thesis."""
    return dataclasses.field(default=default, metadata={"doc": doc, "source": source})


class AbstractSolver(abc.ABC):
    """Base of all solvers.

    Class attributes
    ----------------
    name : registry id (kebab-case), e.g. ``"sqsd"``.
    summary : one line for ``harness list solvers``.
    handles : problem features the solver accepts: subset of {"bounds", "ineq", "eq"}.
    family : ``"thesis"`` (written here from the thesis) or ``"established"``.
    """

    name: ClassVar[str]
    summary: ClassVar[str]
    handles: ClassVar[frozenset[str]] = frozenset()
    family: ClassVar[str] = "established"

    def can_solve(self, problem: Problem) -> str | None:
        """None if the solver applies to ``problem``, else the reason it does not."""
        missing = problem.form - self.handles
        if missing:
            return f"{self.name} does not handle {', '.join(sorted(missing))} constraints"
        return None

    @abc.abstractmethod
    def minimize(self, oracle: Oracle) -> SolverOutput:
        """Run from ``oracle.x0``; evaluate the problem only through ``oracle``."""

    @classmethod
    def options(cls) -> list[dict[str, Any]]:
        """Option table generated from the dataclass fields (name, default, doc, source)."""
        rows = []
        for f in dataclasses.fields(cls):  # type: ignore[arg-type]
            default = f.default if f.default is not dataclasses.MISSING else (
                f.default_factory() if f.default_factory is not dataclasses.MISSING else None  # type: ignore[misc]
            )
            rows.append({"name": f.name, "default": default, "doc": f.metadata.get("doc", ""),
                         "source": f.metadata.get("source", "")})
        return rows

    def settings(self) -> dict[str, Any]:
        """The option values of this instance, JSON-friendly (nested solvers as dicts)."""
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            v = getattr(self, f.name)
            if isinstance(v, AbstractSolver):
                v = {"solver": v.name, **v.settings()}
            out[f.name] = v
        return out
