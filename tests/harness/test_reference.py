"""Stored references (harness/_reference.py): written by `harness reference`/`run`, read by tables."""

from __future__ import annotations

import json

from harness._reference import load_reference, update_reference
from harness.cli import main


def test_reference_command_rejects_suites_without_one(capsys):
    assert main(["reference", "--suite", "hs"]) == 2
    assert "has no stored reference" in capsys.readouterr().err


def test_update_writes_once_and_keeps_what_is_stored(tmp_path, monkeypatch):
    import manipulators.synthesis.rpr2_exact as rx

    calls = []
    monkeypatch.setattr(rx, "exact_optimum", lambda kind: calls.append(kind) or {"f": 1.0, "d": [0.0] * 5,
                                                                                 "starts": 1, "minima": []})
    monkeypatch.setattr(rx, "exact_polish", lambda d: {"f": 2.0})
    path = update_reference(tmp_path, "rpr2", None)
    doc = json.loads(path.read_text())
    assert doc["suite"] == "rpr2" and doc["data"]["exact_optimum"]["f"] == 1.0
    assert len(doc["data"]["polish"]) == 4  # the thesis's four d* of Table 4.7
    update_reference(tmp_path, "rpr2", None)  # nothing missing: not recomputed
    assert calls == ["e"]
    assert load_reference(tmp_path, "rpr2")["exact_optimum"]["f"] == 1.0
    update_reference(tmp_path, "rpr2", None, fresh=True)
    assert calls == ["e", "e"]


def test_missing_reference_is_empty_and_the_table_says_so(tmp_path):
    import pathlib

    from harness._api import load_results
    from harness.tables.rpr2 import tables

    assert load_reference(tmp_path, "rpr2") == {}
    runs = load_results("rpr2", pathlib.Path(__file__).resolve().parents[2] / "results")
    t47 = [t for t in tables(runs, {}) if t.name == "table_4_7"][0]
    assert not (t47.frame["solver"] == "(exact-model optimum)").any()
    assert any("No stored exact-model reference" in n for n in t47.notes)
