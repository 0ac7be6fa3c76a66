"""Histories of gradient-only solvers carry f, so profiles and tables tell the same story."""

import pathlib

import numpy as np
import pytest

from harness._profiles import reference_data_profile
from harness._store import Store
from harness.tables.hs import tables
from problems import get_suite
from solvers import solve

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("solver", ["lfopc", "etopc"])
def test_gradient_only_histories_record_f_outside_the_count(solver):
    problem = get_suite("hs").case("hs071/n=4/x0").problem
    r = solve(problem, solver)
    h = np.asarray(r.history)
    assert len(h) == r.nfg and np.isfinite(h[:, 1]).all() and np.isfinite(h[:, 2]).all()
    assert r.nf == 0  # LFOPC never asks for f: the history's values are report evaluations


def test_reference_data_profile_final_values_equal_table_3_1_solved_counts():
    runs = Store(ROOT / "results", "hs").load()
    runs = runs[runs["overrides"] == ""]
    summary = next(t for t in tables(runs) if t.name.endswith("summary")).frame.set_index("solver")
    _, d = reference_data_profile(runs, er_tol=1e-5, feas_tol=1e-6)
    cases = runs.loc[runs["status"] != "not_applicable", "case_id"].nunique()
    for solver in d.columns:
        assert round(d[solver].iloc[-1] * cases) == summary.loc[solver, "solved"], solver
    assert {"lfopc", "etopc", "dynamic-q"} <= set(d.columns)
