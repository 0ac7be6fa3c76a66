"""Defects found by a new-user audit of the harness (2026-11-29), each pinned by a test:
empty lists, repeated solvers or options, option values in the wrong numeric type, bad
solver modules, bad targets, and what compare, prune and Table 3.1 make of option runs and
not-applicable runs."""

import json
import math
import pathlib

import pandas as pd
import pytest

import harness
from harness._compare import compare_runs
from harness._runner import _plan, plan_suite
from harness._store import Store
from harness.cli import main
from harness.tables import build_tables

HERE = pathlib.Path(__file__).parent
TINY = str(HERE / "tiny_suite.py")



@pytest.mark.parametrize("flag, value", [("--problems", ""), ("--solvers", ""), ("--solvers", ",")])
def test_an_empty_list_is_refused_not_read_as_everything(tmp_path, capsys, flag, value, cli_error):
    line = cli_error(["run", "--suite-file", TINY, flag, value, "--out", str(tmp_path), "--quiet"])
    assert f"no {flag} given" in line
    assert not Store(tmp_path, "tiny").exists()


@pytest.mark.parametrize("solvers, says", [
    ("sqsd,sqsd[]", "is given twice"),
    ("sqsd[rho=2],sqsd[rho=2.0]", "is given twice"),  # one setting written two ways
    ("sqsd[rho=1,rho=2]", "rho given more than once"),
])
def test_a_repeated_solver_or_option_is_refused(tmp_path, capsys, solvers, says, cli_error):
    assert says in cli_error(["run", "--suite-file", TINY, "--solvers", solvers, "--out", str(tmp_path)])


def test_option_values_take_their_options_type():
    _, specs = _plan("hs", None, ["dynamic-q[max_iter=1e2]", "sqsd[rho=2]"], ["hs002"], None, 600.0, ())
    by = {sp.solver: sp for sp in specs}
    assert by["dynamic-q"].options["max_iter"] == 100 and type(by["dynamic-q"].options["max_iter"]) is int
    assert by["dynamic-q"].overrides == '{"max_iter": 100}'
    _, same = _plan("hs", None, ["dynamic-q[max_iter=100]", "sqsd[rho=2.0]"], ["hs002"], None, 600.0, ())
    assert [sp.run_key for sp in specs] == [sp.run_key for sp in same]


def test_an_integer_option_written_as_a_float_runs(tmp_path):
    summary = harness.run_suite("hs", solvers=["dynamic-q[max_iter=2e1]"], problems=["hs002"], out=tmp_path,
                                jobs=1, progress=None)
    assert summary.failed == 0
    row = harness.load_results("hs", tmp_path).iloc[0]
    assert row["status"] != "error" and json.loads(row["settings"])["max_iter"] == 20


@pytest.mark.parametrize("content, says", [
    ("raise RuntimeError('boom')\n", "solver module {p} raised RuntimeError at import (line 1): boom"),
    ("def (\n", "solver module {p} raised SyntaxError"),
    (None, "solver module {p} does not exist"),
])
def test_a_bad_solver_module_is_bad_input_named_as_such(tmp_path, capsys, content, says, cli_error):
    p = tmp_path / "mod.py"
    if content is not None:
        p.write_text(content)
    line = cli_error(["run", "--suite-file", TINY, "--solvers", "sqsd", "--solver-module", str(p),
                           "--out", str(tmp_path / "out")])
    assert says.format(p=p) in line


def test_an_unknown_solver_module_name(tmp_path, capsys, cli_error):
    line = cli_error(["run", "--suite-file", TINY, "--solver-module", "no_such_module_xyz",
                           "--out", str(tmp_path)])
    assert "solver module no_such_module_xyz cannot be imported" in line


@pytest.mark.parametrize("kw, says", [
    ({"timeout": "10"}, "--timeout must be a number"),
    ({"jobs": 1.5}, "--jobs must be a whole number"),
    ({"solvers": []}, "no solvers given"),
    ({"solvers": [1]}, "solvers must be a list of ids"),
])
def test_python_api_arguments_are_checked(tmp_path, kw, says):
    with pytest.raises(harness.HarnessArgumentError, match=says):
        harness.run_suite("hs", problems=["hs002"], out=tmp_path, progress=None, **kw)


def test_python_api_takes_one_comma_separated_string_like_the_command_line(tmp_path):
    plan = plan_suite("hs", solvers="scipy-slsqp,sqsd[rho=0.5]", problems="hs002", out=tmp_path)
    assert list(plan["solver"]) == ["scipy-slsqp", "sqsd[rho=0.5]", "all"]


def test_dry_run_total_is_unknown_when_a_solvers_time_is(tmp_path):
    plan = plan_suite("hs", solvers=["scipy-slsqp"], problems=["hs002"], out=tmp_path)
    assert math.isnan(plan["estimated run time [s]"].iloc[-1])


