"""Five Hock-Schittkowski problems written by hand (HS convention g >= 0 turned into g <= 0).

Used by the thesis-solver tests so they do not depend on the hs suite module.
Values from problems/hs/hock_schittkowski.json.
"""

import numpy as np

from problems import Problem


def hs010() -> Problem:
    return Problem(
        name="hs010", x0=[-10.0, 10.0], objective=lambda x: x[0] - x[1], gradient=lambda x: np.array([1.0, -1.0]),
        ineq=lambda x: np.array([3 * x[0] ** 2 - 2 * x[0] * x[1] + x[1] ** 2 - 1]),
        ineq_jacobian=lambda x: np.array([[6 * x[0] - 2 * x[1], -2 * x[0] + 2 * x[1]]]), f_ref=-1.0)


def hs012() -> Problem:
    return Problem(
        name="hs012", x0=[0.0, 0.0],
        objective=lambda x: 0.5 * x[0] ** 2 + x[1] ** 2 - x[0] * x[1] - 7 * x[0] - 7 * x[1],
        gradient=lambda x: np.array([x[0] - x[1] - 7, 2 * x[1] - x[0] - 7]),
        ineq=lambda x: np.array([4 * x[0] ** 2 + x[1] ** 2 - 25]),
        ineq_jacobian=lambda x: np.array([[8 * x[0], 2 * x[1]]]), f_ref=-30.0)


def hs022() -> Problem:
    return Problem(
        name="hs022", x0=[2.0, 2.0], objective=lambda x: (x[0] - 2) ** 2 + (x[1] - 1) ** 2,
        gradient=lambda x: np.array([2 * (x[0] - 2), 2 * (x[1] - 1)]),
        ineq=lambda x: np.array([x[0] + x[1] - 2, x[0] ** 2 - x[1]]),
        ineq_jacobian=lambda x: np.array([[1.0, 1.0], [2 * x[0], -1.0]]), f_ref=1.0)


def hs071() -> Problem:
    def f(x):
        return x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2]

    def g(x):
        s = x[0] + x[1] + x[2]
        return np.array([x[3] * (2 * x[0] + x[1] + x[2]), x[0] * x[3], x[0] * x[3] + 1, x[0] * s])

    return Problem(
        name="hs071",
        x0=[1.0, 5.0, 5.0, 1.0],
        objective=f,
        gradient=g,
        ineq=lambda x: np.array([25 - x[0] * x[1] * x[2] * x[3]]),
        ineq_jacobian=lambda x: (
            -np.array([[x[1] * x[2] * x[3], x[0] * x[2] * x[3], x[0] * x[1] * x[3], x[0] * x[1] * x[2]]])
        ),
        eq=lambda x: np.array([x @ x - 40]),
        eq_jacobian=lambda x: 2 * x[None, :],
        lower=1.0,
        upper=5.0,
        f_ref=17.0140172891563,
    )


def hs076() -> Problem:
    H = np.array([[2, 0, -1, 0], [0, 1, 0, 0], [-1, 0, 2, 1], [0, 0, 1, 1]], dtype=float)
    c = np.array([-1.0, -3.0, 1.0, -1.0])
    A = np.array([[1, 2, 1, 1], [3, 1, 2, -1], [0, -1, -4, 0]], dtype=float)
    bvec = np.array([5.0, 4.0, -1.5])
    return Problem(
        name="hs076", x0=[0.5] * 4, objective=lambda x: 0.5 * x @ H @ x + c @ x, gradient=lambda x: H @ x + c,
        ineq=lambda x: A @ x - bvec, ineq_jacobian=lambda x: A, lower=0.0, f_ref=-4.681818181818182)


# thesis Table 3.1, Dynamic-Q N^fg
THESIS_NFG = {"hs010": 13, "hs012": 9, "hs022": 3, "hs071": 6, "hs076": 8}
ALL = [hs010, hs012, hs022, hs071, hs076]
