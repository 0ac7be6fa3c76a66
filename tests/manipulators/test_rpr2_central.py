"""Suite rpr2-central (E synthesis with central differences, suite rpr2's settings otherwise) and Table 4.7c."""

import numpy as np
import pandas as pd

from harness import plan_suite
from harness.tables import build_tables
from manipulators.synthesis import rpr2_central_suite as C
from manipulators.synthesis.rpr2_spread_suite import N_PERTURBED
from manipulators.synthesis.rpr2_suite import STARTS
from manipulators.synthesis.rpr2_suite import SUITE as RPR2
from problems import get_suite


def test_only_the_difference_scheme_differs_from_the_rpr2_and_rpr2_spread_cases():
    suite, spread = get_suite("rpr2-central"), get_suite("rpr2-spread")
    cases = suite.cases()
    assert len(cases) == len(STARTS) * (N_PERTURBED + 1) and {c.problem_id for c in cases} == {"rpr2-e"}
    for c in cases:
        s = spread.case(c.case_id)  # the same case id, start and x0 as Table 4.7s's
        assert c.start == s.start and np.array_equal(c.problem.x0, s.problem.x0)
        assert (c.problem.fd, s.problem.fd) == ("central", "forward")
        assert c.problem.fd_step == s.problem.fd_step == 1e-3
        assert c.options == RPR2.case(f"rpr2-e/n=5/{c.meta['thesis_start']}").options
    d = np.asarray(STARTS["SP3"], dtype=float) + 0.2
    p = suite.case("rpr2-e/n=5/SP3").problem
    assert p.objective(d) == RPR2.case("rpr2-e/n=5/SP3").problem.objective(d)  # the same functions


def test_the_literal_dynamic_q_runs_from_the_thesis_starts_only(tmp_path):
    plan = plan_suite("rpr2-central", out=tmp_path).set_index("solver")
    assert plan.loc["dynamic-q", "planned"] == len(STARTS)
    assert plan.loc["dynamic-q-plus", "planned"] == plan.loc["scipy-slsqp", "planned"] == 44
    assert set(C.SOLVERS) == {"dynamic-q", "dynamic-q-plus", "scipy-slsqp"}


def test_table_4_7c_counts_ends_by_thesis_start_and_solver():
    sp2 = [-4.570, -2.203, 4.545, 5.542, 5.527]  # the thesis's SP2 design: f 2.850, exact dW_p 0.0066
    runs = pd.DataFrame([
        {"problem": "rpr2-e", "start": start, "solver": solver, "f": 2.85, "nfg": 100, "status": "failed",
         "x": sp2, "max_violation": 1e-6}
        for start, solver in [("SP2", "dynamic-q"), ("SP2", "dynamic-q-plus"), ("SP2~1", "dynamic-q-plus"),
                              ("SP2~2", "dynamic-q-plus")]])
    (t,) = build_tables("rpr2-central", runs)
    assert t.name == "table_4_7c" and "central" in t.title
    rows = t.frame.set_index("solver")
    assert rows.loc["dynamic-q", "runs"] == 1 and rows.loc["dynamic-q-plus", "runs"] == 3
    assert rows.loc["dynamic-q-plus", "f* <= 3.2, dW_p <= 0.01"] == "3 of 3"
