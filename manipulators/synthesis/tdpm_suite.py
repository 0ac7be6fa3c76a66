"""Suite ``tdpm``: cable robots synthesized for the largest dextrous workspace (thesis Section 6.6).

Problems ``tdpm3-l1`` ... ``tdpm3-l3`` and ``tdpm4-l1`` ... ``tdpm4-l3`` (3 or 4 cables,
loads L1-L3 of Table 6.3), formulation (6.29):

    minimize  f(d) = -A_d(d)       d = [beta^1 ... beta^n] (frame points at polar angles
                                    beta^i on the 2 x 2 square, ERRATA mapping)
    subject to  g_i(d) = beta_min - sep(beta^i, beta^{i+1}) <= 0,  i = 1..n (cyclic, i.e.
                also |beta^n - beta^1|), sep = the smaller angle between the two directions

A_d is the dextrous-workspace area on the grid of Algorithm 6.2 with l1 tensions
(Section 6.6.2): 3 cables: [phi_min, phi_max] = [-0.1, 0.1], m = 100, m_sl = 3,
Gamma = 0.05; 4 cables: [-0.2, 0.2], m = 50, m_sl = 21, Gamma = 0.1; central
differences; move limit rho = 0.1. beta_min is not printed: the active separations of
Tables 6.5-6.10 are all 0.174-0.175, so beta_min = 10 degrees (`BETA_MIN`).

Starts ``R1`` ... ``R5``: five random feasible designs per load case from a fixed seed
(sorted angles uniform in [0, 2 pi), accepted when they satisfy (6.29) and have a
non-empty dextrous workspace; the thesis's starts have A_d0 >= 0.0016, and from a zero
area the objective is flat). ``f_ref`` is minus the best published area of the load case.

The objective is piecewise constant (a count of grid points), which is why the thesis
uses Dynamic-Q with a large finite-difference interval; the derivative-free COBYLA is
among the default solvers for the same reason.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from problems import Case, Problem, Suite

from ..cable import BETA_MIN, design_robot, loads

__all__ = ["SUITE", "SETTINGS", "separations", "dextrous_area", "tdpm_problem", "random_starts",
           "published"]

SETTINGS: dict[int, dict[str, Any]] = {
    3: dict(phi=(-0.1, 0.1), resolution=100, slices=3, fd_step=0.05),
    4: dict(phi=(-0.2, 0.2), resolution=50, slices=21, fd_step=0.1),
}
RHO = 0.1            # Dynamic-Q move limit (Section 6.6.2)
N_STARTS = 5         # "five feasible random starting designs" (Section 6.6.2)
SEED = 20030606      # fixed seed of the random starts [OWN]
SOLVERS = ("dynamic-q", "dynamic-q-plus", "scipy-slsqp", "nlopt-mma", "scipy-cobyla")
TABLES = {(3, "L1"): "6.5", (3, "L2"): "6.6", (3, "L3"): "6.7",
          (4, "L1"): "6.8", (4, "L2"): "6.9", (4, "L3"): "6.10"}


def separations(d: np.ndarray) -> np.ndarray:
    """Angles between consecutive frame points (i, i+1) and (n, 1), in [0, pi] (6.29)."""
    d = np.asarray(d, dtype=float)
    diff = np.roll(d, -1) - d
    return np.abs((diff + np.pi) % (2 * np.pi) - np.pi)


def dextrous_area(d: np.ndarray, load: str) -> float:
    """A_d(d): dextrous-workspace area of design d under a load case (Section 6.6.2 settings)."""
    d = np.asarray(d, dtype=float)
    if not np.all(np.isfinite(d)):
        raise ValueError(f"design angles must be finite, got {d}")
    s = SETTINGS[d.size]
    robot = design_robot(d)
    return robot.dextrous_workspace(s["phi"][0], s["phi"][1], loads()[load], resolution=s["resolution"],
                                    slices=s["slices"], tensions="l1").area


@functools.cache
def published() -> dict[tuple[int, str], list[dict[str, Any]]]:
    """Tables 6.5-6.10 rows per (cables, load): run, N^g, d0, A_d0, d*, A_d*."""
    from problems.reference import thesis_table

    out: dict[tuple[int, str], list[dict[str, Any]]] = {}
    for r in thesis_table("table_6_5_to_6_10_tdpm_synthesis").itertuples():
        n = int(r.cables)

        def vec(p: str, r: Any = r, n: int = n) -> list[float]:
            return [float(getattr(r, f"{p}_beta{i}")) for i in range(1, n + 1)]

        out.setdefault((n, r.load), []).append(dict(
            table=r.table, run=int(r.run), ng=int(r.ng), d0=vec("d0"), A_d0=float(r.A_d0),
            dstar=vec("dstar"), A_dstar=float(r.A_dstar)))
    return out


@functools.cache
def random_starts(cables: int, load: str, count: int = N_STARTS) -> tuple[tuple[float, ...], ...]:
    """``count`` random feasible designs (fixed seed per load case); see the module doc."""
    rng = np.random.default_rng([SEED, cables, int(load[1:])])
    found: list[tuple[float, ...]] = []
    for _ in range(2000):
        d = np.round(np.sort(rng.uniform(0.0, 2 * np.pi, cables)), 4)
        if np.all(separations(d) >= BETA_MIN) and dextrous_area(d, load) > 0:
            found.append(tuple(float(v) for v in d))
            if len(found) == count:
                return tuple(found)
    raise RuntimeError(f"found only {len(found)} feasible random starts for {cables} cables, {load}")


def tdpm_problem(cables: int, load: str, start: Any) -> Problem:
    """Problem (6.29) for ``cables`` (3 or 4) and load case ``load`` (L1-L3) from ``start``."""
    if cables not in SETTINGS:
        raise ValueError(f"cables must be 3 or 4 (the thesis's configurations), got {cables!r}")
    if load not in loads():
        raise ValueError(f"unknown load case {load!r}; valid: {', '.join(loads())}")
    s = SETTINGS[cables]
    best = max(published()[(cables, load)], key=lambda r: r["A_dstar"])
    return Problem(
        name=f"tdpm{cables}-{load.lower()}", x0=np.asarray(start, dtype=float),
        objective=lambda d: -dextrous_area(d, load),
        ineq=lambda d: BETA_MIN - separations(d),
        fd="central", fd_step=s["fd_step"], f_ref=-best["A_dstar"], x_ref=best["dstar"],
        source=f"Hay 2003, Sec. 6.6, eq. (6.29), Table {TABLES[(cables, load)]}",
        tags=("manipulator", "tdpm", f"{cables}-cable", load),
        meta={"cables": cables, "load": load, **s, "beta_min": BETA_MIN, "tensions": "l1"},
    )


def _options() -> dict[str, dict[str, Any]]:
    """rho = 0.1 (Section 6.6.2). Established solvers' tolerances [OWN]: the objective changes
    in steps of one grid cell (~1e-3 of A_d), so finer tolerances only add evaluations; caps
    keep a run within minutes (each evaluation is a dextrous workspace, up to ~40 ms)."""
    opts = {
        # the thesis's Dynamic-Q with rho = 0.1; its stopping tolerances are not restated in
        # Section 6.6.2, so Dynamic-Q's defaults (Section 3.4) apply, with an iteration cap
        "dynamic-q": {"rho": RHO, "max_iter": 150},  # >= the thesis's largest N^g (83)
        "scipy-cobyla": {"rhobeg": RHO, "tol": 1e-3, "maxfev": 400},
        "scipy-slsqp": {"maxiter": 40, "ftol": 1e-6},
        "nlopt-mma": {"maxeval": 80, "xtol_rel": 1e-4, "ftol_rel": 1e-5},
    }
    return opts


def _build() -> list[Case]:
    cases = []
    opts = _options()
    for cables in (3, 4):
        for load in ("L1", "L2", "L3"):
            for i, d0 in enumerate(random_starts(cables, load), start=1):
                cases.append(Case(tdpm_problem(cables, load, d0), f"tdpm{cables}-{load.lower()}",
                                  start=f"R{i}", options=opts,
                                  meta={"table": TABLES[(cables, load)], "cables": cables, "load": load}))
    return cases


SUITE = Suite(
    name="tdpm",
    description="cable robots (thesis Ch. 6): frame angles for the largest dextrous workspace, "
                "3 and 4 cables, loads L1-L3 (Tables 6.5-6.10), five random starts each",
    build=_build,
    solvers=SOLVERS,
    tables="harness.tables.tdpm",
    figures="harness.figures.tdpm",
)
