"""The solver registry: kebab-case ids -> solver classes, loaded lazily.

Built-in solvers are listed in `_catalog.py` as ``"module:Class"`` so that importing
`solvers` does not import CasADi, NLopt or cvxpy. Users add their own with `register`;
a name collision is an error (Nevergrad's registry rule).
"""

from __future__ import annotations

import ast
import re
from typing import Any

from problems._registry import Registry, UnknownName

from ._base import AbstractSolver
from ._catalog import BUILTIN

__all__ = ["register", "unregister", "get_solver_class", "solver_names", "make_solver", "parse_spec", "UnknownSolver"]

class UnknownSolver(UnknownName):
    """An unknown solver id; the message lists the valid ones."""


def _check(name: str, cls: Any) -> None:
    if not (isinstance(cls, type) and issubclass(cls, AbstractSolver)):
        raise TypeError("register() needs a subclass of solvers.AbstractSolver")
    if getattr(cls, "name", None) != name:
        raise ValueError(f"solver class {cls.__name__} has name {getattr(cls, 'name', None)!r}, registered as {name!r}")


#: the solver registry (`problems._registry.Registry`, shared with the suites')
REGISTRY: Registry[type[AbstractSolver]] = Registry("solver", BUILTIN, _check, UnknownSolver)


def solver_names() -> list[str]:
    """All registered solver ids, built-in first."""
    return REGISTRY.names()


def register(cls: type[AbstractSolver]) -> type[AbstractSolver]:
    """Register a solver class under its ``name`` (usable as a decorator). Collisions raise ValueError."""
    if not (isinstance(cls, type) and issubclass(cls, AbstractSolver)):
        raise TypeError("register() needs a subclass of solvers.AbstractSolver")
    return REGISTRY.register(getattr(cls, "name", None), cls)  # type: ignore[arg-type]  # checked there


def unregister(name: str) -> None:
    """Remove a user-registered solver (built-ins cannot be removed)."""
    REGISTRY.unregister(name)


def get_solver_class(name: str) -> type[AbstractSolver]:
    return REGISTRY.get(name)


SPEC_SYNTAX = "name[key=value,...]"
#: spec values that ast.literal_eval does not read but that name a float (inf: "no limit" in several options)
_FLOAT_WORDS = frozenset({"inf", "+inf", "-inf", "nan"})


def parse_spec(spec: str) -> tuple[str, dict[str, Any]]:
    """``"lfopc[delta_t=0.5,mu1=1e4]"`` -> ("lfopc", {...}) (benchopt's syntax).

    Values are Python literals (``ast.literal_eval``); ``inf``, ``-inf`` and ``nan`` are floats;
    anything else is kept as a string. An option given twice is an error.
    """
    m = re.fullmatch(r"\s*([^\[\]\s]+)\s*(?:\[(.*)\])?\s*", spec)
    if not m:
        raise ValueError(f"cannot parse solver specification {spec!r}; expected {SPEC_SYNTAX}")
    name, params = m.group(1), m.group(2)
    opts: dict[str, Any] = {}
    if params:
        for item in params.split(","):
            if "=" not in item:
                raise ValueError(f"solver parameter {item!r} in {spec!r} is not key=value; expected {SPEC_SYNTAX}")
            k, v = (s.strip() for s in item.split("=", 1))
            if not k:
                raise ValueError(f"solver parameter {item!r} in {spec!r} has an empty option name; "
                                 f"expected {SPEC_SYNTAX}")
            if k in opts:
                raise ValueError(f"option {k} given more than once in solver specification {spec!r}")
            if v in _FLOAT_WORDS:
                opts[k] = float(v)
                continue
            try:
                opts[k] = ast.literal_eval(v)
            except (ValueError, SyntaxError):
                opts[k] = v
    return name, opts


def make_solver(spec: str | AbstractSolver, **options: Any) -> AbstractSolver:
    """A configured solver instance from a name (optionally ``name[k=v]``) and options.

    Unknown option names raise ValueError listing the valid ones; so does an option given
    both in the specification and as a keyword.
    """
    if isinstance(spec, AbstractSolver):
        if options:
            import dataclasses

            type(spec).check_option_names(options)
            return dataclasses.replace(spec, **options)  # type: ignore[type-var]  # a dataclass instance
        return spec
    name, spec_opts = parse_spec(spec)
    cls = get_solver_class(name)
    twice = sorted(set(spec_opts) & set(options))
    if twice:
        raise ValueError(f"option(s) {', '.join(twice)} given more than once: in the solver specification "
                         f"{spec!r} and as keyword(s)")
    opts = {**spec_opts, **options}
    cls.check_option_names(opts)
    return cls(**opts)
