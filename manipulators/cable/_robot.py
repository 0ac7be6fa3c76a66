"""`CableRobot`: the planar tendon-driven parallel manipulator of thesis Chapter 6."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from .._checks import is_number
from . import _geometry as geo
from ._distribution import METHODS, distribute
from ._pointwise import BACKENDS, solve_pointwise

__all__ = ["CableRobot"]


def _points(name: str, value: Any) -> np.ndarray:
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be an (n, 2) array of numbers, got {value!r}") from exc
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or inf: {arr.tolist()}")
    arr.setflags(write=False)
    return arr


@dataclasses.dataclass(frozen=True, eq=False)
class CableRobot:
    """A planar platform held by n >= 3 cables (thesis Section 6.2, Figs. 6.1-6.2).

    Parameters
    ----------
    frame_points : array_like, shape (n, 2)
        Frame (winch) attachment points c^i in the global frame (Table 6.2).
    platform_points : array_like, shape (n, 2)
        Platform attachment points abar^i in the platform frame (Table 6.1).
    t_min, t_max : float
        Tension limits (6.21); Table 6.4: 5 and 100. Need 0 <= t_min < t_max.
    l_min : float
        Minimum cable length (6.22); Table 6.4: 0.1.
    det_min : float or None
        Singularity limit |det J| >= D_min (6.24, absolute value per ERRATA); Table 6.4
        uses 1e-3 for the 3-cable robot. Only meaningful for n = 3 (J square); None = off.
    """

    frame_points: np.ndarray
    platform_points: np.ndarray
    t_min: float = 5.0
    t_max: float = 100.0
    l_min: float = 0.1
    det_min: float | None = None

    def __post_init__(self) -> None:
        set_ = lambda k, v: object.__setattr__(self, k, v)  # the dataclass is frozen
        c = _points("frame_points", self.frame_points)
        a = _points("platform_points", self.platform_points)
        if c.shape != a.shape:
            raise ValueError(f"frame_points {c.shape} and platform_points {a.shape} must have the same shape (n, 2)")
        if c.shape[0] < 3:
            raise ValueError(f"a planar cable robot needs n >= 3 cables, got n = {c.shape[0]}")
        set_("frame_points", c)
        set_("platform_points", a)
        for name in ("t_min", "t_max", "l_min"):
            v = float(getattr(self, name))
            if not np.isfinite(v) or v < 0:
                raise ValueError(f"{name} must be a finite number >= 0, got {getattr(self, name)!r}")
            set_(name, v)
        if not self.t_min < self.t_max:
            raise ValueError(f"need t_min < t_max, got t_min = {self.t_min}, t_max = {self.t_max}")
        if self.det_min is not None:
            d = float(self.det_min)
            if not np.isfinite(d) or d < 0:
                raise ValueError(f"det_min must be None or a finite number >= 0, got {self.det_min!r}")
            if c.shape[0] != 3:
                raise ValueError(f"det_min (6.24) needs a square Jacobian, i.e. n = 3 cables; got n = {c.shape[0]}")
            set_("det_min", d)

    # ------------------------------------------------------------ constructors
    @classmethod
    def from_angles(cls, betas: Any, platform_points: Any, **limits: Any) -> CableRobot:
        """Frame points at polar angles beta^i on the 2 x 2 square frame (Section 6.6.1).

        The mapping c = (cos beta, sin beta) / max(|cos beta|, |sin beta|) is the ERRATA's.
        """
        b = np.asarray(betas, dtype=float)
        if b.ndim != 1:
            raise ValueError(f"betas must be a vector of n angles, got shape {b.shape}")
        return cls(geo.frame_point(b), platform_points, **limits)

    # ------------------------------------------------------------ structure
    @property
    def n(self) -> int:
        """Number of cables."""
        return int(self.frame_points.shape[0])

    def kinematics(self, u: Any, phi: Any) -> dict[str, np.ndarray]:
        """Kinematics of k poses: cable vectors (6.2), a^i (6.3), lengths (6.4), S (6.11).

        Returns a dict with ``ell`` (k, n, 2), ``a`` (k, n, 2), ``lengths`` (k, n),
        ``S`` (k, 3, n) and, for n = 3, ``det`` (k,) = det J = det S.
        """
        U, P = geo.as_poses(u, phi)
        ell, a = geo.cable_vectors(self.frame_points, self.platform_points, U, P)
        lengths = geo.cable_lengths(ell)
        S = geo.structure_matrix(ell, a, lengths)
        out = {"ell": ell, "a": a, "lengths": lengths, "S": S}
        if self.n == 3:
            out["det"] = geo.det3(S)
        return out

    def lengths(self, u: Any, phi: Any) -> np.ndarray:
        """Cable lengths l_i (6.4) of k poses, shape (k, n)."""
        return self.kinematics(u, phi)["lengths"]

    def structure_matrix(self, u: Any, phi: Any) -> np.ndarray:
        """Structure matrix S (6.11) of k poses, shape (k, 3, n)."""
        return self.kinematics(u, phi)["S"]

    def jacobian(self, u: Any, phi: Any) -> np.ndarray:
        """Jacobian J (6.7) of k poses, shape (k, n, 3); J = S^T."""
        return np.swapaxes(self.structure_matrix(u, phi), 1, 2)

    # ------------------------------------------------------------ tensions
    def _wrench(self, wrench: Any, k: int) -> np.ndarray:
        w = np.asarray(wrench, dtype=float)
        if w.shape not in ((3,), (k, 3)):
            raise ValueError(f"wrench must be [f_x, f_y, tau] (shape (3,) or ({k}, 3)), got shape {w.shape}")
        if not np.all(np.isfinite(w)):
            raise ValueError(f"wrench contains NaN or inf: {w}")
        return np.broadcast_to(w, (k, 3))

    def geometric_ok(self, kin: dict[str, np.ndarray]) -> np.ndarray:
        """Length limit (6.22) and, if set, the singularity limit |det J| >= D_min (6.24)."""
        ok = np.all(kin["lengths"] >= self.l_min, axis=1)
        if self.det_min is not None:
            ok &= np.abs(kin["det"]) >= self.det_min
        return ok

    def tensions_batch(self, u: Any, phi: Any, wrench: Any, method: str = "l1", *,
                       backend: str = "exact", tol: float = 1e-10) -> tuple[np.ndarray, np.ndarray]:
        """Tensions at k poses: (feasible (k,), T (k, n) with NaN rows where infeasible).

        Feasible means tensions within [t_min, t_max] exist (for ``min-norm``: the
        minimum-norm tensions are within), the cables are at least l_min long and, for
        n = 3 with det_min set, |det J| >= det_min.

        Parameters
        ----------
        method : one of ``"min-norm"`` (6.14), ``"l2"`` (6.17), ``"l1"`` (6.19),
            ``"l2-max"``, ``"l1-max"`` (maximum-norm, stiffest tensions).
        backend : ``"exact"`` (closed form, vectorized: n = 3 unique solution, n = 4
            Algorithm 6.1, any n basic-solution enumeration; l2 exact for n <= 4) or a
            per-pose solver: ``"lfopc"`` (in-house, as in the thesis; l2), ``"osqp"``,
            ``"clarabel"`` (cvxpy; l2 and l1), ``"highs"`` (cvxpy; l1), ``"linprog"``
            (scipy.optimize.linprog HiGHS; l1).
        """
        if method not in METHODS:
            raise ValueError(f"unknown tension method {method!r}; valid: {', '.join(METHODS)}")
        if not (is_number(tol) and math.isfinite(tol) and tol >= 0):
            # tol widens the limits [t_min - tol, t_max + tol] the exact enumeration accepts: a
            # negative one shifted every tension, a NaN one made every pose infeasible
            raise ValueError(f"tol must be a finite number >= 0 (the tolerance on the tension limits), got {tol!r}")
        kin = self.kinematics(u, phi)
        k = kin["S"].shape[0]
        w = self._wrench(wrench, k)
        geo_ok = self.geometric_ok(kin)
        if backend == "exact":
            feas, T = distribute(kin["S"], w, self.t_min, self.t_max, method, tol)
        elif backend in BACKENDS:
            feas, T = solve_pointwise(kin["S"], w, self.t_min, self.t_max, method, backend)
        else:
            raise ValueError(f"unknown tension backend {backend!r}; valid: exact, {', '.join(BACKENDS)}")
        feas = feas & geo_ok
        return feas, np.where(feas[:, None], np.asarray(T, dtype=float), np.nan)

    def tensions(self, u: Any, phi: float, wrench: Any, method: str = "l1", *,
                 backend: str = "exact", tol: float = 1e-10) -> np.ndarray | None:
        """Cable tensions t (n,) at one pose, or None when no feasible tensions exist.

        See `tensions_batch` for ``method`` and ``backend``. Example: the l2 tensions of
        (6.17) with the in-house LfopC as in the thesis: ``method="l2", backend="lfopc"``.
        """
        u = np.asarray(u, dtype=float)
        if u.shape != (2,):
            raise ValueError(f"tensions() takes one position u of shape (2,), got {u.shape}; use tensions_batch")
        if np.ndim(phi) != 0:
            raise ValueError("tensions() takes one orientation phi (a number); use tensions_batch")
        feas, T = self.tensions_batch(u, phi, wrench, method, backend=backend, tol=tol)
        return T[0].copy() if feas[0] else None

    # ------------------------------------------------------------ workspaces
    def workspace(self, phi: float, wrench: Any, method: str = "grid", resolution: int = 50,
                  tensions: str = "l1", **kwargs: Any):
        """Constant-orientation workspace W^C[phi] (6.23); see `manipulators.cable.workspace`."""
        from ._workspace import constant_orientation_workspace

        return constant_orientation_workspace(self, phi, wrench, method=method, resolution=resolution,
                                              tensions=tensions, **kwargs)

    def dextrous_workspace(self, phi_min: float, phi_max: float, wrench: Any, resolution: int = 50,
                           slices: int = 21, tensions: str = "l1", **kwargs: Any):
        """Dextrous workspace W^D[phi_min, phi_max] (6.28) as the intersection of slices (Section 6.5)."""
        from ._workspace import dextrous_workspace

        return dextrous_workspace(self, phi_min, phi_max, wrench, resolution=resolution, slices=slices,
                                  tensions=tensions, **kwargs)

    def __repr__(self) -> str:
        return (f"CableRobot(n={self.n}, t_min={self.t_min:g}, t_max={self.t_max:g}, "
                f"l_min={self.l_min:g}, det_min={self.det_min})")
