"""Cable-robot workspaces: grid (Algorithm 6.2), chord (Algorithm 6.3), dextrous (Section 6.5),
and the published optimal designs of Tables 6.5-6.10."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from manipulators.cable import CableRobot, design_robot, loads, thesis_robot
from problems.reference import thesis_table

TOL_PUBLISHED = 0.03  # acceptance: within 3 % of the published A_d*


def _published():
    rows = []
    for r in thesis_table("table_6_5_to_6_10_tdpm_synthesis").itertuples():
        n = int(r.cables)
        d = [float(getattr(r, f"dstar_beta{i}")) for i in range(1, n + 1)]
        marks = ()
        if r.table == "6.6" and r.run == "4":
            # The only published design we do not reproduce: a local maximum whose printed
            # d* gives 0.167 here (0.175 at most within +-0.01 rad of it), not 0.2504; the
            # 23 other designs agree within 1.1 %. Kept visible as a strict xfail.
            marks = (pytest.mark.xfail(strict=True, reason="Table 6.6 run 4: printed d* gives A = 0.167, not 0.2504"),)
        rows.append(pytest.param(n, r.load, d, float(r.A_dstar), marks=marks, id=f"T{r.table}-{r.load}-run{r.run}"))
    return rows


def dextrous(robot, load):
    if robot.n == 3:  # Section 6.6.2: [-0.1, 0.1], m = 100, m_sl = 3
        return robot.dextrous_workspace(-0.1, 0.1, loads()[load], resolution=100, slices=3)
    return robot.dextrous_workspace(-0.2, 0.2, loads()[load], resolution=50, slices=21)


@pytest.mark.parametrize("n,load,d,published", _published())
def test_published_optimal_designs(n, load, d, published):
    area = dextrous(design_robot(d), load).area
    assert abs(area - published) <= TOL_PUBLISHED * published, (area, published)


def test_grid_layout_and_area():
    """ERRATA: (m + 1)^2 points on [min c_x, max c_x] x [min c_y, max c_y]; area = count x cell."""
    robot = thesis_robot(4)
    ws = robot.workspace(0.0, loads()["L1"], resolution=40)
    x, y = ws.grid
    assert x.size == y.size == 41 and ws.mask.shape == (41, 41)
    assert (x[0], x[-1], y[0], y[-1]) == (-1.0, 1.0, -0.5, 0.5)
    assert ws.area == pytest.approx(ws.mask.sum() * (2 / 40) * (1 / 40))
    # every grid point agrees with the one-pose tension call
    X, Y = np.meshgrid(x, y)
    rng = np.random.default_rng(0)
    for i in rng.choice(X.size, 200, replace=False):
        u = np.array([X.flat[i], Y.flat[i]])
        assert (robot.tensions(u, 0.0, loads()["L1"]) is not None) == ws.mask.flat[i]


def test_methods_share_the_feasible_set_and_min_norm_is_smaller():
    robot = CableRobot([[1, 0.15], [-1, 0.15], [-1, -0.15], [1, -0.15]], thesis_robot(4).platform_points)
    w = loads()["L1"]
    masks = {m: robot.workspace(0.0, w, tensions=m).mask for m in ("l1", "l2", "l1-max", "l2-max", "min-norm")}
    for m in ("l2", "l1-max", "l2-max"):
        np.testing.assert_array_equal(masks[m], masks["l1"])
    assert not np.any(masks["min-norm"] & ~masks["l1"])
    assert masks["min-norm"].sum() < 0.5 * masks["l1"].sum()  # Fig. 6.3: severe underestimate
    # the kept tension field satisfies equilibrium and bounds at every feasible point
    ws = robot.workspace(0.0, w, tensions="l2")
    T = ws.info["tensions"][ws.mask]
    X, Y = np.meshgrid(*ws.grid)
    S = robot.structure_matrix(np.column_stack([X[ws.mask], Y[ws.mask]]), 0.0)
    assert np.max(np.abs(np.einsum("kin,kn->ki", S, T) + w)) < 1e-9
    assert T.min() >= 5 - 1e-9 and T.max() <= 100 + 1e-9


def test_three_cable_singularity_limit():
    """(6.24) on |det J|: the phi = 0 workspace has a gap at x = 0 (Section 6.4.2)."""
    robot = thesis_robot(3)
    ws = robot.workspace(0.0, loads()["L1"], resolution=100)
    x = ws.grid[0]
    assert not ws.mask[:, np.argmin(np.abs(x))].any()
    free = CableRobot(robot.frame_points, robot.platform_points, det_min=None)
    assert free.workspace(0.0, loads()["L1"], resolution=100).mask.sum() >= ws.mask.sum()


def test_dextrous_is_intersection_of_slices_and_mid_check():
    robot = design_robot([0.7572, 2.922, 3.097, 5.449])
    w = loads()["L3"]
    ws = robot.dextrous_workspace(-0.2, 0.2, w, resolution=30, slices=5)
    inter = np.ones_like(ws.mask)
    for p in np.linspace(-0.2, 0.2, 5):
        inter &= robot.workspace(p, w, resolution=30).mask
    np.testing.assert_array_equal(ws.mask, inter)
    two = robot.dextrous_workspace(-0.2, 0.2, w, resolution=30, slices=2)
    mid = robot.workspace(0.0, w, resolution=30).mask
    ext = robot.workspace(-0.2, w, resolution=30).mask & robot.workspace(0.2, w, resolution=30).mask
    assert two.info["mid_slice_valid"] == (not np.any(ext & ~mid))
    with pytest.raises(ValueError, match="phi_min <= phi_max"):
        robot.dextrous_workspace(0.2, -0.2, w)
    with pytest.raises(ValueError, match="slices"):
        robot.dextrous_workspace(-0.2, 0.2, w, slices=1)
    with pytest.raises(ValueError, match="resolution"):
        robot.workspace(0.0, w, resolution=0)
    with pytest.raises(ValueError, match="unknown workspace method"):
        robot.workspace(0.0, w, method="monte-carlo")


@pytest.mark.parametrize("n,load,phi", [(3, "L2", 0.05), (4, "L1", 0.0), (4, "L3", -0.2)])
def test_chord_matches_fine_grid(n, load, phi):
    robot = thesis_robot(n)
    w = loads()[load]
    ws = robot.workspace(phi, w, method="chord", chord=0.05 if (n, load) != (4, "L3") else 0.02)
    fine = robot.workspace(phi, w, resolution=300)
    assert ws.info["closed"] and ws.method == "chord"
    assert ws.area == pytest.approx(fine.area, rel=0.03)
    assert shapely.Polygon(ws.boundary).exterior.is_ccw
    # boundary points lie on the boundary: feasible within the bisection tolerance
    C = __import__("manipulators.cable._chord", fromlist=["x"]).constraint_function(robot, phi, w)
    nb = ws.boundary
    assert np.mean(np.all(C(nb) <= 0, axis=1)) > 0.95
    assert ws.bifurcations.shape[0] >= 2


# ----------------------------------------------------------------- benchmarks
def test_bench_grid_l1(benchmark):
    """4-cable constant-orientation grid workspace, m = 50, l1 tensions (target < 2 ms)."""
    robot = thesis_robot(4)
    ws = benchmark(robot.workspace, 0.0, loads()["L1"], resolution=50, tensions="l1")
    assert ws.area > 1.0


def test_bench_grid_l2_exact(benchmark):
    """Same with the exact constrained l2 tensions (6.17) (target < 20 ms; thesis 29.3 s)."""
    robot = thesis_robot(4)
    ws = benchmark(robot.workspace, 0.0, loads()["L1"], resolution=50, tensions="l2")
    assert np.isfinite(ws.info["tensions"][ws.mask]).all()


def test_bench_dextrous_4(benchmark):
    """Dextrous 4-cable workspace, m = 50, 21 slices (target < 40 ms)."""
    robot = design_robot([0.7572, 2.922, 3.097, 5.449])
    ws = benchmark(robot.dextrous_workspace, -0.2, 0.2, loads()["L3"], resolution=50, slices=21)
    assert ws.area > 1.2


def test_bench_one_lp_per_grid_point(benchmark):
    """The baseline: one LP (scipy HiGHS) per grid point, timed on a 60-point subsample.

    ``extra_info["extrapolated_grid_s"]`` is the time for the 2601 points of m = 50;
    compare with test_bench_grid_l1 (acceptance: >= 1000x). Also checks the verdicts agree.
    """
    robot = thesis_robot(4)
    w = loads()["L1"]
    ws = robot.workspace(0.0, w, resolution=50)
    X, Y = np.meshgrid(*ws.grid)
    idx = np.random.default_rng(0).choice(X.size, 60, replace=False)
    U = np.column_stack([X.flat[idx], Y.flat[idx]])

    def lp_path():
        return robot.tensions_batch(U, 0.0, w, "l1", backend="linprog")[0]

    feas = benchmark(lp_path)
    np.testing.assert_array_equal(feas, ws.mask.flat[idx])
    if benchmark.stats is not None:
        benchmark.extra_info["extrapolated_grid_s"] = benchmark.stats.stats.mean * X.size / idx.size


@pytest.mark.parametrize("n", [5, 6])
def test_grid_workspace_many_cables_matches_lp(n):
    """n >= 5: the vectorized basic-solution test agrees with one LP per grid point."""
    from manipulators.cable import frame_point

    rng = np.random.default_rng(n)
    robot = CableRobot(frame_point(np.linspace(0, 2 * np.pi, n, endpoint=False) + 0.3),
                       rng.uniform(-0.1, 0.1, (n, 2)))
    w = loads()["L2"]
    ws = robot.workspace(0.1, w, resolution=24, tensions="l1")
    assert 0 < ws.mask.sum() < ws.mask.size
    X, Y = np.meshgrid(*ws.grid)
    idx = rng.choice(X.size, 40, replace=False)
    U = np.column_stack([X.flat[idx], Y.flat[idx]])
    feas_lp = robot.tensions_batch(U, 0.1, w, "l1", backend="linprog")[0]
    np.testing.assert_array_equal(feas_lp, ws.mask.flat[idx])
    T = ws.info["tensions"][ws.mask]
    assert T.min() >= robot.t_min - 1e-9 and T.max() <= robot.t_max + 1e-9


def test_loads_are_read_only_copies():
    """An in-place change of a load case is refused instead of reaching every later caller
    (tdpm_suite included); replacing an entry changes only the caller's dict."""
    w = loads()["L1"]
    with pytest.raises(ValueError, match="read-only"):
        w *= 2
    mine = loads()
    mine["L1"] = 2 * mine["L1"]
    assert loads()["L1"].tolist() == [0.0, -10.0, 0.0]


def test_grid_workspace_refuses_unknown_keywords():
    with pytest.raises(TypeError, match="resolutoin"):
        thesis_robot(4).workspace(0.0, loads()["L1"], resolutoin=5)


def test_empty_workspaces_say_why():
    """Grid, chord and dextrous workspaces that are empty carry info["reason"], naming the limits."""
    r = thesis_robot(4)
    tight = CableRobot(r.frame_points, r.platform_points, t_min=0.0, t_max=1e-6)
    w = loads()["L1"]
    for ws in (tight.workspace(0.0, w), tight.workspace(0.0, w, method="chord", resolution=20),
               tight.dextrous_workspace(-0.1, 0.1, w, resolution=20, slices=3),
               r.workspace(0.0, [0.0, -1e5, 0.0], resolution=20)):
        assert ws.area == 0.0
        assert "none of the" in ws.info["reason"] and "cable tensions within" in ws.info["reason"]
    assert "reason" not in r.workspace(0.0, w, resolution=20).info
