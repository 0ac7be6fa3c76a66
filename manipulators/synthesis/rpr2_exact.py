"""The exact E and P problems of the 2-RPR synthesis ((4.14), (4.21)): analyses of the ``rpr2``
suite, not problems of it.

The suite's E problem (`rpr2_suite.e_problem`) uses the thesis's chord method and triangle
scheme (4.9).  Here the same synthesis is written exactly and smoothly (closed-form areas,
leg limits on W_p's boundary) and solved by SciPy SLSQP: `exact_optimum` (a multistart)
and `exact_polish` (where the exact problem goes from a given d*).  Both are optimizations,
so the tables never call them: `reference` computes what Table 4.7 needs once, and
``python -m harness reference --suite rpr2`` (or ``harness run``) stores it in
``results/rpr2/reference.json`` (docs/harness.md, "Stored references").
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..prescribed import PRESCRIBED, Prescribed
from ..rpr2 import inverse_condition
from .rpr2_suite import LMAX_RATIO, P_LIMITS, P_START, STARTS, design_o

__all__ = ["EXACT_K", "KINV_K", "exact_e_problem", "exact_p_problem", "exact_polish", "exact_optimum",
           "thesis_e_designs", "reference", "design_key"]

EXACT_K = 512  # points of W_p's boundary at which the exact E and P problems' leg limits are imposed
KINV_K = 2048  # equally spaced boundary points of suite rpr2's P objective (`rpr2_suite._p_objective`)


def thesis_e_designs() -> dict[str, np.ndarray]:
    """Table 4.7's published d* per start (empty if the reference data are unavailable)."""
    try:
        from problems.reference import thesis_table

        t = thesis_table("table_4_7_E_synthesis")
    except Exception:  # noqa: BLE001  (reference data optional at run time)
        return {}
    return {r["start"]: np.array([float(r[c]) for c in ("x_A", "y_A", "x_B", "l1_min", "l2_min")])
            for _, r in t.iterrows()}


def exact_e_problem(prescribed: Prescribed | str = "P1", k: int = EXACT_K):
    """E synthesis (4.14) in exact, smooth form: ``(f, cons)`` for SciPy, each returning
    (value, derivative) of the design vector d = [xA, yA, xB, l1min, l2min] (l_max = 1.5 l_min).

    W_p is inside W_c iff (i) W_p lies above the base line, y_min(W_p) >= yA, and (ii) every
    leg length over W_p's boundary lies in [l_i^min, 1.5 l_i^min] (4.4, 4.13). (ii) suffices
    for the annuli because the far side of an annulus (unbounded) and its hole are each
    connected and, if they miss dW_p, lie wholly inside or wholly outside W_p: the far side
    is unbounded, so outside; the hole contains its pivot, which is on the base line and
    so, by (i), not an interior point of W_p (also: a hole of radius l_min ~ 5 cannot fit
    in P1, whose inscribed radius is < 1.2). Then h = dW_p = 0 and dW_c = area(W_c) -
    area(W_p), so (4.14) is exactly: min ``RPR2.exact_area`` - area(W_p) subject to ``cons``
    >= 0, the leg limits at ``k`` equally spaced boundary points (4k values) and (i).
    Both analytic: no chord method, no triangle scheme (4.9), no finite differences.
    """
    P = PRESCRIBED[prescribed] if isinstance(prescribed, str) else prescribed
    B = P.points(k)
    y_min = float(min(B[:, 1].min(), P.points(16 * k)[:, 1].min()))
    a_p = float(P.area())

    def f(d):
        m = design_o(d)
        if m is None:  # xA == xB or l_min <= 0: SLSQP's bounds keep l_min > 0
            return a_p, np.zeros(5)
        a, g = m.exact_area(grad=True)  # g by (xA, yA, xB, r1, r2, R1, R2), R = 1.5 r
        return a - a_p, np.array([g[0], g[1], g[2], g[3] + LMAX_RATIO * g[5], g[4] + LMAX_RATIO * g[6]])

    def cons(d):
        xA, yA, xB, r1, r2 = np.asarray(d, dtype=float)
        dy = B[:, 1] - yA
        l1, l2 = np.hypot(B[:, 0] - xA, dy), np.hypot(B[:, 0] - xB, dy)
        e1x, e1y, e2x, e2y = (B[:, 0] - xA) / l1, dy / l1, (B[:, 0] - xB) / l2, dy / l2
        z, one = np.zeros(k), np.ones(k)
        val = np.concatenate([l1 - r1, LMAX_RATIO * r1 - l1, l2 - r2, LMAX_RATIO * r2 - l2, [y_min - yA]])
        jac = np.vstack([np.column_stack([-e1x, -e1y, z, -one, z]),
                         np.column_stack([e1x, e1y, z, LMAX_RATIO * one, z]),
                         np.column_stack([z, -e2y, -e2x, z, -one]),
                         np.column_stack([z, e2y, e2x, z, LMAX_RATIO * one]),
                         [[0.0, -1.0, 0.0, 0.0, 0.0]]])
        return val, jac

    return f, cons


