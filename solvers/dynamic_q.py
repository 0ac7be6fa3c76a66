"""Dynamic-Q: successive spherical quadratic approximations solved by LFOPC (thesis Algorithm 3.2).

One outer iteration = one evaluation of f, g, h and all gradients at the iterate x^i
through the counting oracle (one N^fg, Section 3.4); the approximate subproblem P[i]
(eqs. 3.4-3.9, `solvers._spherical`) is solved by an LFOPC instance held as the field
``subsolver`` (composition), and its evaluations are not oracle calls.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from problems import Oracle

from ._base import AbstractSolver, option
from ._result import SolverOutput, Status
from ._spherical import SphericalSubproblem, two_point_curvature
from .lfopc import LFOPC

__all__ = ["DynamicQ"]

CLIPS = ("none", "sqsd", "saoi")
CENTRES = ("current", "literal")
NORMALIZE = ("cap", "unit", "none")
SQSD_C_MIN = 1e-60  # Algorithm 2.2: replacement for a negative curvature
SAOI_A_MIN = 1e-5  # SAOi defaults.f atol1
COMPROMISE_TOL = 1e-6  # a subproblem solution violating P[i]'s constraints by more is a compromise


def _finite(ev: dict[str, Any]) -> bool:
    return bool(
        np.isfinite(ev["f"]) and all(np.all(np.isfinite(ev[k])) for k in ("g", "ineq", "ineq_jac", "eq", "eq_jac"))
    )


@dataclasses.dataclass(frozen=True)
class DynamicQ(AbstractSolver):
    """The Dynamic-Q method, Algorithm 3.2 with termination (3.10)/(3.11).

    P[0] is linear; for i >= 1 the curvatures a, b_j, c_k interpolate f, g_j, h_k at
    x^{i-1} and x^i (eq. 3.6).  Bounds are exact (3.7); the move limit (3.8) is a
    sphere of radius rho.  x^{i+1} is the LFOPC solution of P[i], taken without line
    search or acceptance test.  Stops when ||x^i - x^{i-1}||/(1 + ||x^i||) < eps_x, or
    when x^i is feasible (every violation < eps_c) and
    |f^i - f_best|/(1 + |f_best|) < eps_f, f_best the lowest previous feasible f.
    """

    name = "dynamic-q"
    summary = "Dynamic-Q: spherical quadratic subproblems solved by LFOPC (thesis Alg. 3.2)"
    family = "thesis"
    handles = frozenset({"bounds", "ineq", "eq"})

    rho: float = option(1.0, "move limit (radius of the sphere (3.8))", "Sec. 3.4: rho = 1 for Table 3.1 [THESIS]")
    eps_f: float = option(1e-8, "normalized change of f from the best feasible f (3.11)", "Sec. 3.4 [THESIS]")
    eps_x: float = option(1e-5, "normalized step size (3.10)", "Sec. 3.4 [THESIS]")
    eps_c: float = option(1e-6, "feasibility: every constraint violation < eps_c", "Sec. 3.4 [THESIS]")
    step_stop_feasible: bool = option(True, "accept the step test (3.10) only at a feasible iterate "
                                      "(every violation < eps_c); False: (3.10) alone, as printed",
                                      "[OWN] (a 'converged' infeasible point is useless; affects e.g. HS106)")
    nonfinite_backtrack: int = option(5, "if f, g or h is non-finite at a new iterate, halve the step back "
                                      "towards x^(i-1) up to this many times (each is an oracle point)",
                                      "[OWN] (robustness on design problems with undefined regions)")
    max_iter: int = option(100, "maximum number of outer iterations (subproblems)",
                           "[OWN] (thesis: 'a maximum number of iterations', no value; HS13 ends on it at N^fg = 50)")
    subsolver: LFOPC = option(LFOPC(max_steps=2000), "LFOPC instance solving the subproblems (its delta is "
                              "replaced by sub_delta * rho); default: thesis LFOPC with a 2000-step cap per phase",
                              "Alg. 3.2 step 3 [THESIS]; App. B; step cap [OWN]")
    sub_delta: float = option(1.0, "LFOP step limit inside P[i] as a multiple of rho",
                              "[OWN] algorithms.md 4.3 (delta = rho; textbook delta = 1 is scale-blind)")
    curvature_clip: str = option("none", "'none' (3.6 as is), 'sqsd' (a < 0 -> 1e-60), "
                                 "'saoi' (a >= 1e-5, b_j >= 0)", "[OWN]; [SAOi] diaHess_sq1s; Alg. 2.2")
    move_centre: str = option("current", "'current' (x^c = x^i) or 'literal' (x^c = x^{i-1}, x^0 for i = 0)",
                              "eq. (3.8) text; resolution [OWN] algorithms.md 4.2")
    rho_reduction: bool = option(False, "halve rho when feasible f rises above f_best or steps reverse",
                                 "[OWN] algorithms.md 4.5 (off reproduces the thesis)")
    normalize_constraints: str = option("unit", "scale the approximate constraints of P[i] by 1/||grad|| at x^i: "
                                        "'unit' always, 'cap' only where ||grad|| > 1 (penalty stiffness at most "
                                        "~2 mu), 'none' (as printed); the move limit likewise by 1/(2 rho)",
                                        "[OWN] (same feasible set; keeps LFOPC's phase 1 within its step cap)")
    clip_to_bounds: bool = option(True, "project the subproblem solution onto the exact bounds (3.7)",
                                  "[OWN]: the bounds are exact, LFOPC's penalty leaves ~1e-9 excess")
    on_cap: str = option("best", "point returned when max_iter ends the run: 'best' = the best feasible "
                         "iterate (the least infeasible one if none is feasible), 'last' = the last iterate",
                         "[OWN]: the thesis is silent on the cap; its '$' runs report no point. 'last' is "
                         "the literal reading of Alg. 3.2; 'best' keeps a run that cycles near the optimum "
                         "from returning a worse point")

    def __post_init__(self) -> None:
        for k in ("rho", "sub_delta"):
            v = getattr(self, k)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"dynamic-q: {k} must be a positive finite number, got {v!r}")
        for k in ("eps_f", "eps_x", "eps_c"):
            v = getattr(self, k)
            if not (isinstance(v, (int, float)) and v >= 0):
                raise ValueError(f"dynamic-q: {k} must be >= 0, got {v!r}")
        if not (isinstance(self.max_iter, (int, np.integer)) and self.max_iter >= 1):
            raise ValueError(f"dynamic-q: max_iter must be an integer >= 1, got {self.max_iter!r}")
        if not (isinstance(self.nonfinite_backtrack, (int, np.integer)) and self.nonfinite_backtrack >= 0):
            raise ValueError(
                f"dynamic-q: nonfinite_backtrack must be an integer >= 0, got {self.nonfinite_backtrack!r}"
            )
        if not isinstance(self.subsolver, LFOPC):
            raise ValueError(f"dynamic-q: subsolver must be an LFOPC instance, got {type(self.subsolver).__name__}")
        if self.normalize_constraints not in NORMALIZE:
            raise ValueError(f"dynamic-q: normalize_constraints must be one of {NORMALIZE}, "
                             f"got {self.normalize_constraints!r}")
        if self.curvature_clip not in CLIPS:
            raise ValueError(f"dynamic-q: curvature_clip must be one of {CLIPS}, got {self.curvature_clip!r}")
        if self.move_centre not in CENTRES:
            raise ValueError(f"dynamic-q: move_centre must be one of {CENTRES}, got {self.move_centre!r}")
        if self.on_cap not in ("best", "last"):
            raise ValueError(f"dynamic-q: on_cap must be 'best' or 'last', got {self.on_cap!r}")

    # ------------------------------------------------------------------ helpers
    def _clip(self, a: float, b: np.ndarray) -> tuple[float, np.ndarray]:
        if self.curvature_clip == "sqsd":
            return (a if a >= 0.0 else SQSD_C_MIN), b
        if self.curvature_clip == "saoi":
            return max(a, SAOI_A_MIN), np.maximum(b, 0.0)
        return a, b

    @staticmethod
    def _violation(ev: dict[str, Any], x: np.ndarray, lo: np.ndarray, up: np.ndarray) -> float:
        v = max(float(np.max(lo - x, initial=0.0)), float(np.max(x - up, initial=0.0)))
        v = max(v, float(np.max(ev["ineq"], initial=0.0)), float(np.max(np.abs(ev["eq"]), initial=0.0)))
        return v

    # ------------------------------------------------------------------ algorithm
    def minimize(self, oracle: Oracle) -> SolverOutput:
        lo, up = oracle.lower, oracle.upper
        x = oracle.x0
        rho = float(self.rho)
        rho_floor = 1e-3 * rho
        prev: dict[str, Any] | None = None
        x_centre_prev = x  # x^{i-1} for move_centre = "literal" (x^0 at i = 0)
        f_best: float | None = None
        curv = (0.0, np.zeros(oracle.n_ineq), np.zeros(oracle.n_eq))
        log: list[dict[str, Any]] = []
        n_sub_steps = 0
        step_prev: np.ndarray | None = None
        x_best, best_key = x, (1, math.inf, math.inf)  # (infeasible?, violation, f): smallest is best
        for i in range(self.max_iter + 1):
            # Step 1: evaluate everything at x^i (one N^fg)
            ev = oracle.evaluate(x)
            n_back = 0
            while not _finite(ev) and prev is not None and n_back < self.nonfinite_backtrack:
                # [OWN] a subproblem solution where the problem is undefined (e.g. a degenerate
                # design): halve the step back towards x^{i-1}; each retry is one oracle point
                x = prev["x"] + 0.5 * (x - prev["x"])
                ev = oracle.evaluate(x)
                n_back += 1
            if not _finite(ev):
                return SolverOutput(prev["x"] if prev else x, Status.ERROR,
                                    f"non-finite f, gradient or constraint at iterate {i}", nit=i,
                                    extra=self._extra(log, n_sub_steps, f_best))
            f = ev["f"]
            viol = self._violation(ev, x, lo, up)
            feasible = viol < self.eps_c
            rec = {"i": i, "f": f, "max_violation": viol, "rho": rho, "n_backtracks": n_back}
            log.append(rec)
            if prev is not None:
                # Termination (3.10), (3.11)
                step = float(np.linalg.norm(x - prev["x"]))
                if step / (1.0 + float(np.linalg.norm(x))) < self.eps_x and (feasible or not self.step_stop_feasible):
                    return SolverOutput(x, Status.CONVERGED, "normalized step < eps_x (3.10)", nit=i,
                                        extra=self._extra(log, n_sub_steps, f_best))
                if feasible and f_best is not None and abs(f - f_best) / (1.0 + abs(f_best)) < self.eps_f:
                    return SolverOutput(x, Status.CONVERGED, "normalized change of best feasible f < eps_f (3.11)",
                                        nit=i, extra=self._extra(log, n_sub_steps, f_best))
            if self.rho_reduction and prev is not None and rho > rho_floor:
                d_now = x - prev["x"]
                rising = feasible and f_best is not None and f > f_best
                reverse = step_prev is not None and float(d_now @ step_prev) < -0.5 * float(
                    np.linalg.norm(d_now) * np.linalg.norm(step_prev))
                if rising or reverse:
                    rho = max(0.5 * rho, rho_floor)
                step_prev = d_now
            if feasible and (f_best is None or f < f_best):
                f_best = f
            key = (0, 0.0, f) if feasible else (1, viol, f)
            if key < best_key:
                x_best, best_key = x, key
            if i == self.max_iter:
                break
            # Step 2: curvatures (3.6); P[0] linear
            if prev is not None:
                dx = prev["x"] - x
                if float(dx @ dx) > 0.0:
                    a = float(two_point_curvature(np.array([prev["f"]]), np.array([f]), ev["g"][None, :], dx)[0])
                    b = two_point_curvature(prev["ineq"], ev["ineq"], ev["ineq_jac"], dx)
                    c = two_point_curvature(prev["eq"], ev["eq"], ev["eq_jac"], dx)
                    a, b = self._clip(a, b)
                    curv = (a, b, c)
                # zero step (only possible with eps_x = 0): keep the previous curvatures
            rec.update(a=curv[0])
            centre = x if self.move_centre == "current" else x_centre_prev
            sub = self._subproblem(x, ev, curv, lo, up, centre, rho)
            # Step 3: solve P[i] with LFOPC from x^i
            solver = dataclasses.replace(self.subsolver, delta=self.sub_delta * rho)
            res = solver.solve_form(sub, x)
            n_sub_steps += res.ng
            rec.update(sub_ng=res.ng, sub_reasons=[ph.reason for ph in res.phases], sub_active=res.active.count,
                       sub_violation=float(res.max_violation))
            x_new = res.x
            if self.clip_to_bounds:
                x_new = np.clip(x_new, lo, up)
            # Step 4
            x_centre_prev = x
            prev = {"x": x, "f": f, "ineq": ev["ineq"], "eq": ev["eq"]}
            x = x_new
        if self.on_cap == "best":
            x = x_best
        return SolverOutput(x, Status.MAX_ITER, f"max_iter = {self.max_iter} outer iterations reached"
                            f" (returned: {self.on_cap} iterate)",
                            nit=self.max_iter, extra=self._extra(log, n_sub_steps, f_best))

    def _subproblem(self, x, ev, curv, lo, up, centre, rho) -> SphericalSubproblem:
        """P[i] (3.9); with ``normalize_constraints`` g~_j, h~_k are divided by ||grad|| (see the option)."""
        g0, Jg, b = ev["ineq"], ev["ineq_jac"], curv[1]
        h0, Jh, c = ev["eq"], ev["eq_jac"], curv[2]
        ms = 1.0
        if self.normalize_constraints != "none":
            floor = 1.0 if self.normalize_constraints == "cap" else 1e-12
            sg = 1.0 / np.maximum(np.linalg.norm(Jg, axis=1), floor)
            sh = 1.0 / np.maximum(np.linalg.norm(Jh, axis=1), floor)
            g0, Jg, b = g0 * sg, Jg * sg[:, None], b * sg
            h0, Jh, c = h0 * sh, Jh * sh[:, None], c * sh
            ms = 1.0 / max(2.0 * rho, floor)
        return SphericalSubproblem(x, ev["g"], curv[0], g0, Jg, b, h0, Jh, c, lo, up, centre, rho, ms)

    @staticmethod
    def _extra(log: list[dict[str, Any]], n_sub_steps: int, f_best: float | None) -> dict[str, Any]:
        # P[i] with no point meeting its approximate constraints: LFOPC returns its best compromise
        # (App. B), so x^{i+1} reduces the violation of the model, not f
        n_comp = sum(1 for r in log if r.get("sub_violation", 0.0) > COMPROMISE_TOL)
        return {"n_subproblems": max(len(log) - 1, 0), "n_compromise_subproblems": n_comp,
                "n_sub_steps": n_sub_steps, "f_best": f_best, "iterations": log}
