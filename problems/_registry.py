"""One registry type for everything looked up by name: solvers and suites.

Built-in entries are ``"module:attribute"`` strings imported on first use, so listing
names never imports CasADi, NLopt, cvxpy or a large problem library.  Users add their
own entries with `Registry.register`; a name that is already taken is refused, built-in
or not (Nevergrad's registry rule), so a plug-in can never silently replace another.
"""

from __future__ import annotations

import importlib
import re
from collections.abc import Callable, Mapping
from typing import Any, Generic, TypeVar

__all__ = ["Registry", "UnknownName", "MissingExtra", "OPTIONAL", "require"]

#: optional third-party modules -> the extra of ``pyproject.toml`` that installs them
OPTIONAL: dict[str, str] = {"nlopt": "nlopt", "cvxpy": "convex", "distributed": "dask", "dask": "dask"}


class MissingExtra(ImportError):
    """An optional dependency is not installed; the message names the extra to install."""


def _missing(exc: ModuleNotFoundError, what: str) -> MissingExtra | None:
    top = (exc.name or "").split(".")[0]
    if top not in OPTIONAL:
        return None
    extra = OPTIONAL[top]
    return MissingExtra(f"{what} needs the optional dependency {top!r}: pip install 'haybench[{extra}]' "
                        f"(in a clone: pip install -e '.[{extra}]'; '.[all]' installs every extra)")


def require(module: str, what: str) -> Any:
    """``importlib.import_module(module)``, or `MissingExtra` naming the extra that provides it."""
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        err = _missing(exc, what)
        if err is None:
            raise
        raise err from None

T = TypeVar("T")

NAME = re.compile(r"[a-z0-9][a-z0-9\-]*")


class UnknownName(KeyError):
    """A name that is not registered; the message lists the valid ones."""

    def __str__(self) -> str:  # KeyError quotes its message; we want plain text
        return str(self.args[0])


class Registry(Generic[T]):
    """Names (kebab-case) -> objects of one kind, built-in ones loaded lazily.

    ``kind`` names the entries in messages ("solver", "suite"); ``builtin`` maps names to
    ``"module:attribute"``; ``check`` validates an object before it is registered or
    after a built-in is loaded (raising TypeError/ValueError); ``error`` is the exception
    type raised for unknown names (a subclass of `UnknownName`).
    """

    def __init__(self, kind: str, builtin: Mapping[str, str], check: Callable[[str, Any], None] | None = None,
                 error: type[UnknownName] = UnknownName):
        self.kind = kind
        self._builtin = dict(builtin)
        self._user: dict[str, T] = {}
        self._loaded: dict[str, T] = {}
        self._check = check
        self._error = error

    def names(self) -> list[str]:
        """Every registered name, built-in first, in registration order."""
        return list(self._builtin) + [k for k in self._user if k not in self._builtin]

    def __contains__(self, name: object) -> bool:
        return name in self._builtin or name in self._user

    def is_builtin(self, name: str) -> bool:
        return name in self._builtin

    def module_of(self, name: str) -> str | None:
        """The module defining a built-in entry (None for user entries or unknown names)."""
        target = self._builtin.get(name)
        return target.partition(":")[0] if target else None

    def register(self, name: str, obj: T) -> T:
        """Add ``obj`` under ``name``; a name already taken (built-in or user) raises ValueError."""
        if not isinstance(name, str) or not NAME.fullmatch(name):
            raise ValueError(f"{self.kind} name must be kebab-case (lower-case letters, digits, '-'), got {name!r}")
        if name in self:
            raise ValueError(f"a {self.kind} named {name!r} is already registered")
        if self._check is not None:
            self._check(name, obj)
        self._user[name] = obj
        return obj

    def unregister(self, name: str) -> None:
        """Remove a user entry (built-ins cannot be removed; unknown names are ignored)."""
        self._user.pop(name, None)

    def get(self, name: str) -> T:
        """The object registered under ``name`` (a built-in is imported on first use)."""
        if name in self._user:
            return self._user[name]
        if name in self._loaded:
            return self._loaded[name]
        if name not in self._builtin:
            raise self._error(f"unknown {self.kind} {name!r}; valid {self.kind}s: {', '.join(self.names())}")
        module, _, attr = self._builtin[name].partition(":")
        obj = getattr(require(module, f"{self.kind} {name!r}"), attr)
        if self._check is not None:
            self._check(name, obj)
        self._loaded[name] = obj
        return obj
