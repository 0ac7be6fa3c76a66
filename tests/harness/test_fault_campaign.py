"""The fault campaign (docs/harness.md, "Fault campaign") on a two-problem sample: every
scenario it runs must end with a store equal to the clean run's, and it refuses a bad
selection with exit status 2."""

import pytest

from harness import fault_campaign


def test_sample_campaign_ends_equal_to_the_clean_run(tmp_path, capsys):
    rc = fault_campaign.main(["--out", str(tmp_path), "--problems", "hs010,hs071",
                              "--scenarios", "kill-harness,sigint,concurrent,truncated"])
    out = capsys.readouterr().out
    report = (tmp_path / "fault_campaign.md").read_text()
    assert rc == 0, out
    names = ["kill-harness-1", "kill-harness-2", "kill-harness-3", "sigint", "concurrent", "truncated"]
    for name in names:
        assert f"{name}: ok" in out and f"| {name} |" in report
    assert "kill-worker" not in out and "DIFFERS" not in out
    assert "clean run: 18 runs" in out  # 2 problems x the 9 default solvers of suite hs


def test_unknown_scenario_is_refused(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        fault_campaign.main(["--out", str(tmp_path), "--scenarios", "kill-harness,unplug"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "unknown scenario(s) unplug" in err and "kill-worker" in err


def test_unknown_problem_is_refused_before_any_fault(tmp_path, capsys):
    rc = fault_campaign.main(["--out", str(tmp_path), "--problems", "hs999", "--scenarios", "sigint"])
    assert rc == 2
    err = capsys.readouterr().err
    assert "the clean run failed" in err and "hs999" in err
    assert not (tmp_path / "sigint").exists()
