"""Appendix A problems 12-14: the scalable test functions (any n), vectorized.

* 12: extended homogeneous quadratic  f = sum_i i x_i^2, x0 = [3, ..., 3].
* 13: extended (chained) Rosenbrock  f = sum_{i<n} 100 (x_{i+1} - x_i^2)^2 + (1 - x_i)^2,
  x0 = [-1.2, 1, -1.2, 1, ...] [113].
* 14: extended Manevich  f = sum_i (1 - x_i)^2 / 2^(i-1), x0 = 0 [116]; its Hessian
  diag(2^(1-i)) has condition number 2^(n-1) (about 1e60 at n = 200, thesis Section 2.5).

Minus signs lost in the OCR of Appendix A are restored from the cited sources; the
printed x* = [0 ...] / [1 ...] and f(x*) = 0 fix them unambiguously.
"""

from __future__ import annotations

import numpy as np

from .._problem import Problem, ProblemError

__all__ = ["homogeneous_quadratic", "extended_rosenbrock", "manevich", "EXTENDED_BUILDERS"]


def _check_n(name: str, n: int, minimum: int = 1) -> int:
    if int(n) != n or n < minimum:
        raise ProblemError(f"{name}: n must be an integer >= {minimum}, got {n!r}")
    return int(n)


def homogeneous_quadratic(n: int) -> Problem:
    """Problem 12 at dimension n."""
    n = _check_n("a12", n)
    w = np.arange(1.0, n + 1.0)

    def f(x):
        return float(w @ (x * x))

    def g(x):
        return 2.0 * w * x

    return Problem(name=f"a12_n{n}", x0=np.full(n, 3.0), objective=f, gradient=g, f_ref=0.0,
                   x_ref=np.zeros(n), tags=("quadratic", "scalable"),
                   source="Hay (2003) Appendix A, problem 12: extended homogeneous quadratic")


def extended_rosenbrock(n: int) -> Problem:
    """Problem 13 at dimension n (chained form, as printed: the sum runs over i = 1..n-1)."""
    n = _check_n("a13", n, 2)
    x0 = np.where(np.arange(n) % 2 == 0, -1.2, 1.0)

    def f(x):
        t = x[1:] - x[:-1] ** 2
        r = 1.0 - x[:-1]
        return float(100.0 * (t @ t) + r @ r)

    def g(x):
        t = x[1:] - x[:-1] ** 2
        out = np.zeros_like(x)
        out[:-1] = -400.0 * x[:-1] * t - 2.0 * (1.0 - x[:-1])
        out[1:] += 200.0 * t
        return out

    return Problem(name=f"a13_n{n}", x0=x0, objective=f, gradient=g, f_ref=0.0, x_ref=np.ones(n),
                   tags=("valley", "scalable"),
                   source="Hay (2003) Appendix A, problem 13: extended Rosenbrock [113]")


def manevich(n: int) -> Problem:
    """Problem 14 at dimension n."""
    n = _check_n("a14", n)
    w = 0.5 ** np.arange(n)  # 1 / 2^(i-1), exact powers of two

    def f(x):
        r = 1.0 - x
        return float(w @ (r * r))

    def g(x):
        return -2.0 * w * (1.0 - x)

    return Problem(name=f"a14_n{n}", x0=np.zeros(n), objective=f, gradient=g, f_ref=0.0, x_ref=np.ones(n),
                   tags=("quadratic", "ill-conditioned", "scalable"),
                   source="Hay (2003) Appendix A, problem 14: extended Manevich [116]")


EXTENDED_BUILDERS = {"a12": homogeneous_quadratic, "a13": extended_rosenbrock, "a14": manevich}
