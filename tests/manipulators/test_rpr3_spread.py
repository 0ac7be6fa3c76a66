"""Suite rpr3-spread (3-RPR MO and D synthesis from starts within 1e-6 of d0), its table plug-in,
and the perturbed starts shared with rpr2-spread."""

import json

import numpy as np
import pandas as pd
import pytest

from harness.tables import build_tables
from manipulators.synthesis import _spread
from manipulators.synthesis import rpr3_spread_suite as S
from manipulators.synthesis.rpr3_suite import SUITE as RPR3
from problems import get_suite


def test_perturbed_starts_are_seeded_small_and_keyed_by_case():
    x0 = np.array([-0.75, 0.0, 0.75, 1.5, 0.75])
    np.testing.assert_array_equal(_spread.perturbed(x0, (0, 0), 0, 1e-6), x0)
    a = _spread.perturbed(x0, (0, 0), 3, 1e-6)
    np.testing.assert_array_equal(a, _spread.perturbed(x0, (0, 0), 3, 1e-6))  # same key and k: same start
    assert 0 < np.max(np.abs(a - x0)) <= 1e-6
    assert not np.array_equal(a, _spread.perturbed(x0, (0, 1), 3, 1e-6))  # another case: another start
    assert not np.array_equal(a, _spread.perturbed(x0, (0, 0), 4, 1e-6))


@pytest.mark.parametrize("k, eps", [(-1, 1e-6), (1.5, 1e-6), (1, 0.0), (1, float("nan"))])
def test_bad_index_or_size_is_rejected(k, eps):
    with pytest.raises(ValueError, match="k must|eps must"):
        _spread.perturbed(np.zeros(2), (0,), k, eps)


@pytest.mark.parametrize("label", ["d0", "d0~4", "SP2~10"])
def test_start_labels_round_trip(label):
    assert _spread.start_label(*_spread.parse_start(label)) == label


def test_suite_is_registered_with_every_case_and_copy():
    suite = get_suite("rpr3-spread")
    assert suite.solvers == ("dynamic-q", "dynamic-q-plus", "scipy-slsqp")
    cases = suite.cases()
    assert len(cases) == len(S.KINDS) * len(S.PRESCRIBED) * (S.N_PERTURBED + 1)
    assert {c.problem_id for c in cases} == {f"rpr3-{k}-{p.lower()}" for k in S.KINDS for p in S.PRESCRIBED}
    case = suite.case("rpr3-d-p2/n=5/d0~3")
    assert case.meta["k"] == 3 and case.meta["kind"] == "d" and case.meta["prescribed"] == "P2"


def test_cases_use_the_rpr3_suite_settings_and_problems():
    spread = get_suite("rpr3-spread")
    for pid in ("rpr3-mo-p1", "rpr3-d-p3"):
        ref = RPR3.case(f"{pid}/n=5/d0")
        nominal, copy = spread.case(f"{pid}/n=5/d0"), spread.case(f"{pid}/n=5/d0~5")
        assert copy.options == ref.options
        np.testing.assert_array_equal(nominal.problem.x0, ref.problem.x0)
        assert 0 < np.max(np.abs(np.asarray(copy.problem.x0) - np.asarray(ref.problem.x0))) <= S.EPS
        assert copy.problem.fd == ref.problem.fd and copy.problem.fd_step == ref.problem.fd_step


def test_table_counts_enclosed_ends_against_the_stored_optima():
    # the exact-model best of MO P1 (stored in results/rpr3-spread/reference.json) encloses W_p;
    # the start d0 does not (MO P1 is infeasible at d0: W_p leaves the workspace)
    best = [-1.672693971930773, 0.8863942675247938, 1.4902385741065023, 0.9430834171370769, 1.095396011444928]
    d0 = [-0.75, 0.0, 0.75, 1.5, 0.75]
    rows = [("dynamic-q-plus", "d0", -0.4291, best), ("dynamic-q-plus", "d0~1", -0.9, d0),
            ("dynamic-q-plus", "d0~2", -0.17, best), ("dynamic-q", "d0", -0.8, d0)]
    runs = pd.DataFrame([{"suite": "rpr3-spread", "problem": "rpr3-mo-p1", "start": s, "solver": v, "f": f,
                          "x": json.dumps(x), "nfg": 20, "status": "converged"} for v, s, f, x in rows])
    reference = {"exact_optimum": {"mo/P1": {"kinv": 0.4291, "local_kinv": 0.1707}}}
    mo, d = build_tables("rpr3-spread", runs, reference=reference)
    assert mo.name == "table_5_4s" and d.name == "table_5_5s" and d.frame.empty
    frame = mo.frame.set_index("solver")
    assert list(mo.frame["solver"]) == ["dynamic-q", "dynamic-q-plus"]
    plus = frame.loc["dynamic-q-plus"]
    assert plus["runs"] == 3 and plus["f* from d0"] == "0.4291" and plus["f* max"] == "0.9000"
    assert plus["enclosed"] == "2 of 3" and plus["f* of the enclosed ends"] == "0.1700-0.4291"
    assert plus["enclosed, f* >= exact local min - 0.01"] == "2 of 3"
    assert plus["enclosed, f* >= exact best - 0.01"] == "1 of 3"
    assert frame.loc["dynamic-q", "enclosed"] == "0 of 1"


def test_figure_plugin_draws_one_png_with_or_without_a_stored_reference(tmp_path):
    from harness.figures import thesis_figures

    best = [-1.672693971930773, 0.8863942675247938, 1.4902385741065023, 0.9430834171370769, 1.095396011444928]
    rows = [("dynamic-q-plus", "d0", -0.4291, best), ("dynamic-q-plus", "d0~1", -0.9, [-0.75, 0.0, 0.75, 1.5, 0.75]),
            ("dynamic-q", "d0", -0.2, [float("nan")] * 5)]
    runs = pd.DataFrame([{"suite": "rpr3-spread", "problem": "rpr3-mo-p1", "start": s, "solver": v, "f": f,
                          "x": json.dumps(x), "nfg": 20, "status": "converged"} for v, s, f, x in rows])
    (path,) = thesis_figures("rpr3-spread", runs, tmp_path / "rpr3-spread" / "figures")  # no reference.json
    assert path.name == "fig_5_4s_spread.png" and path.stat().st_size > 10_000
    (tmp_path / "rpr3-spread" / "reference.json").write_text(json.dumps(
        {"data": {"exact_optimum": {"mo/P1": {"kinv": 0.4291, "local_kinv": 0.1707}}}}))
    (again,) = thesis_figures("rpr3-spread", runs, tmp_path / "rpr3-spread" / "figures")
    assert again == path and path.stat().st_size > 10_000
