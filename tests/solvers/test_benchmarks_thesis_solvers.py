"""pytest-benchmark benchmarks of the thesis solvers' hot paths (disabled by default;
``python -m pytest tests --benchmark-enable --benchmark-only``)."""

import pytest

from problems import get_suite
from solvers import Status, solve


@pytest.fixture(scope="module")
def hs071():
    return get_suite("hs").case("hs071/n=4/x0").problem


def test_dynamic_q_one_subproblem(benchmark, hs071):
    """One Dynamic-Q iteration: evaluate at x0, build P[0] (eq. 3.9), solve it by LFOPC."""
    r = benchmark(lambda: solve(hs071, "dynamic-q", max_iter=1))
    assert r.nfg >= 1 and r.status in (Status.MAX_ITER, Status.CONVERGED)


def test_dynamic_q_whole_hs071(benchmark, hs071):
    r = benchmark(lambda: solve(hs071, "dynamic-q"))
    assert r.success


@pytest.fixture(scope="module")
def hs100():
    return get_suite("hs").case("hs100/n=7/x0").problem


def test_lfopc_per_time_step(benchmark, hs100):
    """LFOPC on HS100 with a 200-step cap per phase: ~600 penalty-gradient points, so the
    mean time divided by r.nfg is the cost of one leap-frog time step (oracle included)."""
    r = benchmark(lambda: solve(hs100, "lfopc", max_steps=200))
    assert 3 <= r.nfg <= 3 * 200 + 3


def test_hs_problem_gradient_call(benchmark, hs100):
    """One call of an HS problem's compiled gradient (the problem's own cost per point)."""
    import numpy as np

    x = hs100.x0 + 0.1
    g = benchmark(lambda: hs100.gradient(x))
    assert np.all(np.isfinite(g)) and g.shape == (7,)
