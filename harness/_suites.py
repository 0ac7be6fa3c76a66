"""Where a suite comes from: a catalogue name or a user's Python file.

Problems hold closures and cannot be pickled, so a run never ships a `Problem` to a
worker: it ships a `SuiteRef` (a name or a file path) and a case id, and the worker
rebuilds the case.  Loaded suites are cached per process.
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib
import importlib.util
import os
import pathlib
import re
import sys
import traceback
from collections.abc import Iterable
from types import ModuleType

from problems import Case, Problem, Suite, get_suite
from problems._catalog import check_suite_name

__all__ = ["SuiteRef", "load_suite", "suite_module", "SuiteFileError"]


class SuiteFileError(ImportError):
    """A user's suite file could not be imported (it raised): a bad-input error, in one line."""

_CACHE: dict[SuiteRef, Suite] = {}
_FILE_MODULES: dict[str, ModuleType] = {}


@dataclasses.dataclass(frozen=True)
class SuiteRef:
    """A picklable reference to a suite: ``name`` from the catalogue, or ``file``.

    ``file`` is an absolute path to a Python file defining ``SUITE`` (a
    `problems.Suite`) or ``PROBLEMS`` (a list of `problems.Problem`; optional
    ``NAME`` and ``SOLVERS`` give the suite name and default solvers).
    """

    name: str
    file: str | None = None

    def load(self) -> Suite:
        return load_suite(self)


def _file_module(path: str, what: str = "suite file") -> ModuleType:
    """Import a suite file (or a ``--solver-module`` file: ``what``) by path once per process
    (workers re-import it here)."""
    if path in _FILE_MODULES:
        return _FILE_MODULES[path]
    p = pathlib.Path(path)
    if p.is_dir():
        raise FileNotFoundError(f"{what} {path} is a directory, not a .py file")
    if not p.is_file():
        raise FileNotFoundError(f"{what} {path} does not exist")
    modname = "_harness_suitefile_" + hashlib.sha1(str(p).encode()).hexdigest()[:10]
    spec = importlib.util.spec_from_file_location(modname, p)
    if spec is None or spec.loader is None:
        raise ImportError(f"cannot import {what} {path}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[modname] = module  # dataclasses and pickling look modules up here
    try:
        spec.loader.exec_module(module)
    except Exception as exc:  # noqa: BLE001 - the user's code failed: say where, in one line
        del sys.modules[modname]
        tb = [f for f in traceback.extract_tb(exc.__traceback__) if f.filename == str(p)]
        where = f" (line {tb[-1].lineno})" if tb else ""
        raise SuiteFileError(f"{what} {path} raised {type(exc).__name__} at import{where}: {exc}") from None
    _FILE_MODULES[path] = module
    return module


def _suite_from_module(module: ModuleType, path: str) -> Suite:
    suite = getattr(module, "SUITE", None)
    if isinstance(suite, Suite):
        check_suite_name(suite.name, f"SUITE.name in {path}")
        return suite
    if suite is not None:
        raise ValueError(f"SUITE in {path} is a {type(suite).__name__}, not a problems.Suite")
    problems = getattr(module, "PROBLEMS", None)
    if problems is None:
        raise ValueError(f"suite file {path} defines neither SUITE (a problems.Suite) nor PROBLEMS (a list of Problem)")
    if isinstance(problems, (str, bytes, Problem)) or not isinstance(problems, Iterable):
        hint = " (put it in a list: PROBLEMS = [Problem(...)])" if isinstance(problems, Problem) else ""
        raise ValueError(f"PROBLEMS in {path} must be a non-empty list of problems.Problem, got "
                         f"{type(problems).__name__} {problems!r:.80}{hint}")
    problems = list(problems)
    bad = [type(p).__name__ for p in problems if not isinstance(p, Problem)]
    if bad or not problems:
        raise ValueError(f"PROBLEMS in {path} must be a non-empty list of problems.Problem (got {bad or 'nothing'})")
    default_name = re.sub(r"[^a-z0-9\-]+", "-", pathlib.Path(path).stem.lower().replace("_", "-")).strip("-")
    name = check_suite_name(str(getattr(module, "NAME", default_name) or "user"), f"NAME in {path}")
    names = [p.name for p in problems]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ValueError(f"PROBLEMS in {path} has several problems named {', '.join(map(repr, dup))}: every "
                         "problem needs its own name (it is the problem's id in the results)")
    solvers = getattr(module, "SOLVERS", ())
    if isinstance(solvers, str) or not isinstance(solvers, (list, tuple)) \
            or not all(isinstance(s, str) and s.strip() for s in solvers):
        raise ValueError(f"SOLVERS in {path} must be a list of solver ids (e.g. SOLVERS = [\"sqsd\", "
                         f"\"scipy-lbfgsb\"]; see python -m harness list solvers), got {solvers!r}")
    solvers = tuple(solvers)
    cases = [Case(problem=p, problem_id=p.name) for p in problems]
    return Suite(name=name, description=(module.__doc__ or f"problems from {path}").strip().splitlines()[0],
                 build=lambda: cases, solvers=solvers)


def suite_module(ref: SuiteRef) -> ModuleType | None:
    """The user's suite file as a module (None for catalogue suites)."""
    return _file_module(ref.file) if ref.file else None


def load_suite(ref: SuiteRef) -> Suite:
    """The `Suite` behind ``ref`` (cached per process)."""
    if ref in _CACHE:
        return _CACHE[ref]
    if ref.file:
        suite = _suite_from_module(_file_module(ref.file), ref.file)
    else:
        suite = get_suite(ref.name)
    _CACHE[ref] = suite
    return suite


def ref_for(name: str | None = None, file: str | os.PathLike[str] | None = None) -> SuiteRef:
    """A `SuiteRef` from a catalogue name or a file path (the file's suite name is read)."""
    if file is not None:
        path = str(pathlib.Path(file).resolve())
        suite = _suite_from_module(_file_module(path), path)
        ref = SuiteRef(name=suite.name, file=path)
        _CACHE[ref] = suite
        return ref
    if not name:
        raise ValueError("give a suite name or a suite file")
    return SuiteRef(name=name)


class SolverModuleError(SuiteFileError):
    """A ``--solver-module`` could not be found or imported: a bad-input error, in one line."""


def import_modules(modules: tuple[str, ...]) -> None:
    """Import extra modules (e.g. ones registering solvers) by name or by file path.

    Raises `SolverModuleError` naming the module when it is missing or raises at import.
    """
    for m in modules:
        if not isinstance(m, str) or not m.strip():
            raise SolverModuleError(f"--solver-module needs a module name or a .py file, got {m!r}")
        try:
            if m.endswith(".py") or "/" in m:
                _file_module(str(pathlib.Path(m).resolve()), what="solver module")
            else:
                importlib.import_module(m)
        except SuiteFileError as exc:
            raise SolverModuleError(str(exc)) from None
        except FileNotFoundError as exc:
            raise SolverModuleError(str(exc)) from None
        except ImportError as exc:
            raise SolverModuleError(f"solver module {m} cannot be imported: {exc}") from None
        except Exception as exc:  # noqa: BLE001 - the user's module failed: say so, in one line
            raise SolverModuleError(f"solver module {m} raised {type(exc).__name__} at import: {exc}") from None
