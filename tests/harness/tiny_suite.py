"""A tiny suite for the harness tests: quadratics and Rosenbrock, unconstrained and one
constrained problem (so unconstrained solvers record ``not_applicable``)."""

import numpy as np

from problems import Case, Problem, Suite

NAME = "tiny"


def _quad(n, gamma):
    w = np.linspace(1.0, gamma, n)
    return Problem(name=f"quad{n}", x0=np.full(n, 3.0), objective=lambda x: float(w @ (x * x)),
                   gradient=lambda x: 2 * w * x, f_ref=0.0, x_ref=np.zeros(n), source="tests")


def _rosen():
    def f(x):
        return float(100 * (x[1] - x[0] ** 2) ** 2 + (1 - x[0]) ** 2)

    def g(x):
        return np.array([-400 * x[0] * (x[1] - x[0] ** 2) - 2 * (1 - x[0]), 200 * (x[1] - x[0] ** 2)])

    return Problem(name="rosen", x0=[-1.2, 1.0], objective=f, gradient=g, f_ref=0.0, x_ref=[1.0, 1.0])


def _constrained():
    return Problem(name="con", x0=[2.0, 2.0], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x,
                   ineq=lambda x: np.array([1.0 - x[0]]), f_ref=1.0)


def build():
    return [
        Case(_quad(2, 10.0), "q2", options={"sqsd": {"rho": 1.0}}),
        Case(_quad(20, 100.0), "q20"),
        Case(_rosen(), "rosen", options={"*": {"eps_g": 1e-6, "max_iter": 3000}}),
        Case(_rosen().with_start([2.0, 2.0]), "rosen", start="x1", options={"*": {"max_iter": 3000}}),
        Case(_constrained(), "con"),
    ]


SUITE = Suite(name="tiny", description="harness test suite", build=build, solvers=("sqsd",))


def tables(runs):
    """Table plug-in of the tiny suite (the harness looks for ``tables`` in suite files)."""
    from harness.tables import Table

    frame = runs.pivot_table(index="case_id", columns="solver", values="nfg", aggfunc="first")
    flags = frame > 1000  # "differs": more than 1000 evaluations
    return [Table(name="tiny_nfg", title="Tiny: N^fg per case", frame=frame.astype(object),
                  flags=flags, notes=["cells above 1000 evaluations are flagged"])]
