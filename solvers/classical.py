"""The comparison methods of thesis Tables 2.1-2.2: SD, Fletcher-Reeves, Polak-Ribiere.

The thesis ran them with the CG+ Fortran code of Gilbert & Nocedal (1992) [111] and its
Moré-Thuente line search [112] (Section 2.5); SD is "CG+ with the search direction
modified to the steepest descent direction". This module follows CG+ (routine CGFAM):

* first trial step 1/||grad f(x0)||, afterwards the Shanno-Phua step
  alpha_k = alpha_{k-1} (g_{k-1}^T d_{k-1}) / (g_k^T d_k) (1 after a restart);
* line search CVSMOD: Moré-Thuente with ftol = 1e-4, gtol = 0.1, xtol = 1e-17,
  stpmin = 1e-20, stpmax = 1e20, at most 40 trials, and CG+'s modification that a
  step is accepted only after at least one interpolation (two trials) - this is why
  the thesis's N^fg is about 2 N^it + 1. The safeguarded interpolation step is SciPy's
  MINPACK-2 ``dcstep`` (scipy.optimize._dcsrch);
* PR variants: if the new direction is not a descent direction, the line search
  continues (at most 5 times), as CG+ does; ``positive=True`` is CG+'s PR+ (method 3);
* optional restarts every n iterations (CG+'s IREST = 1);
* a line-search failure ends the run (CG+ IFLAG = -1) with status ``failed``.

Stopping follows the thesis's Algorithm 2.1: ||grad f|| < eps_g or ||x^k - x^{k-1}|| < eps_x.
N^it (``nit``) is the number of line searches; N^fg is measured by the oracle.
"""

from __future__ import annotations

import dataclasses
from typing import Any, ClassVar

import numpy as np
from scipy.optimize._dcsrch import dcstep  # MINPACK-2 safeguarded cubic/quadratic step

from problems import Oracle

from ._base import AbstractSolver, at_least, final, nonneg, option
from ._result import SolverOutput, Status

__all__ = ["AbstractCGPlus", "SteepestDescent", "FletcherReeves", "PolakRibiere", "MoreThuenteSearch"]

XTRAPF = 4.0  # CVSMOD extrapolation factor
P5, P66 = 0.5, 0.66


class MoreThuenteSearch:
    """CG+'s CVSMOD line search on phi(stp) = f(x + stp d), resumable.

    ``phi(stp) -> (f, dphi)`` evaluates the function and its directional derivative.
    `start` initialises a search; `run` iterates until an exit code ``info``:
    1 Wolfe conditions hold (after at least two trials), 2 interval below xtol,
    3 maxfev trials, 4 stp = stpmin, 5 stp = stpmax, 6 rounding errors, 0 bad input.
    After ``info = 1`` the search can be continued with `run` (CG+ does so for PR
    when the new direction is not a descent direction).
    """

    def __init__(self, phi, ftol: float, gtol: float, xtol: float, stpmin: float, stpmax: float, maxfev: int):
        self.phi, self.ftol, self.gtol, self.xtol = phi, ftol, gtol, xtol
        self.stpmin, self.stpmax, self.maxfev = stpmin, stpmax, maxfev

    def start(self, stp: float, f0: float, dg0: float) -> int:
        if stp <= 0 or dg0 >= 0:
            return 0
        self.stp, self.f, self.dg = float(stp), f0, dg0
        self.brackt, self.stage1, self.nfev = False, True, 0
        self.finit, self.dginit, self.dgtest = f0, dg0, self.ftol * dg0
        self.width = self.stpmax - self.stpmin
        self.width1 = self.width / P5
        self.stx, self.fx, self.dgx = 0.0, f0, dg0
        self.sty, self.fy, self.dgy = 0.0, f0, dg0
        self._fresh = True
        return -1

    def _next_step(self) -> None:
        """Update the interval of uncertainty and choose the next trial (CVSMOD label 321)."""
        f, dg, stp = self.f, self.dg, self.stp
        ftest1 = self.finit + stp * self.dgtest
        if self.stage1 and f <= ftest1 and dg >= min(self.ftol, self.gtol) * self.dginit:
            self.stage1 = False
        if self.stage1 and f <= self.fx and f > ftest1:
            # modified function psi(stp) = f - stp*dgtest while no sufficient decrease yet
            dt = self.dgtest
            stx, fxm, dgxm, sty, fym, dgym, stp, brackt = dcstep(
                self.stx, self.fx - self.stx * dt, self.dgx - dt, self.sty, self.fy - self.sty * dt,
                self.dgy - dt, stp, f - stp * dt, dg - dt, self.brackt, self.stmin, self.stmax)
            self.fx, self.fy = fxm + stx * dt, fym + sty * dt
            self.dgx, self.dgy = dgxm + dt, dgym + dt
        else:
            stx, self.fx, self.dgx, sty, self.fy, self.dgy, stp, brackt = dcstep(
                self.stx, self.fx, self.dgx, self.sty, self.fy, self.dgy, stp, f, dg,
                self.brackt, self.stmin, self.stmax)
        self.stx, self.sty, self.stp, self.brackt = stx, sty, float(stp), bool(brackt)
        if self.brackt:  # force a sufficient decrease of the interval
            if abs(self.sty - self.stx) >= P66 * self.width1:
                self.stp = self.stx + P5 * (self.sty - self.stx)
            self.width1 = self.width
            self.width = abs(self.sty - self.stx)

    def run(self) -> int:
        """Iterate to the next exit; returns ``info`` (see class docstring)."""
        if not self._fresh:
            self._next_step()  # continuing after an exit
        self._fresh = False
        while True:
            if self.brackt:
                self.stmin, self.stmax = min(self.stx, self.sty), max(self.stx, self.sty)
            else:
                self.stmin, self.stmax = self.stx, self.stp + XTRAPF * (self.stp - self.stx)
            stp = min(max(self.stp, self.stpmin), self.stpmax)
            if ((self.brackt and (stp <= self.stmin or stp >= self.stmax)) or self.nfev >= self.maxfev - 1
                    or (self.brackt and self.stmax - self.stmin <= self.xtol * self.stmax)):
                stp = self.stx  # unusual termination: return to the best step so far
            self.stp = stp
            self.f, self.dg = self.phi(stp)
            self.nfev += 1
            if not (np.isfinite(self.f) and np.isfinite(self.dg)):
                return 7
            ftest1 = self.finit + stp * self.dgtest
            info = 0
            if self.brackt and (stp <= self.stmin or stp >= self.stmax):
                info = 6
            if stp == self.stpmax and self.f <= ftest1 and self.dg <= self.dgtest:
                info = 5
            if stp == self.stpmin and (self.f > ftest1 or self.dg >= self.dgtest):
                info = 4
            if self.nfev >= self.maxfev:
                info = 3
            if self.brackt and self.stmax - self.stmin <= self.xtol * self.stmax:
                info = 2
            # CG+ modification: accept only after at least one interpolation (nfev > 1)
            if self.f <= ftest1 and abs(self.dg) <= self.gtol * (-self.dginit) and self.nfev > 1:
                info = 1
            if info:
                return info
            self._next_step()


