"""The counting evaluation wrapper placed between every solver and every problem.

Solvers never see a `Problem`; they see an `Oracle`, which evaluates the problem and
measures the cost:

* ``nfg`` -- number of *distinct points* at which the oracle (value, gradient,
  constraints or their Jacobians) was evaluated. A solver that asks for f and then
  for grad f at the same point is counted once (thesis Section 2.5: N^fg counts
  "function-cum-gradient-vector evaluations").
* ``nf``, ``ng`` -- executions of the objective and of its gradient. Finite-difference
  gradients add their function evaluations to ``nf``.
* ``nc``, ``nj`` -- executions of the constraint functions (inequalities and
  equalities together) and of their Jacobians (finite differences add to ``nc``).
* ``nh`` -- Hessian evaluations reported by second-order adapters (Ipopt).

No solver reports its own count: the numbers in every `Result` come from here.
"""

from __future__ import annotations

import hashlib
import math
import time
from typing import Any

import numpy as np

from ._finite_differences import fd_gradient, fd_jacobian
from ._numbers import is_number
from ._problem import Problem, ProblemError, _real_array, _shown, _worst

__all__ = ["Oracle", "OraclePoint", "BudgetExhausted", "Counts"]


class BudgetExhausted(Exception):
    """Raised by the oracle when a solver exceeds its evaluation budget (max_nfg)."""


class Counts(dict):
    """Evaluation counts: nfg, nf, ng, nc, nj, nh."""


#: points of at most this many variables are keyed by their bytes, longer ones by a digest
RAW_KEY_MAX_N = 16


def _key(x: np.ndarray) -> bytes:
    """Key of a point (``x``: a contiguous float64 vector, as `Oracle._enter` makes it).

    Its bytes when short (cheaper than hashing them), else a 16-byte digest of them: two
    points share a key exactly when their bytes are equal (up to digest collisions).
    """
    if x.size <= RAW_KEY_MAX_N:
        return x.tobytes()
    return hashlib.blake2b(x.data, digest_size=16).digest()


def _read_only(a: np.ndarray) -> np.ndarray:
    """A read-only view (the problem may own ``a``; the oracle's cache must not be written)."""
    v = a.view()
    v.setflags(write=False)
    return v


_EMPTY = _read_only(np.zeros(0))
_max = np.maximum.reduce  # ndarray.max without its Python-level wrapper (same reduction)
_F64 = np.dtype(float)
_FLOATS = frozenset({float, np.float64})  # objective values converted without checks
_JAC_KEY = {"ineq": "ineq_jac", "eq": "eq_jac"}
_isfinite, _isnan = math.isfinite, math.isnan


def _max_or_zero(c: np.ndarray) -> float:
    """``float(_max(c, initial=0.0))`` for a float vector ``c``, bitwise.

    For short vectors the reduction's call costs more than a Python ``max`` over the
    values; the Python ``max`` is used where it must give the same float: no NaN among
    the values (their sum is not NaN) and a nonzero result (a zero maximum could be
    +0.0 or -0.0 depending on the order the two reductions compare ties in).
    """
    vals = c.tolist()
    if not _isnan(sum(vals)):
        m = max(vals)
        if m > 0.0:
            return m
        if m < 0.0:
            return 0.0
    return float(_max(c, initial=0.0))


def _abs_max_or_zero(c: np.ndarray) -> float:
    """``float(_max(np.abs(c), initial=0.0))`` for a float vector ``c``, bitwise (see `_max_or_zero`).

    |c_i| >= +0.0 with no signed-zero ties (abs makes every zero +0.0), so without NaN
    the Python ``max`` of the absolute values is the same float.
    """
    vals = c.tolist()
    if not _isnan(sum(vals)):
        return max(0.0, max(map(abs, vals)))
    return float(_max(np.abs(c), initial=0.0))

#: floats of storage for points whose history entries the solver left open (about 80 MB)
HISTORY_POINT_BUDGET = 10_000_000


