"""Ipopt (Wächter & Biegler 2006) through CasADi's ``nlpsol``, evaluating via the oracle.

Ipopt never sees the problem's own functions: f, g and their first derivatives are
CasADi ``Callback`` objects that call the counting `Oracle`, and CasADi is told to use
them (``grad_f``, ``jac_g``) instead of differentiating anything itself. So N^fg, nf,
ng, nc, nj of an Ipopt run are measured exactly like those of the thesis's methods.

Second derivatives: when the problem has a symbolic definition (``Problem.symbolic``,
e.g. the Hock–Schittkowski suite), the exact Hessian of the Lagrangian
sigma f + lam^T [g; h] is built once per problem with CasADi and evaluated by a
counting callback (each evaluation -> ``oracle.count_hessian()``, reported as ``nh``).
Otherwise Ipopt uses its limited-memory quasi-Newton approximation.
"""

from __future__ import annotations

import dataclasses
import re
import weakref
from collections.abc import Callable
from typing import Any, ClassVar

import casadi as ca
import numpy as np

from problems import BudgetExhausted, Oracle, Problem

from ._base import AbstractSolver, at_least, final, nonneg, one_of, option, positive
from ._result import SolverOutput, Status

__all__ = ["Ipopt"]

# Problem -> compiled CasADi Hessian of the Lagrangian (built once per problem object)
_HESS_CACHE: weakref.WeakKeyDictionary[Problem, ca.Function] = weakref.WeakKeyDictionary()


class _PyFunction(ca.Callback):
    """A CasADi function computed by a Python callable returning NumPy arrays.

    Exceptions raised by ``fun`` (for example `BudgetExhausted`) are stored in
    ``errors`` so the adapter can re-raise them after Ipopt returns (CasADi would
    otherwise turn them into a generic "Error in Function::call" and print a traceback).
    """

    def __init__(self, name: str, sp_in: list[ca.Sparsity], sp_out: list[ca.Sparsity],
                 fun: Callable[..., list[np.ndarray]], errors: list[BaseException],
                 jac: Callable[[np.ndarray], np.ndarray] | None = None):
        ca.Callback.__init__(self)
        self._sp_in, self._sp_out, self._fun, self._errors = sp_in, sp_out, fun, errors
        self._jac, self._jac_fun = jac, None
        self.construct(name, {})

    # CasADi differentiates the NLP once while building auxiliary functions (the
    # gradient of the Lagrangian for the multipliers); give it the oracle's Jacobian.
    def has_jacobian(self) -> bool:
        return self._jac is not None

    def get_jacobian(self, name: str, inames: list[str], onames: list[str], opts: dict) -> ca.Function:
        sp_x, sp_y = self._sp_in[0], self._sp_out[0]
        jac = self._jac
        self._jac_fun = _PyFunction(name, [sp_x, sp_y], [ca.Sparsity.dense(sp_y.numel(), sp_x.numel())],
                                    lambda x, y: [jac(x.ravel())], self._errors)  # type: ignore[misc]  # CasADi stub
        return self._jac_fun

    def get_n_in(self) -> int:
        return len(self._sp_in)

    def get_n_out(self) -> int:
        return len(self._sp_out)

    def get_sparsity_in(self, i: int) -> ca.Sparsity:
        return self._sp_in[i]

    def get_sparsity_out(self, i: int) -> ca.Sparsity:
        return self._sp_out[i]

    def eval(self, args: list[Any]) -> list[Any]:
        if not self._errors:
            try:
                outs = self._fun(*[np.asarray(a, dtype=float) for a in args])
                dms = [ca.DM(np.asarray(o, dtype=float).reshape(sp.size1(), sp.size2()))
                       for sp, o in zip(self._sp_out, outs)]
                return [d if sp.is_dense() else ca.project(d, sp) for sp, d in zip(self._sp_out, dms)]
            except Exception as exc:  # noqa: BLE001  (re-raised by the adapter after Ipopt returns)
                self._errors.append(exc)
        # After a failure, answer NaN (Ipopt treats it as an evaluation error and backs off)
        # instead of raising: CasADi prints a traceback for every raising callback, and
        # _StopOnError ends the run at the end of the current iteration.
        return [ca.DM(sp, np.nan) for sp in self._sp_out]


