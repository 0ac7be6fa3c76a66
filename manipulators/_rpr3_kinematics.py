"""Pure kinematics of the 3-RPR planar parallel manipulator (thesis Section 5.3).

Platform of length ``2r`` with mid-point ``u = (x_P, y_P)`` and orientation ``w = phi_P``;
platform joints ``A = u - r e(w)`` and ``B = u + r e(w)``, ``e(w) = (cos w, sin w)``.
Leg 1 joins base point C to A, leg 2 joins D to A, leg 3 joins E to B (eq. 5.7), with
``y_C = y_D = y_E``.  Everything is vectorized over poses: ``U`` has shape ``(k, 2)`` and
``w`` is a scalar or shape ``(k,)``.
"""

from __future__ import annotations

import numpy as np

from ._checks import planar_poses

__all__ = ["leg_vectors", "leg_lengths", "jacobian", "inverse_condition", "LEG_SIGN"]

#: Which platform end a leg attaches to: -1 for A = u - r e(w) (legs 1, 2), +1 for B (leg 3).
LEG_SIGN = np.array([-1.0, -1.0, 1.0])


def leg_vectors(base: np.ndarray, r: float, U, w) -> np.ndarray:
    """Leg vectors from the base joints to the platform joints, shape ``(k, 3, 2)`` (eq. 5.7)."""
    U, w = planar_poses(U, w)
    e = np.stack([np.cos(w), np.sin(w)], axis=1)  # (k, 2)
    platform = U[:, None, :] + (LEG_SIGN[None, :, None] * r) * e[:, None, :]
    return platform - base[None, :, :]


def leg_lengths(base: np.ndarray, r: float, U, w) -> np.ndarray:
    """Inverse kinematics ``v(u, w)``: the three leg lengths, shape ``(k, 3)`` (eq. 5.7)."""
    L = leg_vectors(base, r, U, w)
    return np.sqrt(np.einsum("kij,kij->ki", L, L))


def jacobian(base: np.ndarray, r: float, U, w) -> np.ndarray:
    """Normalized Jacobian ``J`` of eq. (5.13), shape ``(k, 3, 3)``.

    Row i is ``[x_i/(r v_i), y_i/(r v_i), -s_i r (x_i sin w - y_i cos w)/v_i]`` with
    ``(x_i, y_i)`` the leg vector (``x_AC``, ``y_AC`` ... of eq. 5.12) and ``s_i`` the
    platform end.  Taken literally as printed (positional columns divided by ``r v_i``,
    rotational column by ``v_i``), which reproduces Table 5.3's f(d0)
    (problems/reference/ERRATA.md).  ``J @ [r u1', r u2', w'] = v'``.
    """
    U, w = planar_poses(U, w)
    L = leg_vectors(base, r, U, w)
    v = np.sqrt(np.einsum("kij,kij->ki", L, L))
    x, y = L[..., 0], L[..., 1]
    s, c = np.sin(w)[:, None], np.cos(w)[:, None]
    rot = -LEG_SIGN[None, :] * r * (x * s - y * c)
    with np.errstate(divide="ignore", invalid="ignore"):
        J = np.stack([x / (r * v), y / (r * v), rot / v], axis=2)
    return J


def inverse_condition(J: np.ndarray) -> np.ndarray:
    """``kappa^-1`` of square Jacobians ``(k, n, n)`` by eqs. (4.19)-(4.20), ``W = I/n``.

    ``kappa = ||J|| ||J^-1||`` with ``||J|| = sqrt(tr(J W J^T)) = ||J||_F / sqrt(n)``, so
    ``kappa^-1 = n / (||J||_F ||J^-1||_F)``.  For n = 3, ``J^-1 = adj(J)/det J`` with the
    adjugate's columns the cross products of J's rows, so
    ``kappa^-1 = 3 |det J| / (||J||_F ||adj J||_F)``: exactly 0 at a singularity, no
    inversion needed.
    """
    J = np.asarray(J, dtype=float)
    if J.ndim != 3 or J.shape[1:] != (3, 3):
        raise ValueError(f"inverse_condition expects (k, 3, 3) Jacobians, got {J.shape}")
    a, b, c = J[:, 0, :], J[:, 1, :], J[:, 2, :]
    bc, ca, ab = np.cross(b, c), np.cross(c, a), np.cross(a, b)
    det = np.einsum("ij,ij->i", a, bc)
    nj = np.sqrt(np.einsum("kij,kij->k", J, J))
    nadj = np.sqrt(np.einsum("ij,ij->i", bc, bc) + np.einsum("ij,ij->i", ca, ca) + np.einsum("ij,ij->i", ab, ab))
    with np.errstate(divide="ignore", invalid="ignore"):
        out = 3.0 * np.abs(det) / (nj * nadj)
    return np.where(np.isfinite(out), out, 0.0)
