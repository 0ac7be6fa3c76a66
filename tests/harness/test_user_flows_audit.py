"""Defects found by a new-user audit of the bring-your-own-problem and own-solver flows
(2026-12-01), each pinned by a test: suite files whose PROBLEMS, SOLVERS or SUITE have the
wrong type, tables of a store holding only runs with options, a log-ratio plot with no pair
to draw, figure and report targets that are files, and docs/harness.md's own-solver example."""

import os
import pathlib
import re
import subprocess
import sys

import pytest

from harness._store import Store
from harness.cli import main

HERE = pathlib.Path(__file__).parent
ROOT = HERE.parents[1]
PROBLEM = "Problem(name='bowl', x0=[1.0, 2.0], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x)"



@pytest.mark.parametrize("body, says", [
    (f"PROBLEMS = {PROBLEM}", "put it in a list"),  # was exit 3: TypeError: 'Problem' object is not iterable
    ("PROBLEMS = 5", "PROBLEMS in"),  # was exit 3
    ("PROBLEMS = 'bowl'", "got str 'bowl'"),
    (f"SOLVERS = 'sqsd'\nPROBLEMS = [{PROBLEM}]", "SOLVERS in"),  # was "unknown solver 's'"
    (f"SOLVERS = 5\nPROBLEMS = [{PROBLEM}]", "SOLVERS in"),  # was exit 3
    ("SUITE = 'hs'", "not a problems.Suite"),
])
def test_a_suite_file_with_values_of_the_wrong_type_is_bad_input(tmp_path, capsys, body, says, cli_error):
    f = tmp_path / "mine.py"
    f.write_text("from problems import Problem\n" + body + "\n")
    line = cli_error(["run", "--suite-file", str(f), "--out", str(tmp_path / "out"), "--quiet"])
    assert says in line and str(f) in line
    assert not Store(tmp_path / "out", "mine").exists()


def test_problems_may_be_any_iterable_of_problems(tmp_path, capsys):
    f = tmp_path / "mine.py"
    f.write_text(f"from problems import Problem\nPROBLEMS = ({PROBLEM},)\nSOLVERS = ('sqsd',)\n")
    assert main(["run", "--suite-file", str(f), "--out", str(tmp_path), "--quiet", "--no-table"]) == 0


def test_tables_of_a_store_with_only_option_runs_say_why_there_is_none(tmp_path, capsys, mine_file, cli_error):
    out = str(tmp_path / "out")
    assert main(["run", "--suite-file", str(mine_file), "--solvers", "sqsd[rho=0.5]", "--out", out,
                 "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "tables not rendered: no runs of mine with the suite's own settings" in err
    assert not list((tmp_path / "out" / "mine").glob("*.md"))  # no empty, malformed table written
    line = cli_error(["table", "--suite-file", str(mine_file), "--out", out])
    assert "sqsd[rho=0.5]" in line and "leave out" in line


def test_log_ratio_with_no_pair_to_draw_is_bad_input(tmp_path, capsys, mine_file, cli_error):
    out = str(tmp_path)
    assert main(["run", "--suite-file", str(mine_file), "--solvers", "sqsd", "--out", out, "--quiet",
                 "--no-table"]) == 0
    line = cli_error(["plot", "--suite-file", str(mine_file), "--kind", "log-ratio", "--out", out])
    assert "no log-ratio profile to draw for mine" in line and "stored solvers: sqsd" in line


def test_figure_and_report_targets_that_are_files_are_bad_input(tmp_path, capsys, mine_file, cli_error):
    out = tmp_path
    assert main(["run", "--suite-file", str(mine_file), "--solvers", "sqsd", "--out", str(out), "--quiet",
                 "--no-table"]) == 0
    (out / "mine" / "figures").write_text("")  # was exit 3: FileExistsError
    (out / "report").write_text("")
    line = cli_error(["plot", "--suite-file", str(mine_file), "--kind", "profile", "--out", str(out)])
    assert "figures is a file" in line
    assert "report is a file" in cli_error(["report", "--out", str(out), "--quiet"])


def test_the_own_solver_example_of_docs_harness_runs_as_it_says(tmp_path):
    text = (ROOT / "docs" / "harness.md").read_text()
    for name in ("mine", "my_solver"):
        body = re.search(rf"```python\n(# {name}\.py\n.*?)```", text, re.S)
        assert body, f"docs/harness.md has no {name}.py example"
        (tmp_path / f"{name}.py").write_text(body.group(1))
    env = {**os.environ, "PYTHONPATH": str(ROOT)}

    def run(*solvers):
        return subprocess.run([sys.executable, "-m", "harness", "run", "--suite-file", "mine.py", "--solver-module",
                               "my_solver.py", "--solvers", ",".join(solvers), "--out", "out", "--quiet",
                               "--no-table"], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)

    assert run("my-gd", "sqsd").returncode == 0
    assert run("my-gd[step=0.3]").returncode == 0
    bad = run("my-gd[step=-1]")
    assert bad.returncode == 2 and "valid: a number > 0" in bad.stderr and "Traceback" not in bad.stderr
    listed = subprocess.run([sys.executable, "-m", "harness", "list", "solvers", "--solver-module", "my_solver.py"],
                            cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert listed.returncode == 0 and "my-gd" in listed.stdout and "step = 0.1" in listed.stdout
    runs = Store(tmp_path / "out", "mine").load().set_index(["solver", "overrides"])
    assert runs.loc[("my-gd", ""), "nfg"] == 92  # the counts the text gives
    assert runs.loc[("my-gd", '{"step": 0.3}'), "nfg"] == 24
    assert runs.loc[("my-gd", ""), "status"] == "converged"


def test_a_scheduler_without_the_dask_executor_is_bad_input(tmp_path, capsys, mine_file, cli_error):
    # was: silently ignored, the runs went to local workers
    line = cli_error(["run", "--suite-file", str(mine_file), "--scheduler", "tcp://127.0.0.1:8786",
                           "--out", str(tmp_path), "--quiet"])
    assert "--executor dask" in line
    assert not Store(tmp_path, "mine").exists()


@pytest.mark.parametrize("objective, says", [
    ("lambda x: np.array([float(x @ x)])", "ndarray of shape (1,)"),  # was accepted; every solver then failed
    ("lambda x: np.array([[float(x @ x)]])", "ndarray of shape (1, 1)"),
    ("lambda x: None", "returned None"),  # was a NaN warning, then an error row per solver
])
def test_an_objective_that_does_not_return_one_number_is_refused(tmp_path, capsys, objective, says, cli_error):
    f = tmp_path / "mine.py"
    f.write_text(f"import numpy as np\nfrom problems import Problem\n"
                 f"PROBLEMS = [Problem(name='bowl', x0=[1.0, 2.0], objective={objective})]\n")
    line = cli_error(["run", "--suite-file", str(f), "--out", str(tmp_path / "out"), "--quiet"])
    assert line.startswith("error: problem 'bowl': objective(x0) returned") and says in line


def test_check_problem_of_something_else_says_what_it_needs():
    import harness

    with pytest.raises(TypeError, match="needs a problems.Problem"):  # was AttributeError: no attribute 'x0'
        harness.check_problem("bowl")
