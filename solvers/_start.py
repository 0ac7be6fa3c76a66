"""What every established adapter does before it calls its library: the start point it hands
over, and the one problem shape it answers itself (one small module, so that the adapters that
share it do not import each other: a change to one adapter's module then leaves the other
adapters' stored runs current)."""

from __future__ import annotations

import numpy as np

from problems import Oracle

from ._result import SolverOutput, Status

__all__ = ["more_equalities_than_variables", "start_in_bounds"]


def start_in_bounds(oracle: Oracle) -> np.ndarray:
    """x0 projected onto the simple bounds.

    SciPy's SLSQP and NLopt clip x0 themselves, but SLSQP first evaluates the
    constraints at the *unclipped* x0 (to count them), which would cost one extra,
    meaningless N^fg; projecting first avoids it and treats every adapter alike.
    """
    return np.clip(oracle.x0, oracle.lower, oracle.upper)


def more_equalities_than_variables(oracle: Oracle, native: str, why: str,
                                   native_status: int | None = None) -> SolverOutput | None:
    """The failed run an SQP adapter records, without calling its library, when m_eq > n.

    An SQP method's equality-constrained step needs m_eq <= n; each library meets the
    case differently, and badly (SciPy's SLSQP corrupts the process's heap, trust-constr
    raises a bare "expected square matrix", NLopt's SLSQP an empty ``invalid_argument``;
    S2MPJ's HS25NE and LEWISPOL have it). ``native`` names the library's own verdict,
    ``why`` the reason for answering first. None when the problem is not over-determined.
    """
    if oracle.n_eq <= oracle.n:
        return None
    return SolverOutput(start_in_bounds(oracle), Status.FAILED,
                        f"{native}: more equality constraints than variables ({oracle.n_eq} > n = {oracle.n}; "
                        f"answered before calling the library: {why})",
                        extra={} if native_status is None else {"native_status": native_status})
