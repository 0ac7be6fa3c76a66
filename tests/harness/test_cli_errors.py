"""Bad input exits 2 with one line, harness failures exit 3, nothing is run or stored first
(docs/harness.md, "Exit status")."""

import pathlib

import pytest

from harness._store import Store
from harness.cli import main

HERE = pathlib.Path(__file__).parent
TINY = str(HERE / "tiny_suite.py")


def _one_line_error(capsys, code_expected, argv):
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == code_expected, err
    assert err and err[-1].startswith("error:") and "Traceback" not in "\n".join(err)
    return err[-1]


@pytest.mark.parametrize("opt, says", [("nonsense=1", "valid options: rho"), ("rho=abc", "rho"), ("rho=-1", "rho")])
def test_invalid_solver_options_exit_2_before_any_work(tmp_path, capsys, opt, says):
    line = _one_line_error(capsys, 2, ["run", "--suite-file", TINY, "--solvers", f"sqsd[{opt}]",
                                       "--out", str(tmp_path), "--quiet"])
    assert says in line
    assert not Store(tmp_path, "tiny").exists()


@pytest.mark.parametrize("value", ["-5", "nan"])
def test_bad_timeout(tmp_path, capsys, value):
    assert "--timeout" in _one_line_error(capsys, 2, ["run", "--suite-file", TINY, "--solvers", "sqsd",
                                                      "--timeout", value, "--out", str(tmp_path)])


def test_unwritable_out_found_before_solver_work(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("")
    assert "cannot write results" in _one_line_error(
        capsys, 2, ["run", "--suite-file", TINY, "--solvers", "sqsd", "--out", str(blocker / "sub")])


def test_suite_file_raising_at_import(tmp_path, capsys):
    bad = tmp_path / "bad_suite.py"
    bad.write_text("import math\n\nraise RuntimeError('boom')\n")
    line = _one_line_error(capsys, 2, ["run", "--suite-file", str(bad), "--out", str(tmp_path)])
    assert "line 3" in line and "boom" in line


_ONE_PROBLEM = "from problems import Problem\n\nPROBLEMS = [{problems}]\n"
_Q = "Problem(name='a', x0=[1.0], objective=lambda x: float(x[0] ** 2))"


@pytest.mark.parametrize("name", ["../../escape", "/abs", "a/b", ".hidden", "Mixed_Case"])
def test_a_suite_name_that_is_not_a_plain_directory_name_is_refused(tmp_path, capsys, name):
    bad = tmp_path / "named.py"
    bad.write_text(f"NAME = {name!r}\n" + _ONE_PROBLEM.format(problems=_Q))
    out = tmp_path / "out" / "deeper"
    line = _one_line_error(capsys, 2, ["run", "--suite-file", str(bad), "--solvers", "sqsd", "--out", str(out),
                                       "--quiet"])
    assert "must be kebab-case" in line
    assert not any(tmp_path.rglob("*.parquet")) and not any(tmp_path.rglob("*_summary.*"))


def test_problems_with_one_name_are_bad_input(tmp_path, capsys):
    bad = tmp_path / "dup.py"
    bad.write_text(_ONE_PROBLEM.format(problems=f"{_Q}, {_Q}"))
    line = _one_line_error(capsys, 2, ["run", "--suite-file", str(bad), "--solvers", "sqsd", "--out", str(tmp_path)])
    assert "several problems named 'a'" in line


def test_register_suite_refuses_a_path_like_name():
    from problems import Suite, register_suite

    with pytest.raises(ValueError, match="kebab-case"):
        register_suite(Suite(name="../x", description="", build=list, solvers=()))


def test_load_results_of_an_unknown_suite_says_so(tmp_path):
    from harness import load_results
    from harness._api import NoResults

    with pytest.raises(NoResults, match="not a built-in suite.*hs"):
        load_results("nope", tmp_path)
    with pytest.raises(NoResults, match="run `python -m harness run --suite hs"):
        load_results("hs", tmp_path)


def test_report_out_missing(capsys):
    assert "does not exist" in _one_line_error(capsys, 2, ["report", "--out", "/nonexistent/results"])


def test_compare_bad_tolerance(capsys):
    _one_line_error(capsys, 2, ["compare", "results", "results", "--nfg-tol", "-1"])


def test_compare_exit_codes_distinguish_regressions_from_failures(tmp_path, capsys):
    a, b = tmp_path / "a", tmp_path / "b"
    for d in (a, b):
        main(["run", "--suite-file", TINY, "--solvers", "sqsd", "--problems", "q2", "--out", str(d), "--quiet"])
    assert main(["compare", str(a), str(b)]) == 0
    runs = Store(b, "tiny").load()
    runs.loc[:, "success"] = False  # solved -> unsolved
    runs.to_parquet(Store(b, "tiny").parquet, index=False)
    assert main(["compare", str(a), str(b)]) == 1
    Store(b, "tiny").parquet.write_bytes(b"PAR1 truncated")
    capsys.readouterr()
    line = _one_line_error(capsys, 3, ["compare", str(a), str(b)])
    assert "repair" in line


def test_directories_that_are_not_suites_are_skipped_by_report_and_compare(tmp_path):
    """A results directory may hold other folders (notes, __pycache__): the suite listing of
    report and compare skips names that cannot be suites instead of refusing them."""
    from harness._report import suites_under

    assert main(["run", "--suite-file", TINY, "--solvers", "sqsd", "--problems", "q2", "--out", str(tmp_path),
                 "--quiet"]) == 0
    (tmp_path / "My Notes").mkdir()
    (tmp_path / "__pycache__").mkdir()
    (tmp_path / "Old_Runs").mkdir()
    (tmp_path / "Old_Runs" / "counts.csv").write_text("")
    assert suites_under(tmp_path) == ["tiny"]
    assert main(["compare", str(tmp_path), str(tmp_path)]) == 0
