"""One registry type for solvers and suites (problems/_registry.py); suites declare their plug-ins."""

from __future__ import annotations

import importlib

import numpy as np
import pytest

import solvers
from problems import Case, Problem, Suite, UnknownSuite, get_suite, register_suite, suite_names, unregister_suite
from problems._catalog import REGISTRY as SUITES
from solvers._registry import REGISTRY as SOLVERS


def _suite(name: str) -> Suite:
    p = Problem(name="q", x0=[1.0, 2.0], objective=lambda x: float(x @ x), gradient=lambda x: 2 * x)
    return Suite(name=name, description="test", build=lambda: [Case(p, "q")], solvers=("scipy-bfgs",))


def test_solvers_and_suites_share_one_registry_type():
    assert type(SUITES) is type(SOLVERS)
    assert SUITES.kind == "suite" and SOLVERS.kind == "solver"


def test_register_a_suite_then_refuse_collisions():
    s = _suite("my-suite")
    register_suite(s)
    try:
        assert get_suite("my-suite") is s and "my-suite" in suite_names()
        with pytest.raises(ValueError, match="already registered"):
            register_suite(_suite("my-suite"))
        with pytest.raises(ValueError, match="already registered"):
            register_suite(_suite("hs"))  # a built-in name
    finally:
        unregister_suite("my-suite")
    with pytest.raises(UnknownSuite, match="valid suites: appendix-a, hs"):
        get_suite("my-suite")


def test_bad_suite_registrations_are_refused():
    with pytest.raises(TypeError, match="expected a problems.Suite"):
        SUITES.register("not-a-suite", object())  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="kebab-case"):
        register_suite(_suite("Bad Name"))


def test_solver_collision_with_a_builtin_is_refused():
    import dataclasses

    @dataclasses.dataclass(frozen=True)
    class FakeSQSD(solvers.AbstractSolver):
        name = "sqsd"
        summary = "a second sqsd"

        def minimize(self, oracle):
            raise NotImplementedError

    with pytest.raises(ValueError, match="already registered"):
        solvers.register(FakeSQSD)


@pytest.mark.parametrize("name", suite_names())
def test_every_builtin_suite_declares_loadable_plugins(name):
    suite = get_suite(name)
    assert suite.tables, f"suite {name} declares no table plug-in"
    assert callable(importlib.import_module(suite.tables).tables)
    if suite.figures:
        assert callable(importlib.import_module(suite.figures).figures)
    assert SUITES.module_of(name) and np.all([isinstance(s, str) for s in suite.solvers])


def test_a_missing_extra_is_named(monkeypatch):
    """Without NLopt installed, asking for an NLopt solver names the extra to install."""
    import sys

    from problems._registry import MissingExtra, Registry

    monkeypatch.setitem(sys.modules, "nlopt", None)  # as if not installed
    monkeypatch.delitem(sys.modules, "solvers.nlopt_adapters", raising=False)
    reg: Registry = Registry("solver", {"nlopt-mma": "solvers.nlopt_adapters:NloptMMA"})
    with pytest.raises(MissingExtra, match=r"solver 'nlopt-mma' needs the optional dependency 'nlopt': "
                                           r"pip install 'haybench\[nlopt\]'"):
        reg.get("nlopt-mma")


def test_dask_executor_without_dask_is_bad_input(monkeypatch):
    import sys

    from harness._dask import dask_map
    from harness._plan import HarnessArgumentError

    monkeypatch.setitem(sys.modules, "distributed", None)
    with pytest.raises(HarnessArgumentError, match=r"haybench\[dask\]"):
        list(dask_map([], "local:1"))
