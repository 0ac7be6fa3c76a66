"""The ``spatial`` suite: 8-cable dextrous volume and Gough-Stewart box enclosure (docs/spatial.md)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from manipulators.synthesis.spatial_suite import (
    CABLE,
    GS,
    cable_design,
    cable_problem,
    dextrous_rays,
    gs_constraints,
    gs_design,
    gs_problem,
    ray_volume,
    sphere_directions,
)
from problems import get_suite


def test_suite_has_the_four_formulations_with_at_least_8_design_variables():
    suite = get_suite("spatial")
    assert [c.problem.name for c in suite.cases()] == ["spatial-cable-9", "spatial-cable-13", "spatial-gs-9",
                                                        "spatial-gs-18"]
    assert all(c.problem.n >= 8 and c.problem.is_constrained for c in suite.cases())
    assert suite.tables == "harness.tables.spatial" and suite.figures == "harness.figures.spatial"


def test_ray_volume_of_a_ball_is_exact():
    assert ray_volume(np.full(32, 0.7)) == pytest.approx(4 / 3 * math.pi * 0.7**3, rel=1e-12)
    D = sphere_directions(200)
    assert np.allclose(np.linalg.norm(D, axis=1), 1.0) and np.allclose(D.mean(axis=0), 0.0, atol=0.02)


def test_dextrous_rays_end_on_the_boundary():
    """Each reach is dextrous just inside (every load and orientation) and not just outside."""
    m = cable_design(cable_problem(9).x0)
    c = np.asarray(CABLE["centre"])
    D = sphere_directions(CABLE["n_rays"])
    r = dextrous_rays(m, tol=1e-9)
    assert np.all(r > 0)

    def dextrous(P):
        return np.logical_and.reduce([m.feasible(P, rot, w) for rot in CABLE["orientations"] for w in CABLE["loads"]])

    cut = r < CABLE["reach"]
    assert dextrous(c + (r[cut] - 1e-6)[:, None] * D[cut]).all()
    assert not dextrous(c + (r[cut] + 1e-6)[:, None] * D[cut]).any()


def test_the_start_volume_and_its_continuity():
    p = cable_problem(9)
    x0 = np.asarray(p.x0)
    v0 = -p.objective(x0)
    assert 1.0 < v0 < 2.0
    assert abs(-p.objective(x0 + 1e-6) - v0) < 1e-3  # continuous in the design: finite differences see a slope


def test_thirteen_variables_extend_the_nine():
    """The 13-variable cable design at the 9-variable start's widening is the same robot."""
    a, b = cable_design(cable_problem(9).x0), cable_design(cable_problem(13).x0)
    assert np.array_equal(a.frame_points, b.frame_points) and np.array_equal(a.platform_points, b.platform_points)


def test_gs_gradient_and_constraints():
    p = gs_problem(9)
    x = np.asarray(p.x0) + 0.01
    fd = np.array([(p.objective(x + 1e-7 * e) - p.objective(x)) / 1e-7 for e in np.eye(p.n)])
    assert np.allclose(p.gradient(x), fd, atol=1e-6)
    g = gs_constraints(p.x0)
    assert g.shape == (p.n_ineq,) and np.all(np.isfinite(g)) and g.max() <= 0  # the start encloses the box
    # the epigraph rows equal t - kappa^-1 at the box points
    m = gs_design(p.x0)
    P = np.asarray([[0.0, 0.0, p.x0[7]]])
    assert m.inverse_condition(P, GS["orientations"][0])[0] > 0.3


def test_eighteen_variables_extend_the_nine():
    a, b = gs_design(gs_problem(9).x0), gs_design(gs_problem(18).x0)
    assert np.allclose(a.base_points, b.base_points) and np.allclose(a.platform_points, b.platform_points)


def test_bad_input_and_degenerate_designs():
    with pytest.raises(ValueError, match="9 or 13"):
        cable_problem(10)
    with pytest.raises(ValueError, match="9 or 18"):
        gs_problem(5)
    assert cable_design([-1.0, 1, 2.5, 0.5, 0.2, 0.1, 0.3, 0, 0]) is None
    assert cable_problem(9).objective(np.array([-1.0, 1, 2.5, 0.5, 0.2, 0.1, 0.3, 0, 0])) == 0.0
    bad = np.array(gs_problem(9).x0)
    bad[5], bad[6] = 1.2, 0.7  # l_min > l_max
    assert gs_design(bad) is None and np.all(np.isfinite(gs_constraints(bad))) and gs_constraints(bad).max() > 0


def test_table_and_figure_plugins_on_stored_like_runs(tmp_path):
    from harness.figures.spatial import figures
    from harness.tables.spatial import tables

    rows = []
    for prob in (cable_problem(9), gs_problem(9)):
        x0 = np.asarray(prob.x0)
        rows.append({"suite": "spatial", "problem": prob.name, "case_id": f"{prob.name}/n={prob.n}/d0", "n": prob.n,
                     "solver": "dynamic-q", "status": "converged", "nfg": 1, "x": x0, "f": prob.objective(x0),
                     "max_violation": 0.0, "wall_time_s": 0.1})
    t_runs, t_growth = tables(pd.DataFrame(rows))
    assert len(t_runs.frame) == 2 and "grid volume" in t_runs.frame["independent check"].iloc[0]
    assert "enclosed" in t_runs.frame["independent check"].iloc[1]
    assert list(t_growth.frame["solver"]) == ["dynamic-q"]
    paths = figures(pd.DataFrame(rows), tmp_path)
    assert {p.name for p in paths} >= {"fig_spatial_cable.png", "fig_spatial_gs.png"}
