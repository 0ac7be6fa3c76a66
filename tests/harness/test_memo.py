"""The on-disk memo of expensive table inputs (harness/_memo.py)."""

import numpy as np

from harness import _memo


def test_computed_once_per_arguments_and_recomputed_when_unreadable(tmp_path, monkeypatch):
    monkeypatch.setenv("HAYBENCH_CACHE", str(tmp_path))
    calls = []

    def compute(v):
        calls.append(v)
        return {"d": np.array([v, 2.0]), "kinv": 0.5 * v}

    mods = ("manipulators.synthesis.rpr3_suite",)
    a = _memo.memo("t", mods, (1,), lambda: compute(1))
    b = _memo.memo("t", mods, (1,), lambda: compute(1))
    assert calls == [1] and b["kinv"] == a["kinv"] and np.array_equal(a["d"], b["d"])
    _memo.memo("t", mods, (2,), lambda: compute(2))
    assert calls == [1, 2]
    for f in tmp_path.glob("t-*.pkl"):
        f.write_bytes(b"not a pickle")
    assert _memo.memo("t", mods, (1,), lambda: compute(1))["kinv"] == 0.5 and calls == [1, 2, 1]


def test_unwritable_cache_still_returns_the_value(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    monkeypatch.setenv("HAYBENCH_CACHE", str(blocker / "sub"))  # a directory under a file cannot exist
    assert _memo.memo("t", ("harness._memo",), (), lambda: 42) == 42
