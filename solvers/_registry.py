"""The solver registry: kebab-case ids -> solver classes, loaded lazily.

Built-in solvers are listed in `_catalog.py` as ``"module:Class"`` so that importing
`solvers` does not import CasADi, NLopt or cvxpy. Users add their own with `register`;
a name collision is an error (Nevergrad's registry rule).
"""

from __future__ import annotations

import ast
import importlib
import re
from typing import Any

from ._base import AbstractSolver
from ._catalog import BUILTIN

__all__ = ["register", "unregister", "get_solver_class", "solver_names", "make_solver", "parse_spec", "UnknownSolver"]

_USER: dict[str, type[AbstractSolver]] = {}
_LOADED: dict[str, type[AbstractSolver]] = {}


class UnknownSolver(KeyError):
    def __str__(self) -> str:  # KeyError quotes its message; we want plain text
        return str(self.args[0])


def solver_names() -> list[str]:
    """All registered solver ids, built-in first."""
    return list(BUILTIN) + [k for k in _USER if k not in BUILTIN]


def register(cls: type[AbstractSolver]) -> type[AbstractSolver]:
    """Register a solver class (usable as a decorator). Collisions raise ValueError."""
    if not (isinstance(cls, type) and issubclass(cls, AbstractSolver)):
        raise TypeError("register() needs a subclass of solvers.AbstractSolver")
    name = getattr(cls, "name", None)
    if not isinstance(name, str) or not re.fullmatch(r"[a-z0-9][a-z0-9\-]*", name):
        raise ValueError(f"solver name must be kebab-case, got {name!r}")
    if name in BUILTIN or name in _USER:
        raise ValueError(f"a solver named {name!r} is already registered")
    _USER[name] = cls
    return cls


def unregister(name: str) -> None:
    """Remove a user-registered solver (built-ins cannot be removed)."""
    _USER.pop(name, None)


def get_solver_class(name: str) -> type[AbstractSolver]:
    if name in _USER:
        return _USER[name]
    if name in _LOADED:
        return _LOADED[name]
    if name not in BUILTIN:
        raise UnknownSolver(f"unknown solver {name!r}; valid solvers: {', '.join(solver_names())}")
    module, _, clsname = BUILTIN[name].partition(":")
    cls = getattr(importlib.import_module(module), clsname)
    _LOADED[name] = cls
    return cls


def parse_spec(spec: str) -> tuple[str, dict[str, Any]]:
    """``"lfopc[delta_t=0.5,mu1=1e4]"`` -> ("lfopc", {...}) (benchopt's syntax)."""
    m = re.fullmatch(r"\s*([^\[\]\s]+)\s*(?:\[(.*)\])?\s*", spec)
    if not m:
        raise ValueError(f"cannot parse solver specification {spec!r}")
    name, params = m.group(1), m.group(2)
    opts: dict[str, Any] = {}
    if params:
        for item in params.split(","):
            if "=" not in item:
                raise ValueError(f"solver parameter {item!r} in {spec!r} is not key=value")
            k, v = (s.strip() for s in item.split("=", 1))
            try:
                opts[k] = ast.literal_eval(v)
            except (ValueError, SyntaxError):
                opts[k] = v
    return name, opts


def make_solver(spec: str | AbstractSolver, **options: Any) -> AbstractSolver:
    """A configured solver instance from a name (optionally ``name[k=v]``) and options.

    Unknown option names raise ValueError listing the valid ones.
    """
    if isinstance(spec, AbstractSolver):
        if options:
            import dataclasses

            type(spec).check_option_names(options)
            return dataclasses.replace(spec, **options)  # type: ignore[type-var]
        return spec
    name, spec_opts = parse_spec(spec)
    cls = get_solver_class(name)
    opts = {**spec_opts, **options}
    cls.check_option_names(opts)
    return cls(**opts)
