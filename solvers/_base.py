"""The abstract solver: every solver is a frozen dataclass whose fields are its options.

Solvers are composed, not subclassed (Equinox's abstract-or-final rule): Dynamic-Q holds
an LFOPC instance as its subproblem solver.
"""

from __future__ import annotations

import abc
import dataclasses
import math
from collections.abc import Callable
from typing import Any, ClassVar, final

from problems import Oracle, Problem
from problems._numbers import is_integer, is_number

from ._result import SolverOutput

__all__ = ["AbstractSolver", "option", "Check", "NotApplicable", "positive", "nonneg", "at_least", "between",
           "one_of", "final"]


class NotApplicable(ValueError):
    """The solver cannot handle this problem's form (e.g. constraints for SQSD)."""


@dataclasses.dataclass(frozen=True)
class Check:
    """A declarative test of one option value: ``test(value)`` and the text saying what is valid."""

    test: Callable[[Any], bool]
    text: str

    def __call__(self, value: Any) -> bool:
        try:
            return bool(self.test(value))
        except TypeError:
            return False


def positive(finite: bool = True) -> Check:
    """value > 0 (and finite unless ``finite=False``)."""
    if finite:
        return Check(lambda v: v > 0 and math.isfinite(v), "a finite number > 0")
    return Check(lambda v: v > 0, "a number > 0")


def nonneg(finite: bool = True) -> Check:
    """value >= 0 (and finite unless ``finite=False``: only for an option whose doc gives inf a meaning)."""
    if finite:
        return Check(lambda v: v >= 0 and math.isfinite(v), "a finite number >= 0")
    return Check(lambda v: v >= 0, "a number >= 0")


def at_least(lo: float, or_none: bool = False) -> Check:
    """value >= lo (None also allowed if ``or_none``)."""
    if or_none:
        return Check(lambda v: v is None or v >= lo, f">= {lo} or None")
    return Check(lambda v: v >= lo, f">= {lo}")


def between(lo: float, hi: float, closed: str = "") -> Check:
    """lo < value < hi; ``closed`` may hold "lo" and/or "hi" to include that end."""
    lo_ok: Callable[[Any], bool] = (lambda v: v >= lo) if "lo" in closed else (lambda v: v > lo)
    hi_ok: Callable[[Any], bool] = (lambda v: v <= hi) if "hi" in closed else (lambda v: v < hi)
    text = ("[" if "lo" in closed else "(") + f"{lo}, {hi}" + ("]" if "hi" in closed else ")")
    return Check(lambda v: lo_ok(v) and hi_ok(v), f"in {text}")


def one_of(*values: Any) -> Check:
    """value is one of ``values``."""
    return Check(lambda v: v in values, "one of " + ", ".join(repr(v) for v in values))


def option(default: Any, doc: str, source: str = "", check: Check | None = None) -> Any:
    """A solver option: its default, meaning, thesis provenance and (optionally) the check of its value.

    Every option is checked once, when the solver is built (`AbstractSolver.__post_init__`): its
    type against the field's annotation (float, int, bool, str, optionally ``| None``) and then
    ``check``.
    """
    return dataclasses.field(default=default, metadata={"doc": doc, "source": source, "check": check})


def _type_ok(annotation: Any, value: Any) -> tuple[bool, str]:
    """Whether ``value`` fits a simple annotation; (True, "") for annotations we do not check."""
    text = annotation if isinstance(annotation, str) else getattr(annotation, "__name__", str(annotation))
    parts = [t.strip() for t in text.split("|")]
    if "None" in parts:
        if value is None:
            return True, ""
        parts.remove("None")
    if len(parts) != 1:
        return True, ""
    kind = parts[0]
    if kind == "bool":
        return isinstance(value, bool) or type(value).__name__ == "bool_", "a bool"
    if kind == "float":
        return is_number(value), "a number"
    if kind == "int":
        ok = is_integer(value)
        ok = ok or (isinstance(value, float) and value.is_integer())  # e.g. max_steps=1e4 from a spec
        return ok, "an integer"
    if kind == "str":
        return isinstance(value, str), "a string"
    return True, ""


def _valid_text(kind: str, check: Check | None) -> str:
    """What is valid for an option: the check's text when it names the kind itself ("a finite number
    > 0", "one of 'fixed', 'auto'"), else the kind followed by it ("an integer >= 1"), else the kind."""
    if check is None:
        return kind
    if not kind or check.text.startswith(("a ", "an ", "one of ")):
        return check.text
    return f"{kind} {check.text}"


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

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        for base in cls.__mro__[1:]:
            if base.__dict__.get("__final__"):  # set by typing.final
                raise TypeError(f"solver class {base.__name__} is final; compose it (hold an instance) "
                                f"instead of subclassing it")

    def __post_init__(self) -> None:
        """Check every option once: its type (from the annotation), its `Check`, then `check_together`.

        Last, a NaN in a float option is refused (never a setting; it can come from a spec's ``nan``),
        after `check_together` so that a solver's own message for it comes first.
        """
        nans = []
        for f in dataclasses.fields(self):  # type: ignore[arg-type]  # concrete solvers are dataclasses
            value = getattr(self, f.name)
            ok, kind = _type_ok(f.type, value)
            check: Check | None = f.metadata.get("check")
            if ok and (check is None or check(value)):
                if kind == "a number" and value is not None and math.isnan(value):
                    nans.append(f)
                continue
            what = _valid_text(kind, check)
            why = "" if ok or what == kind else f" (not {kind})"
            raise ValueError(f"{self.name}: option {f.name}={value!r} is invalid{why}; valid: {what}")
        self.check_together()
        for f in nans:
            raise ValueError(f"{self.name}: option {f.name}=nan is invalid; valid: a number other than NaN")

    def check_together(self) -> None:  # noqa: B027 - an optional hook, not an abstract method
        """Checks relating several options (e.g. mu0 <= mu1); raise ValueError. Default: none."""

    @classmethod
    def check_option_names(cls, names: Any) -> None:
        """ValueError naming the solver, the unknown option names and the valid ones."""
        valid = [f.name for f in dataclasses.fields(cls)]  # type: ignore[arg-type]  # a dataclass subclass
        unknown = sorted(set(names) - set(valid))
        if unknown:
            raise ValueError(f"unknown option(s) {', '.join(unknown)} for solver {cls.name!r}; valid options: "
                             f"{', '.join(valid) or '(none)'}")

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
        for f in dataclasses.fields(cls):  # type: ignore[arg-type]  # a dataclass subclass
            default = f.default if f.default is not dataclasses.MISSING else (
                f.default_factory() if f.default_factory is not dataclasses.MISSING else None
            )
            check = f.metadata.get("check")
            rows.append({"name": f.name, "default": default, "doc": f.metadata.get("doc", ""),
                         "source": f.metadata.get("source", ""), "check": check.text if check else ""})
        return rows

    def settings(self) -> dict[str, Any]:
        """The option values of this instance, JSON-friendly (nested solvers as dicts)."""
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):  # type: ignore[arg-type]  # concrete solvers are dataclasses
            v = getattr(self, f.name)
            if isinstance(v, AbstractSolver):
                v = {"solver": v.name, **v.settings()}
            out[f.name] = v
        return out