def _rows(**over):
    base = {"suite": "hs", "case_id": "hs002/n=2/x0", "solver": "dynamic-q", "settings_hash": "h", "nfg": 10,
            "success": True, "status": "converged", "rel_error": 0.0, "f": 1.0, "overrides": "", "extra": "{}"}
    return {**base, **over}


def test_compare_keeps_runs_with_different_options_apart():
    old = pd.DataFrame([_rows(), _rows(settings_hash="a", overrides='{"rho": 0.5}', nfg=10)])
    new = pd.DataFrame([_rows(), _rows(settings_hash="b", overrides='{"rho": 0.3}', nfg=40)])
    c = compare_runs(old, new)
    assert len(c.regressions) == 0 and list(c.changes["solver"]) == ["dynamic-q"]
    assert list(c.only_old["solver"]) == ["dynamic-q[rho=0.5]"] and list(c.only_new["solver"]) == ["dynamic-q[rho=0.3]"]


def test_table_3_1_shows_not_applicable_runs_as_such_and_leaves_them_out_of_the_counts():
    def row(solver, status, nfg):
        return {"suite": "hs", "problem": "hs002", "n": 2, "case_id": "hs002/n=2/x0", "solver": solver, "f": 0.0504,
                "f_ref": 0.0504261879, "max_violation": 0.0, "status": status, "nfg": nfg, "finished_at": "t"}

    runs = pd.DataFrame([row("scipy-slsqp", "converged", 12), row("sqsd", "not_applicable", None)])
    main_table, summary = build_tables("hs", runs)
    assert main_table.frame.iloc[0]["sqsd N^fg"] == "n/a"
    s = summary.frame.set_index("solver").loc["sqsd"]
    assert s["problems"] == 0 and s["failed (~)"] == 0 and s["total N^fg"] == 0


def test_bad_targets_and_empty_stores_exit_2(tmp_path, capsys, cli_error):
    (tmp_path / "file").write_text("")
    empty = tmp_path / "empty"
    empty.mkdir()
    assert "no stored results" in cli_error(["report", "--out", str(empty)])
    assert "is a file" in cli_error(["report", "--out", str(tmp_path / "file")])
    assert "hs-all" in cli_error(["reference", "--suite", "hs-all", "--out", str(empty)])
    assert not (empty / "hs-all").exists()
    with pytest.raises(SystemExit) as exc:
        main(["run", "--suite", "hs", "--out", ""])
    assert exc.value.code == 2
    harness.run_suite("hs", solvers=["scipy-slsqp"], problems=["hs002"], out=tmp_path / "r", jobs=1, progress=None)
    assert "is a file" in cli_error(["baseline", "--suite", "hs", "--out", str(tmp_path / "r"),
                                          "--to", str(tmp_path / "file")])
    assert "does not exist" in cli_error(["export", "--suite", "hs", "--out", str(tmp_path / "r"),
                                               "--to", str(tmp_path / "nowhere" / "x.h5")])


def test_a_malformed_local_scheduler_is_bad_input(tmp_path, capsys, cli_error):
    line = cli_error(["run", "--suite-file", TINY, "--executor", "dask", "--scheduler", "local:abc",
                           "--out", str(tmp_path)])
    assert "'local' or 'local:N'" in line


def test_prune_dry_run_changes_nothing(tmp_path, capsys):
    harness.run_suite("hs", solvers=["scipy-slsqp", "sqsd[rho=0.5]"], problems=["hs002"], out=tmp_path, jobs=1,
                      progress=None)
    before = len(harness.load_results("hs", tmp_path))
    assert main(["prune", "--suite", "hs", "--solvers", "scipy-slsqp", "--out", str(tmp_path), "--dry-run"]) == 0
    assert "would remove 1 stored rows (sqsd 1); nothing changed" in capsys.readouterr().out
    assert len(harness.load_results("hs", tmp_path)) == before


def test_a_run_that_never_starts_leaves_no_empty_store(tmp_path, monkeypatch):
    import harness._runner as runner

    def no_scheduler(*args, **kwargs):
        raise OSError("Timed out trying to connect to tcp://127.0.0.1:1 after 30 s")
        yield  # a generator, as the real executor

    monkeypatch.setattr(runner, "_execute", no_scheduler)
    with pytest.raises(OSError, match="Timed out"):
        harness.run_suite(suite_file=TINY, solvers=["sqsd"], out=tmp_path, progress=None)
    assert not Store(tmp_path, "tiny").exists() and not (tmp_path / "tiny" / "manifest.json").exists()


def test_a_solver_repeated_in_a_python_list_is_refused_too(tmp_path):
    # equal string literals are one object: the check must compare positions, not identity
    with pytest.raises(harness.HarnessArgumentError, match="'sqsd' is given twice"):
        plan_suite("hs", solvers=["sqsd", "sqsd"], problems=["hs002"], out=tmp_path)
