"""``--problems`` with an unknown id: the message lists the valid ids in the form the user
used (case ids for a case id, i.e. text with "/", problem ids otherwise), at most
`harness._plan.MAX_LISTED_IDS` of them, with a "did you mean" when some are close."""

from __future__ import annotations

import importlib.util
import pathlib
import re

import numpy as np
import pytest

from harness._plan import HarnessArgumentError, select_cases
from problems import Case, Problem, Suite

HERE = pathlib.Path(__file__).parent
TINY = str(HERE / "tiny_suite.py")


def _tiny() -> Suite:
    spec = importlib.util.spec_from_file_location("tiny_suite_for_select", TINY)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.SUITE


def _bowl(name: str, n: int) -> Problem:
    return Problem(name=name, x0=np.ones(n), objective=lambda x: float(x @ x), gradient=lambda x: 2 * x, f_ref=0.0)


def _big() -> Suite:
    """50 problems p00..p49 with one case each (p07 has two starts)."""
    def build():
        cases = [Case(_bowl(f"p{i:02d}", 2 + i % 3), f"p{i:02d}") for i in range(50)]
        cases.append(Case(_bowl("p07", 3).with_start([2.0, 2.0, 2.0]), "p07", start="x1"))
        return cases

    return Suite(name="big", description="select_cases messages", build=build, solvers=("sqsd",))


def _message(suite: Suite, problems: list[str]) -> str:
    with pytest.raises(HarnessArgumentError) as exc:
        select_cases(suite, problems)
    return str(exc.value)


def test_an_unknown_case_id_lists_case_ids():
    msg = _message(_tiny(), ["q2/n=3/x0"])
    assert "unknown case id(s) q2/n=3/x0" in msg
    assert "valid case ids: q2/n=2/x0, q20/n=20/x0, rosen/n=2/x0, rosen/n=2/x1, con/n=2/x0" in msg
    assert "valid problems" not in msg


def test_an_unknown_case_id_suggests_the_cases_of_its_problem():
    msg = _message(_tiny(), ["rosen/n=3/x0"])
    assert re.search(r"rosen/n=3/x0 \(did you mean rosen/n=2/x0, rosen/n=2/x1", msg), msg


def test_an_unknown_problem_id_still_lists_problem_ids():
    msg = _message(_tiny(), ["zz"])
    assert msg.startswith("unknown problem(s) zz in suite tiny; valid problems: q2, q20, rosen, con")
    assert "did you mean" not in msg  # nothing is close to zz
    assert "case id" not in msg


def test_a_misspelt_problem_id_gets_a_did_you_mean():
    msg = _message(_tiny(), ["rosn"])
    assert "unknown problem(s) rosn (did you mean rosen?) in suite tiny" in msg


def test_problem_and_case_ids_are_answered_each_in_their_form():
    msg = _message(_tiny(), ["q2", "zz", "con/n=2/x9"])
    problems_part, cases_part = msg.split("; unknown case id(s) ")
    assert "zz" in problems_part and "valid problems: q2, q20, rosen, con" in problems_part
    assert cases_part.startswith("con/n=2/x9 (did you mean con/n=2/x0")
    assert "valid case ids: q2/n=2/x0" in cases_part


def test_the_list_is_capped():
    from harness._plan import MAX_LISTED_IDS

    msg = _message(_big(), ["p99"])
    listed = msg.split("valid problems: ", 1)[1].split(" ... ")[0].split(", ")
    assert listed == [f"p{i:02d}" for i in range(MAX_LISTED_IDS)]
    assert f"... and {50 - MAX_LISTED_IDS} more" in msg and "list problems" in msg
    msg = _message(_big(), ["p99/n=2/x0"])
    listed = msg.split("valid case ids: ", 1)[1].split(" ... ")[0].split(", ")
    assert len(listed) == MAX_LISTED_IDS and all("/" in c for c in listed)
    assert f"... and {51 - MAX_LISTED_IDS} more" in msg


def test_equally_close_ids_come_in_the_suites_order():
    msg = _message(_big(), ["p7"])
    assert "p7 (did you mean p07, " in msg


def test_known_ids_still_select():
    suite = _tiny()
    assert [c.case_id for c in select_cases(suite, ["rosen"])] == ["rosen/n=2/x0", "rosen/n=2/x1"]
    assert [c.case_id for c in select_cases(suite, ["rosen/n=2/x1", "q2"])] == ["q2/n=2/x0", "rosen/n=2/x1"]


def test_cli_dry_run_names_case_ids(cli_error):
    line = cli_error(["run", "--suite", "hs", "--problems", "hs002/n=3/x0", "--dry-run"])
    assert "unknown case id(s) hs002/n=3/x0 (did you mean hs002/n=2/x0" in line
    assert "valid case ids: hs002/n=2/x0, hs010/n=2/x0" in line
    line = cli_error(["run", "--suite", "hs", "--problems", "hs999", "--dry-run"])
    assert "unknown problem(s) hs999 in suite hs; valid problems: hs002, hs010" in line
    assert "hs002/n=2/x0" not in line
