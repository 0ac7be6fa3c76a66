"""run_suite / load_results / CLI basics on the tiny suite: rows, resume, --fresh, exit codes."""

import json

import pandas as pd
import pytest

import harness
from harness import HarnessArgumentError
from harness._store import Store
from harness.cli import main


def run(tiny_file, out, **kw):
    kw.setdefault("jobs", 1)
    return harness.run_suite(suite_file=tiny_file, out=out, progress=None, **kw)


def test_rows_resume_and_fresh(tiny_file, tmp_path):
    s1 = run(tiny_file, tmp_path)
    assert (s1.planned, s1.executed, s1.skipped, s1.not_applicable) == (5, 5, 0, 1)
    df = harness.load_results("tiny", tmp_path)
    assert len(df) == 5 and df["run_key"].is_unique
    q2 = df[df.case_id == "q2/n=2/x0"].iloc[0]
    assert q2.status == "converged" and q2.success and q2.nfg > 0 and q2.rel_error < 1e-8
    assert json.loads(q2.settings)["rho"] == 1.0
    hist = json.loads(q2.history)
    assert len(hist) == q2.nfg and hist[0][0] == 1 and isinstance(hist[0][0], int)
    con = df[df.case_id == "con/n=2/x0"].iloc[0]
    assert con.status == "not_applicable" and "ineq" in con.message and not con.success
    # the pending per-run files were consolidated
    assert not list((tmp_path / "tiny" / "runs").glob("*.json"))
    # second run: no solver work
    s2 = run(tiny_file, tmp_path)
    assert (s2.executed, s2.skipped) == (0, 5) and "no solver work" in str(s2)
    # --fresh re-runs and replaces (no duplicates), deterministic counts
    s3 = run(tiny_file, tmp_path, fresh=True)
    assert s3.executed == 5
    df3 = harness.load_results("tiny", tmp_path)
    assert len(df3) == 5
    pd.testing.assert_series_equal(df.set_index("case_id").nfg.sort_index(), df3.set_index("case_id").nfg.sort_index())
    manifest = json.loads((tmp_path / "tiny" / "manifest.json").read_text())
    assert len(manifest["sessions"]) == 2 and manifest["latest"]["packages"]["numpy"]


def test_solver_options_and_problem_selection(tiny_file, tmp_path):
    s = run(tiny_file, tmp_path, solvers=["sqsd", "sqsd[rho=0.25]"], problems=["q2", "rosen/n=2/x1"])
    assert s.executed == 4
    df = harness.load_results("tiny", tmp_path)
    assert sorted(json.loads(v)["rho"] for v in df.settings) == [0.25, 0.25, 1.0, 1.0]
    assert df.settings_hash.nunique() == 4  # rosen carries max_iter=3000, q2 does not


def test_pending_rows_visible_and_duplicates_dropped(tiny_file, tmp_path):
    run(tiny_file, tmp_path, problems=["q2"])
    store = Store(tmp_path, "tiny")
    row = store.load().iloc[0].to_dict()
    row["x"] = list(row["x"])
    row["finished_at"] = "9999"  # newer copy of the same run, not yet consolidated
    row["nit"] = int(row["nit"]) + 1
    row = {k: (int(v) if hasattr(v, "dtype") and "int" in str(v.dtype).lower() else v) for k, v in row.items()}
    store.write_run(json.loads(json.dumps(row, default=int)))
    df = store.load()
    assert len(df) == 1 and df.nit.iloc[0] == row["nit"]


def test_bad_arguments(tiny_file, tmp_path):
    with pytest.raises(HarnessArgumentError, match="valid solvers"):
        run(tiny_file, tmp_path, solvers=["no-such"])
    with pytest.raises(HarnessArgumentError, match="valid problems: q2"):
        run(tiny_file, tmp_path, problems=["zz"])
    with pytest.raises(HarnessArgumentError, match="valid suites"):
        harness.run_suite("no-such-suite", out=tmp_path, progress=None)


@pytest.mark.parametrize("argv", [
    ["run", "--suite", "no-such-suite"],
    ["run", "--suite-file", "TINY", "--solvers", "nope"],
    ["run", "--suite-file", "TINY", "--problems", "nope"],
    ["run", "--suite-file", "TINY", "--jobs", "0"],
    ["list", "problems", "--suite", "nope"],
])
def test_cli_bad_names_exit_2(argv, tiny_file, tmp_path, capsys):
    argv = [tiny_file if a == "TINY" else a for a in argv] + (["--out", str(tmp_path)] if argv[0] == "run" else [])
    assert main(argv) == 2
    assert "valid" in capsys.readouterr().err or "jobs" in " ".join(argv)


