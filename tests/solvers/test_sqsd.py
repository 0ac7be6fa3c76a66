"""SQSD (Algorithm 2.2): closed forms of Section 2.4, step control, counting, Table 2.1 rows."""

import numpy as np
import pytest

from problems import Problem
from problems.appendix_a import make_case
from problems.reference import thesis_table
from solvers import solve
from solvers.sqsd import C_MIN, SQSD

TABLE = thesis_table("table_2_1_2_2_sqsd_sd_fr_pr")
SQSD_ROWS = TABLE[TABLE["method"] == "SQSD"]


def _recording(problem: Problem):
    """The same problem, recording every point where the gradient is evaluated."""
    seen = []

    def grad(x):
        seen.append(np.array(x, dtype=float))
        return problem.gradient(x)

    return problem.replace(gradient=grad), seen


def _bivariate(alpha, beta, gamma):
    return Problem(name="q2", x0=[alpha, beta], objective=lambda x: float(x[0] ** 2 + gamma * x[1] ** 2),
                   gradient=lambda x: np.array([2 * x[0], 2 * gamma * x[1]]))


@pytest.mark.parametrize("alpha,beta,gamma,rho", [(1.0, 0.5, 3.0, 1.0), (-2.0, 1.0, 1.5, 2.0), (0.3, -0.8, 5.0, 0.5)])
def test_first_iterates_match_the_closed_forms_of_section_2_4(alpha, beta, gamma, rho):
    p, seen = _recording(_bivariate(alpha, beta, gamma))
    solve(p, "sqsd", rho=rho, max_iter=2, eps_g=0.0, eps_x=0.0)
    x0, x1, x2 = seen[:3]
    g0 = np.array([2 * alpha, 2 * gamma * beta])
    delta = rho / np.linalg.norm(g0)  # c0 = ||grad f(x0)|| / rho = 1 / delta
    # eq. (2.8) and (2.9)
    np.testing.assert_allclose(x1, [alpha * (1 - 2 * delta), beta * (1 - 2 * gamma * delta)], rtol=1e-13)
    assert np.sum((x1 - x0) ** 2) == pytest.approx(4 * delta**2 * (alpha**2 + gamma**2 * beta**2), rel=1e-13)
    # eq. (2.12): c1; eq. (2.14)-(2.16): x2 = [alpha (1-2 delta) mu1, beta (1-2 gamma delta) omega1]
    r = beta**2 / alpha**2
    c1 = 2 * (alpha**2 + gamma**3 * beta**2) / (alpha**2 + gamma**2 * beta**2)
    g1 = np.array([2 * x1[0], 2 * gamma * x1[1]])
    assert np.linalg.norm(g1) / c1 < rho  # precondition: the second step is not limited
    mu1 = 1 - (1 + gamma**2 * r) / (1 + gamma**3 * r)
    omega1 = 1 - (gamma + gamma**3 * r) / (1 + gamma**3 * r)
    np.testing.assert_allclose(x2, [alpha * (1 - 2 * delta) * mu1, beta * (1 - 2 * gamma * delta) * omega1],
                               rtol=1e-10, atol=1e-14)
    assert omega1 == pytest.approx((1 - gamma) / (1 + gamma**3 * r))  # eq. (2.25)


def test_gamma_one_converges_in_the_second_iteration():
    p, seen = _recording(_bivariate(2.0, -1.0, 1.0))
    r = solve(p, "sqsd", rho=2.0)  # ||x^1|| < rho: the second step is not limited
    np.testing.assert_allclose(seen[2], 0.0, atol=1e-15)  # mu1 = omega1 = 0
    assert r.status.value == "converged" and r.nfg == 3


def test_negative_curvature_is_replaced_and_the_step_limited_to_rho():
    p = Problem(name="concave", x0=[1.0, 0.5], objective=lambda x: float(-(x @ x)), gradient=lambda x: -2 * x)
    p, seen = _recording(p)
    solve(p, "sqsd", rho=0.25, max_iter=3)
    steps = [np.linalg.norm(b - a) for a, b in zip(seen, seen[1:])]
    # c_k < 0 -> 1e-60, so -grad/c_k is huge and Step 2 cuts it back to rho
    np.testing.assert_allclose(steps, 0.25, rtol=1e-12)
    assert C_MIN == 1e-60


