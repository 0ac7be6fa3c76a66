"""Table renders never start an optimization (docs/harness.md, "Stored references").

Every committed suite's tables are rendered from its stored runs and stored reference with
every optimizer patched to raise: the counting Oracle (the front door of every solver in
`solvers`), `solvers.solve`, SciPy's differential evolution and linprog, and SciPy's
minimize with any method but Nelder-Mead.  Allowed: the workspace computations of Table 5.2
(Algorithm 5.1's own steps, eqs. 5.27-5.29: a least-squares assembly point and a
Nelder-Mead point of greatest dexterity), which are part of the thesis's method of drawing
a workspace, not an optimization of a design.
"""

from __future__ import annotations

import pathlib

import pytest

import problems
import solvers
from harness._api import load_results
from harness._reference import load_reference
from harness.tables import build_tables
from problems import hs

RESULTS = pathlib.Path(__file__).resolve().parents[2] / "results"
SUITES = sorted(p.parent.name for p in RESULTS.glob("*/runs.parquet"))


class OptimizationInTable(AssertionError):
    pass


def _forbid(name):
    def raiser(*args, **kwargs):
        raise OptimizationInTable(f"{name} called while rendering a table")

    return raiser


@pytest.fixture
def no_optimizers(monkeypatch):
    import scipy.optimize

    monkeypatch.setattr(problems.Oracle, "__init__", _forbid("problems.Oracle"))
    monkeypatch.setattr(solvers, "solve", _forbid("solvers.solve"))
    for fn in ("differential_evolution", "linprog", "shgo", "dual_annealing"):
        monkeypatch.setattr(scipy.optimize, fn, _forbid(f"scipy.optimize.{fn}"))
    minimize = scipy.optimize.minimize

    def guarded_minimize(fun, x0, *args, method=None, **kwargs):
        if method != "Nelder-Mead":  # Algorithm 5.1's dexterity point (5.29) is the only allowed use
            raise OptimizationInTable(f"scipy.optimize.minimize(method={method!r}) called while rendering a table")
        return minimize(fun, x0, *args, method=method, **kwargs)

    monkeypatch.setattr(scipy.optimize, "minimize", guarded_minimize)


def test_the_patch_catches_an_optimization(no_optimizers):
    """The guard itself: a solver run and a SciPy minimize both raise under it."""
    import scipy.optimize

    with pytest.raises(OptimizationInTable):
        scipy.optimize.minimize(lambda x: x @ x, [1.0])
    with pytest.raises(OptimizationInTable):
        solvers.solve(hs.problem("10"), "scipy-slsqp")


SLOW_TABLES = ("rpr3", "rpr3-spread")  # exact enclosures of every design (D: 201 slices), ~20 s each


@pytest.mark.parametrize("suite", [s for s in SUITES if s not in SLOW_TABLES])
def test_tables_render_without_optimizing(suite, no_optimizers):
    runs = load_results(suite, RESULTS)
    tables = build_tables(suite, runs, reference=load_reference(RESULTS, suite))
    assert tables and all(len(t.frame) for t in tables)


@pytest.mark.slow
@pytest.mark.parametrize("suite", SLOW_TABLES)
def test_rpr3_tables_render_without_optimizing(suite, no_optimizers):
    """rpr3's and rpr3-spread's tables take ~20 s (exact enclosures of every design on 201
    slices): slow marker."""
    runs = load_results(suite, RESULTS)
    tables = build_tables(suite, runs, reference=load_reference(RESULTS, suite))
    assert tables and all(len(t.frame) for t in tables)
