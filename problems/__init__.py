"""Optimization problems: the `Problem` type, the counting `Oracle`, and the suites.

>>> from problems import Problem, get_suite
>>> p = Problem(name="quad", x0=[3, 3], objective=lambda x: x @ x, gradient=lambda x: 2 * x)
"""

from ._catalog import UnknownSuite as UnknownSuite
from ._catalog import get_suite as get_suite
from ._catalog import register_suite as register_suite
from ._catalog import suite_names as suite_names
from ._catalog import unregister_suite as unregister_suite
from ._finite_differences import fd_gradient as fd_gradient
from ._finite_differences import fd_jacobian as fd_jacobian
from ._oracle import BudgetExhausted as BudgetExhausted
from ._oracle import Oracle as Oracle
from ._problem import Problem as Problem
from ._problem import ProblemError as ProblemError
from ._suite import Case as Case
from ._suite import Suite as Suite