class _StopOnError(ca.Callback):
    """Ipopt's per-iteration callback: ask Ipopt to stop once a callback has failed."""

    def __init__(self, n: int, m: int, errors: list[BaseException]):
        ca.Callback.__init__(self)
        self._sizes = {"x": n, "f": 1, "g": m, "lam_x": n, "lam_g": m, "lam_p": 0}
        self._errors = errors
        self.construct("stop_on_error", {})

    def get_n_in(self) -> int:
        return ca.nlpsol_n_out()

    def get_n_out(self) -> int:
        return 1

    def get_sparsity_in(self, i: int) -> ca.Sparsity:
        return ca.Sparsity.dense(self._sizes[ca.nlpsol_out(i)], 1)

    def eval(self, args: list[Any]) -> list[Any]:
        return [1 if self._errors else 0]


def _casadi_name(prefix: str, name: str) -> str:
    """A valid CasADi function name from a problem name ('my-problem' -> 'ipopt_my_problem')."""
    return re.sub(r"_+", "_", f"{prefix}_{re.sub(r'[^0-9A-Za-z]', '_', name)}").rstrip("_")


def _hessian_function(problem: Problem) -> ca.Function:
    """Upper triangle of the Hessian of sigma f + lam^T [g; h], from ``problem.symbolic``."""
    cached = _HESS_CACHE.get(problem)
    if cached is not None:
        return cached
    n, m = problem.n, problem.n_ineq + problem.n_eq
    x = ca.SX.sym("x", n)
    sym = problem.symbolic(x)  # type: ignore[misc]  # checked non-None by the caller
    parts = [ca.SX(v) for k in ("ineq", "eq") if (v := sym.get(k)) is not None and ca.SX(v).numel() > 0]
    c = ca.vertcat(*parts) if parts else ca.SX(0, 1)
    if c.numel() != m:
        raise ValueError(f"{problem.name}: symbolic() gives {c.numel()} constraints, the problem has {m}")
    sigma, lam = ca.SX.sym("sigma"), ca.SX.sym("lam", m)
    lag = sigma * ca.SX(sym["f"]) + (ca.dot(lam, c) if m else 0)
    hess = ca.triu(ca.densify(ca.hessian(lag, x)[0]))
    fun = ca.Function(_casadi_name("hess_lag", problem.name), [x, sigma, lam], [ca.densify(hess)])
    _HESS_CACHE[problem] = fun
    return fun


