"""The thesis's run settings for the Appendix A suite (Section 2.5, Tables 2.1-2.2).

Sources (vendored in problems/reference/thesis_tables/run_settings.csv):

* eps_g = 1e-5, eps_x = 1e-8 for every run, except eps_g = 1e-75 ("~ 0") and
  eps_x = 1e-12 for problem 12 at n = 50000 and all problems 14 (Section 2.5, l. 806).
* SQSD step limit rho: Table 2.1's rho column - 1 by default, 0.3 for problems 4 and 9,
  10 for problem 8, 2 for problem 11, 1e4 for problems 12 (1e10 at n = 50000),
  sqrt(n)/10 for problems 13 (text l. 896; the table prints it rounded: 0.3, 1, 1.73,
  2.45, 3.16), and problems 14 at both rho = 1 and rho = 10 (l. 898).
* Caps: the "> N" entries of Tables 2.1-2.2 give the N^fg after which SD/FR/PR were
  stopped on that row (20000 unless the row shows otherwise). We cap every
  non-SQSD solver of that row at the same N^fg.
"""

from __future__ import annotations

import math

__all__ = ["DIMENSIONS", "EXTREME_TOL", "STANDARD_TOL", "cap_for", "rho_for", "tolerances_for", "thesis_label"]

STANDARD_TOL = {"eps_g": 1e-5, "eps_x": 1e-8}
EXTREME_TOL = {"eps_g": 1e-75, "eps_x": 1e-12}

#: dimensions run in the thesis for the scalable problems
DIMENSIONS = {
    "a12": (20, 200, 2000, 20000, 50000),
    "a13": (10, 100, 300, 600, 1000),
    "a14": (20, 40, 60, 100, 200),
}

_RHO = {"a04": 0.3, "a08": 10.0, "a09": 0.3, "a11": 2.0}

# "> N" caps printed in Tables 2.1-2.2 (largest N on the row), keyed by (problem, n)
_CAPS = {
    ("a12", 20000): 10_000, ("a12", 50000): 10_000,
    ("a13", 1000): 30_000,
    ("a14", 40): 30_000, ("a14", 60): 30_000, ("a14", 100): 50_000, ("a14", 200): 100_000,
}
DEFAULT_CAP = 20_000


def tolerances_for(problem_id: str, n: int) -> dict[str, float]:
    """eps_g, eps_x of Section 2.5 for this row."""
    if problem_id == "a14" or (problem_id == "a12" and n == 50000):
        return dict(EXTREME_TOL)
    return dict(STANDARD_TOL)


def rho_for(problem_id: str, n: int) -> float:
    """SQSD step limit of Table 2.1 (the rho = 1 run for problems 14)."""
    if problem_id == "a12":
        return 1e10 if n == 50000 else 1e4
    if problem_id == "a13":
        return math.sqrt(n) / 10.0
    return _RHO.get(problem_id, 1.0)


def cap_for(problem_id: str, n: int) -> int:
    """N^fg cap of the comparison solvers on this row."""
    return _CAPS.get((problem_id, n), DEFAULT_CAP)


def thesis_label(problem_id: str) -> str:
    """The table's problem label: a05a -> '5(a)', a12 -> '12'."""
    num = problem_id[1:3].lstrip("0")
    return f"{num}({problem_id[3:]})" if len(problem_id) > 3 else num
