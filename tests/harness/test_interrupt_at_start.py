"""Ctrl-C while the harness is still importing ends with one line and exit 130, no traceback."""

from __future__ import annotations

import runpy
import sys

import pytest


def test_ctrl_c_during_the_imports_is_one_line(monkeypatch, capsys):
    import harness.cli

    def interrupted(argv=None):  # where a Ctrl-C in `from ._api import ...` (pandas) lands
        raise KeyboardInterrupt

    monkeypatch.setattr(harness.cli, "main", interrupted)
    monkeypatch.setattr(sys, "argv", ["harness", "list", "suites"])
    with pytest.raises(SystemExit) as exc:
        runpy.run_module("harness", run_name="__main__", alter_sys=False)
    assert exc.value.code == 130
    err = capsys.readouterr().err
    assert err.strip() == "interrupted: finished runs are stored; run again to resume"
