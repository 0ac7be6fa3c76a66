"""The catalogue's summaries of suites cutest and hs-all (what `harness list` prints of them,
without building a problem) agree with the built cases, field by field, and listing through
them builds nothing and changes no run's code version."""

import pytest

import problems.s2mpj._cases as s2mpj_cases
from harness._codeversion import ROOT, module_closure
from harness._listing import list_problems, list_suites
from harness._runner import HarnessArgumentError
from harness._suites import SuiteRef
from problems import get_suite
from problems._catalog import SUMMARIES, case_summaries


def _fields_of_cases(cases):
    return [(c.case_id, c.problem_id, c.n, c.problem.form, c.problem.f_ref, c.problem.source) for c in cases]


def _fields_of_summaries(rows):
    return [(r.case_id, r.problem_id, r.n, r.form, r.f_ref, r.source) for r in rows]


def test_hs_all_summaries_are_its_cases():
    """All 127 instances, in the suite's order, with Table 3.1's optima where it has them."""
    rows = case_summaries("hs-all")
    assert len(rows) == 127 and sum(r.f_ref is not None for r in rows) == 40
    assert _fields_of_summaries(rows) == _fields_of_cases(get_suite("hs-all").cases())


@pytest.mark.parametrize("selection", ["n<=2", r"name~_\d+_\d+$,n<=8,size=all", r"name~^HS7\d$"])
def test_cutest_summaries_are_its_cases(selection):
    """Every form (n <= 2: 152 instances), extra sizes of constrained variable-dimension
    problems (56), and HS problems with known optima; the whole default campaign was compared
    once by its listing, 779 of 779 lines equal."""
    rows = case_summaries("cutest", selection)
    assert rows
    assert _fields_of_summaries(rows) == _fields_of_cases(get_suite("cutest").select(selection).cases())


def test_hs_all_selection_restricts_as_the_suite_does():
    rows = case_summaries("hs-all", "type=u")
    assert [r.case_id for r in rows] == [c.case_id for c in get_suite("hs-all").select("type=u").cases()]


def test_listing_builds_no_problem(monkeypatch):
    """`harness list problems` and `harness list suites` read the catalogue: with problem
    building broken they still list cutest's selections and count its default campaign."""
    def refuse(*args, **kwargs):
        raise AssertionError("a listing built a problem")

    monkeypatch.setattr(s2mpj_cases, "s2mpj_problem", refuse)
    lines = list(list_problems(SuiteRef("cutest"), "type=u,n<=100"))
    assert lines[0] == f"# {len(lines) - 1} problems of suite cutest selected by 'type=u,n<=100'"
    assert any(line.startswith("DIAMON2DLS/n=66/x0 ") for line in lines)  # minutes to build
    counts = {line.split()[0]: line.split()[1] for line in list_suites() if line.split()[0] in SUMMARIES}
    assert counts == {"hs-all": "127", "cutest": str(len(case_summaries("cutest")))}


@pytest.mark.parametrize("selection, message", [("n", "cannot read selection term"),
                                                ("name=NOSUCHPROBLEM", "unknown S2MPJ problem"),
                                                ("n>100000", "picks no problem")])
def test_bad_selection_is_an_argument_error(selection, message):
    with pytest.raises(HarnessArgumentError, match=message):
        list(list_problems(SuiteRef("cutest"), selection))


def test_suites_without_a_catalogue_are_listed_from_their_cases():
    assert case_summaries("hs") is None
    assert len(list(list_problems(SuiteRef("hs")))) == 40


def test_summaries_are_in_no_run_code_version():
    """Nothing a run of cutest or hs-all imports imports the summaries, so adding or editing
    them invalidates no stored run (harness._codeversion)."""
    closure = module_closure(("problems.s2mpj.cutest_suite", "problems.s2mpj.hs_all_suite", "solvers.dynamic_q_plus"))
    names = {p.relative_to(ROOT).as_posix() for p in closure}
    assert "problems/s2mpj/cutest_suite.py" in names
    assert not names & {"problems/s2mpj/_summaries.py", "problems/_case_summary.py"}