def exact_p_problem(prescribed: Prescribed | str = "P1", k: int = EXACT_K, k_kinv: int = KINV_K):
    """P synthesis (4.21) in exact, smooth (epigraph) form: ``cons(z) -> (value, jacobian)``,
    value >= 0 where the design z = [xA, yA, xB, t] is feasible (l in [4, 7], Section 4.7.3).

    Suite ``rpr2`` maximizes f(d) = min kappa^-1 over ``k_kinv`` equally spaced points of
    dP subject to g(d) <= 0 (4.16) on chord workspaces.  Here: max t subject to
    kappa^-1(b_i) - t >= 0 at those same points (eq. 4.23: kappa^-1 = (y - yA)(xB - xA) /
    (l1 l2), so t* equals the suite's f at an enclosing design), and P inside the exact
    workspace, stated as in `exact_e_problem`: every leg length at ``k`` points of dP within
    [4, 7] (4k rows) and P above the base line (one row).  Rows: k_kinv + 4k + 1, all with
    analytic derivatives.  A design with xA == xB has kappa^-1 = 0 (and finite derivatives).
    """
    P = PRESCRIBED[prescribed] if isinstance(prescribed, str) else prescribed
    B, U = P.points(k), _kinv_points(P, k_kinv)
    y_min = float(min(B[:, 1].min(), U[:, 1].min(), P.points(16 * k)[:, 1].min()))
    (lo, _), (hi, _) = P_LIMITS

    def cons(z):
        xA, yA, xB, t = np.asarray(z, dtype=float)
        # kappa^-1 = dy w / (l1 l2) at U and its derivatives, written without dividing by dy or w
        ux, dy = U[:, 0], U[:, 1] - yA
        a1, a2, w = ux - xA, ux - xB, xB - xA
        l1, l2 = np.hypot(a1, dy), np.hypot(a2, dy)
        kv = inverse_condition(xA, yA, xB, U)
        q = 1.0 / (l1 * l2)
        dk = np.column_stack([-dy * q + kv * a1 / l1**2,
                              -w * q + kv * dy * (1.0 / l1**2 + 1.0 / l2**2),
                              dy * q + kv * a2 / l2**2,
                              -np.ones(k_kinv)])
        bx, by = B[:, 0], B[:, 1] - yA
        m1, m2 = np.hypot(bx - xA, by), np.hypot(bx - xB, by)
        e1x, e1y, e2x, e2y = (bx - xA) / m1, by / m1, (bx - xB) / m2, by / m2
        zk = np.zeros(k)
        val = np.concatenate([kv - t, m1 - lo, hi - m1, m2 - lo, hi - m2, [y_min - yA]])
        jac = np.vstack([dk,
                         np.column_stack([-e1x, -e1y, zk, zk]), np.column_stack([e1x, e1y, zk, zk]),
                         np.column_stack([zk, -e2y, -e2x, zk]), np.column_stack([zk, e2y, e2x, zk]),
                         [[0.0, -1.0, 0.0, 0.0]]])
        return val, jac

    return cons


def _kinv_points(P: Prescribed, k_kinv: int) -> np.ndarray:
    """The ``k_kinv`` equally spaced points of dP over which suite rpr2 takes min kappa^-1."""
    return P.points_at(2 * np.pi * np.arange(k_kinv) / k_kinv)


def _lifted(d, U: np.ndarray) -> np.ndarray:
    """[xA, yA, xB, t] with t = min kappa^-1 of the design d over the points U: the kappa rows of
    `exact_p_problem` hold there, with equality at the minimizing point."""
    d = np.asarray(d, dtype=float)
    return np.append(d, float(inverse_condition(d[0], d[1], d[2], U).min()))


def p_start(prescribed: Prescribed | str = "P1", k_kinv: int = KINV_K) -> np.ndarray:
    """The exact P problem's start: Section 4.7.3's d0 with t = min kappa^-1 at d0 (the suite's
    f(d0)), so that it is exactly as feasible as d0 is."""
    P = PRESCRIBED[prescribed] if isinstance(prescribed, str) else prescribed
    return _lifted(P_START, _kinv_points(P, k_kinv))


