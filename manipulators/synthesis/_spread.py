"""Perturbed starts for the spread suites (``rpr2-spread``, ``rpr3-spread``).

A synthesis end that moves far under a change of the start below the precision to which
the thesis prints it (three decimals at most) is not determined by what the thesis states,
and no implementation can pin it; one that stays put can be.  The spread suites run each
case from its start and from copies of it moved by at most ``eps`` in every component.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .._checks import is_integer, is_number

__all__ = ["perturbed", "start_label", "parse_start"]


def perturbed(x0, key: Sequence[int], k: int, eps: float) -> np.ndarray:
    """Start ``k`` about ``x0`` (k = 0: ``x0`` itself): every component moved by eps * U(-1, 1).

    Seeded by (``key``, k), so the same starts come out on every machine and in every run;
    ``key`` names the case (e.g. the index of the thesis start) so that cases get their own
    perturbations.
    """
    if not (is_integer(k) and k >= 0):
        raise ValueError(f"k must be an integer >= 0, got {k!r}")
    if not (is_number(eps) and eps > 0):
        raise ValueError(f"eps must be a number > 0, got {eps!r}")
    x0 = np.asarray(x0, dtype=float)
    if k == 0:
        return x0
    rng = np.random.default_rng([*(int(i) for i in key), int(k)])
    return x0 + eps * rng.uniform(-1.0, 1.0, x0.size)


def start_label(base: str, k: int) -> str:
    """``("SP3", 7)`` -> ``"SP3~7"``; k = 0 -> ``"SP3"`` (the start itself)."""
    return base if k == 0 else f"{base}~{k}"


def parse_start(label: str) -> tuple[str, int]:
    """``"SP3~7"`` -> ("SP3", 7); ``"SP3"`` -> ("SP3", 0): the inverse of `start_label`."""
    base, _, k = label.partition("~")
    return base, int(k) if k else 0
