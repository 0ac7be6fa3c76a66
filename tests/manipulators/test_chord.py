"""The generic chord method (Appendix C): accuracy against exact geometry, closure,
orientation, bifurcation points, error handling, non-smooth constraints, speed."""

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from manipulators import RPR2, chord_boundary
from manipulators.workspace import InfeasibleInterior, Workspace, is_ccw, polygon_area

P_START = RPR2(-4.0, -0.1, 4.0, (4.0, 4.0), (7.0, 7.0))


def _random_designs(n, seed=0):
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        xA, xB = rng.uniform(-5, -1), rng.uniform(1, 5)
        lo = rng.uniform(2.5, 5.5, 2)
        r = RPR2(xA, rng.uniform(-2, 1), xB, tuple(lo), tuple(lo * rng.uniform(1.2, 1.9, 2)))
        if r.interior_point() is not None:
            out.append(r)
    return out


DESIGNS = [P_START] + _random_designs(6)


@pytest.mark.parametrize("r", DESIGNS, ids=lambda r: f"{r.xA:.2f},{r.yA:.2f},{r.xB:.2f}")
def test_area_points_and_bifurcations_against_exact_geometry(r):
    ws = r.workspace(0.1)
    assert ws.info["closed"]
    exact = r.exact_region(quad_segs=2048).area
    assert abs(ws.area - exact) <= 0.005 * exact
    C = r.constraints(ws.boundary)
    # every boundary point: no limit violated, one limit active (to 1e-6)
    assert C.max() <= 1e-6
    assert np.all(np.abs(C.max(axis=1)) <= 1e-6)
    # bifurcation points: two limits active (to 1e-8)
    for b in ws.bifurcations:
        c = np.sort(np.abs(r.constraints(b[None])[0]))
        assert c[1] <= 1e-8
    assert np.all(ws.active[ws.active >= 0] < 5)


def test_start_design_has_the_expected_corners():
    ws = P_START.workspace(0.1)
    # the outer circles l1 = l2 = 7 meet on x = 0, and l_max/l_min circles at x = +-2.0625
    bx = np.sort(ws.bifurcations[:, 0])
    assert np.any(np.isclose(bx, 0.0, atol=1e-9))
    assert np.any(np.isclose(bx, -2.0625, atol=1e-9)) and np.any(np.isclose(bx, 2.0625, atol=1e-9))


def test_chord_lengths_are_d_between_traced_points():
    ws = P_START.workspace(0.1, bifurcations=False)
    steps = np.hypot(*np.diff(ws.boundary, axis=0).T)
    assert np.allclose(steps, 0.1, atol=1e-8)


def test_interior_point_must_be_feasible():
    with pytest.raises(InfeasibleInterior, match="not strictly feasible"):
        chord_boundary(P_START.constraints, (0.0, -5.0), 0.1)
    with pytest.raises(ValueError, match="chord length"):
        chord_boundary(P_START.constraints, (0.0, 5.0), 0.0)


def test_empty_workspace_is_reported_not_raised():
    r = RPR2(-10.0, 0.0, 10.0, (1.0, 1.0), (2.0, 2.0))  # legs too short to meet
    ws = r.workspace(0.1)
    assert ws.is_empty and ws.area == 0.0 and ws.boundary.shape == (0, 2)


def test_disc_with_smooth_and_indicator_constraints():
    def disc(U):
        return (np.hypot(U[:, 0] - 1.0, U[:, 1] + 2.0) - 1.5)[:, None]

    def indicator(U):  # 0/1 "infeasible" flag, as for cable tensions (Algorithm 6.3)
        return (disc(U) > 0).astype(float)

    exact = np.pi * 1.5**2
    for smooth, f in ((True, disc), (False, indicator)):
        ws = chord_boundary(f, (1.0, -2.0), 0.05, smooth=smooth, tol=1e-9)
        assert ws.info["closed"] and is_ccw(ws.boundary)
        assert abs(ws.area - exact) < 0.002 * exact
        assert np.max(np.abs(disc(ws.boundary))) < 1e-8


def test_square_corners_by_newton_and_by_bisection():
    def box(U):
        return np.column_stack((U[:, 0] - 1, -1 - U[:, 0], U[:, 1] - 1, -1 - U[:, 1]))

    for smooth, f in ((True, box), (False, lambda U: (box(U) > 0).astype(float))):
        ws = chord_boundary(f, (0.1, 0.2), 0.3, smooth=smooth, tol=1e-10)
        assert ws.bifurcations.shape == (4, 2)
        assert np.allclose(np.abs(ws.bifurcations), 1.0, atol=1e-8)
        assert ws.area == pytest.approx(4.0, abs=1e-7)


