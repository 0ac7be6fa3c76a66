"""Appendix A problems 1-11: the fixed-size test functions of thesis Tables 2.1-2.2.

Each builder returns a `Problem` with the exact objective and gradient as printed in
thesis Appendix A (lines 3014-3052 of the OCR text). The OCR lost most minus signs in
problems 6-11 (``(x3 x4)`` for ``(x3 - x4)`` ...); the signs restored here are those of
the cited sources (Moré, Garbow & Hillstrom 1981 [113]; the cubic valley [115]) and are
the only reading under which the printed x* and f(x*) hold.
"""

from __future__ import annotations

import numpy as np

from .._problem import Problem

__all__ = ["CLASSIC_BUILDERS", "ZLOBEC_F_STAR", "FREUDENSTEIN_LOCAL_F"]

ZLOBEC_F_STAR = -1.91177218907  # Appendix A, problem 5(b): f(x*) as printed
# Freudenstein & Roth local minimum at about (11.41, -0.8968) (Table 2.1/2.2 "*" rows: 48.9)
FREUDENSTEIN_LOCAL_F = 48.98425367924


def _p01() -> Problem:
    """Problem 1: x1^2 + 2 x2^2 + 3 x3^2 - 2 x1 - 4 x2 - 6 x3 + 6."""
    c = np.array([1.0, 2.0, 3.0])

    def f(x):
        return float(c @ (x * x) - 2.0 * c @ x + 6.0)

    def g(x):
        return 2.0 * c * x - 2.0 * c

    return Problem(name="a01", x0=[3.0, 3.0, 3.0], objective=f, gradient=g, f_ref=0.0,
                   x_ref=[1.0, 1.0, 1.0], source="Hay (2003) Appendix A, problem 1", tags=("quadratic",))


def _p02() -> Problem:
    """Problem 2: x1^4 - 2 x1^2 x2 + x1^2 + x2^2 - 2 x1 + 1."""

    def f(x):
        x1, x2 = x
        return float(x1**4 - 2 * x1**2 * x2 + x1**2 + x2**2 - 2 * x1 + 1)

    def g(x):
        x1, x2 = x
        return np.array([4 * x1**3 - 4 * x1 * x2 + 2 * x1 - 2, -2 * x1**2 + 2 * x2])

    return Problem(name="a02", x0=[3.0, 3.0], objective=f, gradient=g, f_ref=0.0, x_ref=[1.0, 1.0],
                   source="Hay (2003) Appendix A, problem 2")


def _p03() -> Problem:
    """Problem 3: x1^4 - 8 x1^3 + 25 x1^2 + 4 x2^2 - 4 x1 x2 - 32 x1 + 16."""

    def f(x):
        x1, x2 = x
        return float(x1**4 - 8 * x1**3 + 25 * x1**2 + 4 * x2**2 - 4 * x1 * x2 - 32 * x1 + 16)

    def g(x):
        x1, x2 = x
        return np.array([4 * x1**3 - 24 * x1**2 + 50 * x1 - 4 * x2 - 32, 8 * x2 - 4 * x1])

    return Problem(name="a03", x0=[3.0, 3.0], objective=f, gradient=g, f_ref=0.0, x_ref=[2.0, 1.0],
                   source="Hay (2003) Appendix A, problem 3")


def _valley(name: str, power: int, source: str) -> Problem:
    """100 (x2 - x1^p)^2 + (1 - x1)^2: Rosenbrock (p = 2, problem 4), cubic valley (p = 3, problem 9)."""

    def f(x):
        x1, x2 = x
        return float(100.0 * (x2 - x1**power) ** 2 + (1.0 - x1) ** 2)

    def g(x):
        x1, x2 = x
        t = x2 - x1**power
        return np.array([-200.0 * t * power * x1 ** (power - 1) - 2.0 * (1.0 - x1), 200.0 * t])

    return Problem(name=name, x0=[-1.2, 1.0], objective=f, gradient=g, f_ref=0.0, x_ref=[1.0, 1.0],
                   source=source, tags=("valley",))


