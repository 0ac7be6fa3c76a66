"""Input checks shared by every manipulator: poses and positions must be finite, and
scalar arguments must be numbers (`is_number`, `is_integer`; a bool is neither).

A NaN or infinite pose is bad input. It is refused where it enters, with the offending
rows named, because downstream it would read as something else: a singular pose
(kappa^-1 = 0 for the 3-RPR), an infeasible one (cable robots), or a NaN condition number.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["finite_rows", "planar_poses", "is_number", "is_integer"]


def is_number(v: Any) -> bool:
    """A real number: int, float, NumPy integer or floating (finite or not).

    A bool (also ``np.bool_``) is not one, though Python counts it as an int: ``True`` for a
    length or a tolerance is a mistake, not 1.  Neither is a string, an array (even 0-d) or
    a complex number.
    """
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))


def is_integer(v: Any) -> bool:
    """An integer: int or NumPy integer, not a bool (nor ``np.bool_``), nor an integral float."""
    return isinstance(v, (int, np.integer)) and not isinstance(v, (bool, np.bool_))


def finite_rows(a: np.ndarray, what: str, show: Any = None) -> np.ndarray:
    """Return ``a`` (k, m) if every row is finite, else raise ValueError naming the rows.

    ``show(i)`` gives the text shown for the first bad row (default: the row itself).
    """
    bad = ~np.all(np.isfinite(a), axis=1)
    if bad.any():
        i = np.flatnonzero(bad)
        first = show(int(i[0])) if show is not None else a[i[0]].tolist()
        raise ValueError(f"{what} contain NaN or inf at row(s) {i[:5].tolist()}{' ...' if i.size > 5 else ''}: {first}")
    return a


def planar_poses(u: Any, phi: Any) -> tuple[np.ndarray, np.ndarray]:
    """Planar poses: positions (k, 2) or (2,) and orientations phi, a number or (k,).

    Returns ``(U, phi)`` with shapes (k, 2) and (k,), both finite.
    """
    U = np.asarray(u, dtype=float)
    if U.ndim == 1:
        U = U[None, :]
    if U.ndim != 2 or U.shape[1] != 2:
        raise ValueError(f"positions u must have shape (2,) or (k, 2), got {np.shape(u)}")
    P = np.asarray(phi, dtype=float)
    if P.ndim == 0:
        P = np.full(U.shape[0], float(P))
    if P.shape != (U.shape[0],):
        raise ValueError(f"orientation phi must be a number or one per position ({U.shape[0]},), got shape {P.shape}")
    finite_rows(np.column_stack([U, P]), "poses", lambda i: f"u = {U[i].tolist()}, phi = {float(P[i])}")
    return U, P