@final
@dataclasses.dataclass(frozen=True)
class Ipopt(AbstractSolver):
    """Interior-point filter line-search method (Ipopt) via ``casadi.nlpsol``."""

    name = "ipopt"
    summary = "Ipopt interior point (CasADi nlpsol); exact Lagrangian Hessian if the problem is symbolic, else L-BFGS"
    family = "established"
    handles = frozenset({"bounds", "ineq", "eq"})

    #: Ipopt's ``return_status`` strings -> Status
    STATUS_MAP: ClassVar[dict[str, Status]] = {
        "Solve_Succeeded": Status.CONVERGED,
        "Solved_To_Acceptable_Level": Status.CONVERGED,
        "Feasible_Point_Found": Status.CONVERGED,
        "Maximum_Iterations_Exceeded": Status.MAX_ITER,
        "Maximum_CpuTime_Exceeded": Status.TIMEOUT,
        "Maximum_WallTime_Exceeded": Status.TIMEOUT,
        "Infeasible_Problem_Detected": Status.FAILED,
        "Search_Direction_Becomes_Too_Small": Status.FAILED,
        "Diverging_Iterates": Status.FAILED,
        "User_Requested_Stop": Status.FAILED,
        "Restoration_Failed": Status.FAILED,
        "Error_In_Step_Computation": Status.FAILED,
        "Not_Enough_Degrees_Of_Freedom": Status.FAILED,
        "Invalid_Number_Detected": Status.ERROR,
        "Invalid_Problem_Definition": Status.ERROR,
        "Invalid_Option": Status.ERROR,
        "Insufficient_Memory": Status.ERROR,
        "Internal_Error": Status.ERROR,
        "Unrecoverable_Exception": Status.ERROR,
        "NonIpopt_Exception_Thrown": Status.ERROR,
    }

    tol: float = option(1e-8, "Ipopt 'tol': scaled NLP error (KKT) tolerance", "Ipopt default 1e-8", check=positive())
    max_iter: int = option(3000, "Ipopt iteration cap", "Ipopt default 3000", check=at_least(1))
    hessian: str = option("auto", "'auto' (exact if problem.symbolic else limited-memory), 'exact' or "
                          "'limited-memory'", "", check=one_of("auto", "exact", "limited-memory"))
    bound_relax_factor: float = option(0.0, "Ipopt relaxes bounds by this factor; 0 keeps returned points exactly "
                                       "inside the bounds (Ipopt default 1e-8)", "problems/hs/hock_schittkowski.md",
                                       check=nonneg())
    mu_strategy: str = option("monotone", "barrier update: 'monotone' or 'adaptive'", "Ipopt default 'monotone'",
                              check=one_of("monotone", "adaptive"))

    def minimize(self, oracle: Oracle) -> SolverOutput:
        problem = oracle.problem
        exact = self.hessian == "exact" or (self.hessian == "auto" and problem.symbolic is not None)
        if exact and problem.symbolic is None:
            raise ValueError(f"ipopt: hessian='exact' needs problem.symbolic, which {problem.name} does not define")
        n, m_i, m_e = oracle.n, oracle.n_ineq, oracle.n_eq
        m = m_i + m_e
        errors: list[BaseException] = []
        dense = ca.Sparsity.dense
        sx, sp0 = dense(n, 1), ca.Sparsity(0, 1)

        def cons(x: np.ndarray) -> np.ndarray:
            x = x.ravel()
            return np.concatenate([oracle.ineq(x), oracle.eq(x)])

        def cons_jac(x: np.ndarray) -> np.ndarray:
            x = x.ravel()
            return np.vstack([oracle.ineq_jac(x), oracle.eq_jac(x)])

        keep = [  # Callbacks must outlive the solver call
            _PyFunction("f", [sx], [dense(1, 1)], lambda x: [oracle.f(x.ravel())], errors,
                        jac=lambda x: oracle.grad(x).reshape(1, -1)),
            _PyFunction("grad_f", [sx, sp0], [dense(1, 1), sx],
                        lambda x, p: list(oracle.f_and_grad(x.ravel())), errors),
        ]
        xs = ca.MX.sym("x", n)
        nlp: dict[str, Any] = {"x": xs, "f": keep[0](xs)}
        opts: dict[str, Any] = {
            "grad_f": keep[1],
            "print_time": False,
            "verbose_init": False,
            "show_eval_warnings": False,
            "ipopt": {
                "print_level": 0,
                "sb": "yes",
                "tol": self.tol,
                "max_iter": self.max_iter,
                "bound_relax_factor": self.bound_relax_factor,
                "mu_strategy": self.mu_strategy,
            },
        }
        if m:
            keep.append(_PyFunction("g", [sx], [dense(m, 1)], lambda x: [cons(x)], errors, jac=cons_jac))
            keep.append(_PyFunction("jac_g", [sx, sp0], [dense(m, 1), dense(m, n)],
                                    lambda x, p: [cons(x), cons_jac(x)], errors))
            nlp["g"] = keep[2](xs)
            opts["jac_g"] = keep[3]
        if exact:
            hfun = _hessian_function(problem)

            def hess(x: np.ndarray, p: np.ndarray, lam_f: np.ndarray, lam_g: np.ndarray) -> list[np.ndarray]:
                oracle.count_hessian()
                return [np.asarray(hfun(x.ravel(), lam_f.item(), lam_g.ravel()), dtype=float)]

            keep.append(_PyFunction("hess_lag", [sx, sp0, dense(1, 1), dense(m, 1)], [ca.Sparsity.upper(n)],
                                    hess, errors))
            opts["hess_lag"] = keep[-1]
        else:
            opts["ipopt"]["hessian_approximation"] = "limited-memory"
        keep.append(_StopOnError(n, m, errors))
        opts["iteration_callback"] = keep[-1]
        solver = ca.nlpsol(_casadi_name("ipopt", problem.name), "ipopt", nlp, opts)
        # x0 as given: Ipopt pushes it inside the bounds itself (bound_push), by design
        args: dict[str, Any] = {"x0": oracle.x0, "lbx": oracle.lower, "ubx": oracle.upper}
        if m:
            args["lbg"] = np.concatenate([np.full(m_i, -np.inf), np.zeros(m_e)])
            args["ubg"] = np.zeros(m)
        try:
            sol = solver(**args)
            x = np.asarray(sol["x"], dtype=float).ravel()
        except RuntimeError:
            x = None
        if errors:  # a budget or a problem error inside a callback is the real story
            budget = [e for e in errors if isinstance(e, BudgetExhausted)]
            raise budget[0] if budget else errors[0]
        stats = solver.stats()
        rs = str(stats.get("return_status", "unknown"))
        if x is None:
            x = oracle.last_x
        status = self.STATUS_MAP.get(rs, Status.FAILED)
        return SolverOutput(x, status, f"Ipopt: {rs}", nit=int(stats.get("iter_count", 0)),
                            extra={"native_status": rs, "hessian": "exact" if exact else "limited-memory"})
