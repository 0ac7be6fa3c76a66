"""Appendix A suite: problem definitions, exact gradients, reference optima, thesis settings."""

import math

import numpy as np
import pytest

from problems import get_suite
from problems.appendix_a import (
    CLASSIC_BUILDERS,
    EXTENDED_BUILDERS,
    SOLVERS,
    build_cases,
    make_case,
)
from problems.appendix_a._settings import cap_for, rho_for, thesis_label, tolerances_for

SUITE = get_suite("appendix-a")

# small instances of the scalable formulas: the same code paths as n = 50000
SMALL_N = {"a12": (1, 7, 30), "a13": (2, 7, 30), "a14": (1, 7, 30)}


def _all_small_problems():
    for pid, build in CLASSIC_BUILDERS.items():
        yield pid, build()
    for pid, build in EXTENDED_BUILDERS.items():
        for n in SMALL_N[pid]:
            yield f"{pid}_n{n}", build(n)


PROBLEMS = dict(_all_small_problems())


def _central_fd(f, x, h=1e-6):
    g = np.zeros_like(x)
    for i in range(x.size):
        e = np.zeros_like(x)
        e[i] = h * max(1.0, abs(x[i]))
        g[i] = (f(x + e) - f(x - e)) / (2 * e[i])
    return g


@pytest.mark.parametrize("name", list(PROBLEMS))
def test_gradient_matches_finite_differences_at_random_points(name):
    p = PROBLEMS[name]
    rng = np.random.default_rng(abs(hash(name)) % 2**32)
    points = [p.x0] + [p.x0 + rng.normal(scale=0.7, size=p.n) for _ in range(4)]
    if p.x_ref is not None:
        points.append(p.x_ref + rng.normal(scale=0.1, size=p.n))
    for x in points:
        g = p.gradient(x)
        fd = _central_fd(p.objective, x)
        assert g.shape == (p.n,)
        np.testing.assert_allclose(g, fd, rtol=1e-5, atol=1e-5 * (1 + np.abs(fd).max()), err_msg=f"{name} at {x}")


@pytest.mark.parametrize("name", list(PROBLEMS))
def test_reference_point_is_stationary_with_reference_value(name):
    p = PROBLEMS[name]
    assert p.f_ref is not None and p.x_ref is not None
    # Zlobec's x* is printed to 8 digits; the rest are exact
    tol = 1e-6 if name.startswith("a05") else 1e-12
    assert abs(p.objective(p.x_ref) - p.f_ref) <= tol * (1 + abs(p.f_ref))
    assert np.linalg.norm(p.gradient(p.x_ref)) <= (1e-6 if name.startswith("a05") else 1e-12)


def test_zlobec_start_a_reaches_the_printed_minimum():
    from scipy.optimize import minimize

    p = CLASSIC_BUILDERS["a05a"]()
    r = minimize(p.objective, p.x0, jac=p.gradient, method="BFGS", options={"gtol": 1e-9})
    assert abs(r.fun - p.f_ref) < 1e-10
    assert np.max(np.abs(r.x - p.x_ref)) < 1e-7


def test_freudenstein_local_minimum_is_48_98():
    p = CLASSIC_BUILDERS["a08"]()
    from scipy.optimize import minimize

    r = minimize(p.objective, [11.4, -0.9], jac=p.gradient, method="BFGS", options={"gtol": 1e-10})
    assert r.fun == pytest.approx(p.meta["local_minimum_f"], rel=1e-9)


def test_large_instances_build_and_evaluate_vectorized():
    for pid, n in (("a12", 50000), ("a13", 1000), ("a14", 200)):
        p = EXTENDED_BUILDERS[pid](n)
        assert p.n == n
        assert np.isfinite(p.objective(p.x0)) and p.gradient(p.x0).shape == (n,)
    # Manevich n = 200: weights down to 2^-199 (condition number ~ 1e60, Section 2.5)
    w = -EXTENDED_BUILDERS["a14"](200).gradient(np.zeros(200)) / 2
    assert w[0] / w[-1] == pytest.approx(2.0**199)


def test_starting_points_as_printed():
    assert list(make_case("a13", 6).problem.x0) == [-1.2, 1, -1.2, 1, -1.2, 1]
    assert list(make_case("a11").problem.x0) == [-3, 1, -3, -1]
    assert list(make_case("a08").problem.x0) == [0.5, -2]
    assert not make_case("a14", 20).problem.x0.any()


def test_suite_ids_dimensions_and_default_solvers():
    cases = SUITE.cases()
    ids = SUITE.problem_ids()
    assert ids == ["a01", "a02", "a03", "a04", "a05a", "a05b", *[f"a{i:02d}" for i in range(6, 15)]]
    dims = {pid: sorted({c.n for c in cases if c.problem_id == pid}) for pid in ("a12", "a13", "a14")}
    assert dims == {"a12": [20, 200, 2000, 20000, 50000], "a13": [10, 100, 300, 600, 1000],
                    "a14": [20, 40, 60, 100, 200]}
    assert SUITE.solvers == SOLVERS == ("sqsd", "sd", "fletcher-reeves", "polak-ribiere",
                                        "scipy-cg", "scipy-bfgs", "scipy-lbfgsb")
    assert len(cases) == len(build_cases()) == 12 + 5 + 5 + 10


def test_thesis_settings_on_the_cases():
    by_id = {c.case_id: c for c in SUITE.cases()}
    assert by_id["a01/n=3/x0"].options["*"] == {"eps_g": 1e-5, "eps_x": 1e-8}
    for cid in ("a12/n=50000/x0", "a14/n=20/x0", "a14/n=200/x0/rho=10"):
        assert by_id[cid].options["*"] == {"eps_g": 1e-75, "eps_x": 1e-12}
    assert by_id["a12/n=20000/x0"].options["*"]["eps_g"] == 1e-5
    rho = {cid: c.options["sqsd"]["rho"] for cid, c in by_id.items()}
    assert (rho["a04/n=2/x0"], rho["a08/n=2/x0"], rho["a09/n=2/x0"], rho["a11/n=4/x0"]) == (0.3, 10, 0.3, 2)
    assert rho["a12/n=2000/x0"] == 1e4 and rho["a12/n=50000/x0"] == 1e10
    assert rho["a13/n=300/x0"] == pytest.approx(math.sqrt(300) / 10)
    assert rho["a14/n=40/x0"] == 1 and rho["a14/n=40/x0/rho=10"] == 10
    assert by_id["a14/n=40/x0/rho=10"].meta["solvers"] == ("sqsd",)
    assert by_id["a13/n=1000/x0"].options["sd"] == {"max_fg": 30000, "max_iter": 30000}
    assert by_id["a14/n=200/x0"].options["polak-ribiere"]["max_fg"] == 100000
    assert by_id["a12/n=20000/x0"].options["fletcher-reeves"]["max_fg"] == 10000
    assert by_id["a08/n=2/x0"].meta["thesis_local_minimum_solvers"] == ("sd", "fletcher-reeves", "polak-ribiere")
    assert cap_for("a01", 3) == 20000 and rho_for("a05a", 3) == 1.0
    assert tolerances_for("a12", 20) == {"eps_g": 1e-5, "eps_x": 1e-8}
    assert thesis_label("a05b") == "5(b)" and thesis_label("a12") == "12"


def test_unknown_problem_and_missing_n_are_clear_errors():
    with pytest.raises(ValueError, match="valid: a01"):
        make_case("a99")
    with pytest.raises(ValueError, match="needs n"):
        make_case("a13")
    with pytest.raises(ValueError, match="n must be an integer >= 2"):
        EXTENDED_BUILDERS["a13"](1)
