"""The benchmark harness: run suites, store results, render tables, plots and reports.

>>> import harness
>>> summary = harness.run_suite("appendix-a", solvers=["sqsd"], out="results")
>>> runs = harness.load_results("appendix-a")
>>> tables, paths = harness.render_tables("appendix-a")

Command line: ``python -m harness --help``.
"""

from ._api import NoResults as NoResults
from ._api import load_results as load_results
from ._api import render_tables as render_tables
from ._plan import HarnessArgumentError as HarnessArgumentError
from ._runner import RunSummary as RunSummary
from ._runner import run_suite as run_suite
