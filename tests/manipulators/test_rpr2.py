"""2-RPR kinematics (Section 4.3, Appendix D): Jacobian (4.22) and kappa^-1 (4.23)."""

import numpy as np
import pytest
import shapely

from manipulators import RPR2
from manipulators.rpr2 import inverse_condition

R = RPR2(-3.5, -0.6, 4.2, (4.0, 3.5), (6.5, 7.0))
RNG = np.random.default_rng(1)
U = np.column_stack((RNG.uniform(-3, 3, 20), RNG.uniform(0.5, 6, 20)))


@pytest.mark.parametrize("derivative, values", [("jacobian", "leg_lengths"),  # of the inverse kinematics
                                                  ("constraint_jacobian", "constraints")])
def test_jacobians_against_central_differences(derivative, values):
    h = 1e-6
    J = getattr(R, derivative)(U)
    fun = getattr(R, values)
    for k in range(2):
        e = np.zeros(2)
        e[k] = h
        fd = (fun(U + e) - fun(U - e)) / (2 * h)
        assert np.allclose(J[:, :, k], fd, atol=1e-8)


def test_inverse_condition_is_det_j_and_one_over_kappa():
    J = R.jacobian(U)
    det = np.linalg.det(J)
    kinv = R.inverse_condition(U)
    assert np.allclose(kinv, det, atol=1e-12)
    # kappa = ||J|| ||J^-1|| with ||A|| = sqrt(tr(A W A^T)), W = I/2 (4.19)-(4.20)
    norm = lambda A: np.sqrt(np.einsum("kij,kij->k", A, A) / 2)
    kappa = norm(J) * norm(np.linalg.inv(J))
    assert np.allclose(kinv, 1 / kappa, rtol=1e-10)
    assert np.all((kinv > 0) & (kinv <= 1 + 1e-12))


def test_kappa_inverse_is_one_on_the_ridge_circle():
    # (4.24): the circle of radius (xB - xA)/2 about the base midpoint
    t = np.linspace(0.1, np.pi - 0.1, 9)
    c, rad = (R.xA + R.xB) / 2, (R.xB - R.xA) / 2
    pts = np.column_stack((c + rad * np.cos(t), R.yA + rad * np.sin(t)))
    assert np.allclose(R.inverse_condition(pts), 1.0)
    assert np.allclose(inverse_condition(R.xA, R.yA, R.xB, pts), 1.0)


def test_forward_inverts_inverse_kinematics():
    L = R.leg_lengths(U)
    assert np.allclose(R.forward(L[:, 0], L[:, 1]), U)


@pytest.mark.parametrize("kw,msg", [
    (dict(xA=1.0, yA=0.0, xB=1.0), "singular"),
    (dict(xA=0.0, yA=0.0, xB=1.0, l_min=(3, 3), l_max=(2, 4)), "l_min < l_max"),
    (dict(xA=0.0, yA=0.0, xB=1.0, l_min=(0, 3), l_max=(2, 4)), "> 0"),
    (dict(xA=np.nan, yA=0.0, xB=1.0), "finite"),
])
def test_invalid_designs_raise_clear_errors(kw, msg):
    with pytest.raises(ValueError, match=msg):
        RPR2(**kw)


def test_interior_point_is_strictly_inside():
    u = R.interior_point()
    assert np.all(R.constraints(u[None]) < 0)


def test_interior_point_is_the_mid_range_pose_eq_c7():
    """Appendix C.4: u0 has both legs at mid-range, so it moves continuously with the design."""
    u0 = R.interior_point()
    mid = 0.5 * (np.array(R.l_min) + np.array(R.l_max))
    assert np.allclose(R.leg_lengths(u0[None, :])[0], mid, atol=1e-12)


def test_discretized_o_objective_has_no_steps_under_small_perturbations():
    """The radiating point of the chord trace must not jump between designs 1e-5 apart
    (a grid argmax did: forward differences at SP4 read gradients of ~4e2)."""
    from manipulators.synthesis.rpr2_suite import STARTS, o_problem

    f = o_problem("SP4").objective
    x = np.array(STARTS["SP4"])
    g = [np.array([(f(x + h * e) - f(x)) / h for e in np.eye(5)]) for h in (1e-5, 1e-3)]
    assert np.max(np.abs(g[0])) < 5.0
    assert np.allclose(g[0], g[1], atol=0.05)


