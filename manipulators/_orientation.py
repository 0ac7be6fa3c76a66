"""Closed-form orientation sets of a leg whose squared length is a cosine in the orientation.

For an RPR leg between a base point ``b`` and a platform point ``u + s r e(w)``
(``e(w) = (cos w, sin w)``, ``s = +1`` or ``-1``) the squared leg length is

    l^2(w) = P + Q cos(w - alpha),   P = rho^2 + r^2,  Q = 2 r rho,

with ``rho = |u - b|`` and ``alpha`` the polar angle of ``s (u - b)``.  The leg-length
limits ``l_min <= l <= l_max`` (thesis eq. 5.3) therefore allow the orientations with
``cos(w - alpha)`` in ``[(l_min^2 - P)/Q, (l_max^2 - P)/Q]``: at most two arcs of the
circle.  This module intersects such sets analytically, vectorized over points.  It is
the closed-form replacement of the thesis's numerical orientation-workspace problem
(5.26), which Section 5.5.4 suggests ("it may be possible to determine such orientation
workspaces analytically").

All functions take arrays broadcast to a common shape ``(k,)`` per leg.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "cosine_leg",
    "component_containing",
    "cos_extremes_on_interval",
    "allowed_arcs",
    "intersect_arcs",
    "wrap_pi",
]

TWO_PI = 2.0 * np.pi
_Q_TINY = 1e-300  # a leg with rho = 0 has constant length; keeps the division finite


def wrap_pi(a: np.ndarray | float) -> np.ndarray:
    """Wrap angles to (-pi, pi]."""
    return np.pi - np.mod(np.pi - np.asarray(a, dtype=float), TWO_PI)


def wrap_2pi(a: np.ndarray) -> np.ndarray:
    """Wrap angles to [0, 2 pi)."""
    return np.mod(np.asarray(a, dtype=float), TWO_PI)


def cosine_leg(U: np.ndarray, base: np.ndarray, sign: float, r: float):
    """Parameters ``(P, Q, alpha)`` of ``l^2(w) = P + Q cos(w - alpha)`` for points ``U``.

    Parameters
    ----------
    U : (k, 2) positions of the platform mid-point.
    base : (2,) base joint of the leg.
    sign : +1 if the leg attaches at ``u + r e(w)``, -1 if at ``u - r e(w)`` (eq. 5.7).
    r : platform half-length.
    """
    g = U - base
    rho2 = np.einsum("ij,ij->i", g, g)
    rho = np.sqrt(rho2)
    gamma = np.arctan2(g[:, 1], g[:, 0])
    alpha = gamma if sign > 0 else gamma + np.pi
    return rho2 + r * r, 2.0 * r * rho, alpha


def _half_widths(P, Q, lmin, lmax):
    """``a_lo, a_hi, empty``: allowed ``|w - alpha|`` lies in ``[a_lo, a_hi]``."""
    Qs = np.maximum(Q, _Q_TINY)
    c_lo = (lmin * lmin - P) / Qs
    c_hi = (lmax * lmax - P) / Qs
    empty = (c_lo > 1.0) | (c_hi < -1.0) | (c_lo > c_hi)
    a_lo = np.arccos(np.clip(c_hi, -1.0, 1.0))
    a_hi = np.arccos(np.clip(c_lo, -1.0, 1.0))
    return a_lo, a_hi, empty


def component_containing(P, Q, alpha, lmin, lmax, w_ref):
    """Connected interval of allowed orientations that contains ``w_ref``, per point.

    Returns ``(w_lo, w_hi)``: NaN where ``w_ref`` itself violates the limits, and
    ``-inf, +inf`` where every orientation is allowed.
    """
    a_lo, a_hi, empty = _half_widths(P, Q, lmin, lmax)
    t = wrap_pi(w_ref - alpha)
    at = np.abs(t)
    ok = ~empty & (at >= a_lo) & (at <= a_hi)
    full_low = a_lo <= 0.0  # the two arcs join through theta = 0
    full_high = a_hi >= np.pi  # ... and through theta = pi
    # Component in theta for a reference on the positive arc [a_lo, a_hi]; the negative
    # side is the mirror image.
    up = np.where(full_high, np.where(full_low, np.inf, TWO_PI - a_lo), a_hi)
    down = np.where(full_low, np.where(full_high, -np.inf, -a_hi), a_lo)
    pos = t >= 0.0
    hi = np.where(pos, up, -down)
    lo = np.where(pos, down, -up)
    w_lo = np.where(ok, w_ref + (lo - t), np.nan)
    w_hi = np.where(ok, w_ref + (hi - t), np.nan)
    return w_lo, w_hi


def cos_extremes_on_interval(alpha, a, b):
    """Min and max of ``cos(w - alpha)`` for ``w`` in ``[a, b]`` and whether each is interior.

    Returns ``(cmin, cmax, min_interior, max_interior)``; an extreme is *interior* when
    it is attained at a critical angle strictly inside ``(a, b)`` (not at an end).
    """
    width = b - a
    ca = np.cos(a - alpha)
    cb = np.cos(b - alpha)
    d_max = wrap_2pi(alpha - a)  # first angle >= a where cos(w - alpha) = 1
    d_min = wrap_2pi(alpha + np.pi - a)
    max_int = (d_max > 0.0) & (d_max < width)
    min_int = (d_min > 0.0) & (d_min < width)
    cmax = np.where(max_int, 1.0, np.maximum(ca, cb))
    cmin = np.where(min_int, -1.0, np.minimum(ca, cb))
    return cmin, cmax, min_int, max_int


def allowed_arcs(P: float, Q: float, alpha: float, lmin: float, lmax: float) -> list[tuple[float, float]]:
    """Allowed orientations of one leg at one point as arcs ``[lo, hi]`` with ``lo`` in (-pi, pi]."""
    a_lo, a_hi, empty = (float(v) for v in _half_widths(np.float64(P), np.float64(Q), lmin, lmax))
    if empty:
        return []
    if a_lo <= 0.0 and a_hi >= np.pi:
        return [(-np.pi, np.pi)]
    if a_lo <= 0.0:
        return [(float(wrap_pi(alpha - a_hi)), float(wrap_pi(alpha - a_hi)) + 2 * a_hi)]
    if a_hi >= np.pi:
        lo = float(wrap_pi(alpha + a_lo))
        return [(lo, lo + TWO_PI - 2 * a_lo)]
    return [
        (float(wrap_pi(alpha + a_lo)), float(wrap_pi(alpha + a_lo)) + a_hi - a_lo),
        (float(wrap_pi(alpha - a_hi)), float(wrap_pi(alpha - a_hi)) + a_hi - a_lo),
    ]


def _unwrap_arcs(arcs):
    """Arcs as intervals of [-pi, 3 pi) that cover the circle once (for intersection)."""
    out = []
    for lo, hi in arcs:
        if hi - lo >= TWO_PI - 1e-15:
            out.append((-np.pi, np.pi))
            continue
        lo = float(wrap_pi(lo))
        hi = lo + (hi - lo if hi >= lo else hi - lo + TWO_PI)
        if hi > np.pi:  # split at pi
            out.append((lo, np.pi))
            out.append((-np.pi, hi - TWO_PI))
        else:
            out.append((lo, hi))
    return out


def intersect_arcs(per_leg: list[list[tuple[float, float]]]) -> list[tuple[float, float]]:
    """Intersection of the legs' arc sets, as disjoint intervals of [-pi, pi] (sorted)."""
    current = [(-np.pi, np.pi)]
    for arcs in per_leg:
        pieces = _unwrap_arcs(arcs)
        nxt = []
        for a0, a1 in current:
            for b0, b1 in pieces:
                lo, hi = max(a0, b0), min(a1, b1)
                if hi >= lo:
                    nxt.append((lo, hi))
        current = sorted(nxt)
    # merge pieces touching at +-pi or at each other
    merged: list[tuple[float, float]] = []
    for lo, hi in current:
        if merged and lo <= merged[-1][1] + 1e-14:
            merged[-1] = (merged[-1][0], max(merged[-1][1], hi))
        else:
            merged.append((lo, hi))
    return merged
