"""One interface over the thesis's optimizers and the established ones.

>>> from solvers import solve
>>> result = solve(problem, "sqsd", rho=0.3)

Solvers: ``solver_names()``; their options: ``get_solver_class(name).options()`` or
``python -m harness list solvers``.
"""

from ._base import AbstractSolver as AbstractSolver
from ._base import NotApplicable as NotApplicable
from ._base import option as option
from ._registry import UnknownSolver as UnknownSolver
from ._registry import get_solver_class as get_solver_class
from ._registry import make_solver as make_solver
from ._registry import parse_spec as parse_spec
from ._registry import register as register
from ._registry import solver_names as solver_names
from ._registry import unregister as unregister
from ._result import Result as Result
from ._result import SolverOutput as SolverOutput
from ._result import Status as Status
from ._solve import solve as solve