def test_trace_narrower_than_the_chord_is_redone_and_encloses_the_radiating_point():
    """A small lens (area 0.27) whose tips are narrower than d = 0.5: the first trace does not
    close around the radiating point; the re-trace at a smaller chord is accurate."""
    m = RPR2(-5.006011568544285, -0.10553532405737842, 5.598621135904642, (4.150287869114623, 3.1302070772501334),
             (1.5 * 4.150287869114623, 1.5 * 3.1302070772501334))
    ws = m.workspace(0.5)
    assert ws.info.get("refined_from") == 0.5
    assert ws.contains(m.interior_point()[None, :])[0]
    assert abs(ws.area - m.exact_region().area) < 0.01 * m.exact_region().area


def test_sharp_corner_at_the_start_of_the_trace_does_not_double_back():
    """A thin crescent with a sharp tip next to b^1: the trace used to step across the tip
    and back (area 0.001 for an exact 4.92, then a re-trace). Now the chord step skips the
    crossing behind the corner: one simple trace that cuts only the tip narrower than d."""
    m = RPR2(-1.001, -1.009, 4.216, (3.187, 4.998), (1.5 * 3.187, 1.5 * 4.998))
    ws = m.workspace(0.5)
    assert shapely.LinearRing(ws.boundary).is_simple
    assert ws.contains(m.interior_point()[None, :])[0]
    assert abs(ws.area - m.exact_region().area) < 0.025 * m.exact_region().area


# ---------------------------------------------------------------- closed-form area (lens inclusion-exclusion)
def _random_designs(n=40, seed=3):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        lo = rng.uniform(0.3, 5.0, 2)
        out.append(RPR2(rng.uniform(-4, 0), rng.uniform(-2, 2), rng.uniform(0.05, 6), tuple(lo),
                        tuple(lo + rng.uniform(0.1, 4.0, 2))))
    return out


SPECIAL = [
    RPR2(-5.0, 0.0, 5.0, (1.0, 1.0), (2.0, 3.0)),    # disjoint outer disks: area 0
    RPR2(-1.0, 0.0, 1.0, (4.0, 0.5), (5.0, 1.0)),    # annulus 2 wholly inside hole 1: area 0
    RPR2(-0.1, 0.3, 0.1, (1.0, 2.0), (6.0, 3.0)),    # annulus 2 nested in annulus 1
    RPR2(-0.1, 0.3, 0.1, (1.0, 1.5), (3.0, 4.0)),    # nearly concentric, holes nested
    RPR2(-2.0, 0.0, 2.0, (1.0, 1.0), (2.0, 2.0)),    # outer circles tangent (c = R1 + R2)
    RPR2(-1.5, 0.0, 1.5, (1.0, 1.0), (4.0, 4.0)),    # hole circles touch (c = r1 + r2)
    RPR2(-0.5, 0.0, 0.5, (2.0, 1.0), (3.0, 4.0)),    # internally tangent circles (c = r1 - r2, R2 - R1)
    RPR2(3.0, -1.0, -3.0, (5.0, 5.5), (7.5, 8.25)),  # xB < xA
]


@pytest.mark.parametrize("m", _random_designs() + SPECIAL)
def test_exact_area_matches_the_shapely_region(m):
    # exact_region approximates circles by 4096-gons (relative area error ~1e-7)
    assert m.exact_area() == pytest.approx(m.exact_region().area, rel=1e-6, abs=1e-6 * max(m.l_max) ** 2)


def test_exact_area_of_disjoint_and_empty_cases_is_zero():
    assert SPECIAL[0].exact_area() == 0.0 and SPECIAL[1].exact_area() == pytest.approx(0.0, abs=1e-12)
    # annulus 2 inside annulus 1: half the area of annulus 2
    assert SPECIAL[2].exact_area() == pytest.approx(0.5 * np.pi * (3.0**2 - 2.0**2), rel=1e-12)


# (not at the tangent cases: L is C^1 there, but central differences err by ~sqrt(h))
@pytest.mark.parametrize("m", _random_designs(12, seed=5) + SPECIAL[2:4] + SPECIAL[7:])
def test_exact_area_gradient_against_central_differences(m):
    a, g = m.exact_area(grad=True)
    v = np.array([m.xA, m.yA, m.xB, *m.l_min, *m.l_max])
    h = 1e-6

    def area(w):
        return RPR2(w[0], w[1], w[2], (w[3], w[4]), (w[5], w[6])).exact_area()

    fd = np.array([(area(v + h * e) - area(v - h * e)) / (2 * h) for e in np.eye(7)])
    assert np.allclose(g, fd, atol=1e-6)
