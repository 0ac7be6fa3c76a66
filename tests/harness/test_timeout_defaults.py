"""The per-suite ``--timeout`` defaults are written once, in `harness._runner.SUITE_TIMEOUTS` and
`DEFAULT_TIMEOUT`: the CLI help is generated from them, and docs/harness.md's options table
must state every one of them (and nothing else)."""

import pathlib
import re

from harness._runner import DEFAULT_TIMEOUT, SUITE_TIMEOUTS
from harness.cli import _parser

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "harness.md"


def _stated_limits(text: str) -> tuple[dict[str, float], list[float]]:
    """From ``text``'s ``;``-separated clauses "N for `a`, `b` and `c` ..." and "N otherwise": the
    limit stated for each named suite, and the limits stated for every other suite."""
    named: dict[str, float] = {}
    otherwise: list[float] = []
    for clause in text.split(";"):
        m = re.search(r"(\d+(?:\.\d+)?)\s+(?:s\s+)?(for|otherwise)\b", clause)
        if m is None:
            continue
        if m.group(2) == "otherwise":
            otherwise.append(float(m.group(1)))
        else:
            for name in re.findall(r"`([a-z][a-z0-9-]*)`", clause[m.end():]):
                assert name not in named, f"suite {name} is given two limits"
                named[name] = float(m.group(1))
    return named, otherwise


def test_docs_state_every_suite_default_timeout():
    rows = [line for line in DOC.read_text().splitlines() if line.startswith("| `--timeout")]
    assert len(rows) == 1, "docs/harness.md: one options-table row for --timeout"
    named, otherwise = _stated_limits(rows[0])
    assert named == SUITE_TIMEOUTS, f"docs/harness.md's --timeout row says {named}; SUITE_TIMEOUTS is {SUITE_TIMEOUTS}"
    assert otherwise == [DEFAULT_TIMEOUT], f"docs/harness.md's --timeout row: default {otherwise}, " \
                                           f"not {DEFAULT_TIMEOUT}"


def _timeout_help() -> str:
    run = _parser()._subparsers._group_actions[0].choices["run"]
    (action,) = [a for a in run._actions if "--timeout" in a.option_strings]
    return action.help


def test_cli_help_names_every_suite_default_timeout():
    text = _timeout_help()
    for suite, limit in SUITE_TIMEOUTS.items():
        assert re.search(rf"\b{re.escape(suite)}\b", text) and f"{limit:g} for " in text, (suite, text)
    assert f"{DEFAULT_TIMEOUT:g} otherwise" in text


def test_cli_help_is_generated_from_suite_timeouts(monkeypatch):
    import harness._runner as runner

    monkeypatch.setattr(runner, "SUITE_TIMEOUTS", {"a": 5.0, "b": 7.5, "c": 5.0})
    monkeypatch.setattr(runner, "DEFAULT_TIMEOUT", 99.0)
    assert "default 5 for a and c, 7.5 for b, 99 otherwise and for --suite-file;" in _timeout_help()
