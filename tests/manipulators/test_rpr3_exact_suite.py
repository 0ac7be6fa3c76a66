"""Suite rpr3-exact (3-RPR SO/MO/D synthesis in exact form) and its table plug-in (Table 5.3x)."""

import numpy as np
import pandas as pd
import pytest

from harness.tables import build_tables
from manipulators.synthesis import rpr3_exact_suite as S
from manipulators.synthesis.rpr3_exact import CASES, exact_constraints
from manipulators.synthesis.rpr3_suite import PRESCRIBED3, SETTINGS, design
from problems import get_suite
from solvers import solve


def test_suite_is_registered_with_every_case_at_the_rpr3_starts():
    suite = get_suite("rpr3-exact")
    cases = suite.cases()
    assert [(c.meta["kind"], c.start) for c in cases] == list(CASES)
    for c in cases:
        z0 = np.asarray(c.problem.x0)
        np.testing.assert_array_equal(z0[:5], SETTINGS[c.meta["kind"]]["start"])
        assert not c.options  # every solver at its defaults
        assert c.problem.lower[4] == S.R_MIN > 0 and np.isneginf(c.problem.lower[[0, 1, 2, 3, 5]]).all()


@pytest.mark.parametrize("kind", ["so", "mo", "d"])
def test_start_meets_the_kappa_rows_and_t_is_the_start_design_min_kappa(kind):
    p = S.exact_problem(kind, "P2", k=32)
    z0 = np.asarray(p.x0, dtype=float)
    g = p.ineq(z0)
    n_kappa = 32 * (1 if kind == "so" else 2 if kind == "d" else 3)
    assert g[-n_kappa:].max() == pytest.approx(0.0, abs=1e-12)  # t0 = min kappa^-1 on the kappa slices
    assert p.objective(z0) == -z0[5]


def test_constraints_are_exact_leg_limits_and_kappa():
    """Rows against a direct evaluation of RPR3.constraints and inverse_condition at one design."""
    z = np.array([-0.5, 0.03, 1.2, 1.5, 0.6, 0.5])
    m = design(z[:5])
    B = PRESCRIBED3["P2"].points(16)
    c = exact_constraints("mo", "P2", 16)(z)
    phis = SETTINGS["mo"]["phis"]
    legs = np.concatenate([m.constraints(B, p).ravel() for p in phis])
    kv = np.concatenate([m.inverse_condition(B, p) for p in phis])
    np.testing.assert_allclose(c, np.concatenate([-legs, kv - z[5]]))
    assert exact_constraints("so", "P1", 16)(np.r_[np.zeros(5), 0.1]).max() == -1.0  # invalid design: all -1


@pytest.mark.parametrize("kw", [{"kind": "xo"}, {"kind": "mo", "prescribed": "P7"}, {"kind": "d", "k": 1}])
def test_bad_arguments_name_what_is_valid(kw):
    with pytest.raises(ValueError, match="so|P1|integer"):
        S.exact_problem(**kw)


def test_dynamic_q_plus_reaches_the_exact_local_optimum_of_mo_p2():
    """MO/P2 from the suite's start: SLSQP on the same exact model (rpr3_exact.exact_optimum) ends at 0.6785."""
    r = solve(S.exact_problem("mo", "P2"), "dynamic-q-plus")
    assert r.success and r.max_violation <= 1e-6
    assert -r.f == pytest.approx(0.6785, abs=2e-4)


def test_table_names_the_optimum_reached_and_flags_other_ends():
    ref = {"exact_optimum": {"mo/P1": {"kinv": 0.4291, "d": [0] * 5, "local_kinv": 0.17065, "local_d": [0] * 5}}}
    runs = pd.DataFrame([
        {"problem": "rpr3-mo-exact", "start": "P1", "solver": "dynamic-q-plus", "f": -0.170652, "max_violation": 0.0,
         "nfg": 22, "status": "converged", "x": [0.0] * 6, "wall_time_s": 2.0},
        {"problem": "rpr3-mo-exact", "start": "P1", "solver": "scipy-slsqp", "f": -0.5, "max_violation": 0.2,
         "nfg": 8, "status": "converged", "x": [0.0] * 6, "wall_time_s": 0.4},
        {"problem": "rpr3-mo-exact", "start": "P1", "solver": "ipopt", "f": -0.3, "max_violation": 0.0,
         "nfg": 30, "status": "converged", "x": [0.0] * 6, "wall_time_s": 1.0},
    ])
    (t,) = build_tables("rpr3-exact", runs, reference=ref)
    ours = t.frame[t.frame["N^fg"] != ""].set_index("solver")
    assert ours.loc["dynamic-q-plus", "reached"] == "local min from d0"
    assert ours.loc["scipy-slsqp", "reached"] == "none (infeasible)"
    assert ours.loc["ipopt", "reached"] == "none"
    assert t.flags.loc[t.frame["N^fg"] != "", "reached"].tolist() == [False, True, True]
