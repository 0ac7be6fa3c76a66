"""Suite rpr2-spread (Dynamic-Q, Dynamic-Q+ and SLSQP from starts within 1e-6 of SP1-SP4) and its table plug-in."""

import json

import numpy as np
import pandas as pd
import pytest

from harness.tables import build_tables
from manipulators.synthesis import rpr2_spread_suite as S
from manipulators.synthesis.rpr2_suite import STARTS
from manipulators.synthesis.rpr2_suite import SUITE as RPR2
from problems import get_suite


def test_suite_is_registered_and_has_every_start_and_copy():
    suite = get_suite("rpr2-spread")
    assert suite.solvers == ("dynamic-q", "dynamic-q-plus", "scipy-slsqp")
    cases = suite.cases()
    assert len(cases) == 2 * len(STARTS) * (S.N_PERTURBED + 1)
    assert {c.problem_id for c in cases} == {"rpr2-o", "rpr2-e"}
    assert suite.case("rpr2-e/n=5/SP3~4").meta["thesis_start"] == "SP3"


def test_perturbed_starts_are_small_seeded_and_distinct():
    for sp, x0 in STARTS.items():
        np.testing.assert_array_equal(S.perturbed_start(sp, 0), x0)
        xs = [S.perturbed_start(sp, k) for k in range(1, S.N_PERTURBED + 1)]
        for x in xs:
            assert 0 < np.max(np.abs(x - np.asarray(x0))) <= S.EPS
        assert len({tuple(x) for x in xs}) == S.N_PERTURBED
        np.testing.assert_array_equal(xs[2], S.perturbed_start(sp, 3))  # same seed, same start


def test_cases_use_the_rpr2_suite_settings():
    spread = get_suite("rpr2-spread")
    for pid in ("rpr2-o", "rpr2-e"):
        ref = RPR2.case(f"{pid}/n=5/SP2")
        case = spread.case(f"{pid}/n=5/SP2~5")
        assert case.options_for("dynamic-q", ["eps_x", "eps_f", "rho"]) == ref.options_for(
            "dynamic-q", ["eps_x", "eps_f", "rho"])
        np.testing.assert_allclose(case.problem.x0, ref.problem.x0, atol=S.EPS)
        d = np.asarray(ref.problem.x0, dtype=float) + 0.3
        assert case.problem.objective(d) == ref.problem.objective(d)


@pytest.mark.parametrize("bad", [("SP5", 1), ("SP1", -1), ("SP1", 1.5)])
def test_bad_start_or_index_is_rejected_with_the_valid_values(bad):
    with pytest.raises(ValueError, match="SP1|integer"):
        S.perturbed_start(*bad)


def test_parse_start():
    assert S.parse_start("SP3~7") == ("SP3", 7)
    assert S.parse_start("SP3") == ("SP3", 0)


def test_table_counts_ends_within_the_tolerance_of_table_4_7():
    # thesis SP2 design: f 2.850, exact dW_p 0.0066 (within); thesis SP1 design: exact dW_p 0.0109 (not)
    sp2 = [-4.570, -2.203, 4.545, 5.542, 5.527]
    sp1 = [-4.152, -2.461, 4.060, 5.491, 5.441]
    rows = [("rpr2-e", "SP1", 2.885, sp1), ("rpr2-e", "SP1~1", 2.84967, sp2), ("rpr2-e", "SP1~2", 6.0, sp1),
            ("rpr2-o", "SP2", 0.6174, sp2), ("rpr2-o", "SP2~1", 0.61, sp2), ("rpr2-o", "SP3~2", 0.70, sp2)]
    runs = pd.DataFrame([{"problem": p, "start": s, "solver": "dynamic-q", "f": f, "x": json.dumps(x), "nfg": 10,
                          "status": "converged"} for p, s, f, x in rows])
    (table,) = build_tables("rpr2-spread", runs)
    frame = table.frame.set_index(["synthesis", "start", "solver"])
    e = frame.loc[("E", "SP1", "dynamic-q")]
    assert e["runs"] == 3 and e["within tolerance"] == "1 of 3"
    assert e["f* <= 3.2, dW_p <= 0.01"] == "1 of 3"  # only the SP2 design: SP1's leaves dW_p 0.0109
    assert e["f* min"] == "2.8497" and e["f* max"] == "6.0000" and e["thesis f* vs ends"] == "inside"
    o = frame.loc[("O", "SP2", "dynamic-q")]
    assert o["within tolerance"] == "2 of 2" and o["f* from the start itself"] == "0.6174"
    assert o["f* <= 3.2, dW_p <= 0.01"] == ""  # E's target only
    assert o["thesis f* vs ends"] == "0.000982 above all"  # thesis SP2: 0.618382
    o3 = frame.loc[("O", "SP3", "dynamic-q")]
    assert o3["within tolerance"] == "0 of 1" and o3["thesis f* vs ends"] == "0.05956 below all"
    assert o3["f* from the start itself"] == ""  # no run from SP3 itself


def test_table_has_one_row_per_solver_with_the_literal_algorithm_first():
    sp2 = json.dumps([-4.570, -2.203, 4.545, 5.542, 5.527])
    rows = [("dynamic-q-plus", "SP2", 3.0), ("dynamic-q-plus", "SP2~1", 3.5), ("dynamic-q", "SP2", 2.85)]
    runs = pd.DataFrame([{"problem": "rpr2-e", "start": s, "solver": v, "f": f, "x": sp2, "nfg": 10,
                          "status": "converged"} for v, s, f in rows])
    (table,) = build_tables("rpr2-spread", runs)
    assert list(table.frame["solver"]) == ["dynamic-q", "dynamic-q-plus"]
    plus = table.frame.iloc[1]
    assert plus["runs"] == 2 and plus["f* from the start itself"] == "3.0000"
    assert plus["f* <= 3.2, dW_p <= 0.01"] == "1 of 2"  # 3.5 is above the target


def test_figure_plugin_draws_one_png(tmp_path):
    from harness.figures import thesis_figures

    x = json.dumps([-4.570, -2.203, 4.545, 5.542, 5.527])
    runs = pd.DataFrame([{"problem": p, "start": s, "solver": "dynamic-q", "f": f, "x": x, "nfg": 10,
                          "status": "converged"}
                         for p, s, f in [("rpr2-e", "SP1", 3.3), ("rpr2-e", "SP1~1", 3.1), ("rpr2-o", "SP3", 0.64)]]
                        + [{"problem": "rpr2-e", "start": "SP1", "solver": "dynamic-q-plus", "f": 3.2, "x": x,
                            "nfg": 10, "status": "failed"}])
    (path,) = thesis_figures("rpr2-spread", runs, tmp_path)
    assert path.exists() and path.stat().st_size > 10_000
