"""The `Problem` type: one optimization problem, defined from Python callables.

Convention (thesis eq. 3.3): minimize f(x) subject to g_j(x) <= 0, h_k(x) = 0 and
simple bounds lower <= x <= upper.  Missing first derivatives are replaced by finite
differences (thesis Sections 4.5.2, 5.8.2: forward or central, interval Gamma), and
those function evaluations are counted by the evaluation wrapper like any other.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from ._numbers import is_finite_number, is_integer

__all__ = ["Problem", "ProblemError"]

FD_SCHEMES = ("forward", "central")


class ProblemError(ValueError):
    """A problem definition or an input point is invalid."""


def _real_array(value: Any) -> np.ndarray | None:
    """``value`` as a float array, or None unless it is real numbers (None, str, bool, complex are not)."""
    try:
        a = np.asarray(value)
    except (TypeError, ValueError):  # ragged nesting
        return None
    return a.astype(float, copy=False) if a.dtype.kind in "iuf" else None


def _shown(value: Any) -> str:
    """``value``, shortly, for an error message."""
    if isinstance(value, np.ndarray):
        return f"an array of shape {value.shape} and dtype {value.dtype}"
    return f"{value!r:.60}"


def _worst(a: float, b: float) -> float:
    """``max(a, b)`` (the same float), but NaN if either is NaN: a NaN constraint value is violated."""
    return b if b > a or b != b else a


def _as_vector(name: str, value: Any, n: int | None = None) -> np.ndarray:
    arr = _real_array(value)
    if arr is None:
        raise ProblemError(f"{name} must be a vector of numbers, got {_shown(value)}")
    if arr.ndim == 0 and n is not None:
        arr = np.full(n, float(arr))
    if arr.ndim != 1:
        raise ProblemError(f"{name} must be one-dimensional, got shape {arr.shape}")
    if n is not None and arr.shape[0] != n:
        raise ProblemError(f"{name} has length {arr.shape[0]}, expected n = {n}")
    return arr


@dataclasses.dataclass(frozen=True, eq=False)
class Problem:
    """A (possibly constrained) minimization problem.

    Parameters
    ----------
    name : str
        Identifier, e.g. ``"a04"`` or ``"hs071"``.
    x0 : array_like, shape (n,)
        Starting point.
    objective : callable ``f(x) -> float``
    gradient : callable ``g(x) -> (n,)``, optional
        Exact gradient. ``None`` means finite differences (``fd``, ``fd_step``).
    ineq : callable ``g(x) -> (m,)``, optional
        Inequality constraints in the convention ``g(x) <= 0`` (thesis eq. 3.3).
    ineq_jacobian : callable ``J(x) -> (m, n)``, optional
        Jacobian of ``ineq``; ``None`` means finite differences.
    eq, eq_jacobian : callables, optional
        Equality constraints ``h(x) = 0`` and their Jacobian ``(q, n)``.
    lower, upper : array_like or float, optional
        Simple bounds (``-inf``/``+inf`` for none). Kept exact by the thesis's
        methods (eq. 3.7).
    f_ref, x_ref : optional
        Best known optimum value and point (for E^r, eq. 2.34 / 3.12, and I^inf).
    source : str
        Where the problem comes from (thesis appendix, HS number, ...).
    fd : {"forward", "central"}
        Finite-difference scheme used where a derivative is missing.
    fd_step : float
        Finite-difference interval Gamma (absolute).
    symbolic : callable, optional
        ``symbolic(x) -> dict(f=..., ineq=..., eq=...)`` building CasADi expressions of
        the same functions from a CasADi symbol ``x``; lets Ipopt use exact Hessians.
    tags : tuple of str
    meta : mapping
        Free-form extra information (for example the thesis's reported local minimum).
    """

    name: str
    x0: np.ndarray
    objective: Callable[[np.ndarray], float]
    gradient: Callable[[np.ndarray], np.ndarray] | None = None
    ineq: Callable[[np.ndarray], np.ndarray] | None = None
    ineq_jacobian: Callable[[np.ndarray], np.ndarray] | None = None
    eq: Callable[[np.ndarray], np.ndarray] | None = None
    eq_jacobian: Callable[[np.ndarray], np.ndarray] | None = None
    lower: np.ndarray | None = None
    upper: np.ndarray | None = None
    f_ref: float | None = None
    x_ref: np.ndarray | None = None
    source: str = ""
    fd: str = "forward"
    fd_step: float = 1e-6
    symbolic: Callable[[Any], Mapping[str, Any]] | None = None
    tags: tuple[str, ...] = ()
    meta: Mapping[str, Any] = dataclasses.field(default_factory=dict)
    n_ineq: int | None = None
    n_eq: int | None = None

    def __post_init__(self) -> None:
        set_ = lambda k, v: object.__setattr__(self, k, v)  # the dataclass is frozen
        if not isinstance(self.name, str) or not self.name:
            raise ProblemError("Problem.name must be a non-empty string")
        x0 = _as_vector(f"{self.name}: x0", self.x0)
        if x0.size == 0:
            raise ProblemError(f"{self.name}: x0 is empty")
        if not np.all(np.isfinite(x0)):
            raise ProblemError(f"{self.name}: x0 contains NaN or inf: {x0}")
        set_("x0", x0)
        n = x0.size
        if not callable(self.objective):
            raise ProblemError(f"{self.name}: objective must be callable")
        for attr in ("gradient", "ineq", "ineq_jacobian", "eq", "eq_jacobian", "symbolic"):
            v = getattr(self, attr)
            if v is not None and not callable(v):
                raise ProblemError(f"{self.name}: {attr} must be callable or None")
        if self.ineq is None and self.ineq_jacobian is not None:
            raise ProblemError(f"{self.name}: ineq_jacobian given without ineq")
        if self.eq is None and self.eq_jacobian is not None:
            raise ProblemError(f"{self.name}: eq_jacobian given without eq")
        lo = np.full(n, -np.inf) if self.lower is None else _as_vector(f"{self.name}: lower", self.lower, n)
        up = np.full(n, np.inf) if self.upper is None else _as_vector(f"{self.name}: upper", self.upper, n)
        if np.any(np.isnan(lo)) or np.any(np.isnan(up)):
            raise ProblemError(f"{self.name}: bounds contain NaN")
        if np.any(lo > up):
            bad = np.flatnonzero(lo > up)
            raise ProblemError(f"{self.name}: lower > upper at indices {bad.tolist()}")
        set_("lower", lo)
        set_("upper", up)
        if self.x_ref is not None:
            x_ref = _as_vector(f"{self.name}: x_ref", self.x_ref, n)
            if not np.all(np.isfinite(x_ref)):
                raise ProblemError(f"{self.name}: x_ref contains NaN or inf: {x_ref}")
            set_("x_ref", x_ref)
        if self.f_ref is not None:
            if not is_finite_number(self.f_ref):
                raise ProblemError(f"{self.name}: f_ref must be a finite number or None, got {self.f_ref!r}")
            set_("f_ref", float(self.f_ref))
        if self.fd not in FD_SCHEMES:
            raise ProblemError(f"{self.name}: fd must be one of {FD_SCHEMES}, got {self.fd!r}")
        if not (is_finite_number(self.fd_step) and self.fd_step > 0):
            raise ProblemError(f"{self.name}: fd_step must be a positive number, got {self.fd_step!r}")
        set_("tags", tuple(self.tags))
        for which in ("ineq", "eq"):  # constraint counts: when not given, evaluated once at x0 (uncounted set-up)
            fun, count = getattr(self, which), getattr(self, f"n_{which}")
            if count is None and fun is None:
                count = 0
            elif count is None:
                c = fun(x0)
                values = _real_array(c)
                if values is None:
                    raise ProblemError(f"{self.name}: {which}(x0) returned {_shown(c)}; expected a vector of numbers")
                count = values.size
            elif not (is_integer(count) and count >= 0):
                raise ProblemError(f"{self.name}: n_{which} must be a non-negative integer or None, got {count!r}")
            elif count and fun is None:
                raise ProblemError(f"{self.name}: n_{which} = {count} given without {which}")
            set_(f"n_{which}", int(count))

    # ----------------------------------------------------------------- structure
    @property
    def n(self) -> int:
        """Number of variables."""
        return int(self.x0.size)

    @property
    def has_bounds(self) -> bool:
        return bool(np.any(np.isfinite(self.lower)) or np.any(np.isfinite(self.upper)))

    @property
    def is_constrained(self) -> bool:
        """True if the problem has any constraint, bounds included."""
        return self.n_ineq > 0 or self.n_eq > 0 or self.has_bounds

    @property
    def form(self) -> frozenset[str]:
        """Structural features used to match solver capabilities."""
        feats = set()
        if self.n_ineq:
            feats.add("ineq")
        if self.n_eq:
            feats.add("eq")
        if self.has_bounds:
            feats.add("bounds")
        return frozenset(feats)

    def with_start(self, x0: Any, name: str | None = None) -> Problem:
        """The same problem from another starting point."""
        return dataclasses.replace(self, x0=x0, name=name or self.name)

    def replace(self, **changes: Any) -> Problem:
        """A copy with some fields changed (e.g. ``fd_step``)."""
        return dataclasses.replace(self, **changes)

    # ------------------------------------------------------------- diagnostics
    def max_violation(self, x: np.ndarray) -> float:
        """Largest constraint violation at x: max(0, g_j), |h_k| and bound excess.

        NaN if a constraint value is NaN (a NaN constraint is not satisfied).
        Uncounted; for reporting and verification only.
        """
        x = np.asarray(x, dtype=float)
        v = 0.0
        if self.n_ineq:
            g = np.atleast_1d(np.asarray(self.ineq(x), dtype=float))
            v = _worst(v, float(np.max(g, initial=0.0)))
        if self.n_eq:
            h = np.atleast_1d(np.asarray(self.eq(x), dtype=float))
            v = _worst(v, float(np.max(np.abs(h), initial=0.0)))
        if self.has_bounds:  # v first: a NaN v stays NaN
            v = max(v, float(np.max(self.lower - x, initial=0.0)), float(np.max(x - self.upper, initial=0.0)))
        return v

    def __repr__(self) -> str:
        parts = [f"name={self.name!r}", f"n={self.n}"]
        if self.n_ineq:
            parts.append(f"n_ineq={self.n_ineq}")
        if self.n_eq:
            parts.append(f"n_eq={self.n_eq}")
        if self.has_bounds:
            parts.append("bounds")
        return f"Problem({', '.join(parts)})"
