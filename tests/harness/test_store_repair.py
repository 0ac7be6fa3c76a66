"""A truncated runs.parquet costs at most the last merge: the previous generation is kept,
every command names the file and the repair command, and a broken suite does not break
the report of the others."""

import pathlib
import subprocess

import pytest

import harness
from harness._store import CorruptStore, Store
from harness.cli import main

TINY = str(pathlib.Path(__file__).with_name("tiny_suite.py"))


def _run(out, problems):
    harness.run_suite(suite_file=TINY, solvers=["sqsd"], problems=problems, out=out, jobs=1, progress=None)


def test_truncated_store_is_named_and_repaired(tmp_path, capsys):
    _run(tmp_path, ["q2"])
    _run(tmp_path, ["q20"])  # second merge: the first generation is kept beside it
    store = Store(tmp_path, "tiny")
    assert store.previous.exists() and len(store.load()) == 2
    data = store.parquet.read_bytes()
    store.parquet.write_bytes(data[: len(data) // 2])
    with pytest.raises(CorruptStore, match="repair --suite tiny"):
        store.load()
    for argv in (["run", "--suite-file", TINY, "--solvers", "sqsd", "--out", str(tmp_path), "--quiet"],
                 ["table", "--suite-file", TINY, "--out", str(tmp_path)]):
        assert main(argv) == 3
        err = capsys.readouterr().err
        assert "runs.parquet is unreadable" in err and "Traceback" not in err
    assert main(["repair", "--suite", "tiny", "--out", str(tmp_path)]) == 0
    runs = store.load()
    assert list(runs["problem"]) == ["q2"]  # only the last merge is lost ...
    _run(tmp_path, ["q2", "q20"])  # ... and a plain re-run redoes it
    assert sorted(store.load()["problem"]) == ["q2", "q20"]
    assert "nothing to repair" in store.repair()


def test_broken_suite_does_not_break_the_report(tmp_path):
    _run(tmp_path, ["q2"])
    other = tmp_path / "broken"
    other.mkdir()
    (other / "runs.parquet").write_bytes(b"not parquet")
    page = harness.write_report(tmp_path).read_text()
    assert "results not readable" in page and "tiny" in page


def test_report_embed_is_self_contained(tmp_path, capsys):
    _run(tmp_path, ["q2", "q20"])
    assert harness.plot("tiny", "profile", out=tmp_path)
    assert main(["report", "--out", str(tmp_path), "--embed"]) == 0
    assert "report: [1/1] tiny" in capsys.readouterr().err  # progress lines
    page = (tmp_path / "report" / "index.html").read_text()
    assert 'src="data:image/png;base64,' in page and '.png"' not in page


def test_repair_without_previous_generation_says_so(tmp_path):
    """A fresh clone has no runs.prev.parquet: repair must not claim a restore, and names git's copy."""
    _run(tmp_path, ["q2"])  # one merge only: no previous generation
    store = Store(tmp_path, "tiny")
    assert not store.previous.exists()
    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    subprocess.run(["git", "-C", str(tmp_path), "add", "tiny/runs.parquet"], check=True)
    data = store.parquet.read_bytes()
    store.parquet.write_bytes(data[: len(data) // 2])
    msg = store.repair()
    assert "restored" not in msg and "no previous generation" in msg
    assert f"git checkout -- {store.parquet}" in msg
