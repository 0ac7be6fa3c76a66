"""`harness._history.thin_history`: what profiles read survives the thinning.

Invariant (property test): for every feasibility tolerance and every target f, the first
evaluation of the thinned history that is feasible and reaches the target exists exactly
when it does in the full history, and its count is the full history's rounded up by at
most the documented factor (nfg_last / nfg_first)^(1 / bins).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from harness._history import thin_history


def _first_hit(h: list[list[float]], tol: float, target: float) -> float | None:
    for nfg, f, v in h:
        if float(v) <= tol and float(f) <= target:
            return nfg
    return None


def _history(seed: int, m: int, constrained: bool) -> list[list[float]]:
    rng = np.random.default_rng(seed)
    f = np.cumsum(rng.normal(-0.01, 1.0, m))  # wandering, mostly falling
    v = np.abs(rng.normal(0, 1, m)) * np.exp(-np.arange(m) / (m / 4)) if constrained else np.zeros(m)
    v[rng.random(m) < 0.3] = 0.0
    return [[i + 1, float(a), float(b)] for i, (a, b) in enumerate(zip(f, v))]


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000), m=st.integers(50, 3000), bins=st.integers(2, 40),
       constrained=st.booleans())
def test_first_hits_survive(seed: int, m: int, bins: int, constrained: bool) -> None:
    full = _history(seed, m, constrained)
    thin = json.loads(thin_history(json.dumps(full), bins))
    assert thin[-1] == full[-1] and thin[0] == full[0]
    assert [r[0] for r in thin] == sorted({r[0] for r in thin})  # a subsequence, in order
    factor = (full[-1][0] / full[0][0]) ** (1 / bins)
    fs = np.array([r[1] for r in full])
    for tol in (0.0, 1e-3, 0.5, np.inf):
        for target in np.quantile(fs, [0.0, 0.01, 0.2, 0.5, 1.0]):
            a, b = _first_hit(full, tol, target), _first_hit(thin, tol, target)
            assert (a is None) == (b is None)
            if a is not None:
                assert a <= b <= a * factor * (1 + 1e-12)


def test_feasible_descent_shrinks_to_about_the_bins() -> None:
    full = [[i, 1.0 / i, 0.0] for i in range(1, 100_001)]
    thin = json.loads(thin_history(json.dumps(full), 100))
    assert len(thin) <= 101


def test_short_history_unchanged_and_bad_bins_refused() -> None:
    text = json.dumps([[1, 3.0, 0.0], [2, 4.0, 0.0]])
    assert thin_history(text, 10) == text
    with pytest.raises(ValueError, match=">= 2"):
        thin_history(text, 1)


def test_nan_and_string_values_are_kept_safe() -> None:
    full = [[1, "nan", 0.0], [2, 5.0, "inf"], [3, 4.0, 0.0]] + [[i, 4.0 - i * 1e-3, 0.0] for i in range(4, 50)]
    thin = json.loads(thin_history(json.dumps(full), 5))
    assert thin[-1] == full[-1]
    hit = _first_hit(thin, 0.0, 4.0)  # first reached at evaluation 3; the bins round it up
    assert hit is not None and 3 <= hit <= 3 * (49 / 1) ** (1 / 5)
