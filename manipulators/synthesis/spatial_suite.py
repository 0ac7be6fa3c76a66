"""Suite ``spatial``: synthesis of spatial manipulators, as the thesis recommends (Sec. 7.4).

Two formulations, each an ordinary `problems.Problem` of >= 8 design variables, in two
sizes so that solvers can be compared as the number of design variables grows
(docs/spatial.md, "Synthesis"):

* ``spatial-cable-9`` / ``-13``: the largest dextrous wrench-feasible volume of an
  8-cable robot (`SpatialCableRobot`), frame and platform attachment points under
  symmetry (9 variables: frame half-widths, the two frame levels, platform half-sizes and
  two twist angles; 13: top and bottom frame and platform rectangles sized separately).
  The volume is that of the region reachable from a fixed centre along 32 rays, each ray's
  reach the first loss of wrench feasibility by bisection, minimized over every load and
  orientation of the set (the intersection of star-shaped sets about the centre): the
  spatial counterpart of the thesis's chord/bisection dextrous workspace (Algorithm 5.1,
  Ch. 6), continuous in the design, so the counted finite differences see its slope.
  Constraints: a perimeter budget for the frame and a radius limit for the platform.
* ``spatial-gs-9`` / ``-18``: a Gough-Stewart platform (`GoughStewart`) whose workspace
  must enclose a prescribed box over a set of orientations, with the best worst-case
  inverse condition number: max t s.t. t <= kappa^-1 and l_min <= |l_i| <= l_max at 27
  points of the box (its corners, edge and face centres and centre) for every
  orientation, and a stroke ratio l_max <= 1.8 l_min (9 variables under 3-fold symmetry:
  base and platform radii, pair half-angles, twist, leg limits, box height, t; 18 with all
  twelve joint angles free).

Derivatives: the objective of the GS problems is -t (exact gradient); everything else by
the harness's counted forward differences.  Infeasible or degenerate designs never raise:
the cable volume is 0 when the centre itself is not wrench-feasible, and a GS design with
coincident joints has kappa^-1 = 0.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from problems import Case, Problem, Suite

from ..spatial import GoughStewart, SpatialCableRobot, distribute6, ray_reach

__all__ = ["SUITE", "SOLVERS", "cable_problem", "gs_problem", "cable_design", "gs_design", "CABLE", "GS",
           "dextrous_rays", "sphere_directions"]

DEG = math.pi / 180.0

# ------------------------------------------------------------------ the 8-cable robot
#: Settings of the cable synthesis: tension limits (N), loads (6-D wrenches on the platform,
#: gravity of a 10 kg platform and a disturbed case), orientations (extrinsic x-y-z angles),
#: the centre the rays start from, their reach and number, the bisection tolerance, and the
#: budgets of the two constraints.
CABLE: dict[str, Any] = {
    "t_min": 10.0, "t_max": 1000.0,
    "loads": ((0.0, 0.0, -98.1, 0.0, 0.0, 0.0), (15.0, 15.0, -98.1, 2.0, -2.0, 1.0)),
    "orientations": ((0.0, 0.0, 0.0), (10 * DEG, 0.0, 0.0), (0.0, 10 * DEG, 0.0)),
    "centre": (0.0, 0.0, 1.5), "reach": 3.0, "n_rays": 32, "tol": 1e-7,
    "perimeter": 8.0,  # 2 (ax + ay) per frame rectangle, metres (binding: the room allows 10)
    "platform_radius": 0.4,  # |b_i| <= this, metres
}


def sphere_directions(k: int) -> np.ndarray:
    """k unit vectors spread evenly over the sphere (Fibonacci lattice), each standing
    for the solid angle 4 pi / k."""
    i = np.arange(k) + 0.5
    z = 1.0 - 2.0 * i / k
    phi = math.pi * (1.0 + math.sqrt(5.0)) * i
    r = np.sqrt(1.0 - z * z)
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def _corners(ax: float, ay: float, z: float, twist: float) -> np.ndarray:
    """The four corners (+-ax, +-ay, z) of a rectangle turned by ``twist`` about z."""
    c, s = math.cos(twist), math.sin(twist)
    xy = np.array([[ax, ay], [-ax, ay], [-ax, -ay], [ax, -ay]])
    return np.column_stack([xy[:, 0] * c - xy[:, 1] * s, xy[:, 0] * s + xy[:, 1] * c, np.full(4, z)])


def _cable_parts(d: np.ndarray) -> tuple[np.ndarray, ...]:
    """(ax_t, ay_t, ax_b, ay_b, z_t, z_b, bx_t, by_t, bx_b, by_b, bz, tw_a, tw_b) from 9 or 13 variables."""
    if d.size == 9:
        ax, ay, zt, zb, bx, by, bz, ta, tb = d
        return ax, ay, ax, ay, zt, zb, bx, by, bx, by, bz, ta, tb
    if d.size == 13:
        return tuple(d)
    raise ValueError(f"a cable design has 9 or 13 variables; got {d.size}")


def cable_design(d: Any) -> SpatialCableRobot | None:
    """The 8-cable robot of design d (None if degenerate: a non-finite or non-positive size).

    Cables 1-4 run from the top frame rectangle (height z_t) to the top of the platform
    (z = +b_z in the platform frame), cables 5-8 from the bottom rectangle (z_b) to its
    bottom (-b_z); frame and platform rectangles are turned by the twists tw_a, tw_b.
    """
    d = np.asarray(d, dtype=float)
    p = _cable_parts(d)
    if not np.all(np.isfinite(d)) or min(p[0], p[1], p[2], p[3], p[6], p[7], p[8], p[9], p[10]) <= 0:
        return None
    ax_t, ay_t, ax_b, ay_b, zt, zb, bx_t, by_t, bx_b, by_b, bz, ta, tb = (float(v) for v in p)
    frame = np.vstack([_corners(ax_t, ay_t, zt, ta), _corners(ax_b, ay_b, zb, ta)])
    plat = np.vstack([_corners(bx_t, by_t, bz, tb), _corners(bx_b, by_b, -bz, tb)])
    return SpatialCableRobot(frame, plat, CABLE["t_min"], CABLE["t_max"])


def dextrous_rays(robot: SpatialCableRobot, centre: Any = None, directions: Any = None, reach: float | None = None,
                  tol: float | None = None) -> np.ndarray:
    """Reach of the dextrous wrench-feasible workspace along each ray from ``centre``.

    For every ray, bisection on [0, reach] for the first point that is not wrench-feasible
    (l1 tensions, every load of `CABLE`) at some orientation of `CABLE`: all rays,
    orientations and loads advance together, one vectorized tension solve per load and
    step.  Zero for every ray when the centre itself is not dextrous.
    """
    c = np.asarray(CABLE["centre"] if centre is None else centre, dtype=float)
    D = sphere_directions(CABLE["n_rays"]) if directions is None else np.asarray(directions, dtype=float)
    reach = float(CABLE["reach"] if reach is None else reach)
    tol = float(CABLE["tol"] if tol is None else tol)

    rots = CABLE["orientations"]

    def dextrous(P: np.ndarray) -> np.ndarray:
        # one tension solve per load over every (orientation, point): the vectorized l1 path
        S = np.concatenate([robot.structure_matrices(P, rot) for rot in rots])
        ok = np.ones(len(P), dtype=bool)
        for w in CABLE["loads"]:
            feas = distribute6(S, np.asarray(w, dtype=float), robot.t_min, robot.t_max, "l1", need_tensions=False)[0]
            ok &= np.asarray(feas).reshape(len(rots), len(P)).all(axis=0)
        return ok

    if not dextrous(c[None])[0]:
        return np.zeros(len(D))
    return ray_reach(dextrous, c, D, reach, tol)


def ray_volume(radii: np.ndarray) -> float:
    """Volume of the star-shaped region with these reaches along evenly spread rays:
    (1/3) sum r_k^3 (4 pi / k)."""
    return float(4.0 * math.pi / len(radii) * np.sum(np.asarray(radii) ** 3) / 3.0)


class _CableEvaluator:
    """f and g of one design share one ray computation (the counting Oracle is in front)."""

    def __init__(self) -> None:
        self._key: bytes | None = None
        self._val = 0.0

    def volume(self, d: np.ndarray) -> float:
        d = np.asarray(d, dtype=float)
        if d.tobytes() != self._key:
            m = cable_design(d)
            self._val = 0.0 if m is None else ray_volume(dextrous_rays(m))
            self._key = d.tobytes()
        return self._val


def _cable_constraints(d: np.ndarray) -> np.ndarray:
    ax_t, ay_t, ax_b, ay_b, zt, zb, bx_t, by_t, bx_b, by_b, bz, ta, tb = _cable_parts(np.asarray(d, dtype=float))
    r2 = CABLE["platform_radius"] ** 2
    return np.array([2 * (ax_t + ay_t) - CABLE["perimeter"], 2 * (ax_b + ay_b) - CABLE["perimeter"],
                     bx_t ** 2 + by_t ** 2 + bz ** 2 - r2, bx_b ** 2 + by_b ** 2 + bz ** 2 - r2])


CABLE_START9 = (2.0, 2.0, 2.5, 0.5, 0.2, 0.1, 0.3, -0.25, -0.5)  # centre dextrous, V = 1.45 m^3
CABLE_LOWER9 = (0.5, 0.5, 2.0, 0.0, 0.05, 0.05, 0.05, -math.pi / 4, -math.pi / 4)
CABLE_UPPER9 = (2.5, 2.5, 3.0, 1.0, 0.35, 0.35, 0.35, math.pi / 4, math.pi / 4)


def _cable_bounds(n: int) -> tuple[tuple[float, ...], tuple[float, ...], tuple[float, ...]]:
    if n == 9:
        return CABLE_START9, CABLE_LOWER9, CABLE_UPPER9
    x, lo, up = CABLE_START9, CABLE_LOWER9, CABLE_UPPER9

    def widen(v: tuple[float, ...]) -> tuple[float, ...]:  # 9 -> 13: rectangles sized separately
        return (v[0], v[1], v[0], v[1], v[2], v[3], v[4], v[5], v[4], v[5], v[6], v[7], v[8])

    return widen(x), widen(lo), widen(up)


def cable_problem(n: int = 9) -> Problem:
    """The largest dextrous wrench-feasible volume of the 8-cable robot: min -V(d) s.t. the
    perimeter and platform-radius budgets (n = 9 or 13 design variables)."""
    if n not in (9, 13):
        raise ValueError(f"cable synthesis has 9 or 13 design variables; got {n}")
    x0, lo, up = _cable_bounds(n)
    ev = _CableEvaluator()
    return Problem(
        name=f"spatial-cable-{n}", x0=np.array(x0), lower=np.array(lo), upper=np.array(up),
        objective=lambda d: -ev.volume(d), ineq=_cable_constraints, n_ineq=4,
        fd="forward", fd_step=1e-4,
        source="our extension of Hay 2003 Ch. 6 / Sec. 7.4 (docs/spatial.md)",
        tags=("manipulator", "spatial", "cable"),
        meta={"kind": "cable", "n_design": n},
    )


# ------------------------------------------------------------------ the Gough-Stewart platform
#: Settings of the GS synthesis: the prescribed box (half-sizes, metres; centre (0, 0, z_c)
#: with z_c a design variable), the orientation set, and the stroke ratio.
GS: dict[str, Any] = {
    "half": (0.15, 0.15, 0.1),
    "orientations": ((0.0, 0.0, 0.0), (10 * DEG, 0.0, 0.0), (-10 * DEG, 0.0, 0.0), (0.0, 10 * DEG, 0.0),
                     (0.0, -10 * DEG, 0.0)),
    "stroke": 1.8,
}


def _box_points() -> np.ndarray:
    """The 27 points of the prescribed box (offsets from its centre): corners, edge and
    face centres, centre."""
    g = np.array([-1.0, 0.0, 1.0])
    X, Y, Z = np.meshgrid(g, g, g, indexing="ij")
    return np.column_stack([X.ravel(), Y.ravel(), Z.ravel()]) * np.asarray(GS["half"])


BOX = _box_points()


def _gs_angles(d: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, float, float, float, float]:
    """(base angles, platform angles, R_b, R_p, l_min, l_max, z_c) from 9 or 18 variables (t last)."""
    k = np.arange(3) * 2 * math.pi / 3
    if d.size == 9:
        rb, rp, ab, ap, tw, lmin, lmax, zc, _ = d
        base = np.concatenate([k - ab, k + ab])
        plat = np.concatenate([k + math.pi / 3 + tw - ap, k - math.pi / 3 + tw + ap])
        return base, plat, rb, rp, lmin, lmax, zc
    if d.size == 18:
        return d[0:6], d[6:12], d[12], d[13], d[14], d[15], d[16]
    raise ValueError(f"a Gough-Stewart design has 9 or 18 variables; got {d.size}")


def gs_design(d: Any) -> GoughStewart | None:
    """The hexapod of design d (None if degenerate: non-finite, or leg limits out of order)."""
    d = np.asarray(d, dtype=float)
    base, plat, rb, rp, lmin, lmax, _ = _gs_angles(d)
    if not np.all(np.isfinite(d)) or rb <= 0 or rp <= 0 or not (0 <= lmin < lmax):
        return None
    a = np.column_stack([rb * np.cos(base), rb * np.sin(base), np.zeros(6)])
    b = np.column_stack([rp * np.cos(plat), rp * np.sin(plat), np.zeros(6)])
    return GoughStewart(a, b, float(lmin), float(lmax))


def gs_constraints(d: Any) -> np.ndarray:
    """g(d) <= 0: leg limits at every box point and orientation (lmin - |l|, |l| - lmax), the
    epigraph t - kappa^-1, and the stroke ratio l_max - 1.8 l_min."""
    d = np.asarray(d, dtype=float)
    _, _, _, _, lmin, lmax, zc = _gs_angles(d)
    t = d[-1]
    m = gs_design(d)
    P = BOX + np.array([0.0, 0.0, zc])
    n_pose = len(P) * len(GS["orientations"])
    if m is None:  # degenerate: every pose infeasible by a margin that still has a slope
        return np.concatenate([np.full(12 * n_pose, 1.0 + abs(lmin - lmax)), np.full(n_pose, t),
                               [lmax - GS["stroke"] * lmin]])
    legs, kinv = [], []
    for rot in GS["orientations"]:
        L = np.linalg.norm(m.legs(P, rot), axis=2)  # (27, 6)
        legs.append(np.concatenate([lmin - L, L - lmax], axis=1).ravel())
        kinv.append(m.inverse_condition(P, rot))
    return np.concatenate([np.concatenate(legs), t - np.concatenate(kinv), [lmax - GS["stroke"] * lmin]])


GS_START9 = (0.6, 0.3, 10 * DEG, 10 * DEG, 0.0, 0.7, 1.2, 0.8, 0.0)
GS_LOWER9 = (0.3, 0.1, 2 * DEG, 2 * DEG, -math.pi / 3, 0.3, 0.5, 0.3, 0.0)
GS_UPPER9 = (1.0, 0.6, 55 * DEG, 55 * DEG, math.pi / 3, 1.5, 2.5, 1.5, 1.0)


def _gs_bounds(n: int) -> tuple[tuple[float, ...], tuple[float, ...], tuple[float, ...]]:
    if n == 9:
        return GS_START9, GS_LOWER9, GS_UPPER9
    base, plat, rb, rp, lmin, lmax, zc = _gs_angles(np.asarray(GS_START9))
    x0 = (*base, *plat, rb, rp, lmin, lmax, zc, 0.0)
    lo = (*(base - math.pi / 6), *(plat - math.pi / 6), *GS_LOWER9[0:2], *GS_LOWER9[5:8], 0.0)
    up = (*(base + math.pi / 6), *(plat + math.pi / 6), *GS_UPPER9[0:2], *GS_UPPER9[5:8], 1.0)
    return tuple(map(float, x0)), tuple(map(float, lo)), tuple(map(float, up))


def gs_problem(n: int = 9) -> Problem:
    """Best worst-case kappa^-1 of a hexapod enclosing the prescribed box over the orientation
    set: min -t s.t. `gs_constraints` <= 0 (n = 9 or 18 variables, t last)."""
    if n not in (9, 18):
        raise ValueError(f"Gough-Stewart synthesis has 9 or 18 design variables; got {n}")
    x0, lo, up = _gs_bounds(n)
    grad = np.zeros(n)
    grad[-1] = -1.0
    n_ineq = len(BOX) * len(GS["orientations"]) * 13 + 1
    return Problem(
        name=f"spatial-gs-{n}", x0=np.array(x0), lower=np.array(lo), upper=np.array(up),
        objective=lambda d: -float(d[-1]), gradient=lambda d: grad.copy(),
        ineq=gs_constraints, n_ineq=n_ineq, fd="forward", fd_step=1e-6,
        source="our extension of Hay 2003 Sec. 7.4 (docs/spatial.md)",
        tags=("manipulator", "spatial", "gough-stewart"),
        meta={"kind": "gs", "n_design": n},
    )


# ------------------------------------------------------------------ the suite
SOLVERS = ("dynamic-q", "dynamic-q-plus", "lfopc", "etopc", "scipy-slsqp", "scipy-trust-constr", "ipopt",
           "nlopt-slsqp", "nlopt-mma", "scipy-cobyla")


def _options(kind: str) -> dict[str, dict[str, Any]]:
    """The same evaluation budgets for every case (about 50 gradients' worth): one cable
    volume costs ~0.05-0.1 s, so the suite fits in ~20 minutes on 2 cores."""
    return {
        "dynamic-q": {"max_iter": 50},
        "dynamic-q-plus": {"max_iter": 50},
        "lfopc": {"max_steps": 30},
        "etopc": {"max_steps": 30},
        "scipy-slsqp": {"maxiter": 50},
        "scipy-trust-constr": {"maxiter": 50},
        "ipopt": {"max_iter": 50},
        "nlopt-slsqp": {"maxeval": 50},
        "nlopt-mma": {"maxeval": 50},
        "scipy-cobyla": {"maxfev": 300},
    }


def _build() -> list[Case]:
    cases = []
    for make, sizes, kind in ((cable_problem, (9, 13), "cable"), (gs_problem, (9, 18), "gs")):
        for n in sizes:
            prob = make(n)
            cases.append(Case(prob, prob.name, start="d0", options=_options(kind), meta={"kind": kind, "n": n}))
    return cases


SUITE = Suite(
    name="spatial",
    description="spatial synthesis (our extension, thesis Sec. 7.4): 8-cable dextrous volume, Gough-Stewart "
                "box enclosure with the best kappa^-1; 9-18 design variables",
    build=_build, solvers=SOLVERS, tables="harness.tables.spatial", figures="harness.figures.spatial",
)
