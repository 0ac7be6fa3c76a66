"""Kinematics and statics of the planar cable (tendon-driven) manipulator, vectorized over poses.

Thesis Section 6.2: cable vectors (6.2), platform rotation (6.3), cable lengths (6.4), the
Jacobian of the constraint equations (6.6)-(6.7) and the structure matrix S = J^T (6.11).
Every function takes k poses at once: positions ``u`` of shape (k, 2) and orientations
``phi`` of shape (k,) (or a scalar, broadcast), and returns arrays with a leading axis k.

Load convention (ERRATA, Chapter 6): the load w = [f_x, f_y, tau] acts at the platform-frame
origin; cable i pulls the platform with t_i * ell^i / l_i, ell^i = c^i - a^i(phi) - u, and
its moment about the origin is a^i x f^{Ci}. Equilibrium (6.10)-(6.11) reads S t + w = 0.
"""

from __future__ import annotations

import numpy as np

from .._checks import planar_poses

__all__ = [
    "frame_point",
    "as_poses",
    "platform_points_global",
    "cable_vectors",
    "cable_lengths",
    "structure_matrix",
    "jacobian",
    "det3",
    "structure_rows",
]


def frame_point(beta: np.ndarray | float) -> np.ndarray:
    """Frame attachment point on the 2 x 2 square frame at polar angle beta.

    ERRATA (Chapter 6): c = (cos beta, sin beta) / max(|cos beta|, |sin beta|), the point
    of the square [-1, 1]^2 boundary seen from the origin at angle beta (Section 6.6.1).

    Parameters
    ----------
    beta : float or array_like, shape (...)
        Design angles beta^i in radians.

    Returns
    -------
    ndarray, shape (..., 2)
    """
    b = np.asarray(beta, dtype=float)
    if not np.all(np.isfinite(b)):
        raise ValueError(f"design angles must be finite, got {b}")
    cs = np.stack([np.cos(b), np.sin(b)], axis=-1)
    return cs / np.max(np.abs(cs), axis=-1, keepdims=True)


def as_poses(u: np.ndarray, phi: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """Validate and broadcast positions (k, 2) or (2,) and orientations (k,) or scalar."""
    return planar_poses(u, phi)


def platform_points_global(platform_points: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """a^i(phi) = T(phi) abar^i, eq. (6.3); returns shape (k, n, 2)."""
    c, s = np.cos(phi)[:, None], np.sin(phi)[:, None]
    ax, ay = platform_points[None, :, 0], platform_points[None, :, 1]
    return np.stack([c * ax - s * ay, s * ax + c * ay], axis=-1)


def cable_vectors(frame_points: np.ndarray, platform_points: np.ndarray, u: np.ndarray,
                  phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Cable vectors ell^i = c^i - a^i(phi) - u (6.2) and global platform points a^i.

    Returns
    -------
    ell : ndarray, shape (k, n, 2)
    a : ndarray, shape (k, n, 2)
    """
    a = platform_points_global(platform_points, phi)
    ell = frame_points[None, :, :] - a - u[:, None, :]
    return ell, a


def cable_lengths(ell: np.ndarray) -> np.ndarray:
    """l_i = ||ell^i||, eq. (6.4); shape (k, n)."""
    return np.hypot(ell[..., 0], ell[..., 1])


def structure_matrix(ell: np.ndarray, a: np.ndarray, lengths: np.ndarray | None = None) -> np.ndarray:
    """Structure matrix S (6.11), shape (k, 3, n): column i = [ell^i, (a^i x ell^i)_z] / l_i.

    S = J^T with J the Jacobian of (6.7). A zero-length cable gives a NaN column.
    """
    length = cable_lengths(ell) if lengths is None else lengths
    mz = a[..., 0] * ell[..., 1] - a[..., 1] * ell[..., 0]
    with np.errstate(invalid="ignore", divide="ignore"):
        inv = 1.0 / length
        return np.stack([ell[..., 0] * inv, ell[..., 1] * inv, mz * inv], axis=1)


def structure_rows(frame_points: np.ndarray, platform_points: np.ndarray, u: np.ndarray,
                   phi: np.ndarray | float) -> tuple[np.ndarray, ...]:
    """The rows of S (6.11) and the cable lengths, cable-major (fast path of the grids).

    ``phi`` is one orientation (a float) or one per pose, shape (k,).

    Same quantities as `cable_vectors` / `structure_matrix`, laid out as (n, k) arrays
    (one contiguous row of k poses per cable): sums over cables are then additions of
    contiguous vectors, several times faster than reductions over a short last axis.

    Returns
    -------
    X, Y, M, lengths : ndarrays, shape (n, k)
        S[:, 0, :].T, S[:, 1, :].T, S[:, 2, :].T and l_i.
    """
    px, py = platform_points[:, 0:1], platform_points[:, 1:2]
    if np.ndim(phi) == 0:  # one orientation (a grid slice): a^i is the same for every pose
        c, s = np.cos(phi), np.sin(phi)
    else:
        c, s = np.cos(phi)[None, :], np.sin(phi)[None, :]
    ax = c * px - s * py                                  # a^i(phi), eq. (6.3)
    ay = s * px + c * py
    ux, uy = np.ascontiguousarray(u[:, 0]), np.ascontiguousarray(u[:, 1])
    ex = (frame_points[:, 0:1] - ax) - ux                 # ell^i, eq. (6.2)
    ey = (frame_points[:, 1:2] - ay) - uy
    lengths = np.sqrt(ex * ex + ey * ey)                  # eq. (6.4)
    with np.errstate(invalid="ignore", divide="ignore"):  # zero-length cable -> NaN column
        inv = 1.0 / lengths
        return ex * inv, ey * inv, (ax * ey - ay * ex) * inv, lengths


def jacobian(ell: np.ndarray, a: np.ndarray) -> np.ndarray:
    """J of eq. (6.7), shape (k, n, 3): v_dot = -J [u_dot, w_dot]; J = S^T."""
    return np.swapaxes(structure_matrix(ell, a), 1, 2)


def det3(M: np.ndarray) -> np.ndarray:
    """Determinants of a stack of 3 x 3 matrices (k, 3, 3), by the rule of Sarrus.

    Faster than ``np.linalg.det`` for many small matrices and exact in form, which the
    closed-form tension tests (Algorithm 6.1) rely on.
    """
    return (M[:, 0, 0] * (M[:, 1, 1] * M[:, 2, 2] - M[:, 1, 2] * M[:, 2, 1])
            - M[:, 0, 1] * (M[:, 1, 0] * M[:, 2, 2] - M[:, 1, 2] * M[:, 2, 0])
            + M[:, 0, 2] * (M[:, 1, 0] * M[:, 2, 1] - M[:, 1, 1] * M[:, 2, 0]))
