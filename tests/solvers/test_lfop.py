"""LFOP core (algorithms.md section 1; thesis Appendix B.3)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from solvers.lfop import LfopParams, lfop


def rosen_grad(x):
    return np.array([-400 * x[0] * (x[1] - x[0] ** 2) - 2 * (1 - x[0]), 200 * (x[1] - x[0] ** 2)])


def test_sphere_from_3_3_reaches_eps_g():
    # algorithms.md section 6: f = x'x/2 from (3, 3) ends with ||grad|| <= 1e-5
    r = lfop(lambda x: x, np.array([3.0, 3.0]))
    assert r.reason == "eps_g" and r.grad_norm <= 1e-5
    assert np.linalg.norm(r.x) <= 1e-5
    assert 1 < r.ng < 200


@pytest.mark.parametrize("guard", [False, True])
def test_rosenbrock_converges_with_and_without_guard(guard):
    r = lfop(rosen_grad, np.array([-1.2, 1.0]), LfopParams(stiffness_guard=guard, max_steps=20_000))
    assert r.reason == "eps_g"
    np.testing.assert_allclose(r.x, [1.0, 1.0], atol=1e-4)


def test_counts_every_gradient_call_and_never_needs_f():
    calls = []

    def grad(x):
        calls.append(x.copy())
        return 2 * x

    r = lfop(grad, np.array([1.0, -2.0, 0.5]))
    assert r.ng == len(calls)
    # the returned point is the last point at which the gradient was evaluated
    np.testing.assert_array_equal(r.x, calls[-1])


def test_stationary_start_stops_at_once():
    r = lfop(lambda x: np.zeros(2), np.array([1.0, 1.0]))
    assert r.ng == 1 and r.reason == "eps_g"


def test_max_steps_flag():
    r = lfop(rosen_grad, np.array([-1.2, 1.0]), LfopParams(max_steps=50))
    assert r.reason == "max_steps" and r.ng == 50


def test_nonfinite_gradient_returns_last_finite_point():
    def grad(x):
        return np.array([np.nan]) if x[0] < 0 else np.array([1.0])

    r = lfop(grad, np.array([0.2]))
    assert r.reason == "nonfinite" and np.all(np.isfinite(r.x))


def test_step_limit_delta_caps_moves():
    pts = []

    def grad(x):
        pts.append(x.copy())
        return np.array([-1.0, 0.0])  # constant force: the particle keeps accelerating

    lfop(grad, np.zeros(2), LfopParams(delta=0.3, max_steps=60, delta1=0.0))
    steps = np.linalg.norm(np.diff(np.array(pts), axis=0), axis=1)
    assert steps.max() <= 0.3 + 1e-12


def test_stiff_penalty_wall_needs_the_guard():
    # algorithms.md 1.6: min ||x||^2 + mu max(0, 1 - x1 - x2)^2, mu = 1e4
    mu = 1e4

    def grad(x):
        g = 1 - x[0] - x[1]
        return 2 * x - 2 * mu * max(g, 0.0) * np.ones(2)

    p = LfopParams(stiffness_guard=True, max_steps=5000)
    r = lfop(grad, np.array([3.0, -1.0]), p)
    assert r.reason == "eps_g"
    np.testing.assert_allclose(r.x, [0.5, 0.5], atol=1e-3)


def test_deterministic():
    a = lfop(rosen_grad, np.array([-1.2, 1.0]))
    b = lfop(rosen_grad, np.array([-1.2, 1.0]))
    assert a.ng == b.ng and np.array_equal(a.x, b.x)


@pytest.mark.parametrize("bad", [dict(delta=0), dict(dt0=-1), dict(m=0), dict(dt_mode="magic"),
                                 dict(interference_anchor="left"), dict(max_steps=0), dict(eps_g=-1)])
def test_invalid_parameters(bad):
    with pytest.raises(ValueError, match="lfop"):
        LfopParams(**bad)


@pytest.mark.parametrize("anchor", ["moving", "fixed"])
@pytest.mark.parametrize("dt_mode", ["fixed", "auto"])
def test_variants_solve_a_quadratic(anchor, dt_mode):
    d = np.array([1.0, 10.0, 100.0])
    r = lfop(lambda x: d * x, np.array([1.0, 1.0, 1.0]), LfopParams(interference_anchor=anchor, dt_mode=dt_mode))
    assert r.reason == "eps_g"


@settings(max_examples=15, deadline=None)
@given(st.lists(st.floats(0.1, 50.0), min_size=2, max_size=5), st.floats(-5, 5))
def test_property_converges_on_convex_diagonal_quadratics(diag, shift):
    d = np.array(diag)
    c = np.full(d.size, shift)
    r = lfop(lambda x: d * (x - c), np.zeros(d.size), LfopParams(stiffness_guard=True, max_steps=20_000))
    assert r.reason == "eps_g"
    assert np.linalg.norm(d * (r.x - c)) <= 1e-5
