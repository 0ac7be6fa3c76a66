"""3-RPR kinematics, Jacobian (5.13), kappa^-1 (4.19-4.20) and orientation ranges (5.26)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from manipulators import RPR3
from manipulators.rpr3 import M_DESIGNS


def test_named_designs_and_validation():
    m = RPR3.named("M3")
    assert np.allclose(m.design, M_DESIGNS["M3"])
    assert np.allclose(m.base[:, 1], 0.0)  # y_C = y_D = y_E
    with pytest.raises(ValueError, match="valid"):
        RPR3.named("M4")
    with pytest.raises(ValueError, match="r must be > 0"):
        RPR3(-1, 0, 1, 2, 0.0)
    with pytest.raises(ValueError, match="finite"):
        RPR3(np.nan, 0, 1, 2, 1)
    with pytest.raises(ValueError, match="l_min < l_max"):
        RPR3(-1, 0, 1, 2, 1, l_min=(2, 2, 2), l_max=(1, 3, 3))
    with pytest.raises(ValueError, match="5 entries"):
        RPR3.from_design([1, 2, 3])
    with pytest.raises(ValueError, match="shape"):
        m.leg_lengths(np.zeros((3, 3)), 0.0)


def test_inverse_kinematics_eq_5_7():
    m = RPR3(-1.0, 0.2, 1.0, 2.0, 0.8)
    u, w = np.array([0.4, 1.3]), 0.3
    A = u - m.r * np.array([math.cos(w), math.sin(w)])
    B = u + m.r * np.array([math.cos(w), math.sin(w)])
    expect = [np.hypot(*(A - m.base[0])), np.hypot(*(A - m.base[1])), np.hypot(*(B - m.base[2]))]
    assert np.allclose(m.leg_lengths(u, w)[0], expect, rtol=0, atol=1e-14)


@pytest.mark.parametrize("name", ["M1", "M2", "M3"])
def test_jacobian_against_finite_differences(name):
    m = RPR3.named(name)
    rng = np.random.default_rng(1)
    U = rng.uniform([-0.5, 0.8], [1.5, 1.8], (20, 2))
    W = rng.uniform(-0.5, 0.5, 20)
    J = m.jacobian(U, W) * np.array([m.r, m.r, 1.0])  # undo the normalization of (5.13)
    h = 1e-6
    for k in range(U.shape[0]):
        cols = []
        for e in np.eye(2):
            cols.append((m.leg_lengths(U[k] + h * e, W[k])[0] - m.leg_lengths(U[k] - h * e, W[k])[0]) / (2 * h))
        cols.append((m.leg_lengths(U[k], W[k] + h)[0] - m.leg_lengths(U[k], W[k] - h)[0]) / (2 * h))
        assert np.allclose(J[k], np.column_stack(cols), atol=1e-8)


def test_kappa_matches_svd_and_finite_difference_scale():
    m = RPR3.named("M1")
    rng = np.random.default_rng(2)
    U = rng.uniform([-0.5, 0.8], [1.5, 1.8], (50, 2))
    W = rng.uniform(-0.5, 0.5, 50)
    got = m.inverse_condition(U, W)
    s = np.linalg.svd(m.jacobian(U, W), compute_uv=False)
    ref = 3.0 / np.sqrt((s**2).sum(1) * (s**-2).sum(1))
    assert np.allclose(got, ref, rtol=1e-12)
    assert np.all((got > 0) & (got <= 1))
    # singular pose: everything collinear on the base line at phi = 0
    assert m.inverse_condition([0.3, 0.0], 0.0)[0] == pytest.approx(0.0, abs=1e-12)


def _brute_range(m, u, w_ref, n=8001):
    ws = np.linspace(w_ref - math.pi, w_ref + math.pi, n)
    V = m.leg_lengths(np.repeat(u[None], n, 0), ws)
    ok = np.all((V <= m.lmax) & (V >= m.lmin), axis=1)
    i0 = n // 2
    if not ok[i0]:
        return None
    j = i0
    while j + 1 < n and ok[j + 1]:
        j += 1
    i = i0
    while i - 1 >= 0 and ok[i - 1]:
        i -= 1
    return ws[i], ws[j], ws[1] - ws[0]


@pytest.mark.parametrize("name", ["M1", "M2", "M3"])
def test_orientation_range_closed_form_against_brute_force(name):
    m = RPR3.named(name)
    rng = np.random.default_rng(3)
    U = rng.uniform([-0.5, 0.9], [1.5, 1.9], (400, 2))
    lo, hi = m.orientation_range(U, 0.0)
    checked = 0
    for k in range(0, 400, 5):
        br = _brute_range(m, U[k], 0.0)
        if br is None:
            assert np.isnan(lo[k]) and np.isnan(hi[k])
            continue
        a, b, h = br
        # a component reaching the end of the sampled window [w_ref - pi, w_ref + pi] may go on
        if a > -math.pi + h:
            assert lo[k] == pytest.approx(a, abs=2 * h)
        else:
            assert lo[k] <= a + 2 * h
        if b < math.pi - h:
            assert hi[k] == pytest.approx(b, abs=2 * h)
        else:
            assert hi[k] >= b - 2 * h
        checked += 1
    assert checked >= 5


def test_orientation_range_numeric_thesis_method_agrees():
    m = RPR3.named("M1")
    U = np.random.default_rng(6).uniform([-0.5, 0.9], [1.5, 1.9], (400, 2))
    U = U[np.isfinite(m.orientation_range(U, 0.0)[0])][:3]
    a = np.column_stack(m.orientation_range(U, 0.0))
    b = np.column_stack(m.orientation_range(U, 0.0, method="numeric"))
    assert np.all(np.isfinite(a))
    assert np.allclose(a, b, atol=1e-6)
    with pytest.raises(ValueError, match="closed"):
        m.orientation_range(U, 0.0, method="magic")


def test_orientation_intervals_contain_component():
    m = RPR3.named("M2")
    u = np.array([0.3, 1.4])
    ivs = m.orientation_intervals(u)
    lo, hi = m.orientation_range(u, 0.0)
    assert any(a <= lo[0] + 1e-12 and hi[0] <= b + 1e-12 for a, b in ivs)


@settings(max_examples=40, deadline=None)
@given(x=st.floats(-1.0, 2.0), y=st.floats(0.3, 2.2), a=st.floats(-0.4, 0.2), width=st.floats(0.0, 0.6))
def test_dextrous_constraints_equal_dense_orientation_sampling(x, y, a, width):
    """Property: closed-form worst-case leg constraints == feasibility at all sampled w."""
    m = RPR3.named("M1")
    u = np.array([[x, y]])
    b = a + width
    c = m.dextrous_constraints(u, a, b, branch=None).max()
    ws = np.linspace(a, b, 801)
    V = m.leg_lengths(np.repeat(u, ws.size, 0), ws)
    worst = max((V - m.lmax).max(), (m.lmin - V).max())
    assert c == pytest.approx(worst, abs=1e-5)  # sampling error of the dense grid


def test_orientation_constraints_same_sign_as_leg_constraints():
    m = RPR3.named("M2")
    rng = np.random.default_rng(4)
    U = rng.uniform([-0.5, 0.9], [1.5, 1.9], (3000, 2))
    a, b = math.radians(-5), math.radians(5)
    c_leg = m.dextrous_constraints(U, a, b, branch=None).max(1)
    c_or = m.orientation_constraints(U, a, b).max(1)
    clear = np.abs(c_leg) > 1e-9
    assert np.array_equal((c_leg <= 0)[clear], (c_or <= 0)[clear])


def test_maximal_constraint_sign():
    m = RPR3.named("M3")
    rng = np.random.default_rng(5)
    U = rng.uniform([-2.5, -2.5], [3.0, 2.5], (300, 2))
    c = m.maximal_constraints(U)[:, 0]
    ws = np.linspace(-math.pi, math.pi, 3601)
    for k in range(0, 300, 3):
        V = m.leg_lengths(np.repeat(U[k:k + 1], ws.size, 0), ws)
        reach = np.any(np.all((V <= m.lmax + 1e-12) & (V >= m.lmin - 1e-12), axis=1))
        if abs(c[k]) > 1e-3:
            assert (c[k] <= 0) == reach