_LS_MESSAGES = {
    0: "line search: improper input (direction is not a descent direction)",
    2: "line search: relative width of the interval of uncertainty below xtol",
    3: "line search: maximum number of trials (maxfev) reached",
    4: "line search: step at the lower bound stpmin",
    5: "line search: step at the upper bound stpmax",
    6: "line search: rounding errors prevent further progress",
    7: "line search: non-finite function or derivative value",
}


@dataclasses.dataclass(frozen=True)
class AbstractCGPlus(AbstractSolver):
    """Common options and loop of the CG+ family (abstract: use SD, FR or PR)."""

    family = "thesis"
    handles = frozenset()
    beta_rule: ClassVar[str]

    eps_g: float = option(1e-5, "stop when ||grad f|| < eps_g", "Alg. 2.1 step 1, Sec. 2.5", check=nonneg())
    eps_x: float = option(1e-8, "stop when ||x^k - x^(k-1)|| < eps_x", "Alg. 2.1 step 3, Sec. 2.5", check=nonneg())
    max_iter: int = option(100_000, "cap on N^it (line searches)", "Tables 2.1-2.2 ('> N' rows)", check=at_least(1))
    max_fg: int | None = option(None, "cap on N^fg (checked before each line search); None = no cap",
                                "Tables 2.1-2.2 print '> N' in the N^fg column", check=at_least(1, or_none=True))
    ftol: float = option(1e-4, "sufficient-decrease parameter of the line search", "CG+ CGFAM (FTOL)")
    gtol: float = option(0.1, "curvature parameter of the line search", "CG+ CGFAM (GTOL)")
    xtol: float = option(1e-17, "relative interval tolerance of the line search", "CG+ CGFAM (XTOL)", check=nonneg())
    stpmin: float = option(1e-20, "smallest line-search step", "CG+ CGFAM (STPMIN)")
    stpmax: float = option(1e20, "largest line-search step", "CG+ CGFAM (STPMAX)")
    maxfev: int = option(40, "trials per line search", "CG+ CGFAM (MAXFEV)", check=at_least(2))
    restart: bool = option(False, "restart with steepest descent every n iterations", "CG+ IREST = 1")

    def check_together(self) -> None:
        if not 0 < self.ftol < self.gtol < 1:
            raise ValueError(f"{self.name}: need 0 < ftol < gtol < 1, got ftol={self.ftol}, gtol={self.gtol}")
        if not 0 < self.stpmin < self.stpmax:
            raise ValueError(f"{self.name}: need 0 < stpmin < stpmax, got {self.stpmin}, {self.stpmax}")

    def _beta(self, betafr: float, betapr: float) -> float:
        raise NotImplementedError

    def minimize(self, oracle: Oracle) -> SolverOutput:
        n = oracle.n
        x = oracle.x0
        f, g = oracle.f_and_grad(x)
        gnorm = float(np.linalg.norm(g))
        if gnorm < self.eps_g:
            return SolverOutput(x, Status.CONVERGED, "||grad f|| < eps_g", nit=0)
        d = -g
        stp1 = 1.0 / gnorm
        new, nrst, it = True, 0, 0
        dg0 = stp = 0.0
        base = {"x": x, "d": d}
        trial: dict[str, Any] = {}

        def phi(a: float) -> tuple[float, float]:
            xt = base["x"] + a * base["d"]
            ft, gt = oracle.f_and_grad(xt)
            trial.update(x=xt, f=ft, g=gt)
            return ft, float(gt @ base["d"])

        ls = MoreThuenteSearch(phi, self.ftol, self.gtol, self.xtol, self.stpmin, self.stpmax, self.maxfev)
        while True:
            if it >= self.max_iter:
                return SolverOutput(x, Status.MAX_ITER, f"max_iter = {self.max_iter} line searches reached", nit=it)
            if self.max_fg is not None and oracle.nfg >= self.max_fg:
                return SolverOutput(x, Status.MAX_ITER, f"N^fg cap max_fg = {self.max_fg} reached", nit=it)
            it += 1
            nrst += 1
            gold = g
            dg = float(d @ g)
            dgold = dg
            stp = 1.0 if new else dg0 / dg  # Shanno-Phua trial step
            if it == 1:
                stp = stp1
            new = False
            base["x"], base["d"] = x, d
            info = ls.start(stp, f, dg)
            ides = 0
            while True:
                if info != 0:
                    info = ls.run()
                if info != 1:
                    # CG+ stops (IFLAG = -1); keep the lower of the base and the last trial
                    if trial and trial["f"] < f:
                        x = trial["x"]
                    msg = _LS_MESSAGES.get(info, f"line search info = {info}")
                    return SolverOutput(x, Status.FAILED, msg, nit=it, extra={"ls_info": info})
                gn = trial["g"]
                gg = float(gn @ gn)
                betapr = (gg - float(gn @ gold)) / gnorm**2
                if self.restart and nrst > n:
                    nrst, new = 0, True
                    break
                if self.beta_rule != "pr":
                    break
                if -gg + betapr * ls.dg < 0:  # the PR direction is a descent direction
                    break
                ides += 1
                if ides > 5:
                    return SolverOutput(trial["x"], Status.FAILED, "descent was not obtained (CG+ IFLAG = -2)", nit=it)
            stp = ls.stp
            x_old, x, f, g = x, trial["x"], trial["f"], trial["g"]
            beta = 0.0 if nrst == 0 else self._beta(gg / gnorm**2, betapr)
            d = -g + beta * d
            dg0 = dgold * stp
            gnorm = float(np.sqrt(gg))
            if gnorm < self.eps_g:
                return SolverOutput(x, Status.CONVERGED, "||grad f|| < eps_g", nit=it)
            if float(np.linalg.norm(x - x_old)) < self.eps_x:
                return SolverOutput(x, Status.CONVERGED, "||x^k - x^(k-1)|| < eps_x", nit=it)


