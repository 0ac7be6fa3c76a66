"""Problems solved instantly (x0 is the minimizer): for measuring the harness's own overhead."""

import numpy as np

from problems import Case, Problem, Suite

NAME = "instant"
N_CASES = 100


def build():
    return [Case(Problem(name=f"z{i:03d}", x0=np.zeros(2), objective=lambda x: float(x @ x),
                         gradient=lambda x: 2 * x, f_ref=0.0), f"z{i:03d}") for i in range(N_CASES)]


SUITE = Suite(name="instant", description="instantly solved problems", build=build, solvers=("sqsd",))
