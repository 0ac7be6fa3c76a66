"""Defects found by a second new-user audit of ``python -m harness`` (2026-12-02), each pinned by a
test: command-line mistakes answered in the harness's one-line form with the option probably
meant, `run --dry-run` accepting what `run` refuses, options silently ignored by `list` and
`plot`, and messages that named the wrong problem (docs/harness.md, "Exit status")."""

import pytest

import harness
from harness.cli import _parser, main


def _usage_error(capsys, argv):
    """The one line a command-line mistake gives (exit 2, no usage block, no traceback)."""
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: python -m harness"), err
    return err[0]


@pytest.mark.parametrize("argv, says", [
    (["run", "--suite", "hs", "--timout", "5", "--dry-run"],
     "unrecognized arguments: --timout 5 (did you mean --timeout?)"),
    (["run", "--suite", "hs", "--dryrun"], "(did you mean --dry-run?)"),
    (["compare", "a", "b", "--nfg-toll", "0.2"], "(did you mean --nfg-tol?)"),
])
def test_a_misspelled_option_is_named_with_the_one_meant(capsys, argv, says):
    line = _usage_error(capsys, argv)
    assert says in line and f"see `python -m harness {argv[0]} --help`" in line


def test_an_option_before_the_command_says_where_it_goes(capsys):
    line = _usage_error(capsys, ["--quiet", "run", "--suite", "hs", "--dry-run"])
    assert line.startswith("error: python -m harness: unrecognized arguments: --quiet (a command's options go after "
                           "it: python -m harness run --quiet ...)")


@pytest.mark.parametrize("argv, says", [
    (["run", "--suite", "hs", "--timeout", "abc"],
     "argument --timeout: needs a number of seconds (0 or inf: no limit), got 'abc'"),
    (["run", "--suite", "hs", "--jobs", "1.5"], "argument --jobs: needs a whole number, got '1.5'"),
    (["compare", "a", "b", "--nfg-tol", "x"], "argument --nfg-tol: needs a number, got 'x'"),
    (["list", "solvres"], "invalid choice: 'solvres'"),
    ([], "the following arguments are required: COMMAND"),
])
def test_a_malformed_value_is_one_line_naming_it(capsys, argv, says):
    assert says in _usage_error(capsys, argv)


@pytest.mark.parametrize("extra, kw, says", [
    (["--jobs", "0"], {"jobs": 0}, "--jobs must be a whole number >= 1, got 0"),
    (["--history-points", "1"], {"history_points": 1}, "--history-points must be a whole number >= 2, got 1"),
    (["--executor", "dask"], {"executor": "dask"}, "--executor dask needs --scheduler"),
    (["--scheduler", "tcp://127.0.0.1:1"], {"scheduler": "tcp://127.0.0.1:1"}, "is for --executor dask"),
])
def test_dry_run_refuses_what_run_refuses(tmp_path, capsys, cli_error, extra, kw, says):
    argv = ["run", "--suite", "hs", "--problems", "hs002", "--solvers", "scipy-slsqp", "--out", str(tmp_path)]
    assert says in cli_error([*argv, "--dry-run", *extra])
    with pytest.raises(harness.HarnessArgumentError) as exc:
        harness.run_suite("hs", problems=["hs002"], solvers=["scipy-slsqp"], out=tmp_path, progress=None, **kw)
    assert says in str(exc.value)


@pytest.mark.parametrize("argv, says", [
    (["list", "solvers", "--suite", "hs"], "--suite applies to `list problems` only, not `list solvers`"),
    (["list", "suites", "--select", "type=u"], "--select applies to `list problems` only"),
    (["list", "suites", "--brief"], "--brief applies to `list solvers` only, not `list suites`"),
])
def test_list_refuses_options_it_would_ignore(capsys, cli_error, argv, says):
    assert says in cli_error(argv)


def test_plot_refuses_a_problem_for_a_kind_that_draws_every_case(tmp_path, capsys, cli_error):
    line = cli_error(["plot", "--suite", "hs", "--kind", "profile", "--problem", "hs002", "--out", str(tmp_path)])
    assert "--problem applies to --kind history only" in line


