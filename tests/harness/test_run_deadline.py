"""The harness tells each run its deadline (`solvers._deadline`), so a solver can stop in time."""

import json
import textwrap

import harness

SUITE = textwrap.dedent('''
    import dataclasses, time
    import numpy as np
    from problems import Problem
    from solvers import AbstractSolver, SolverOutput, Status, register, solver_names
    from solvers._deadline import run_deadline

    NAME = "deadlines"
    SOLVERS = ["read-deadline"]
    PROBLEMS = [Problem(name=f"p{i}", x0=np.zeros(2), objective=lambda x: float(x @ x), gradient=lambda x: 2 * x)
                for i in range(3)]

    @dataclasses.dataclass(frozen=True)
    class ReadDeadline(AbstractSolver):
        name = "read-deadline"
        summary = "reports the deadline it was given"

        def minimize(self, oracle):
            d = run_deadline()
            oracle.f(oracle.x0)
            return SolverOutput(oracle.x0, Status.CONVERGED, "done",
                                extra={"left": None if d is None else d - time.time()})

    if "read-deadline" not in solver_names():
        register(ReadDeadline)
''')


def test_each_run_gets_its_deadline(tmp_path):
    suite = tmp_path / "deadlines.py"
    suite.write_text(SUITE)
    harness.run_suite(suite_file=suite, out=tmp_path / "res", jobs=1, timeout=40.0, progress=None)
    rows = harness.load_results("deadlines", tmp_path / "res")
    left = [(e if isinstance(e, dict) else json.loads(e))["left"] for e in rows.extra]
    assert len(left) == 3 and all(30.0 < v <= 40.0 for v in left), left
    harness.run_suite(suite_file=suite, out=tmp_path / "res2", jobs=1, timeout=0.0, progress=None)
    rows = harness.load_results("deadlines", tmp_path / "res2")
    assert all((e if isinstance(e, dict) else json.loads(e))["left"] is None for e in rows.extra)
