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