@final
@dataclasses.dataclass(frozen=True)
class SteepestDescent(AbstractCGPlus):
    """Steepest descent with the CG+ line search (thesis Sec. 2.5, Alg. 2.1)."""

    name = "sd"
    summary = "Steepest descent, CG+ Moré-Thuente line search (thesis Table 2.1)"
    beta_rule = "sd"

    def _beta(self, betafr: float, betapr: float) -> float:
        return 0.0


@final
@dataclasses.dataclass(frozen=True)
class FletcherReeves(AbstractCGPlus):
    """Fletcher-Reeves conjugate gradients as in CG+ (method 1)."""

    name = "fletcher-reeves"
    summary = "Fletcher-Reeves CG, CG+ method 1 (thesis Table 2.2)"
    beta_rule = "fr"

    def _beta(self, betafr: float, betapr: float) -> float:
        return betafr


@final
@dataclasses.dataclass(frozen=True)
class PolakRibiere(AbstractCGPlus):
    """Polak-Ribiere conjugate gradients as in CG+ (method 2; ``positive=True``: PR+, method 3)."""

    name = "polak-ribiere"
    summary = "Polak-Ribiere CG, CG+ method 2 (thesis Table 2.2)"
    beta_rule = "pr"

    positive: bool = option(False, "use beta = max(beta_PR, 0) (CG+ method 3, PR+)", "CG+ METHOD = 3")

    def _beta(self, betafr: float, betapr: float) -> float:
        return max(0.0, betapr) if self.positive else betapr