class Oracle:
    """Counting, caching access to a `Problem` for solvers.

    Parameters
    ----------
    problem : Problem
    max_nfg : int, optional
        Budget of distinct evaluation points; exceeding it raises `BudgetExhausted`
        (the solve front door turns that into status ``max_iter``).
    """

    def __init__(self, problem: Problem, max_nfg: int | None = None):
        if not isinstance(problem, Problem):
            raise TypeError(f"Oracle needs a Problem, got {type(problem).__name__}")
        self.problem = problem
        self.max_nfg = max_nfg
        self.nfg = self.nf = self.ng = self.nc = self.nj = self.nh = 0
        self.time_in_evals = 0.0
        self._seen: set[bytes] = set()
        self._last_key: bytes | None = None
        self._cache: dict[str, Any] = {}
        # history rows: [nfg, f, max_violation] for each distinct point, filled as known
        self._hist: list[list[float]] = []
        # points whose f or violation the solver never asked for (gradient-only methods such as
        # LFOPC), kept up to a memory cap so the history can be completed outside the count
        self._unfilled: dict[int, np.ndarray] = {}
        self._unfilled_cap = max(0, HISTORY_POINT_BUDGET // max(problem.n, 1))
        # the problem is frozen: its structure is read once, not on every evaluation
        self._n, self._has_bounds = problem.n, problem.has_bounds
        self._lower, self._upper = problem.lower, problem.upper
        self._m = {"ineq": problem.n_ineq, "eq": problem.n_eq}
        self._funs = {"ineq": problem.ineq, "eq": problem.eq}
        self._jacs = {"ineq": problem.ineq_jacobian, "eq": problem.eq_jacobian}
        self._constrained = bool(problem.n_ineq or problem.n_eq)
        self._m_ineq, self._m_eq = problem.n_ineq, problem.n_eq
        self._raw_key = self._n <= RAW_KEY_MAX_N
        self._gradient = problem.gradient
        self._last: np.ndarray = problem.x0.copy()

    # ------------------------------------------------------------------ structure
    @property
    def n(self) -> int:
        return self._n

    @property
    def x0(self) -> np.ndarray:
        return self.problem.x0.copy()

    @property
    def lower(self) -> np.ndarray:
        return self.problem.lower

    @property
    def upper(self) -> np.ndarray:
        return self.problem.upper

    @property
    def n_ineq(self) -> int:
        return self.problem.n_ineq

    @property
    def n_eq(self) -> int:
        return self.problem.n_eq

    @property
    def has_bounds(self) -> bool:
        return self._has_bounds

    @property
    def name(self) -> str:
        return self.problem.name

    @property
    def last_x(self) -> np.ndarray:
        """The point entered last (where a solver that stopped abnormally was)."""
        return self._last.copy()

    # --------------------------------------------------------------- bookkeeping
    def _enter(self, x: Any) -> np.ndarray:
        """Make ``x`` the current point (a fresh float copy): count it if new, reset the cache if moved."""
        x = np.array(x, dtype=float)
        if x.ndim != 1:
            x = x.reshape(-1)
        if x.size != self._n:
            raise ProblemError(f"{self.name}: point has {x.size} components, expected n = {self.n}")
        k = x.tobytes() if self._raw_key else _key(x)  # _key(x), its test made once per oracle
        if k != self._last_key:
            if k in self._seen:
                self._cache = {}
                self._last = x.copy()
            else:
                if self.max_nfg is not None and self.nfg >= self.max_nfg:  # stays at the last point
                    raise BudgetExhausted(f"evaluation budget of {self.max_nfg} points exhausted")
                self._seen.add(k)
                self.nfg += 1
                bviol = self._bound_viol(x) if self._has_bounds else 0.0
                row = [self.nfg, np.nan, np.nan if self._constrained else bviol]
                index = len(self._hist)
                self._hist.append(row)
                self._cache = {"hist_row": row, "hist_index": index, "bviol": bviol}
                self._last = x.copy()
                if len(self._unfilled) < self._unfilled_cap:
                    self._unfilled[index] = self._last  # never written: shared with last_x
            self._last_key = k
        return x

    def _bound_viol(self, x: np.ndarray) -> float:
        """``max(float(_max(lower - x)), float(_max(x - upper)), 0.0)``, bitwise (see `_max_or_zero`)."""
        d_lo, d_up = self._lower - x, x - self._upper
        a, b = d_lo.tolist(), d_up.tolist()
        if not _isnan(sum(a) + sum(b)):  # no NaN among the differences
            ma, mb = max(a), max(b)
            if ma != 0.0 and mb != 0.0:  # no signed-zero tie: the reductions give the same floats
                return max(ma, mb, 0.0)
        return max(float(_max(d_lo)), float(_max(d_up)), 0.0)

    def _note(self, which: str, value: Any) -> None:
        cache = self._cache
        cache[which] = value
        row = cache.get("hist_row")
        if row is None:
            return
        if which == "f":
            row[1] = float(value)
        else:
            m_ineq, m_eq = self._m_ineq, self._m_eq
            if ("ineq" in cache or not m_ineq) and ("eq" in cache or not m_eq):
                v = cache.get("bviol", 0.0)
                if m_ineq:
                    v = _worst(v, _max_or_zero(cache["ineq"]))
                if m_eq:
                    v = _worst(v, _abs_max_or_zero(cache["eq"]))
                row[2] = v
        if row[1] == row[1] and row[2] == row[2]:  # both known: nothing left to complete
            self._unfilled.pop(cache.get("hist_index", -1), None)

    def _call_f(self, x: np.ndarray) -> float:
        t = time.perf_counter()
        f = self.problem.objective(x)
        val = float(f) if type(f) in _FLOATS else self._number(f)
        self.time_in_evals += time.perf_counter() - t
        self.nf += 1
        return val

    def _number(self, f: Any) -> float:
        """The objective's value ``f``: a number or a 0-d array (as for ``float(f)``), else `ProblemError`."""
        if is_number(f):
            return float(f)
        a = _real_array(f)
        if a is None or a.ndim != 0:
            raise ProblemError(f"{self.name}: objective returned {_shown(f)}; expected one number "
                               "(a float, a NumPy scalar or a 0-d array)")
        return float(a)

    def _values(self, what: str, value: Any) -> np.ndarray:
        """``value`` returned by ``what`` as a float array, else `ProblemError` naming ``what``."""
        a = _real_array(value)
        if a is None:
            raise ProblemError(f"{self.name}: {what} returned {_shown(value)}; expected numbers")
        return a

    def _jacobian(self, which: str, J: Any) -> np.ndarray:
        """The Jacobian ``J`` of ``which`` as an (m, n) float array (a single constraint's may be (n,))."""
        m, n = self._m[which], self._n
        J = self._values(f"{which}_jacobian", J)
        if J.shape == (m, n) or (m == 1 and J.shape == (n,)):
            return J.reshape(m, n)
        hint = f" or ({n},)" if m == 1 else " (it returned the transpose)" if J.shape == (n, m) else ""
        raise ProblemError(f"{self.name}: {which}_jacobian returned shape {J.shape}; "
                           f"expected (m, n) = ({m}, {n}){hint}")

    # The `_..._at(x)` methods evaluate at the current point ``x`` (already entered) and
    # return the cached value: read-only arrays, copied by the public methods below.

    def _f_at(self, x: np.ndarray) -> float:
        if "f" not in self._cache:
            self._note("f", self._call_f(x))
        return self._cache["f"]

    def _grad_at(self, x: np.ndarray) -> np.ndarray:
        cache = self._cache
        if "g" not in cache:
            p = self.problem
            t = time.perf_counter()
            if self._gradient is not None:
                g = self._gradient(x)
                if not (type(g) is np.ndarray and g.dtype is _F64 and g.ndim == 1):
                    g = self._values("gradient", g).reshape(-1)
            else:
                f0 = self._cache.get("f")
                if f0 is None and p.fd == "forward":
                    f0 = self._f_at(x)
                g, evals = fd_gradient(p.objective, x, f0, p.fd_step, p.fd, name=f"{self.name}: objective")
                self.nf += evals
            self.time_in_evals += time.perf_counter() - t
            if g.size != self._n:
                raise ProblemError(f"{self.name}: gradient has {g.size} components, expected {self.n}")
            self.ng += 1
            g = cache["g"] = _read_only(g)
            return g
        return cache["g"]

    def _constraint_at(self, which: str, x: np.ndarray) -> np.ndarray:
        m = self._m[which]
        if m == 0:
            return _EMPTY
        if which not in self._cache:
            fun = self._funs[which]
            t = time.perf_counter()
            c = fun(x)
            if not (type(c) is np.ndarray and c.dtype is _F64 and c.ndim == 1):
                c = self._values(which, c).reshape(-1)
            self.time_in_evals += time.perf_counter() - t
            if c.size != m:
                raise ProblemError(f"{self.name}: {which} returned {c.size} values, expected {m}")
            self.nc += 1
            self._note(which, _read_only(c))
        return self._cache[which]

    def _constraint_jac_at(self, which: str, x: np.ndarray) -> np.ndarray:
        m = self._m[which]
        if m == 0:
            return np.zeros((0, self._n))
        key = _JAC_KEY[which]
        if key not in self._cache:
            p = self.problem
            jac = self._jacs[which]
            t = time.perf_counter()
            if jac is not None:
                J = jac(x)
                if not (type(J) is np.ndarray and J.dtype is _F64 and J.shape == (m, self._n)):
                    J = self._jacobian(which, J)
            else:
                c0 = self._constraint_at(which, x) if p.fd == "forward" else None
                J, evals = fd_jacobian(self._funs[which], x, c0, p.fd_step, p.fd, m=m, name=f"{self.name}: {which}")
                self.nc += evals
            self.time_in_evals += time.perf_counter() - t
            self.nj += 1
            self._cache[key] = _read_only(J)
        return self._cache[key]

    # --------------------------------------------------------------- objective
    def f(self, x: Any) -> float:
        """Objective value."""
        return self._f_at(self._enter(x))

    def grad(self, x: Any) -> np.ndarray:
        """Objective gradient (exact, or finite differences counted in nf)."""
        return self._grad_at(self._enter(x)).copy()

    def f_and_grad(self, x: Any) -> tuple[float, np.ndarray]:
        """Value and gradient at one point (one N^fg)."""
        pt = self.at(x)
        return pt.f(), pt.grad().copy()

    # ------------------------------------------------------------- constraints
    def ineq(self, x: Any) -> np.ndarray:
        """Inequality constraint values g(x) (feasible when <= 0)."""
        return self._constraint_at("ineq", self._enter(x)).copy()

    def eq(self, x: Any) -> np.ndarray:
        """Equality constraint values h(x) (feasible when = 0)."""
        return self._constraint_at("eq", self._enter(x)).copy()

    def ineq_jac(self, x: Any) -> np.ndarray:
        """Jacobian (m, n) of the inequality constraints."""
        return self._constraint_jac_at("ineq", self._enter(x)).copy()

    def eq_jac(self, x: Any) -> np.ndarray:
        """Jacobian (q, n) of the equality constraints."""
        return self._constraint_jac_at("eq", self._enter(x)).copy()

    def at(self, x: Any) -> OraclePoint:
        """The point ``x``, entered once: read f, g, constraints and Jacobians there.

        Counting is that of the methods above: nothing is counted until a quantity is
        read, then the point is one N^fg and each quantity is evaluated once (nf, ng, nc,
        nj). What is saved is re-entering the point (copying and hashing ``x``) for every
        quantity a solver reads at it.
        """
        return OraclePoint(self, x)

    def evaluate(self, x: Any) -> dict[str, Any]:
        """Everything first-order at one point: f, g, ineq, ineq_jac, eq, eq_jac (copies)."""
        pt = self.at(x)
        return {
            "f": pt.f(),
            "g": pt.grad().copy(),
            "ineq": pt.ineq().copy(),
            "ineq_jac": pt.ineq_jac().copy(),
            "eq": pt.eq().copy(),
            "eq_jac": pt.eq_jac().copy(),
        }

    def count_hessian(self, k: int = 1) -> None:
        """Record k Hessian evaluations made by a second-order adapter."""
        self.nh += k

    # ------------------------------------------------------------------ results
    def counts(self) -> Counts:
        return Counts(nfg=self.nfg, nf=self.nf, ng=self.ng, nc=self.nc, nj=self.nj, nh=self.nh)

    def history(self) -> np.ndarray:
        """Array (k, 3) of [nfg, f, max_violation] per distinct point (NaN where not evaluated)."""
        return np.array(self._hist, dtype=float).reshape(-1, 3)

    def complete_history(self) -> np.ndarray:
        """The history with f and the violation filled in where the solver never asked for them.

        Gradient-only methods (LFOPC, ETOPC) never evaluate f, so their histories would say
        nothing about progress.  The missing values are evaluated here, after the run, as
        report evaluations: outside every count and outside the run's timed region.  Points
        beyond `HISTORY_POINT_BUDGET` floats of storage stay NaN.
        """
        h = self.history()
        p = self.problem
        for i, x in self._unfilled.items():
            try:
                if not np.isfinite(h[i, 1]):
                    h[i, 1] = float(p.objective(x))
                if not np.isfinite(h[i, 2]):
                    h[i, 2] = p.max_violation(x)
            except Exception:  # noqa: BLE001 - a point the problem cannot evaluate stays NaN
                continue
        return h


class OraclePoint:
    """One point of an `Oracle`, entered once (`Oracle.at`).

    The point is entered at the first access, not before (a solver that reads nothing
    there evaluates nothing). Its accessors return the oracle's cached values as read-only
    arrays (no copies). If the solver has meanwhile entered another point, the next
    access re-enters this one, counted exactly as ``oracle.grad(x)`` and friends would
    count it.
    """

    __slots__ = ("_oracle", "_key", "x")

    def __init__(self, oracle: Oracle, x: Any):
        self._oracle, self._key, self.x = oracle, None, x

    def _current(self) -> np.ndarray:
        o = self._oracle
        if self._key is None or o._last_key != self._key:
            self.x = o._enter(self.x)
            self._key = o._last_key
        return self.x

    def f(self) -> float:
        return self._oracle._f_at(self._current())

    def grad(self) -> np.ndarray:
        return self._oracle._grad_at(self._current())

    def ineq(self) -> np.ndarray:
        return self._oracle._constraint_at("ineq", self._current())

    def eq(self) -> np.ndarray:
        return self._oracle._constraint_at("eq", self._current())

    def ineq_jac(self) -> np.ndarray:
        return self._oracle._constraint_jac_at("ineq", self._current())

    def eq_jac(self) -> np.ndarray:
        return self._oracle._constraint_jac_at("eq", self._current())