def test_counts_one_point_per_iteration_and_stops_on_eps_x_without_evaluating():
    p, seen = _recording(make_case("a04").problem)
    r = solve(p, "sqsd", rho=0.3)
    assert r.nfg == len(seen) == r.ng == r.nf  # value and gradient together, once per point
    assert r.status.value == "converged"
    tiny = solve(make_case("a04").problem, "sqsd", rho=1e-9, eps_x=1e-8)
    assert tiny.message.startswith("||x^k") and tiny.nfg == 1  # x^1 is not evaluated


def test_option_validation():
    for bad in ({"rho": 0}, {"rho": float("inf")}, {"eps_g": -1}, {"max_iter": 0}):
        with pytest.raises(ValueError, match="sqsd"):
            SQSD(**bad)


def _thesis_sqsd(problem_label, n, rho_row=0):
    rows = SQSD_ROWS[(SQSD_ROWS["problem"] == problem_label) & (SQSD_ROWS["n"] == str(n))]
    return rows.iloc[rho_row]


STRICT_ROWS = ["a01", "a02", "a03", "a04", "a05a", "a05b", "a06", "a07", "a08", "a09", "a10",
               pytest.param("a11", marks=pytest.mark.xfail(
                   strict=True, reason="Wood's function with rho = 2 is rounding-sensitive for SQSD: N^fg spreads "
                                       "over ~270-930 under 1e-13 perturbations of x0 (see test below)"))]


@pytest.mark.parametrize("pid", STRICT_ROWS)
def test_table_2_1_nfg_within_15_percent_and_accuracy(pid):
    case = make_case(pid)
    th = _thesis_sqsd(case.meta["thesis_problem"], case.n)
    assert float(th["rho"]) == pytest.approx(case.options["sqsd"]["rho"])
    r = solve(case.problem, "sqsd", **case.options["*"], **case.options["sqsd"])
    assert r.status.value == "converged"
    assert abs(r.nfg - int(th["nfg"])) <= 0.15 * int(th["nfg"])
    er = abs(r.f - case.problem.f_ref) / (1 + abs(case.problem.f_ref))
    assert er <= max(10 * float(th["er"]), 1e-8)


@pytest.mark.parametrize("n", [20, 200])
def test_table_2_1_problem_12_small_n_within_15_percent(n):
    case = make_case("a12", n)
    r = solve(case.problem, "sqsd", **case.options["*"], **case.options["sqsd"])
    assert abs(r.nfg - int(_thesis_sqsd("12", n)["nfg"])) <= 0.15 * int(_thesis_sqsd("12", n)["nfg"])


def test_wood_count_is_rounding_sensitive_and_brackets_the_thesis_value():
    case = make_case("a11")
    rng = np.random.default_rng(0)
    counts = [solve(case.problem.with_start(case.problem.x0 * (1 + 1e-13 * rng.standard_normal(4))), "sqsd",
                    rho=2.0).nfg for _ in range(12)]
    assert max(counts) > 1.5 * min(counts)  # a wide spread from perturbations at rounding level
    assert min(counts) <= 1.15 * 267 < max(counts)  # Table 2.1 prints 267: within the spread


@pytest.mark.parametrize("n", [pytest.param(200, marks=pytest.mark.slow), 60])
def test_manevich_reaches_the_thesis_accuracy(n):
    """Section 2.5: ||x* - x^c||_inf < 1e-11 despite condition numbers up to ~1e60 (acceptance at n = 200: < 1e-10).

    n = 200 takes 5-20 s (73517 iterations in the thesis), so it is marked slow; n = 60 runs by default.
    """
    case = make_case("a14", n)
    r = solve(case.problem, "sqsd", **case.options["*"], **case.options["sqsd"])
    assert r.status.value == "converged"
    assert np.max(np.abs(r.x - 1.0)) < 1e-10
    thesis = int(_thesis_sqsd("14", n)["nfg"])
    assert abs(r.nfg - thesis) <= 0.5 * thesis