def test_cli_run_table_list(tiny_file, tmp_path, capsys):
    assert main(["run", "--suite-file", tiny_file, "--out", str(tmp_path), "--jobs", "1", "--quiet"]) == 0
    assert "5 runs executed" in capsys.readouterr().out
    assert main(["table", "--suite-file", tiny_file, "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "Tiny: N^fg per case" in out and "| q2/n=2/x0 |" in out
    for ext in ("md", "csv", "tex"):
        assert (tmp_path / "tiny" / f"tiny_nfg.{ext}").exists()
    assert main(["list", "problems", "--suite-file", tiny_file]) == 0
    assert "rosen/n=2/x1" in capsys.readouterr().out
    assert main(["list", "solvers"]) == 0
    assert "sqsd" in capsys.readouterr().out


def test_table_without_plugin_or_results(tmp_path, capsys):
    assert (
        main(["table", "--suite", "appendix-a", "--out", str(tmp_path)]) == 2
    )  # nothing stored where asked: bad input
    assert "no results" in capsys.readouterr().err


def test_progress_bar_and_plain_lines():
    import io

    from harness._progress import Progress

    class Tty(io.StringIO):
        def isatty(self):
            return True

    plain, tty = io.StringIO(), Tty()
    for stream in (plain, tty):
        p = Progress("s", 3, stream, interval=0.0)
        for st in ("converged", "error", "timeout"):
            p.update({"status": st})
        p.close()
    assert plain.getvalue().splitlines()[-1].startswith("s: 3/3 runs, 2 failed") and "\r" not in plain.getvalue()
    assert "\r[" in tty.getvalue() and "ETA" in tty.getvalue() and tty.getvalue().endswith("\n")


def test_code_version_follows_the_import_closure(tmp_path):
    from harness._codeversion import code_version, module_closure

    names = lambda mods: {str(p.relative_to(p.parents[1])) for p in module_closure(mods)}
    sqsd = names(("solvers.sqsd", "problems._suite"))
    assert "solvers/sqsd.py" in sqsd and "problems/_oracle.py" in sqsd
    assert not any(n.startswith("manipulators") or "lfopc" in n for n in sqsd)
    planar = names(("manipulators.synthesis.rpr2_suite",))  # the package's names are lazy
    assert "manipulators/rpr2.py" in planar and not any("spatial" in n or "cable" in n for n in planar)
    f = tmp_path / "suite.py"
    f.write_text("A = 1\n")
    v1 = code_version(("solvers.sqsd",), (str(f),))
    assert code_version(("solvers.sqsd",), (str(f),)) == v1
    f.write_text("A = 2\n")
    import os

    os.utime(f, (1, 1))  # a new mtime, as an edit gives
    assert code_version(("solvers.sqsd",), (str(f),)) != v1


def test_name_registries_are_followed_but_not_hashed(monkeypatch):
    """Registering a suite or solver (editing a catalog) must not invalidate stored runs."""
    from harness import _codeversion as cv

    mods = ("solvers.sqsd", "problems.hs")
    closure = {p.relative_to(cv.ROOT).as_posix() for p in cv.module_closure(mods)}
    assert set(cv.REGISTRIES) <= closure and "problems/hs/_build.py" in closure  # followed
    cv._hash.cache_clear()
    v = cv.code_version(mods)
    monkeypatch.setattr(cv, "REGISTRIES", ())
    cv._hash.cache_clear()
    assert cv.code_version(mods) != v  # so by default their text is left out of the hash
    cv._hash.cache_clear()


def test_crash_between_parquet_replace_and_unlink_leaves_no_duplicates(tiny_file, tmp_path):
    """Consolidation killed after os.replace of runs.parquet but before deleting the run
    files: the rows exist twice on disk, once in every view of the store."""
    run(tiny_file, tmp_path, problems=["q2", "q20"])
    store = Store(tmp_path, "tiny")
    rows = store.load()
    plain = lambda v: None if v is pd.NA else (list(map(float, v)) if hasattr(v, "tolist") else int(v))
    for r in rows.to_dict("records"):  # re-create the per-run files as if never deleted
        store.write_run(json.loads(json.dumps(r, default=plain)))
    assert len(store.load()) == len(rows) == 2
    assert store.consolidate() == 2 and not list(store.pending_dir.glob("*.json"))
    s = run(tiny_file, tmp_path, problems=["q2", "q20"])
    assert s.executed == 0


def test_git_dirty_reflects_the_code_not_the_results(tmp_path, monkeypatch):
    import subprocess

    from harness import _manifest

    def git(*a):
        subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", *a], cwd=tmp_path, check=True,
                       capture_output=True)

    (tmp_path / "results" / "hs").mkdir(parents=True)
    (tmp_path / "results" / "hs" / "table.md").write_text("a")
    (tmp_path / "code.py").write_text("x = 1")
    git("init", "-q")
    git("add", ".")
    git("commit", "-qm", "init")
    monkeypatch.setattr(_manifest, "ROOT", tmp_path)
    (tmp_path / "results" / "hs" / "table.md").write_text("b")  # a run rewrote its results
    assert _manifest.environment()["git_dirty"] is False
    (tmp_path / "code.py").write_text("x = 2")
    assert _manifest.environment()["git_dirty"] is True


def test_dry_run_plans_without_running(tiny_file, tmp_path, capsys):
    """--dry-run says per solver what a run would do and runs nothing; after a run nothing is left."""
    from harness._runner import plan_suite

    def dry(**kw):
        return plan_suite(suite_file=tiny_file, out=tmp_path, **kw)

    plan = dry()
    assert not Store(tmp_path, "tiny").exists()  # nothing ran, nothing was stored
    total = plan.set_index("solver").loc["all"]
    counts = (total["planned"], total["done"], total["to run"], total["replace a stored row"])
    assert counts == (5, 1, 4, 0)  # the not-applicable pair counts as done
    run(tiny_file, tmp_path)
    after = dry().set_index("solver").loc["all"]
    assert (after["done"], after["to run"]) == (5, 0) and after["estimated run time [s]"] == 0
    again = dry(fresh=True).set_index("solver").loc["all"]
    assert again["to run"] == 4 and again["replace a stored row"] == 4 and again["estimated run time [s]"] > 0
    assert main(["run", "--suite-file", str(tiny_file), "--out", str(tmp_path), "--dry-run"]) == 0
    assert "Nothing was run" in capsys.readouterr().out


def test_prune_keeps_exactly_what_a_run_would_produce(tiny_file, tmp_path):
    """Rows of other code or settings (here: a run with other options) go; current ones stay."""
    from harness._runner import prune_suite

    run(tiny_file, tmp_path)
    before = harness.load_results("tiny", tmp_path)
    run(tiny_file, tmp_path, solvers=["sqsd[rho=0.5]"])  # a stored variant the default plan does not contain
    assert len(harness.load_results("tiny", tmp_path)) > len(before)
    removed = prune_suite(suite_file=tiny_file, out=tmp_path)
    assert removed and set(removed) == {"sqsd"}
    after = harness.load_results("tiny", tmp_path)
    assert sorted(after["run_key"]) == sorted(before["run_key"])
    assert prune_suite(suite_file=tiny_file, out=tmp_path) == {}  # nothing left to remove
    assert run(tiny_file, tmp_path).executed == 0  # still a complete store for resume


def test_suite_file_without_tables_gets_the_campaign_tables(mine_file, tmp_path, capsys):
    """A suite file with no ``tables`` of its own: `run` and `table` render the tables of the
    library campaigns (summary, every run) instead of refusing."""
    assert main(["run", "--suite-file", str(mine_file), "--solvers", "sqsd,scipy-bfgs", "--out", str(tmp_path),
                 "--quiet"]) == 0
    assert "mine: Per-solver summary of the campaign" in capsys.readouterr().out
    summary = pd.read_csv(tmp_path / "mine" / "mine_summary.csv")
    assert sorted(summary["solver"]) == ["scipy-bfgs", "sqsd"] and list(summary["solved"]) == [1, 1]
    md = (tmp_path / "mine" / "mine_summary.md").read_text()
    assert "1 case known optimum" in md and "Each solver ran with the suite's settings" in md
    assert main(["table", "--suite-file", str(mine_file), "--out", str(tmp_path)]) == 0
    assert "| bowl/n=2/x0 |" in capsys.readouterr().out


def test_suite_file_without_solvers_runs_every_solver_that_handles_it(mine_file, builtin_solvers_only, tmp_path):
    """Every registered solver, as in a fresh process (without the fixture, the never-returning
    solver another test registered would run too, up to the 600 s time limit)."""
    assert main(["run", "--suite-file", str(mine_file), "--out", str(tmp_path), "--quiet", "--jobs", "2"]) == 0
    runs = Store(tmp_path, "mine").load()
    assert {"sqsd", "dynamic-q", "scipy-bfgs", "ipopt"} <= set(runs["solver"])
    assert (runs["status"] != "not_applicable").all()


@pytest.mark.parametrize("suite", ["appendix-a", "hs", "rpr2", "rpr2-exact", "rpr2-spread", "rpr2-central", "rpr3",
                                   "rpr3-spread", "tdpm", "spatial"])
def test_a_suite_loads_no_project_module_outside_its_code_version(suite):
    """The code version hashes the static import closure; a module loaded some other way (a lazy
    package attribute, importlib by name) would be edited without invalidating stored runs.
    So: build the suite's cases and evaluate its first problem in a fresh interpreter, and every
    project module loaded must be in the closure of the suite module and the solver's."""
    import subprocess
    import sys

    from harness._codeversion import PACKAGES, ROOT, module_closure
    from problems._catalog import BUILTIN

    module = BUILTIN[suite].split(":")[0]
    code = (f"import sys, importlib; m = importlib.import_module({module!r}); c = m.SUITE.cases()[0]; "
            "c.problem.objective(c.problem.x0); import solvers.dynamic_q_plus; "
            f"print('\\n'.join(k for k in sys.modules if k.split('.')[0] in {PACKAGES!r}))")
    loaded = subprocess.run([sys.executable, "-c", code], cwd=ROOT, check=True, capture_output=True,
                            text=True).stdout.split()
    files = {p.relative_to(ROOT).with_suffix("").as_posix().removesuffix("/__init__")
             for p in module_closure((module, "solvers.dynamic_q_plus"))}
    outside = sorted(m for m in loaded if m.replace(".", "/") not in files)
    assert not outside, f"{suite}: loaded but not in the code version: {outside}"


def test_a_run_joining_rows_of_another_cpu_says_so(tiny_file, tmp_path, capsys, monkeypatch):
    """Outcomes decided by the clock depend on the machine: adding runs to rows another CPU made,
    some of them time-outs, prints a note naming both CPUs; on the same CPU, with nothing to run,
    or with no stored outcome of the clock's, it stays silent."""
    from harness import _manifest, _runner

    monkeypatch.setattr(_manifest, "_cpu_model", lambda: "CPU A")
    run(tiny_file, tmp_path, problems=["q2"])
    assert "note:" not in capsys.readouterr().err  # a new store
    run(tiny_file, tmp_path, problems=["q20"])
    assert "note:" not in capsys.readouterr().err  # the same CPU
    assert _manifest.stored_cpu(tmp_path / "tiny") == "CPU A"
    monkeypatch.setattr(_manifest, "_cpu_model", lambda: "CPU B")
    run(tiny_file, tmp_path, problems=["q2"], fresh=True)
    assert "note:" not in capsys.readouterr().err  # no stored time-out: the tiny suite's runs all finish
    monkeypatch.setattr(_runner, "_clock_decided", lambda store: 2)
    monkeypatch.setattr(_manifest, "_cpu_model", lambda: "CPU A")  # B made the last rows
    run(tiny_file, tmp_path, problems=["q2"])
    assert "note:" not in capsys.readouterr().err  # nothing to run
    run(tiny_file, tmp_path, problems=["q2"], fresh=True, timeout=10)
    err = capsys.readouterr().err
    assert "made on 'CPU B', this machine is 'CPU A'" in err and "10 s limit (2 stored" in err
    # --dry-run says it too, after the plan (whose estimates are the stored wall times)
    assert main(["run", "--suite-file", tiny_file, "--out", str(tmp_path), "--problems", "q2", "--fresh",
                 "--dry-run"]) == 0
    assert "note:" not in capsys.readouterr().out  # the same CPU as the last rows
    monkeypatch.setattr(_manifest, "_cpu_model", lambda: "CPU C")
    assert main(["run", "--suite-file", tiny_file, "--out", str(tmp_path), "--problems", "q2", "--fresh",
                 "--dry-run"]) == 0
    assert "made on 'CPU A', this machine is 'CPU C'" in capsys.readouterr().out
