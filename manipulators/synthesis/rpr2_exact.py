"""The exact E problem of the 2-RPR synthesis (4.14): an analysis of the ``rpr2`` suite, not a
problem of it.

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
from .rpr2_suite import LMAX_RATIO, STARTS, design_o

__all__ = ["EXACT_K", "exact_e_problem", "exact_polish", "exact_optimum", "thesis_e_designs", "reference",
           "design_key"]

EXACT_K = 512  # points of W_p's boundary at which the exact E problem's leg limits are imposed


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
    can reach; a multistart, not a proof of global optimality. Only kind "e" here.
    """
    if kind.lower() != "e":
        raise ValueError(f"exact_optimum: only kind 'e' (E synthesis, 4.14), got {kind!r}")
    P = PRESCRIBED[prescribed] if isinstance(prescribed, str) else prescribed
    f, cons = exact_e_problem(P, k)
    rng = np.random.default_rng(seed)
    lo = np.array([-8.0, -4.0, 0.0, 2.0, 2.0])
    hi = np.array([0.0, float(P.points(k)[:, 1].min()), 8.0, 7.0, 7.0])
    starts = list(STARTS.values()) + list(thesis_e_designs().values()) + list(rng.uniform(lo, hi, (n_starts, 5)))
    minima: list[list] = []
    for x0 in starts:
        x = _slsqp(x0, f, cons).x
        if cons(x)[0].min() < -1e-7:
            continue
        fx = float(f(x)[0])
        same = [m for m in minima if abs(m[0] - fx) < 1e-6]
        if same:
            same[0][2] += 1
        else:
            minima.append([fx, x, 1])
    minima.sort(key=lambda m: m[0])
    if not minima:
        return {"d": None, "f": float("nan"), "starts": len(starts), "minima": []}
    return {"d": minima[0][1], "f": minima[0][0], "starts": len(starts), "minima": [tuple(m) for m in minima]}


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