def test_reference_of_an_unknown_suite_says_it_is_unknown(capsys, cli_error):
    assert cli_error(["reference", "--suite", "nosuch"]).startswith("error: unknown suite 'nosuch'; suites with a "
                                                                    "stored reference: rpr2")


def test_compare_of_suite_directories_says_which_directories_it_takes(tmp_path, capsys, cli_error):
    for d in ("old", "new"):
        (tmp_path / d / "hs").mkdir(parents=True)
        (tmp_path / d / "hs" / "runs.parquet").write_bytes(b"")
    line = cli_error(["compare", str(tmp_path / "old" / "hs"), str(tmp_path / "new" / "hs")])
    assert "is the directory of suite 'hs'" in line and f"compare {tmp_path / 'old'} ... --suite hs" in line


def test_every_option_has_a_help_text():
    sub = _parser()._subparsers._group_actions[0]
    missing = [f"{name} {a.option_strings or a.dest}" for name, p in sub.choices.items() for a in p._actions
               if not a.help]
    assert not missing


def test_dry_run_refuses_an_out_that_is_a_file_and_creates_nothing(tmp_path, capsys, cli_error):
    (tmp_path / "file").write_text("")
    line = cli_error(["run", "--suite", "hs", "--problems", "hs002", "--out", str(tmp_path / "file" / "res"),
                      "--dry-run"])
    assert f"{tmp_path / 'file'} is a file, not a directory" in line


def test_dry_run_shows_a_solver_with_options_as_a_solver_of_its_own(tmp_path, tiny_file):
    harness.run_suite(suite_file=tiny_file, solvers=["sqsd"], problems=["q2"], out=tmp_path, jobs=1,
                      progress=None)
    plan = harness.plan_suite(suite_file=tiny_file, solvers=["sqsd", "sqsd[rho=0.5]"], problems=["q2"],
                              out=tmp_path).set_index("solver")
    assert list(plan.index) == ["sqsd", "sqsd[rho=0.5]", "all"]
    assert plan.loc["sqsd", "done"] == plan.loc["sqsd", "planned"] and plan.loc["sqsd", "to run"] == 0
    # sqsd[rho=0.5] sits beside the stored sqsd rows (docs/harness.md): it replaces none of them
    assert plan.loc["sqsd[rho=0.5]", "to run"] == plan.loc["sqsd[rho=0.5]", "planned"] > 0
    assert plan.loc["sqsd[rho=0.5]", "replace a stored row"] == 0


def test_an_interrupted_command_other_than_run_does_not_speak_of_runs(monkeypatch, capsys):
    import harness.cli as cli

    def interrupted(a):
        raise KeyboardInterrupt

    monkeypatch.setitem(cli.COMMANDS, "list", interrupted)
    assert main(["list", "suites"]) == 130
    assert capsys.readouterr().err.strip() == "interrupted: list did not finish"


@pytest.mark.parametrize("command", [["table"], ["plot", "--kind", "profile"]])
def test_a_suite_file_with_nothing_stored_names_the_command_that_stores_it(tmp_path, capsys, mine_file, cli_error,
                                                                          command):
    line = cli_error([*command, "--suite-file", str(mine_file), "--out", str(tmp_path / "res")])
    assert f"run `python -m harness run --suite-file {mine_file} --out {tmp_path / 'res'}` first" in line
    assert "built-in" not in line


@pytest.mark.parametrize("command", [["repair"], ["export", "--to", "x.h5"], ["baseline"], ["reference"],
                                     ["compare", "a", "b"]])
def test_a_suite_name_that_is_a_path_is_bad_input_for_every_command(tmp_path, capsys, command):
    (tmp_path / "sub").mkdir()
    line = _usage_error(capsys, [*command, "--suite", "../hs", "--out" if command[0] != "compare" else "--all",
                                 *([str(tmp_path / "sub")] if command[0] != "compare" else [])])
    assert "argument --suite: suite name '../hs' must be kebab-case" in line
