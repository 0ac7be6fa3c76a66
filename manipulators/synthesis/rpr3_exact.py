"""The exact model of the 3-RPR syntheses: an analysis of the ``rpr3`` suite, not a problem of it.

`exact_optimum` solves SO/MO/D synthesis without the chord method (leg limits on W_p's
boundary, kappa^-1 on the slices) by differential evolution and multistart SLSQP: about
75 s for the nine cases.  The tables never call it: `reference` computes the nine optima
once and ``python -m harness reference --suite rpr3`` (or ``harness run``) stores them in
``results/rpr3/reference.json`` (docs/harness.md, "Stored references").
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .rpr2_exact import _jsonable
from .rpr3_suite import PRESCRIBED3, SETTINGS, _thesis_row, design, exact_enclosure

__all__ = ["GLOBAL_BOX", "exact_constraints", "exact_optimum", "reference", "N_STARTS", "CASES"]

#: starts of the local stage used for the tables
N_STARTS = 40
CASES = tuple((k, p) for k in ("so", "mo", "d") for p in ("P1", "P2", "P3"))

#: Box of the global stage of `exact_optimum` ([x_C, y_C, x_D, x_E, r]): it holds every design of
#: Tables 5.3-5.5 (the thesis's d* and every solver's) with a wide margin.
GLOBAL_BOX = ((-3.0, 1.0), (-1.0, 1.2), (-1.0, 3.5), (-1.0, 3.5), (0.05, 2.0))


def _slices(kind: str):
    """Slices on which the leg limits are imposed (D: 11 over the range) and those of kappa^-1 (5.39)."""
    s = SETTINGS[kind]
    phis = np.linspace(min(s["phis"]), max(s["phis"]), 11) if s["dextrous"] else np.asarray(s["phis"])
    kphis = np.array([min(s["phis"]), max(s["phis"])]) if s["dextrous"] else phis
    return phis, kphis


def exact_constraints(kind: str, prescribed: str = "P1", k: int = 96):
    """``cons(z) >= 0`` of the exact SO/MO/D model, z = [x_C, y_C, x_D, x_E, r, t] (eq. 5.36 and t).

    Rows: minus every leg-length excess beyond its limits at ``k`` points of W_p's boundary
    on every slice of `_slices` (7 per point and slice: `RPR3.constraints`), then
    kappa^-1 - t at the same points on the kappa slices (5.39).  An invalid design (`design`
    is None) gives -1 in every row.  Together they say exactly: W_p inside every required
    constant-orientation workspace and min kappa^-1 >= t (see `exact_optimum`).
    """
    if kind.lower() not in SETTINGS:
        raise ValueError(f"unknown synthesis {kind!r}; valid: {', '.join(SETTINGS)}")
    if prescribed not in PRESCRIBED3:
        raise ValueError(f"unknown prescribed workspace {prescribed!r}; valid: {', '.join(PRESCRIBED3)}")
    phis, kphis = _slices(kind.lower())
    B = PRESCRIBED3[prescribed].points(k)
    n_c = k * 7 * len(phis) + k * len(kphis)

    def cons(z):
        m = design(z[:5])
        if m is None:
            return -np.ones(n_c)
        legs = np.concatenate([m.constraints(B, p).ravel() for p in phis])
        kv = np.concatenate([m.inverse_condition(B, p) for p in kphis])
        return np.concatenate([-legs, kv - z[5]])

    return cons


def exact_optimum(kind: str, prescribed: str = "P1", n_starts: int = 12, k: int = 96, seed: int = 0,
                  global_search: bool = True, de_maxiter: int = 150) -> dict[str, Any]:
    """The best design of the *exact* model, for the tables: no chord method, no g.

    W_p is enclosed in a constant-orientation workspace iff every leg length over W_p's
    boundary is within its limits (an annulus's hole, radius >= 1, cannot fit inside W_p)
    and W_p lies above the base line (the upper branch).  So SO/MO/D synthesis is,
    exactly, ``max t`` subject to ``t <= kappa^-1`` and those limits at ``k`` points of
    W_p's boundary on every slice (D: 11 slices over the range; kappa^-1 on the two range
    ends as in (5.39)) -- smooth constraints, solved by SciPy SLSQP from several starts:

    * global stage (``global_search``): SciPy's differential evolution over `GLOBAL_BOX`
      (fixed ``seed``, Sobol initial population of 75, ``de_maxiter`` generations, its
      feasibility-first constraint handling), on 32 boundary points per slice, max
      ``min kappa^-1`` s.t. the largest leg-limit excess <= 0; its best design starts an
      SLSQP polish on the full problem;
    * local stage: the suite's start, the thesis's d* of Tables 5.3-5.5 and ``n_starts``
      seeded perturbations of it.

    Returns the best d found whose constraints hold, its t (``kinv``), the global stage's
    own result (``de_kinv``, ``de_polished``), `exact_enclosure` of d and its exact
    enclosing orientations (`enclosing_window`): an independent reference for what any
    solver of the chord formulation can reach in our model.  Deterministic; a strong
    search, not a proof of global optimality.  Also ``local_d``, ``local_kinv``: the end
    of the SLSQP polish from the suite's start alone, the exact model's local optimum that
    a local method started there can be expected to reach (MO/D P1: 0.17, against the
    best 0.43 found by the multistart).
    """
    from scipy.optimize import NonlinearConstraint, differential_evolution, minimize

    s = SETTINGS[kind.lower()]
    P = PRESCRIBED3[prescribed]
    phis, kphis = _slices(kind.lower())
    cons = exact_constraints(kind, prescribed, k)

    def polish(x0, t0=0.5):
        res = minimize(lambda z: -z[5], np.append(x0, t0), jac=lambda z: np.r_[np.zeros(5), -1.0], method="SLSQP",
                       constraints=[{"type": "ineq", "fun": cons}], options={"maxiter": 200, "ftol": 1e-10})
        return res.x if cons(res.x).min() > -1e-7 else None

    best, glob = None, {}
    if global_search:
        Bg = P.points(32)
        gphis = phis[:: 2] if s["dextrous"] else phis  # D: 6 of the 11 slices

        def neg_kinv(d):
            m = design(d)
            return 0.0 if m is None else -min(float(m.inverse_condition(Bg, p).min()) for p in kphis)

        def excess(d):
            m = design(d)
            return 1.0 if m is None else max(float(m.constraints(Bg, p).max()) for p in gphis)

        de = differential_evolution(neg_kinv, GLOBAL_BOX, constraints=NonlinearConstraint(excess, -np.inf, 0.0),
                                    seed=seed, popsize=15, maxiter=de_maxiter, tol=1e-8, init="sobol",
                                    polish=False)
        glob = {"de_d": de.x, "de_kinv": -float(de.fun) if excess(de.x) <= 0 else float("nan")}
        z = polish(de.x, max(-float(de.fun), 0.0))
        glob["de_polished"] = float("nan") if z is None else float(z[5])
        best = z

    ref = _thesis_row(s["table"], prescribed)
    starts = [np.asarray(s["start"], float)] + ([ref["d_star"]] if ref else [])
    rng = np.random.default_rng(seed)
    centre = starts[-1]
    starts += [centre + rng.normal(0.0, 0.15, 5) * np.array([1, 0.5, 1, 1, 0.5]) for _ in range(n_starts)]
    local: dict[str, Any] = {"local_d": None, "local_kinv": float("nan")}
    for i, x0 in enumerate(starts):
        z = polish(x0)
        if i == 0 and z is not None:  # where a local method from the suite's start can end
            local = {"local_d": z[:5], "local_kinv": float(z[5])}
        if z is not None and (best is None or z[5] > best[5]):
            best = z
    if best is None:
        return {"d": None, "kinv": float("nan"), "enclosed": False, "ratio": float("nan"), **glob, **local}
    out = {"d": best[:5], "kinv": float(best[5]), **glob, **local}
    out.update(exact_enclosure(kind, best[:5], prescribed))
    return out


def reference(runs=None, stored: dict[str, Any] | None = None) -> dict[str, Any]:
    """The exact-model optimum of every case (``"so/P1"`` ...), as JSON-ready data; stored
    entries are kept (they depend on the code only, not on the runs)."""
    opt = dict((stored or {}).get("exact_optimum") or {})
    for kind, pname in CASES:
        key = f"{kind}/{pname}"
        if key not in opt:
            opt[key] = _jsonable(exact_optimum(kind, pname, n_starts=N_STARTS))
    return {"exact_optimum": opt}