def _slsqp(d0, f, cons, maxiter: int = 300, bounds=None):
    from scipy.optimize import minimize

    return minimize(lambda d: f(d)[0], np.asarray(d0, dtype=float), jac=lambda d: f(d)[1], method="SLSQP",
                    bounds=bounds or [(None, None)] * 3 + [(0.05, None)] * 2,
                    constraints=[{"type": "ineq", "fun": lambda d: cons(d)[0], "jac": lambda d: cons(d)[1]}],
                    options={"maxiter": maxiter, "ftol": 1e-12})


def exact_polish(d0, prescribed: Prescribed | str = "P1", k: int = EXACT_K, box: float = 0.05) -> dict[str, Any]:
    """Is d0 (e.g. a Dynamic-Q d* of Table 4.7) a local minimum of the exact E problem
    (`exact_e_problem`)?

    Returns ``f0`` = area(W_c) - area(W_p) at d0 and ``viol0`` (largest constraint violation
    there, 0 if W_p is enclosed); ``f_proj`` at ``d_proj``, the feasible design nearest to d0,
    and ``box_drop``, how far f falls from there within ``box`` of it in every component (a
    local test: ~0 at a local minimum); ``d``, ``f``, ``viol`` where SciPy SLSQP ends from d0
    (the local minimum it reaches), ``drop`` = f0 - f and ``step`` = |d - d0|.
    """
    from scipy.optimize import minimize

    f, cons = exact_e_problem(prescribed, k)
    d0 = np.asarray(d0, dtype=float)
    viol = lambda d: float(max(0.0, -cons(d)[0].min()))
    proj = minimize(lambda d: float((d - d0) @ (d - d0)), d0, jac=lambda d: 2 * (d - d0), method="SLSQP",
                    constraints=[{"type": "ineq", "fun": lambda d: cons(d)[0], "jac": lambda d: cons(d)[1]}],
                    options={"maxiter": 200, "ftol": 1e-14}).x
    local = _slsqp(proj, f, cons, bounds=list(zip(proj - box, proj + box))).x
    res = _slsqp(d0, f, cons)
    f0, fp, fe = (float(f(x)[0]) for x in (d0, proj, res.x))
    if viol(proj) > 1e-7:  # no enclosing design found near d0 (e.g. a negative leg length): nothing to report
        fp = float("nan")
    return {"d0": d0, "f0": f0, "viol0": viol(d0), "d_proj": proj, "f_proj": fp,
            "box_drop": fp - float(f(local)[0]) if viol(local) < 1e-7 else float("nan"),
            "d": res.x, "f": fe, "viol": viol(res.x), "drop": f0 - fe, "step": float(np.linalg.norm(res.x - d0)),
            "success": bool(res.success)}


def exact_optimum(kind: str = "e", prescribed: Prescribed | str = "P1", n_starts: int = 24, k: int = EXACT_K,
                  seed: int = 0) -> dict[str, Any]:
    """The best design of the exact E problem (4.14) (`exact_e_problem`), for Table 4.7.

    SciPy SLSQP (analytic derivatives) from SP1-SP4 (Table 4.2), the thesis's d* of Table 4.7
    and ``n_starts`` seeded random designs (xA in [-8, 0], yA in [-4, y_min(W_p)], xB in
    [0, 8], l_min in [2, 7]); keeps the ends whose constraints hold (to 1e-7). Returns ``d``,
    ``f`` (= dW_c, with dW_p = 0) of the best, ``starts`` (number of starts) and ``minima``:
    the distinct local minima reached, ``(f, d, count)`` sorted by f (ends within 1e-6 in f
    counted as one). An independent reference for what any solver of the chord formulation
    can reach; a multistart, not a proof of global optimality.  Kind "p": the same for
    `exact_p_problem` (`_exact_p_optimum`).
    """
    if kind.lower() == "p":
        return _exact_p_optimum(prescribed, n_starts, k, seed)
    if kind.lower() != "e":
        raise ValueError(f"exact_optimum: kind must be 'e' (E synthesis, 4.14) or 'p' (P synthesis, 4.21), "
                         f"got {kind!r}")
    P = PRESCRIBED[prescribed] if isinstance(prescribed, str) else prescribed
    f, cons = exact_e_problem(P, k)
    rng = np.random.default_rng(seed)
    lo = np.array([-8.0, -4.0, 0.0, 2.0, 2.0])
    hi = np.array([0.0, float(P.points(k)[:, 1].min()), 8.0, 7.0, 7.0])
    starts = list(STARTS.values()) + list(thesis_e_designs().values()) + list(rng.uniform(lo, hi, (n_starts, 5)))
    ends = []
    for x0 in starts:
        x = _slsqp(x0, f, cons).x
        if cons(x)[0].min() >= -1e-7:
            ends.append((float(f(x)[0]), x))
    return _distinct_ends(ends, len(starts), best=min)


