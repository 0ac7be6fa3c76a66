"""The wall-clock deadline of the current run, when the harness has set one.

The harness kills a run that overstays its time limit, and a killed run keeps nothing: no
point, no history.  A solver that can stop early with a useful answer (`Multistart`,
between its local runs) reads the deadline here and stops in time.  The harness's worker
sets it before each run (`set_run_deadline`); outside a harness run there is none, and
`solvers.solve` never sets one.
"""

from __future__ import annotations

import math
import os
import time

__all__ = ["DEADLINE_ENV", "run_deadline", "set_run_deadline"]

#: environment variable holding the run's deadline in seconds since the epoch (`time.time`)
DEADLINE_ENV = "HAYBENCH_RUN_DEADLINE"


def run_deadline() -> float | None:
    """The current run's deadline on the `time.time` clock, or None if no limit is set."""
    try:
        d = float(os.environ.get(DEADLINE_ENV, ""))
    except ValueError:
        return None
    return d if math.isfinite(d) else None


def set_run_deadline(seconds: float | None) -> None:
    """Set the deadline ``seconds`` from now for this process and its children (None, 0 or inf: none)."""
    if seconds is None or not (0 < seconds < math.inf):
        os.environ.pop(DEADLINE_ENV, None)
    else:
        os.environ[DEADLINE_ENV] = repr(time.time() + float(seconds))
