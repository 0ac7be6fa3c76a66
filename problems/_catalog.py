"""The suite registry: suite name -> `Suite`, built-in suites imported on demand.

Built-in suites are ``"module:SUITE"`` entries of the shared registry type
(`problems._registry.Registry`, the solvers' too), so one broken suite module cannot
break another and listing names imports none.  Users add theirs with `register_suite`;
a name already taken is refused.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from ._registry import NAME, Registry, UnknownName
from ._suite import Suite

if TYPE_CHECKING:  # not imported at run time: the summaries stay out of every run's code version
    from ._case_summary import CaseSummary

__all__ = ["REGISTRY", "get_suite", "suite_names", "register_suite", "unregister_suite", "UnknownSuite",
           "check_suite_name", "is_suite_name", "SUMMARIES", "case_summaries"]

BUILTIN: dict[str, str] = {
    "appendix-a": "problems.appendix_a:SUITE",
    "hs": "problems.hs:SUITE",
    "rpr2": "manipulators.synthesis.rpr2_suite:SUITE",
    "rpr2-spread": "manipulators.synthesis.rpr2_spread_suite:SUITE",
    "rpr2-central": "manipulators.synthesis.rpr2_central_suite:SUITE",
    "rpr2-exact": "manipulators.synthesis.rpr2_exact_suite:SUITE",
    "rpr3-exact": "manipulators.synthesis.rpr3_exact_suite:SUITE",
    "rpr3": "manipulators.synthesis.rpr3_suite:SUITE",
    "rpr3-spread": "manipulators.synthesis.rpr3_spread_suite:SUITE",
    "tdpm": "manipulators.synthesis.tdpm_suite:SUITE",
    "hs-all": "problems.s2mpj.hs_all_suite:SUITE",
    "cutest": "problems.s2mpj.cutest_suite:SUITE",
    "spatial": "manipulators.synthesis.spatial_suite:SUITE",
}

#: built-in suites whose cases a listing reads from their library's catalogue instead of
#: building them: name -> "module:function", ``function(selection or None) -> list[CaseSummary]``
SUMMARIES: dict[str, str] = {
    "hs-all": "problems.s2mpj._summaries:hs_all",
    "cutest": "problems.s2mpj._summaries:cutest",
}


def case_summaries(name: str, selection: str | None = None) -> list[CaseSummary] | None:
    """The cases of built-in suite ``name`` (restricted by ``selection``) as
    `problems._case_summary.CaseSummary` rows, read without building any problem; None if the
    suite has no catalogue (list its cases instead).  A bad selection raises the suite's own
    error (`problems.s2mpj.SelectionError`, a ValueError).  Imported by name, like the suites,
    so that no run's code version includes the summaries."""
    target = SUMMARIES.get(name)
    if target is None:
        return None
    module, attr = target.split(":")
    return list(getattr(importlib.import_module(module), attr)(selection))


def is_suite_name(name: object) -> bool:
    """Whether ``name`` is a valid suite name (kebab-case, `problems._registry.NAME`)."""
    return isinstance(name, str) and NAME.fullmatch(name) is not None


def check_suite_name(name: str, where: str = "suite") -> str:
    """``name`` if it is a valid suite name (kebab-case, as `register_suite` requires), else
    ValueError.  A suite name is a directory of results and a prefix of the files written
    there, so this also keeps a suite file's ``NAME`` from pointing outside ``--out``."""
    if not is_suite_name(name):
        raise ValueError(f"suite name {name!r} ({where}) must be kebab-case (lower-case letters, digits, '-'): it "
                         "names a directory of results")
    return name


class UnknownSuite(UnknownName):
    """An unknown suite name; the message lists the valid ones."""


def _check(name: str, suite: Any) -> None:
    if not isinstance(suite, Suite):
        raise TypeError(f"suite {name!r}: expected a problems.Suite, got {type(suite).__name__}")
    if suite.name != name:
        raise ValueError(f"suite object named {suite.name!r} registered as {name!r}")


#: the suite registry
REGISTRY: Registry[Suite] = Registry("suite", BUILTIN, _check, UnknownSuite)


def suite_names() -> list[str]:
    return REGISTRY.names()


def get_suite(name: str) -> Suite:
    return REGISTRY.get(name)


def register_suite(suite: Suite) -> Suite:
    """Make ``suite`` available by its name to `get_suite` and ``python -m harness --suite``
    (in the process that registers it: a harness run imports the registering module with
    ``--solver-module``).  A name already taken, or one that is not kebab-case, raises ValueError."""
    return REGISTRY.register(suite.name, suite)


def unregister_suite(name: str) -> None:
    REGISTRY.unregister(name)