def _distinct_ends(ends: list[tuple[float, np.ndarray]], n_starts: int, best) -> dict[str, Any]:
    """The multistarts' summary: the feasible ends ``(value, design)`` grouped by value (within
    1e-6: one end, counted), best first (``best`` is min or max), and the best of them."""
    minima: list[list] = []
    for v, d in ends:
        same = [m for m in minima if abs(m[0] - v) < 1e-6]
        if same:
            same[0][2] += 1
        else:
            minima.append([v, d, 1])
    minima.sort(key=lambda m: m[0], reverse=best is max)
    if not minima:
        return {"d": None, "f": float("nan"), "starts": n_starts, "minima": []}
    return {"d": minima[0][1], "f": minima[0][0], "starts": n_starts, "minima": [tuple(m) for m in minima]}


def _exact_p_optimum(prescribed: Prescribed | str, n_starts: int, k: int, seed: int) -> dict[str, Any]:
    """The best design of the exact P problem (`exact_p_problem`), for Table 4.9x.

    SciPy SLSQP (analytic derivatives) from `p_start` and ``n_starts`` seeded random designs
    (xA in [-8, 0], yA in [-4, y_min(P)], xB in [0, 8], each lifted by t = its min kappa^-1);
    keeps the ends whose constraints hold (to 1e-7).  Returns ``d`` (= [xA, yA, xB]) and ``f``
    (= t*, min kappa^-1, maximized) of the best, ``starts`` and ``minima``: the distinct ends
    ``(t, d, count)``, best first (ends within 1e-6 in t counted as one)."""
    from scipy.optimize import minimize

    P = PRESCRIBED[prescribed] if isinstance(prescribed, str) else prescribed
    cons = exact_p_problem(P, k)
    U = _kinv_points(P, KINV_K)
    rng = np.random.default_rng(seed)
    lo, hi = np.array([-8.0, -4.0, 0.0]), np.array([0.0, float(P.points(k)[:, 1].min()), 8.0])
    designs = [np.asarray(P_START, dtype=float)] + list(rng.uniform(lo, hi, (n_starts, 3)))
    ends = []
    for d0 in designs:
        z = minimize(lambda z: -z[3], _lifted(d0, U), jac=lambda z: np.array([0.0, 0.0, 0.0, -1.0]), method="SLSQP",
                     constraints=[{"type": "ineq", "fun": lambda z: cons(z)[0], "jac": lambda z: cons(z)[1]}],
                     options={"maxiter": 300, "ftol": 1e-12}).x
        if np.all(np.isfinite(z)) and cons(z)[0].min() >= -1e-7:
            ends.append((float(z[3]), z[:3]))
    return _distinct_ends(ends, len(designs), best=max)


def design_key(d) -> str:
    """The key of a design in the stored reference: its components, exactly (repr of each float)."""
    return ",".join(repr(float(v)) for v in np.asarray(d, dtype=float).ravel())


def _jsonable(v: Any) -> Any:
    if isinstance(v, np.ndarray):
        return [float(a) for a in v]
    if isinstance(v, (np.floating, np.integer, np.bool_)):
        return v.item()
    if isinstance(v, dict):
        return {k: _jsonable(a) for k, a in v.items()}
    if isinstance(v, (list, tuple)):
        return [_jsonable(a) for a in v]
    return v


def reference(runs, stored: dict[str, Any] | None = None) -> dict[str, Any]:
    """What Table 4.7 needs from the exact model, as JSON-ready data.

    ``exact_optimum``: `exact_optimum("e")`; ``polish``: `exact_polish` of the thesis's d*
    and of every stored E run's end, keyed by `design_key`.  Entries already in ``stored``
    are kept, so a new run costs only its own polish.
    """
    stored = dict(stored or {})
    out: dict[str, Any] = {"exact_optimum": stored.get("exact_optimum") or _jsonable(exact_optimum("e"))}
    polish = dict(stored.get("polish") or {})
    designs = list(thesis_e_designs().values())
    if runs is not None and len(runs):
        e = runs[runs["problem"] == "rpr2-e"]
        designs += [np.asarray(x, dtype=float) for x in e["x"] if x is not None and len(x) == 5]
    for d in designs:
        key = design_key(d)
        if key not in polish:
            try:
                polish[key] = _jsonable(exact_polish(d))
            except Exception as exc:  # noqa: BLE001  (one bad design must not lose the others)
                polish[key] = {"error": f"{type(exc).__name__}: {exc}"}
    out["polish"] = polish
    return out
