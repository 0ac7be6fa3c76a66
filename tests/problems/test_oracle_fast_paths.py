"""The oracle's shortcuts for its history bookkeeping give bitwise the floats of the plain reductions."""

import numpy as np

from problems import Oracle, Problem
from problems._oracle import _abs_max_or_zero, _max, _max_or_zero

SPECIAL = [0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300, 1e308, -1e308, np.inf, -np.inf, np.nan]


def _vectors(rng, count=4000):
    for _ in range(count):
        n = int(rng.integers(1, 9))
        v = rng.standard_normal(n) * 10.0 ** rng.integers(-5, 5, n)
        mask = rng.random(n) < 0.4
        v[mask] = rng.choice(SPECIAL, int(mask.sum()))
        yield v


def _same(a: float, b: float) -> bool:
    return np.float64(a).tobytes() == np.float64(b).tobytes()


def test_max_shortcuts_are_the_reductions_bitwise():
    rng = np.random.default_rng(7)
    for c in _vectors(rng):
        assert _same(_max_or_zero(c), float(_max(c, initial=0.0))), c
        assert _same(_abs_max_or_zero(c), float(_max(np.abs(c), initial=0.0))), c


def test_bound_violation_shortcut_is_the_reductions_bitwise():
    rng = np.random.default_rng(8)
    for x in _vectors(rng, 3000):
        n = x.size
        lo = rng.choice([-np.inf, -1.0, 0.0, -0.0, 0.5], n)
        up = np.maximum(lo, rng.choice([np.inf, 1.0, 0.0, -0.0, 0.5], n))
        p = Problem(name="b", x0=np.zeros(n), objective=lambda z: 0.0, lower=lo, upper=up)
        o = Oracle(p)
        with np.errstate(invalid="ignore"):
            want = max(float(_max(o._lower - x)), float(_max(x - o._upper)), 0.0)
            assert _same(o._bound_viol(x), want), (x, lo, up)
