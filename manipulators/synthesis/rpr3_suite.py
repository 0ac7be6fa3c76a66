"""Suite ``rpr3``: dimensional synthesis of the 3-RPR manipulator (thesis Chapter 5).

Design vector ``d = [x_C, y_C, x_D, x_E, r]`` (eq. 5.36), leg limits ``l_1, l_2 in
[sqrt2, 2]``, ``l_3 in [1, sqrt3]``; prescribed workspaces P1-P3 centred at (1, 1.5), radii
divided by 5, 5, 7 (ERRATA.md).  Each problem is ``min f(d) = -min kappa^-1`` subject to
``g(d) <= 0``:

* ``rpr3-so-p*``: SO synthesis (5.34)-(5.35) at phi = 0; start [-1, 0, 1, 2, 1];
  Dynamic-Q rho = 0.1, eps_f = 1e-6, eps_x = 1e-4, forward differences Gamma = 1e-6.
* ``rpr3-mo-p*``: MO synthesis (5.37)-(5.38), slices -5, 0, +5 degrees; start
  [-0.75, 0, 0.75, 1.5, 0.75]; rho = 0.1, eps_f = 1e-5, eps_x = 1e-4, Gamma = 1e-6.
* ``rpr3-d-p*``: D synthesis (5.39)-(5.40) over [-5, +5] degrees; start as MO (Section
  5.8.2 states none; Table 5.5's f(d0) for P1, P2 equal Table 5.4's); rho = 0.05,
  eps_f = 1e-6, eps_x = 1e-4, central differences Gamma = 1e-3.

All use chord d = 0.02.  ``g`` is eq. (4.16) on the chord workspace(s) with the triangle
scheme (4.9): dW_p if > 0, else -r^2 (MO: S = sum of the slices' dW_p, r the smallest gap
over the slices).  ``kappa^-1`` is minimized over the prescribed boundary densely (1024
angles per slice; the exact minimum), not only at the polar angles of the computed
boundary points as the thesis did -- the two agree at feasible designs, and the dense one
reproduces Table 5.3's f(d0) exactly (ERRATA.md).

Radiating point.  When the prescribed centre O' is strictly inside the workspace it is the
chord method's radiating point, so that the computed boundary points move smoothly with d
(finite differences of g see no jumps from a re-chosen interior point); otherwise the
workspace's own interior-point search (Algorithm 5.1 for the dextrous workspace) is used.

Infeasible designs never raise: an invalid design (r <= 0, non-finite) or an empty
workspace gives g = area(W_p) + (the smallest leg-limit violation over W_p's boundary and
centre), so g keeps a slope towards feasibility; kappa^-1 is still defined (f <= 0).
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np

from problems import Case, Problem, Suite

from ..objectives import delta_areas, delta_areas_exact, min_inverse_condition, polar_angles, radial_gaps, star_shaped
from ..prescribed import Prescribed, chapter5_workspaces
from ..rpr3 import RPR3
from ..workspace import Workspace
from ._arguments import chord_length, lookup
from ._design_cache import DesignCache

__all__ = ["SUITE", "SETTINGS", "START_SO", "START_MO", "PRESCRIBED3", "synthesis_problem", "evaluate",
           "exact_enclosure", "enclosing_window", "window_covers", "design"]

START_SO = (-1.0, 0.0, 1.0, 2.0, 1.0)  # Section 5.6.2 (Haug et al. [16])
START_MO = (-0.75, 0.0, 0.75, 1.5, 0.75)  # Section 5.7.2
DEG = math.pi / 180.0
PRESCRIBED3: dict[str, Prescribed] = chapter5_workspaces()
N_KAPPA = 1024  # angles per slice for the dense min kappa^-1
ENCLOSURE_TOL = 1e-3  # largest area(W_p minus W_c)/area(W_p) counted as enclosed (see exact_enclosure)
WINDOW_TOL = 1e-3  # leg-length slack with which enclosing_window's set must cover the required orientations

# problems/reference/thesis_tables/run_settings.csv, rows of Sections 5.6.2-5.8.2
SETTINGS: dict[str, dict[str, Any]] = {
    "so": dict(phis=(0.0,), dextrous=False, start=START_SO, rho=0.1, eps_f=1e-6, eps_x=1e-4,
               fd="forward", fd_step=1e-6, chord=0.02, table="5.3"),
    "mo": dict(phis=(-5 * DEG, 0.0, 5 * DEG), dextrous=False, start=START_MO, rho=0.1, eps_f=1e-5, eps_x=1e-4,
               fd="forward", fd_step=1e-6, chord=0.02, table="5.4"),
    "d": dict(phis=(-5 * DEG, 5 * DEG), dextrous=True, start=START_MO, rho=0.05, eps_f=1e-6, eps_x=1e-4,
              fd="central", fd_step=1e-3, chord=0.02, table="5.5"),
}
SOLVERS = ("dynamic-q", "dynamic-q-plus", "scipy-slsqp", "ipopt", "nlopt-mma", "scipy-cobyla")


def _kinv_at(m: RPR3, U, phi: float):
    """kappa^-1 of ``m`` at positions U and orientation phi (for `min_inverse_condition`)."""
    return m.inverse_condition(U, phi)


def design(d) -> RPR3 | None:
    """The 3-RPR of design vector d (eq. 5.36) with the Section 5.6.2 leg limits; None if invalid."""
    d = np.asarray(d, dtype=float)
    if d.shape != (5,) or not np.all(np.isfinite(d)):
        return None
    try:
        return RPR3.from_design(d)
    except ValueError:
        return None


class _Evaluator:
    """Workspaces of recent designs for one formulation (f and g at one d share them)."""

    def __init__(self, kind: str, P: Prescribed, chord: float | None = None, size: int = 16):
        s = SETTINGS[kind]
        self.kind, self.P, self.s = kind, P, s
        self.chord = chord_length(chord, s["chord"], f"3-RPR {kind.upper()} synthesis")
        self._memo: DesignCache[tuple[RPR3 | None, list[Workspace]]] = DesignCache(size)
        self._wp: Any = None  # W_p as a shapely polygon, made on first use

    # one workspace per slice (SO, MO) or the dextrous workspace (D); a trace that does not
    # close raises (`check_closed`) and its slice counts as empty, like any chord failure
    def _workspaces(self, m: RPR3) -> list[Workspace]:
        centre = np.asarray(self.P.centre)
        phis = self.s["phis"]
        out = []
        if self.s["dextrous"]:
            a, b = min(phis), max(phis)
            inside = float(np.max(m.dextrous_constraints(centre[None, :], a, b))) < 0
            ws = m.dextrous_workspace(a, b, self.chord, on_open="raise", **({"interior": centre} if inside else {}))
            ws.info["centre_inside"] = inside
            out.append(ws)
        else:
            for phi in phis:
                inside = float(np.max(m.constraints(centre[None, :], phi))) < 0
                try:
                    ws = m.workspace(phi, self.chord, on_open="raise", **({"interior": centre} if inside else {}))
                    ws.info["centre_inside"] = inside
                    out.append(ws)
                except Exception as exc:  # noqa: BLE001  (this slice is empty)
                    out.append(Workspace.empty(reason=f"{type(exc).__name__}: {exc}"))
        return out

    def __call__(self, d) -> tuple[RPR3 | None, list[Workspace]]:
        return self._memo.get(d, self._compute)

    def _compute(self, d: np.ndarray) -> tuple[RPR3 | None, list[Workspace]]:
        m = design(d)
        if m is None:
            return m, [Workspace.empty(reason="invalid design")]
        try:
            return m, self._workspaces(m)
        except Exception as exc:  # noqa: BLE001  (empty workspace or chord failure: never crash a run)
            return m, [Workspace.empty(reason=f"{type(exc).__name__}: {exc}")]

    # ---------------------------------------------------------------- f and g
    def kinv(self, d) -> float:
        """min kappa^-1 over the prescribed boundary at every slice / both range ends."""
        m = design(d)
        if m is None:
            return 0.0
        vals = [min_inverse_condition(functools.partial(_kinv_at, m, phi=phi), self.P, k=N_KAPPA)
                for phi in self.s["phis"]]
        v = min(vals)
        return v if math.isfinite(v) else 0.0

    def parts(self, d) -> dict[str, Any]:
        """dW_p per workspace, gaps, and g (4.16 / 5.35 / 5.38 / 5.40).

        dW_p is the thesis's triangle scheme (4.9) about O' whenever O' is inside the
        workspace -- the only case in which the scheme measures area(W_p minus W_c): its
        rays from O' must cross the computed boundary once.  When O' is outside (the
        workspace traced from another interior point), or when the triangle scheme claims
        enclosure but the polygons say otherwise (a workspace not star-shaped about O'),
        dW_p is the polygon difference area(W_p minus polygon(W_c)) (shapely).  Without
        this the triangle scheme returns meaningless small or zero values at such designs,
        and every solver was drawn to designs that passed g <= 0 with W_p entirely outside.
        An empty workspace contributes ``area(W_p) + violation`` to S, so g is consistent
        across designs whose slices become empty one at a time.
        """
        m, wss = self(d)
        area = float(self.P.area())
        empty = [w.n_boundary < 3 for w in wss]
        viol = self._violation(m, d) if any(empty) else 0.0
        dwp = []
        for w, e in zip(wss, empty):
            if e:
                dwp.append(area + viol)
            elif w.info.get("centre_inside", True) and star_shaped(w.boundary, self.P.centre):
                dwp.append(delta_areas(w, self.P)[0])
            else:
                dwp.append(self._dwp_polygon(w))
        S = float(sum(dwp))
        n_b = [w.n_boundary for w in wss]
        if any(empty):
            return {"g": S, "dwp": dwp, "r": float("nan"), "empty": True, "n_b": n_b}
        if S <= 0:  # the triangle scheme claims enclosure: confirm with the polygons
            poly = [self._dwp_polygon(w) for w in wss]
            if max(poly) > ENCLOSURE_TOL * area:
                return {"g": float(sum(poly)), "dwp": poly, "r": float("nan"), "empty": False, "n_b": n_b,
                        "not_star": True}
        r = float(min(np.min(np.abs(radial_gaps(w, self.P)[0])) for w in wss))
        return {"g": S if S > 0 else -r * r, "dwp": dwp, "r": r, "empty": False, "n_b": n_b}

    def _dwp_polygon(self, w: Workspace) -> float:
        """area(W_p minus the chord polygon of W_c), by shapely (`Workspace.polygon`: an invalid
        outline is repaired with make_valid, as everywhere else in the project)."""
        if self._wp is None:
            self._wp = self.P.polygon(720)
        return float(self._wp.difference(w.polygon()).area)

    def _violation(self, m: RPR3 | None, d) -> float:
        if m is None:
            d = np.asarray(d, dtype=float)
            return 1.0 + (abs(d[4]) if d.shape == (5,) and np.isfinite(d[4]) else 0.0)
        U = np.vstack([self.P.points(64), np.asarray(self.P.centre)[None, :]])
        if self.s["dextrous"]:
            c = m.dextrous_constraints(U, min(self.s["phis"]), max(self.s["phis"]))
        else:
            c = np.max([m.constraints(U, p) for p in self.s["phis"]], axis=0)
        return float(max(np.min(np.max(c, axis=1)), 0.0))


def synthesis_problem(kind: str, prescribed: str = "P1", chord: float | None = None) -> Problem:
    """SO, MO or D synthesis (5.34, 5.37, 5.39) of the 3-RPR as a `Problem`.

    ``min f(d) = -min kappa^-1`` subject to ``g(d) <= 0``; no derivatives (finite
    differences with the thesis's scheme and interval).
    """
    k = _kind(kind, "rpr3.synthesis_problem")
    lookup(PRESCRIBED3, prescribed, "prescribed workspace", "rpr3.synthesis_problem")
    s = SETTINGS[k]
    ev = _Evaluator(k, PRESCRIBED3[prescribed], chord)
    ref = _thesis_row(s["table"], prescribed)
    name = f"rpr3-{k}-{prescribed.lower()}"
    return Problem(
        name=name, x0=s["start"],
        objective=lambda d: -ev.kinv(_vector(d, name)),
        ineq=lambda d: np.array([ev.parts(_vector(d, name))["g"]]), n_ineq=1,
        fd=s["fd"], fd_step=s["fd_step"],
        f_ref=None if ref is None else -ref["f_star"], x_ref=None if ref is None else ref["d_star"],
        source=f"Hay 2003, Sec. {dict(so='5.6', mo='5.7', d='5.8')[k]}, Table {s['table']}",
        tags=("manipulator", "rpr3", k.upper()),
        meta={"kind": k, "prescribed": prescribed, "chord": ev.chord, "phis": s["phis"], "table": s["table"],
              "thesis": ref},
    )


def _kind(kind: Any, where: str) -> str:
    """The formulation's key in SETTINGS ("so", "mo", "d"; any case)."""
    key = kind.lower() if isinstance(kind, str) else kind
    lookup(SETTINGS, key, "synthesis kind", where)
    return key


def _vector(d: Any, name: str) -> Any:
    """d itself if it has the design's shape (5,).  A wrong shape is a caller's error, refused
    here; a non-finite d of the right shape is an invalid design, which g penalizes."""
    if np.shape(d) != (5,):
        raise ValueError(f"{name}: design d must have 5 entries [xC, yC, xD, xE, r], got shape {np.shape(d)}")
    return d


def _thesis_row(table: str, prescribed: str) -> dict[str, Any] | None:
    try:
        from problems.reference import thesis_table

        t = thesis_table("table_5_3_to_5_5_SO_MO_D_synthesis")
    except Exception:  # noqa: BLE001  (reference data optional at run time)
        return None
    row = t[(t["table"] == table) & (t["workspace"] == prescribed)]
    if row.empty:
        return None
    r = row.iloc[0]
    return {"ng": int(r["ng"]), "f_d0": float(r["f_d0"]), "f_star": float(r["f_star"]), "g_star": float(r["g_star"]),
            "d_star": np.array([float(r[c]) for c in ("x_C", "y_C", "x_D", "x_E", "r")])}


# ------------------------------------------------------------------ exact checks for tables
def exact_enclosure(kind: str, d, prescribed: str = "P1", n_slices: int = 201,
                    tol: float = ENCLOSURE_TOL) -> dict[str, Any]:
    """Exact check that W_p is enclosed (shapely): area(W_p minus W_c) for every slice.

    The constant-orientation workspace is the exact intersection of the three leg annuli
    (upper branch); the dextrous workspace the intersection of ``n_slices`` of them
    evenly spaced over the range.  Returns ``dwp_exact`` (largest over the slices), its
    ``ratio`` to area(W_p), ``max_leg_violation`` (largest leg-limit excess over 2048
    points of W_p's boundary, all slices) and ``enclosed`` (ratio <= ``tol``).

    The tolerance: g(d) <= 0 is imposed on the chord polygon (d = 0.02) at the polar
    angles of its vertices (triangle scheme, eq. 4.9), so a design on the constraint can
    miss W_p by slivers of the chord's sagitta, d^2/(8R) ~ 1e-4 here; ``tol = 1e-3``
    accepts those and nothing larger.
    """
    import shapely

    s = SETTINGS[_kind(kind, "rpr3.exact_enclosure")]
    P = lookup(PRESCRIBED3, prescribed, "prescribed workspace", "rpr3.exact_enclosure")
    m = design(d)
    wp = P.polygon(4096)
    if m is None:
        return {"dwp_exact": float(wp.area), "ratio": 1.0, "max_leg_violation": float("inf"), "enclosed": False}
    phis = (np.linspace(min(s["phis"]), max(s["phis"]), n_slices) if s["dextrous"] else s["phis"])
    worst = 0.0
    pts = P.points(2048)
    viol = -np.inf
    for phi in phis:
        region = _annuli(m, phi, shapely)
        worst = max(worst, float(wp.difference(region).area))
        viol = max(viol, float(np.max(m.constraints(pts, phi))))
    ratio = worst / float(wp.area)
    return {"dwp_exact": worst, "ratio": ratio, "max_leg_violation": viol, "enclosed": bool(ratio <= tol)}


def enclosing_window(
    d, prescribed: str = "P1", k: int = 4096, kind: str | None = None, tol: float = WINDOW_TOL
) -> dict[str, Any]:
    """The exact set of orientations phi at which W_p is enclosed in W^C[phi] for design d.

    `RPR3.enclosing_orientations` on ``k`` points of W_p's boundary (eqs. 5.7, 5.14, 5.26;
    with k = 4096 the ends are within ~1e-4 degrees of the continuum's).  SO synthesis
    (5.34) needs phi = 0 in this set, MO (5.37) its three slices, D (5.39) the whole range
    (`window_covers`; ``kind`` "so", "mo" or "d").  Returns ``intervals`` (radians) and,
    when the set is empty, ``slack``: the smallest leg-length slack (limits widened by it) that makes it
    non-empty, i.e. ``min_phi`` of the largest leg excess over W_p's boundary (bisection),
    and ``phi_slack``, the orientation where that is reached (inf / nan when W_p is below
    the base line or d is invalid); ``covers``: `window_covers` of the set with the leg
    limits widened by ``tol`` (designs *on* the constraint, found on sampled boundary
    points, miss the exact set by leg excesses ~1e-4).
    """
    lookup(PRESCRIBED3, prescribed, "prescribed workspace", "rpr3.enclosing_window")
    m = design(d)
    out = {"intervals": [], "slack": float("inf"), "phi_slack": float("nan"), "covers": False if kind else None}
    if m is None:
        return out
    B = PRESCRIBED3[prescribed].points(k)
    iv = m.enclosing_orientations(B)
    out["covers"] = window_covers(kind, m.enclosing_orientations(B, tol=tol)) if kind else None
    if iv or np.any(B[:, 1] < m.yC):
        return out | {"intervals": iv, "slack": 0.0 if iv else float("inf")}
    lo, hi = 0.0, 1e-3
    while not m.enclosing_orientations(B, tol=hi):
        lo, hi = hi, 2.0 * hi
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if m.enclosing_orientations(B, tol=mid) else (mid, hi)
    a, b = m.enclosing_orientations(B, tol=hi)[0]
    return out | {"slack": hi, "phi_slack": 0.5 * (a + b)}


def window_covers(kind: str, intervals) -> bool:
    """Whether the orientations the synthesis requires (SO: 0; MO: the slices; D: the whole
    range) lie in the enclosing set ``intervals`` (radians)."""
    s = SETTINGS[_kind(kind, "rpr3.window_covers")]
    need = [(min(s["phis"]), max(s["phis"]))] if s["dextrous"] else [(p, p) for p in s["phis"]]
    return all(any(lo <= a and b <= hi for lo, hi in intervals) for a, b in need)


def _annuli(m: RPR3, phi: float, shapely, quad: int = 512):
    e = np.array([math.cos(phi), math.sin(phi)])
    sign = (-1.0, -1.0, 1.0)
    region = shapely.box(-50, m.yC, 50, 50)
    for i in range(3):
        c = shapely.Point(m.base[i] - sign[i] * m.r * e)
        region = region.intersection(
            c.buffer(m.lmax[i], quad_segs=quad).difference(c.buffer(m.lmin[i], quad_segs=quad))
        )
    return region


def evaluate(kind: str, d, prescribed: str = "P1", exact: bool = True) -> dict[str, Any]:
    """Every quantity of a design for the tables and figures.

    ``kinv`` (the thesis's f, positive), ``kinv_thesis`` (min kappa^-1 only at the polar
    angles of the computed boundary points, as the thesis evaluates it), ``g``, ``dwp``
    per workspace, ``n_b``, the workspaces and, if ``exact``, `exact_enclosure`.
    """
    k = _kind(kind, "rpr3.evaluate")
    ev = _Evaluator(k, lookup(PRESCRIBED3, prescribed, "prescribed workspace", "rpr3.evaluate"))
    m, wss = ev(d)
    out: dict[str, Any] = {"kinv": ev.kinv(d), **ev.parts(d), "workspaces": wss, "design": m}
    if m is not None and all(w.n_boundary >= 3 for w in wss):
        vals = []
        for w in wss:
            beta = polar_angles(w.boundary, ev.P.centre)[0]
            phis = ev.s["phis"] if ev.s["dextrous"] else [w.info.get("phi", 0.0)]
            for phi in phis:
                vals.append(min_inverse_condition(functools.partial(_kinv_at, m, phi=phi), ev.P, beta=beta))
        out["kinv_thesis"] = float(min(vals))
    if exact:
        out.update(exact_enclosure(k, d, prescribed))
        if m is not None and not ev.s["dextrous"]:
            import shapely

            out["dwp_exact_sum"] = float(sum(delta_areas_exact(_annuli(m, p, shapely), ev.P)[0] for p in ev.s["phis"]))
    return out


# ------------------------------------------------------------------ the suite
def _options(kind: str) -> dict[str, dict[str, Any]]:
    """The thesis's Dynamic-Q settings, and caps that keep the suite within its time budget.

    The caps are the same for every case (SO, MO and D alike) and every start, and sized
    from the thesis: its largest N^g in Tables 5.3-5.5 is 71, so Dynamic-Q keeps its own
    default cap of 100 iterations; each established solver gets about as many gradient
    evaluations (SLSQP / Ipopt 30 iterations, each with a line search; MMA 60 evaluations;
    COBYLA, derivative-free, 300 single points ~ 50 gradients' worth of 5 forward
    differences).  Every g traces 1-3 chord workspaces (20-100 ms), so the suite of 45
    runs fits in ~20 minutes on 2 cores.  NLopt's wall-clock guard is raised to 600 s so
    that the deterministic evaluation cap, not the machine's load, ends the run.
    """
    s = SETTINGS[kind]
    opts: dict[str, dict[str, Any]] = {
        # step test (3.10) as printed, without our feasibility condition: Tables 5.3-5.5 print
        # g* = 0.2E-5 .. 0.1E-4 > 0, so the thesis's Dynamic-Q stopped at (slightly)
        # infeasible iterates; with the condition it cycles at the degenerate boundary of g
        # until the cap (docs/rpr3.md).  The exact enclosure check at d* judges the result.
        "dynamic-q": {"rho": s["rho"], "eps_f": s["eps_f"], "eps_x": s["eps_x"], "max_iter": 100,
                      "step_stop_feasible": False},
        "scipy-slsqp": {"maxiter": 30},
        "scipy-cobyla": {"rhobeg": s["rho"], "tol": s["eps_x"], "maxfev": 300},
        "ipopt": {"max_iter": 30},
        "nlopt-mma": {"maxeval": 60},
    }
    return opts


def _build() -> list[Case]:
    cases = []
    for kind in ("so", "mo", "d"):
        for name in ("P1", "P2", "P3"):
            prob = synthesis_problem(kind, name)
            cases.append(Case(prob, prob.name, start="d0", options=_options(kind),
                              meta={"table": SETTINGS[kind]["table"], "kind": kind, "prescribed": name}))
    return cases


SUITE = Suite(
    name="rpr3",
    description="3-RPR dimensional synthesis (thesis Ch. 5): SO (Table 5.3), MO (5.4), D (5.5)",
    build=_build,
    solvers=SOLVERS,
    tables="harness.tables.rpr3",
    figures="harness.figures.rpr3",
)