def _p04() -> Problem:
    return _valley("a04", 2, "Hay (2003) Appendix A, problem 4: Rosenbrock's parabolic valley [113]")


def _zlobec(name: str, x0: list[float], start: str) -> Problem:
    """Problem 5: Zlobec's function x1^4 + x1^3 - x1 + x2^4 - x2^2 + x2 + x3^2 - x3 + x1 x2 x3."""

    def f(x):
        x1, x2, x3 = x
        return float(x1**4 + x1**3 - x1 + x2**4 - x2**2 + x2 + x3**2 - x3 + x1 * x2 * x3)

    def g(x):
        x1, x2, x3 = x
        return np.array([4 * x1**3 + 3 * x1**2 - 1 + x2 * x3,
                         4 * x2**3 - 2 * x2 + 1 + x1 * x3,
                         2 * x3 - 1 + x1 * x2])

    # x* and f(x*) are printed with start (b); start (a) reaches the same minimum
    # (checked by tests/problems/test_appendix_a.py with a tight BFGS run).
    return Problem(name=name, x0=x0, objective=f, gradient=g, f_ref=ZLOBEC_F_STAR,
                   x_ref=[0.57085597, -0.93955591, 0.76817555],
                   source=f"Hay (2003) Appendix A, problem 5({start}): Zlobec's function [114]")


def _p05a() -> Problem:
    return _zlobec("a05a", [1.0, -1.0, 1.0], "a")


def _p05b() -> Problem:
    return _zlobec("a05b", [0.0, 0.0, 0.0], "b")


def _p06() -> Problem:
    """Problem 6: Powell's quartic (x1 + 10 x2)^2 + 5 (x3 - x4)^2 + (x2 - 2 x3)^4 + 10 (x1 - x4)^4."""

    def f(x):
        x1, x2, x3, x4 = x
        return float((x1 + 10 * x2) ** 2 + 5 * (x3 - x4) ** 2 + (x2 - 2 * x3) ** 4 + 10 * (x1 - x4) ** 4)

    def g(x):
        x1, x2, x3, x4 = x
        a, b, c, d = x1 + 10 * x2, x3 - x4, x2 - 2 * x3, x1 - x4
        return np.array([2 * a + 40 * d**3, 20 * a + 4 * c**3, 10 * b - 8 * c**3, -10 * b - 40 * d**3])

    return Problem(name="a06", x0=[3.0, -1.0, 0.0, 1.0], objective=f, gradient=g, f_ref=0.0,
                   x_ref=[0.0, 0.0, 0.0, 0.0], source="Hay (2003) Appendix A, problem 6: Powell's quartic [113]")


def _p07() -> Problem:
    """Problem 7: -{1/(1 + (x1 - x2)^2) + sin(pi x2 x3 / 2) + exp[-((x1 + x3)/x2 - 2)^2]}."""

    def f(x):
        x1, x2, x3 = x
        u = (x1 + x3) / x2 - 2.0
        return float(-(1.0 / (1.0 + (x1 - x2) ** 2) + np.sin(0.5 * np.pi * x2 * x3) + np.exp(-u * u)))

    def g(x):
        x1, x2, x3 = x
        d = x1 - x2
        a = 2.0 * d / (1.0 + d * d) ** 2  # d/dx1 of -1/(1+d^2)
        u = (x1 + x3) / x2 - 2.0
        e = 2.0 * u * np.exp(-u * u)  # d/du of -exp(-u^2)
        s = 0.5 * np.pi * np.cos(0.5 * np.pi * x2 * x3)
        return np.array([a + e / x2,
                         -a - s * x3 - e * (x1 + x3) / x2**2,
                         -s * x2 + e / x2])

    return Problem(name="a07", x0=[0.0, 1.0, 2.0], objective=f, gradient=g, f_ref=-3.0, x_ref=[1.0, 1.0, 1.0],
                   source="Hay (2003) Appendix A, problem 7 [113]")


