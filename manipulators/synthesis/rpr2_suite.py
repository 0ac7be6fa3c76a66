"""Suite ``rpr2``: dimensional synthesis of the 2-RPR manipulator (thesis Chapter 4).

Problems (ordinary `problems.Problem`s of the design vector d, derivatives by finite
differences with the thesis's scheme and interval):

* ``rpr2-o``: O synthesis (4.8), min 0.5 dW_p + 0.5 dW_c, d = [xA, yA, xB, l1min, l2min],
  l_max = 1.5 l_min, starts SP1-SP4 (Table 4.2), chord 0.5, forward differences
  Gamma = 1e-5 (Section 4.5.2). Unconstrained.
* ``rpr2-e``: E synthesis (4.14), min dW_c s.t. h = dW_p = 0, same design and starts,
  chord 0.1, Gamma = 1e-3 (Section 4.6.2).
* ``rpr2-p1``, ``-p2``, ``-p3``: P synthesis (4.21) for P1-P3: max min_{dP} kappa^-1,
  written as min f = -min kappa^-1, s.t. g(d) <= 0 (4.16), d = [xA, yA, xB], l in [4, 7],
  start [-4, -0.1, 4], chord 0.1 (Section 4.7.3). kappa^-1 is minimized over 2048 equally
  spaced points of the prescribed boundary; the thesis uses the points b_p^i at the polar
  angles of the computed boundary points (Section 4.7.2), which move with the
  discretization; `evaluate` reports both (they differ by ~1e-5).

dW_p, dW_c and g use the thesis's triangle scheme (eq. 4.9) on the chord workspace, checked
(`objectives.delta_areas_checked` [OWN]): where the computed boundary does not wind around
W_p's centre the scheme cannot measure the areas, and the polygon differences of the same
chord boundary are used. Without the check,
designs whose workspace lies beside W_p have h = dW_p = 0 and dW_c < 0.5, below the exact
problem's optimum 2.31, and the better optimizers converged there with W_p entirely
uncovered. `evaluate` also returns the exact values (shapely, exact annulus geometry).

Infeasible designs never raise: a design with no workspace above the base line, or an
invalid one (l_min <= 0, xA == xB, non-finite), has the *empty* workspace, so
dW_c = 0, dW_p = area(W_p) and g = area(W_p) > 0: the natural continuation of the
objective, not an arbitrary penalty. A P-synthesis design with xA == xB has kappa^-1 = 0.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from problems import Case, Problem, Suite

from ..objectives import (
    delta_areas_checked,
    delta_areas_exact,
    enclosure_constraint,
    min_inverse_condition,
    polar_angles,
)
from ..prescribed import P1, PRESCRIBED, Prescribed
from ..rpr2 import RPR2, inverse_condition
from ..workspace import Workspace
from ._arguments import chord_length, lookup
from ._design_cache import DesignCache

__all__ = ["SUITE", "STARTS", "P_START", "design_o", "design_p", "o_problem", "e_problem", "p_problem",
           "evaluate", "SETTINGS"]

# Table 4.2: O/E synthesis starting designs d0 = [xA, yA, xB, l1min, l2min]
STARTS = {
    "SP1": (-2.0, -0.075, 2.0, 3.0, 3.0),
    "SP2": (-4.0, -1.0, 4.0, 5.0, 5.0),
    "SP3": (-1.0, -1.0, 4.0, 3.0, 5.0),
    "SP4": (-5.0, -1.0, 1.0, 5.0, 3.0),
}
P_START = (-4.0, -0.1, 4.0)  # Section 4.7.3, d0 for P1-P3
P_LIMITS = ((4.0, 4.0), (7.0, 7.0))  # l_i^min = 4, l_i^max = 7 (Section 4.7.3)
LMAX_RATIO = 1.5  # l_i^max = 1.5 l_i^min (Section 4.5.2)

# Settings stated in the text (problems/reference/thesis_tables/run_settings.csv):
SETTINGS: dict[str, dict[str, Any]] = {
    "o": dict(chord=0.5, fd="forward", fd_step=1e-5, eps_f=1e-6, eps_x=1e-4, eps_g=1e-3, rho=0.2),  # 4.5.2
    # 4.6.2: chord 0.1, Gamma 1e-3, eps_f 1e-6, eps_x 1e-4; difference scheme and rho not
    # stated -> forward (as in 4.5.2) and rho = 0.2 (as in 4.5.2 and 4.7.3) [OWN]
    "e": dict(chord=0.1, fd="forward", fd_step=1e-3, eps_f=1e-6, eps_x=1e-4, rho=0.2),
    # 4.7.3: chord 0.1, rho 0.2, eps_f 1e-4, eps_x 1e-3; Gamma and scheme not stated ->
    # forward, 1e-3 (as in 4.6.2, the other d = 0.1 experiment) [OWN]
    "p": dict(chord=0.1, fd="forward", fd_step=1e-3, eps_f=1e-4, eps_x=1e-3, rho=0.2),
}

SOLVERS = ("sqsd", "lfopc", "etopc", "dynamic-q", "dynamic-q-plus", "scipy-slsqp", "ipopt", "nlopt-mma", "scipy-cobyla")


# ------------------------------------------------------------------ arguments
def _chord(chord: Any, kind: str, where: str) -> float:
    return chord_length(chord, SETTINGS[kind]["chord"], where)


def _start(start: Any, where: str) -> tuple[float, ...]:
    return lookup(STARTS, start, "start (Table 4.2)", where)


def _prescribed(prescribed: Any, where: str) -> Prescribed:
    """A `Prescribed` workspace, or its name (``"P1"``)."""
    return prescribed if isinstance(prescribed, Prescribed) else lookup(PRESCRIBED, prescribed,
                                                                         "prescribed workspace", where)


def _design(d: Any, n: int, names: str) -> np.ndarray:
    d = np.asarray(d, dtype=float)
    if d.shape != (n,):
        raise ValueError(f"design vector d must have shape ({n},) = [{names}], got shape {d.shape}")
    return d


# ------------------------------------------------------------------ designs
def design_o(d) -> RPR2 | None:
    """The O/E-synthesis design (4.13): l_max = 1.5 l_min; None if invalid."""
    d = _design(d, 5, "xA, yA, xB, l1_min, l2_min")
    try:
        lo = (d[3], d[4])
        return RPR2(d[0], d[1], d[2], l_min=lo, l_max=(LMAX_RATIO * lo[0], LMAX_RATIO * lo[1]))
    except ValueError:
        return None


def design_p(d) -> RPR2 | None:
    """The P-synthesis design d = [xA, yA, xB] with l in [4, 7]; None if invalid."""
    d = _design(d, 3, "xA, yA, xB")
    try:
        return RPR2(d[0], d[1], d[2], l_min=P_LIMITS[0], l_max=P_LIMITS[1])
    except ValueError:
        return None


class _Workspaces:
    """Chord workspaces of recent designs (objective and constraints at one point share one)."""

    def __init__(self, build: Callable[[np.ndarray], RPR2 | None], chord: float, size: int = 16):
        self.build, self.chord = build, chord
        self._memo: DesignCache[tuple[RPR2 | None, Workspace]] = DesignCache(size)

    def __call__(self, d) -> tuple[RPR2 | None, Workspace]:
        return self._memo.get(d, self._compute)

    def _compute(self, d: np.ndarray) -> tuple[RPR2 | None, Workspace]:
        m = self.build(d) if np.all(np.isfinite(d)) else None
        if m is None:
            return m, Workspace.empty(reason="invalid design")
        try:
            return m, m.workspace(self.chord, on_open="raise")  # an open trace is a failed one
        except Exception as exc:  # noqa: BLE001  (never crash mid-run; the design counts as empty)
            return m, Workspace.empty(reason=f"chord method failed: {exc}")


# ------------------------------------------------------------------ problems
def o_problem(start: str = "SP1", prescribed: Prescribed | str = P1, chord: float | None = None) -> Problem:
    """O synthesis (4.8): min 0.5 dW_p + 0.5 dW_c (triangle scheme), unconstrained."""
    s = SETTINGS["o"]
    x0, prescribed = _start(start, "o_problem"), _prescribed(prescribed, "o_problem")
    ws = _Workspaces(design_o, _chord(chord, "o", "o_problem"))

    def f(d):
        _, w = ws(d)
        dwp, dwc = delta_areas_checked(w, prescribed)
        return 0.5 * dwp + 0.5 * dwc

    return Problem(name=f"rpr2-o-{start}", x0=x0, objective=f, fd=s["fd"], fd_step=s["fd_step"],
                   source="Hay 2003, Sec. 4.5, eq. (4.8)", tags=("manipulator", "rpr2", "O"),
                   meta={"prescribed": prescribed.name, "chord": ws.chord, "kind": "o"})


def e_problem(start: str = "SP1", prescribed: Prescribed | str = P1, chord: float | None = None) -> Problem:
    """E synthesis (4.14): min dW_c subject to h = dW_p = 0 (triangle scheme)."""
    s = SETTINGS["e"]
    x0, prescribed = _start(start, "e_problem"), _prescribed(prescribed, "e_problem")
    ws = _Workspaces(design_o, _chord(chord, "e", "e_problem"))
    memo: DesignCache[tuple[float, float]] = DesignCache(16)  # f and h at one design share the areas

    def areas(d) -> tuple[float, float]:
        return memo.get(d, lambda x: delta_areas_checked(ws(x)[1], prescribed))

    return Problem(name=f"rpr2-e-{start}", x0=x0,
                   objective=lambda d: areas(d)[1],
                   eq=lambda d: np.array([areas(d)[0]]),
                   fd=s["fd"], fd_step=s["fd_step"], n_eq=1,
                   source="Hay 2003, Sec. 4.6, eq. (4.14)", tags=("manipulator", "rpr2", "E"),
                   meta={"prescribed": prescribed.name, "chord": ws.chord, "kind": "e"})


def _p_objective(d, w: Workspace | None, prescribed: Prescribed) -> float:
    """-min kappa^-1 over the prescribed boundary.

    ``w`` given: at the points b_p^i at the polar angles beta_c^i of the computed boundary
    (the thesis's evaluation, Section 4.7.2); ``w`` None: at 2048 equally spaced angles
    (what the suite minimizes: a fixed sample makes f a smooth function of d, while the
    beta_c^i move with the discretization; the two differ by ~1e-5 at d = 0.1).
    """
    beta = polar_angles(w.boundary, prescribed.centre)[0] if w is not None and w.n_boundary >= 3 else None
    d = np.asarray(d, dtype=float)
    val = min_inverse_condition(lambda U: inverse_condition(d[0], d[1], d[2], U), prescribed, beta)
    return -val if math.isfinite(val) else 1.0


def p_problem(prescribed: Prescribed | str = "P1", chord: float | None = None) -> Problem:
    """P synthesis (4.21): min -min kappa^-1 subject to g(d) <= 0 (4.16)."""
    P = _prescribed(prescribed, "p_problem")
    s = SETTINGS["p"]
    ws = _Workspaces(design_p, _chord(chord, "p", "p_problem"))

    def f(d):
        return _p_objective(d, None, P)

    def g(d):
        w = ws(d)[1]
        return np.array([enclosure_constraint(w, P, delta_areas_checked(w, P)[0])])

    return Problem(name=f"rpr2-p{P.name[-1]}", x0=P_START, objective=f, ineq=g, n_ineq=1,
                   fd=s["fd"], fd_step=s["fd_step"],
                   source="Hay 2003, Sec. 4.7, eq. (4.21)", tags=("manipulator", "rpr2", "P"),
                   meta={"prescribed": P.name, "chord": ws.chord, "kind": "p"})


# ------------------------------------------------------------------ evaluation for tables
def evaluate(kind: str, d, prescribed: Prescribed | str = "P1", chord: float | None = None,
             exact: bool = True) -> dict[str, Any]:
    """Every quantity of a design, discretized (as minimized) and exact (shapely).

    Returns a dict with ``f`` (the thesis's objective: O: 0.5 dW_p + 0.5 dW_c; E: dW_c;
    P: min kappa^-1, positive), ``dwp``, ``dwc``, ``g`` (4.16), ``h``, ``n_b`` (boundary
    points) and, if ``exact``, ``f_exact``, ``dwp_exact``, ``dwc_exact``, ``kinv_exact``
    (dense min over the prescribed boundary), ``enclosed`` (exact dW_p <= 1e-4 area(W_p)).
    """
    P = _prescribed(prescribed, "evaluate")
    k = kind.lower() if isinstance(kind, str) else kind
    if k not in SETTINGS:
        raise ValueError(f"kind must be one of 'o', 'e', 'p', got {kind!r}")
    build = design_p if k == "p" else design_o
    d = _design(d, 3 if k == "p" else 5, "xA, yA, xB" if k == "p" else "xA, yA, xB, l1_min, l2_min")
    m, w = _Workspaces(build, _chord(chord, k, "evaluate"))(d)
    dwp, dwc = delta_areas_checked(w, P)
    out: dict[str, Any] = {"dwp": dwp, "dwc": dwc, "g": enclosure_constraint(w, P, dwp), "h": dwp,
                           "n_b": w.n_boundary, "area": w.area}
    out["f"] = {"o": 0.5 * dwp + 0.5 * dwc, "e": dwc, "p": -_p_objective(d, None, P)}[k]
    if k == "p":
        out["f_thesis_points"] = -_p_objective(d, w, P)
    if exact:
        if m is None:
            dwp_x, dwc_x = float(P.area()), 0.0
        else:
            dwp_x, dwc_x = delta_areas_exact(m.exact_region(), P)
        out.update(dwp_exact=dwp_x, dwc_exact=dwc_x, enclosed=bool(dwp_x <= 1e-4 * P.area()))
        dd = np.asarray(d, dtype=float)
        kinv = min_inverse_condition(lambda U: inverse_condition(dd[0], dd[1], dd[2], U), P)
        out["kinv_exact"] = kinv
        out["f_exact"] = {"o": 0.5 * dwp_x + 0.5 * dwc_x, "e": dwc_x, "p": kinv}[k]
    return out


# ------------------------------------------------------------------ the suite
def _caps(kind: str) -> dict[str, dict[str, Any]]:
    """Per-solver settings: the thesis's tolerances where a solver has them, and caps that
    keep every run of the suite within its time budget (each evaluation is a workspace)."""
    s = SETTINGS[kind]
    general = {k: s[k] for k in ("eps_f", "eps_x", "eps_g", "rho") if k in s}
    opts: dict[str, dict[str, Any]] = {"*": general}
    # "where applicable, move limits were set to rho = 0.2" (4.5.2): LFOP's step limit and
    # ETOP's largest step along a direction
    opts["lfopc"] = {"delta": s["rho"], "max_steps": 400}
    opts["etopc"] = {"max_step": s["rho"]}
    # caps: about 3x the thesis's largest count for the same formulation (Tables 4.3-4.7:
    # N^g <= 509 for O, <= 573 for E, 12 for P), so that the suite fits in 10 minutes
    opts["sqsd"] = {"max_iter": 600}
    # (3.10) as printed, without our feasibility condition: Table 4.7's h* = 1e-3..7e-3 > 0
    # shows the thesis's Dynamic-Q stopped at infeasible iterates (with it, E never stops
    # before the cap; O is unconstrained and P gives the same runs either way)
    opts["dynamic-q"] = {"max_iter": {"o": 300, "e": 400, "p": 100}[kind], "step_stop_feasible": False}
    opts["scipy-cobyla"] = {"rhobeg": s["rho"], "tol": s["eps_x"], "maxfev": 600}
    opts["scipy-slsqp"] = {"maxiter": 100 if kind == "o" else 40}
    opts["ipopt"] = {"max_iter": 100 if kind == "o" else 40}
    opts["nlopt-mma"] = {"maxeval": 300}
    return opts


def _build() -> list[Case]:
    cases: list[Case] = []
    for sp in STARTS:
        cases.append(Case(o_problem(sp), "rpr2-o", start=sp, options=_caps("o"),
                          meta={"table": {"SP1": "4.3", "SP2": "4.4", "SP3": "4.5", "SP4": "4.6"}[sp]}))
    for sp in STARTS:
        cases.append(Case(e_problem(sp), "rpr2-e", start=sp, options=_caps("e"), meta={"table": "4.7"}))
    for name in ("P1", "P2", "P3"):
        cases.append(Case(p_problem(name), f"rpr2-p{name[-1]}", start="d0", options=_caps("p"),
                          meta={"table": "4.9", "prescribed": name}))
    return cases


SUITE = Suite(
    name="rpr2",
    description="2-RPR dimensional synthesis (thesis Ch. 4): O (Tables 4.3-4.6), E (4.7), P (4.9)",
    build=_build,
    solvers=SOLVERS,
    tables="harness.tables.rpr2",
    figures="harness.figures.rpr2",
)
