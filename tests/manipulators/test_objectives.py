"""Objectives: triangle scheme (4.9, Fig. 4.3) vs exact areas, g (4.16), min kappa^-1 (App. D)."""

import pytest

from manipulators import RPR2
from manipulators.objectives import (
    delta_areas,
    delta_areas_exact,
    enclosure_constraint,
    min_inverse_condition,
    triangle_area,
)
from manipulators.prescribed import P1, P2, P3

START = RPR2(-4.0, -0.1, 4.0, (4.0, 4.0), (7.0, 7.0))


def test_triangle_area_eq_4_9():
    assert triangle_area([[0, 0]], [[2, 0]], [[0, 3]])[0] == pytest.approx(3.0)
    assert triangle_area([[1, 1]], [[2, 2]], [[3, 3]])[0] == 0.0


@pytest.mark.parametrize("P,expected", [(P1, 0.780), (P2, 0.823), (P3, 0.786)])
def test_f_d0_of_table_4_9(P, expected):
    # ERRATA: min kappa^-1 over dP for d0 = [-4, -0.1, 4], l in [4, 7]
    assert round(min_inverse_condition(START.inverse_condition, P), 3) == expected


def test_triangle_scheme_approaches_exact_areas():
    ws = START.workspace(0.1)
    ex = START.exact_region()
    for P in (P1, P2, P3):
        dwp, dwc = delta_areas(ws, P)
        dwp_x, dwc_x = delta_areas_exact(ex, P)
        assert dwp == pytest.approx(dwp_x, abs=0.01) and dwc == pytest.approx(dwc_x, abs=0.01)
        # the union is the same both ways: |W_c| + dW_p = |W_p| + dW_c
        assert ws.area + dwp == pytest.approx(P.area() + dwc, abs=0.01)  # P sampled at beta_c^i


def test_enclosure_constraint_sign():
    ws = START.workspace(0.1)
    assert enclosure_constraint(ws, P1) == pytest.approx(delta_areas(ws, P1)[0])  # not enclosed
    big = RPR2(-4.0, -1.0, 4.0, (3.0, 3.0), (9.0, 9.0)).workspace(0.1)
    assert delta_areas(big, P1)[0] == 0.0
    g = enclosure_constraint(big, P1)
    assert g < 0
    # -r^2 with r the smallest radial gap
    assert -g == pytest.approx(0.0, abs=10.0)
    assert enclosure_constraint(RPR2(-30, 0, 30, (1, 1), (2, 2)).workspace(0.1), P1) == pytest.approx(P1.area())


def test_e_synthesis_point_of_table_4_7():
    # ERRATA: SP1 d* gives f* = 2.885 (exact 2.884), h* = 0.7E-2
    d = [-4.152, -2.461, 4.060, 5.491, 5.441]
    r = RPR2(d[0], d[1], d[2], (d[3], d[4]), (1.5 * d[3], 1.5 * d[4]))
    dwp, dwc = delta_areas(r.workspace(0.1), P1)
    assert dwc == pytest.approx(2.885, abs=2e-3)
    assert dwp == pytest.approx(0.007, abs=1e-3)
    assert delta_areas_exact(r.exact_region(), P1)[1] == pytest.approx(2.884, abs=1e-3)


def test_star_shaped():
    from manipulators.objectives import star_shaped

    square = [[1, 1], [-1, 1], [-1, -1], [1, -1]]
    assert star_shaped(square, [0, 0]) and star_shaped(square[::-1], [0, 0])
    assert not star_shaped(square, [3, 0])  # outside: winds 0 times
    # a C shape around the origin: winds once, but rays to the left cross it three times
    c_shape = [[2, -2], [2, 2], [-2, 2], [-2, 1], [1, 1], [1, -1], [-2, -1], [-2, -2]]
    assert not star_shaped(c_shape, [1.5, 0])
    assert not star_shaped(c_shape, [1.5, 1.5])  # from the corner, rays through the gap hit the lower arm
    assert star_shaped(square, [0.9, -0.5])  # convex: from any inside point
    assert not star_shaped(square[:2], [0, 0])  # fewer than 3 points


def test_checked_areas_see_a_workspace_beside_the_prescribed_one():
    # Dynamic-Q+'s former E-synthesis end from SP3: the chord boundary lies beside W_p and does
    # not wind around its centre; the triangle scheme reports W_p enclosed (dW_p = 0)
    from manipulators.objectives import delta_areas_checked, star_shaped
    from manipulators.synthesis.rpr2_suite import design_o

    ws = design_o([-1.54, 0.0677, 4.389, 1.530, 2.500]).workspace(0.1)
    assert not star_shaped(ws.boundary, P1.centre)
    assert delta_areas(ws, P1)[0] == 0.0
    dwp, dwc = delta_areas_checked(ws, P1)
    assert dwp == pytest.approx(P1.area(), rel=1e-3)  # W_p entirely uncovered
    assert (dwp, dwc) == pytest.approx(delta_areas_exact(ws, P1), rel=1e-12)


@pytest.mark.parametrize("d", [(-2.0, -0.075, 2.0, 3.0, 3.0), (-4.803, -2.181, 4.803, 5.652, 5.652),
                               (-4.152, -2.461, 4.060, 5.491, 5.441)])
def test_checked_areas_are_the_triangle_scheme_where_it_measures(d):
    # a boundary around O' (SP1, not enclosing; the exact-model local minimum and the thesis's
    # E optimum, enclosing): the thesis's values, bit for bit
    from manipulators.objectives import delta_areas_checked
    from manipulators.synthesis.rpr2_suite import design_o

    ws = design_o(d).workspace(0.1)
    assert delta_areas_checked(ws, P1) == delta_areas(ws, P1)