def _p08() -> Problem:
    """Problem 8: Freudenstein and Roth {-13 + x1 + [(5 - x2) x2 - 2] x2}^2 + {-29 + x1 + [(x2 + 1) x2 - 14] x2}^2."""

    def f(x):
        x1, x2 = x
        r1 = -13.0 + x1 + ((5.0 - x2) * x2 - 2.0) * x2
        r2 = -29.0 + x1 + ((x2 + 1.0) * x2 - 14.0) * x2
        return float(r1 * r1 + r2 * r2)

    def g(x):
        x1, x2 = x
        r1 = -13.0 + x1 + ((5.0 - x2) * x2 - 2.0) * x2
        r2 = -29.0 + x1 + ((x2 + 1.0) * x2 - 14.0) * x2
        d1 = -3.0 * x2**2 + 10.0 * x2 - 2.0
        d2 = 3.0 * x2**2 + 2.0 * x2 - 14.0
        return np.array([2.0 * (r1 + r2), 2.0 * (r1 * d1 + r2 * d2)])

    return Problem(name="a08", x0=[0.5, -2.0], objective=f, gradient=g, f_ref=0.0, x_ref=[5.0, 4.0],
                   source="Hay (2003) Appendix A, problem 8: Freudenstein and Roth [113]",
                   meta={"local_minimum_f": FREUDENSTEIN_LOCAL_F})


def _p09() -> Problem:
    return _valley("a09", 3, "Hay (2003) Appendix A, problem 9: cubic valley [115]")


def _p10() -> Problem:
    """Problem 10: Beale [1.5 - x1(1 - x2)]^2 + [2.25 - x1(1 - x2^2)]^2 + [2.625 - x1(1 - x2^3)]^2."""
    y = np.array([1.5, 2.25, 2.625])
    k = np.arange(1, 4)

    def f(x):
        x1, x2 = x
        r = y - x1 * (1.0 - x2**k)
        return float(r @ r)

    def g(x):
        x1, x2 = x
        r = y - x1 * (1.0 - x2**k)
        return np.array([-2.0 * r @ (1.0 - x2**k), 2.0 * r @ (x1 * k * x2 ** (k - 1))])

    return Problem(name="a10", x0=[1.0, 1.0], objective=f, gradient=g, f_ref=0.0, x_ref=[3.0, 0.5],
                   source="Hay (2003) Appendix A, problem 10: Beale [113]")


def _p11() -> Problem:
    """Problem 11: Wood [10(x2 - x1^2)]^2 + (1 - x1)^2 + 90 (x4 - x3^2)^2 + (1 - x3)^2
    + 10 (x2 + x4 - 2)^2 + 0.1 (x2 - x4)^2."""

    def f(x):
        x1, x2, x3, x4 = x
        return float(100 * (x2 - x1**2) ** 2 + (1 - x1) ** 2 + 90 * (x4 - x3**2) ** 2 + (1 - x3) ** 2
                     + 10 * (x2 + x4 - 2) ** 2 + 0.1 * (x2 - x4) ** 2)

    def g(x):
        x1, x2, x3, x4 = x
        a, b, s, d = x2 - x1**2, x4 - x3**2, x2 + x4 - 2, x2 - x4
        return np.array([-400 * a * x1 - 2 * (1 - x1),
                         200 * a + 20 * s + 0.2 * d,
                         -360 * b * x3 - 2 * (1 - x3),
                         180 * b + 20 * s - 0.2 * d])

    return Problem(name="a11", x0=[-3.0, 1.0, -3.0, -1.0], objective=f, gradient=g, f_ref=0.0,
                   x_ref=[1.0, 1.0, 1.0, 1.0], source="Hay (2003) Appendix A, problem 11: Wood [113]")


#: problem id -> builder, in table order
CLASSIC_BUILDERS = {
    "a01": _p01, "a02": _p02, "a03": _p03, "a04": _p04, "a05a": _p05a, "a05b": _p05b,
    "a06": _p06, "a07": _p07, "a08": _p08, "a09": _p09, "a10": _p10, "a11": _p11,
}
