"""pytest-benchmark benchmarks (run once as tests by default; time them with
``python -m pytest tests -k benchmark --benchmark-enable --benchmark-json=bench.json``)."""

import pathlib
import time

import numpy as np

import harness
from solvers import solve

INSTANT = str(pathlib.Path(__file__).with_name("instant_suite.py"))


def test_benchmark_harness_overhead_per_run(benchmark, tmp_path):
    """Harness overhead per run (local executor, one worker) for a problem solved instantly:
    planning, IPC to the worker, row building, the atomic per-run file, consolidation."""
    out = tmp_path / "res"

    def campaign():
        return harness.run_suite(suite_file=INSTANT, out=out, jobs=1, fresh=True, progress=None)

    t0 = time.perf_counter()
    summary = benchmark.pedantic(campaign, rounds=3, iterations=1)  # runs once when benchmarks are disabled
    elapsed = time.perf_counter() - t0
    assert summary.executed == 100
    runs = harness.load_results("instant", out)
    assert (runs.status == "converged").all() and (runs.nfg == 1).all()
    solver_time = float(runs.wall_time_s.sum())
    best = benchmark.stats.stats.min if benchmark.enabled and benchmark.stats else elapsed
    benchmark.extra_info["overhead_ms_per_run"] = 1e3 * (best - solver_time) / summary.executed
    print(f"harness overhead: {benchmark.extra_info['overhead_ms_per_run']:.2f} ms per run")


def _sqsd_problem():
    try:
        from problems import get_suite

        return get_suite("appendix-a").case("a12/n=50000/x0").problem
    except Exception:  # noqa: BLE001 - the suite is optional here: build problem 12 inline
        from problems import Problem

        n = 50000
        w = np.arange(1, n + 1, dtype=float)
        return Problem(name="a12-inline", x0=np.full(n, 3.0), objective=lambda x: float(w @ (x * x)),
                       gradient=lambda x: 2 * w * x, f_ref=0.0)


def test_benchmark_sqsd_iteration_n50000(benchmark):
    """Twenty SQSD iterations (Algorithm 2.2) at n = 50000 through the counting oracle."""
    p = _sqsd_problem()
    r = benchmark(lambda: solve(p, "sqsd", max_iter=20, eps_g=0.0, eps_x=0.0))
    assert r.nit == 20 and r.nfg == 21
