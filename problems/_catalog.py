"""Suite catalogue: suite name -> module defining ``SUITE`` (imported on demand)."""

from __future__ import annotations

import importlib

from ._suite import Suite

__all__ = ["SUITES", "get_suite", "suite_names", "UnknownSuite"]

SUITES: dict[str, str] = {
    "appendix-a": "problems.appendix_a",
    "hs": "problems.hs",
    "rpr2": "manipulators.synthesis.rpr2_suite",
    "rpr2-spread": "manipulators.synthesis.rpr2_spread_suite",
    "rpr3": "manipulators.synthesis.rpr3_suite",
    "tdpm": "manipulators.synthesis.tdpm_suite",
    "hs-all": "problems.s2mpj.hs_all_suite",
    "cutest": "problems.s2mpj.cutest_suite",
}


class UnknownSuite(KeyError):
    def __str__(self) -> str:
        return str(self.args[0])


def suite_names() -> list[str]:
    return list(SUITES)


def get_suite(name: str) -> Suite:
    if name not in SUITES:
        raise UnknownSuite(f"unknown suite {name!r}; valid suites: {', '.join(SUITES)}")
    suite = importlib.import_module(SUITES[name]).SUITE
    if suite.name != name:
        raise RuntimeError(f"module {SUITES[name]} defines suite {suite.name!r}, expected {name!r}")
    return suite