def test_contains_and_polygon():
    ws = P_START.workspace(0.1)
    inside = ws.contains(np.array([[0.0, 5.0], [0.0, 10.0], [0.0, -1.0]]))
    assert inside.tolist() == [True, False, False]
    assert ws.polygon().area == pytest.approx(ws.area)


def test_grid_workspace_contains():
    x = np.linspace(0, 1, 11)
    y = np.linspace(0, 2, 21)
    X, Y = np.meshgrid(x, y)
    ws = Workspace(method="grid", mask=X + Y < 1, grid=(x, y), area=0.5)
    assert ws.contains([[0.1, 0.1], [0.9, 1.5], [5, 5]]).tolist() == [True, False, False]
    with pytest.raises(ValueError, match="mask"):
        Workspace(method="grid", mask=np.ones((3, 3), bool), grid=(x, y))


@settings(max_examples=15, deadline=None)
@given(xA=st.floats(-5, -1), yA=st.floats(-2, 1), xB=st.floats(1, 5),
       l1=st.floats(2.5, 5.5), l2=st.floats(2.5, 5.5), k1=st.floats(1.2, 1.9), k2=st.floats(1.2, 1.9),
       d=st.sampled_from([0.1, 0.25, 0.5]))
def test_boundaries_are_closed_and_counterclockwise(xA, yA, xB, l1, l2, k1, k2, d):
    r = RPR2(xA, yA, xB, (l1, l2), (k1 * l1, k2 * l2))
    ws = r.workspace(d)
    if ws.is_empty:
        assert r.interior_point() is None
        return
    assert ws.info["closed"]
    assert is_ccw(ws.boundary)
    # a trace that missed the radiating point is redone at a halved chord (RPR2.workspace)
    dc = ws.info["chord"]
    assert dc == d or (ws.info.get("refined_from") == d and dc < d)
    assert ws.contains(r.interior_point()[None, :])[0]
    traced = ws.boundary[ws.active >= 0]  # without the inserted bifurcation points
    gaps = np.hypot(*np.diff(np.vstack((traced, traced[:1])), axis=0).T)
    assert np.allclose(gaps[:-1], dc, atol=1e-8)  # constant chord length
    assert gaps[-1] <= 2 * dc + 1e-8  # closure (C.14): b^n within d of b^1 was dropped
    assert polygon_area(ws.boundary) == pytest.approx(ws.area)
    assert shapely.LinearRing(ws.boundary).is_simple  # never doubles back on itself


@pytest.mark.parametrize("d", [0.1, 0.5])
def test_traces_never_double_back_at_sharp_corners(d):
    """The chord circle about a point just past a sharp convex corner dips back into the
    thin wedge behind it; taking that crossing made the trace step back and forth across
    the corner (a quarter of these designs at d = 0.1), harmless to the polygon's area but
    not to the triangle scheme (4.9), which then counted a strip twice (E synthesis: jumps of
    0.25 in dW_c under 1e-3 changes of d).  Every trace must be a simple closed curve."""
    rng = np.random.default_rng(1)
    n_traced = 0
    for _ in range(300):
        lmin = rng.uniform(3, 6.5, 2)
        r = RPR2(rng.uniform(-6, -1), rng.uniform(-3, 1), rng.uniform(1, 6), tuple(lmin), tuple(1.5 * lmin))
        ws = r.workspace(d)
        if ws.n_boundary < 3:
            continue
        n_traced += 1
        assert shapely.LinearRing(ws.boundary).is_simple, (r, d)
    assert n_traced > 250


def test_triangle_scheme_is_continuous_across_a_sharp_corner():
    """E synthesis near Dynamic-Q's SP1 end point: dW_c by the triangle scheme follows the
    exact value along a line of designs (it jumped by 0.25 where the trace doubled back)."""
    from manipulators.objectives import delta_areas
    from manipulators.prescribed import P1

    d0 = np.array([-2.863, -2.967, 2.812, 5.305, 5.288])
    v = np.array([-4.803, -2.181, 4.803, 5.652, 5.652]) - d0
    for t in np.linspace(0.0, 0.1, 11):
        d = d0 + t * v
        r = RPR2(d[0], d[1], d[2], (d[3], d[4]), (1.5 * d[3], 1.5 * d[4]))
        dwc = delta_areas(r.workspace(0.1), P1)[1]
        exact = r.exact_region().difference(P1.polygon(2048)).area
        assert abs(dwc - exact) < 0.02, (t, dwc, exact)


def test_benchmark_one_workspace_at_d01(benchmark):
    ws = benchmark(P_START.workspace, 0.1)
    assert ws.info["closed"]
