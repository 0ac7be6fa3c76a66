"""Planning: (case x solver) -> run specifications with their keys.

A run's key is (suite, problem, n, start, variant, solver, settings hash, code version)
(docs/harness.md, "Results store and resume").  The settings are the solver's full option values after the
case's options are applied, hashed exactly as `harness._record.settings_hash` hashes the
options of the finished run, so a key computed before a run equals the stored one.
"""

from __future__ import annotations

import dataclasses
import difflib
import hashlib
import inspect
import json
from typing import Any

from problems import Case, Suite
from problems._catalog import REGISTRY as SUITE_REGISTRY
from solvers import get_solver_class, make_solver, parse_spec
from solvers._base import _type_ok

from ._codeversion import code_version
from ._record import _jsonable, settings_hash
from ._suites import SuiteRef

__all__ = ["RunSpec", "plan_runs", "parse_solver_spec", "split_specs", "name_list", "overrides_text",
           "HarnessArgumentError"]

class HarnessArgumentError(ValueError):
    """Bad arguments to the harness (unknown names, bad values): CLI exit status 2."""


@dataclasses.dataclass(frozen=True)
class RunSpec:
    """Everything a worker needs to perform one run (picklable, no closures)."""

    suite_ref: SuiteRef
    case_id: str
    problem: str
    n: int
    start: str
    variant: str
    f_ref: float
    solver: str
    options: dict[str, Any]
    settings: str  # JSON of the full option values
    settings_hash: str
    code_version: str
    timeout: float
    modules: tuple[str, ...] = ()
    overrides: str = ""  # options given with the solver id (``sqsd[rho=0.5]``), canonical JSON
    not_applicable: str | None = None  # reason, when the solver cannot handle the problem
    plan_error: str | None = None  # bad options for this case: recorded as an error row

    @property
    def run_key(self) -> str:
        return run_key(self.suite_ref.name, self.problem, self.n, self.start, self.variant,
                       self.solver, self.settings_hash, self.code_version)


def run_key(suite: str, problem: str, n: int, start: str, variant: str, solver: str,
            settings_hash_: str, code_version_: str) -> str:
    """Short stable hash of the run key tuple."""
    blob = json.dumps([suite, problem, int(n), start, variant, solver, settings_hash_, code_version_])
    return hashlib.sha256(blob.encode()).hexdigest()[:20]


def overrides_text(opts: dict[str, Any]) -> str:
    """Canonical text of command-line options ("" for none): part of a stored row's identity."""
    return json.dumps(_jsonable(opts), sort_keys=True) if opts else ""


def _solver_code(name: str, cls: Any, suite_module: str | None, files: tuple[str, ...]) -> str:
    """Code version for runs of ``cls`` on the suite (see `harness._codeversion`)."""
    mods = tuple(m for m in (getattr(cls, "__module__", None), suite_module) if m)
    extra = list(files)
    try:
        f = inspect.getfile(cls)
        if not any(f.endswith(f"{m.replace('.', '/')}.py") for m in mods if m.split(".")[0] in
                   ("solvers", "problems", "manipulators")):
            extra.append(f)  # a user's solver outside the project packages
    except (TypeError, OSError):
        pass
    return code_version(mods, tuple(extra))


def split_specs(s: str) -> list[str]:
    """Split on commas outside brackets: ``"sqsd[rho=1,eps_g=1e-6],sd"`` -> two specs."""
    out, depth, cur = [], 0, ""
    for ch in s:
        depth += ch == "["
        depth -= ch == "]"
        if ch == "," and depth == 0:
            out.append(cur)
            cur = ""
        else:
            cur += ch
    return [x.strip() for x in out + [cur] if x.strip()]


def name_list(value: Any, what: str) -> list[str] | None:
    """``solvers`` / ``problems`` as given to the harness: None (the suite's default), a list
    of names, or one comma-separated string (as on the command line). An explicit empty
    list or string is an error: it would otherwise mean "everything"."""
    if value is None:
        return None
    if isinstance(value, str):
        names = split_specs(value)
    elif isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
        names = [v.strip() for v in value]
    else:
        raise HarnessArgumentError(f"{what} must be a list of ids or one comma-separated string, got {value!r}")
    if not names or not all(names):
        raise HarnessArgumentError(f"no {what} given ({value!r}); leave {what} out for the suite's default")
    return names


def parse_solver_spec(spec: str) -> tuple[str, dict[str, Any]]:
    """``"sqsd[rho=0.5]"`` -> ("sqsd", {"rho": 0.5}); the options override the case's.

    The syntax is the registry's (`solvers.parse_spec`); errors become argument errors, and
    so does an option given twice (the registry would keep the last one silently).
    """
    try:
        name, opts = parse_spec(spec)
    except ValueError as exc:
        raise HarnessArgumentError(str(exc)) from None
    inner = spec[spec.index("[") + 1:spec.rindex("]")] if "[" in spec and "]" in spec else ""
    keys = [item.split("=", 1)[0].strip() for item in inner.split(",") if "=" in item]
    twice = sorted({k for k in keys if keys.count(k) > 1})
    if twice:
        raise HarnessArgumentError(f"option(s) {', '.join(twice)} given more than once in {spec!r}")
    return name, opts


def normalized_options(cls: Any, opts: dict[str, Any]) -> dict[str, Any]:
    """Command-line option values in their option's type: ``max_iter=1e2`` -> 100 (an int
    option given as a float crashed inside the solver), ``rho=2`` -> 2.0, so one setting
    written two ways is one run (its settings hash and stored identity)."""
    types = {f.name: f.type for f in dataclasses.fields(cls)} if dataclasses.is_dataclass(cls) else {}
    out = dict(opts)
    for k, v in opts.items():
        ok, kind = _type_ok(types.get(k, ""), v)  # the annotation reading the solvers' own check uses
        if ok and kind == "an integer" and isinstance(v, float):
            out[k] = int(v)
        elif ok and kind == "a number" and isinstance(v, int):
            out[k] = float(v)
    return out


#: Valid ids an unknown-id message lists at most (the rest are counted, `list problems` shows them).
MAX_LISTED_IDS = 20


def _listed(ids: list[str]) -> str:
    """``ids`` comma-separated, at most `MAX_LISTED_IDS` of them and a count of the rest."""
    shown = ", ".join(ids[:MAX_LISTED_IDS])
    rest = len(ids) - MAX_LISTED_IDS
    if rest <= 0:
        return shown
    return (f"{shown} ... and {rest} more "
            "(`python -m harness list problems` with the same --suite or --suite-file lists them)")


def _did_you_mean(text: str, ids: list[str], problem_of: dict[str, str]) -> str:
    """`` (did you mean a, b?)`` for ``text``, or "" when nothing is close.

    A case id whose problem exists suggests that problem's cases first (``hs002/n=3/x0``:
    ``hs002/n=2/x0``), then the ids `difflib.get_close_matches` finds."""
    same = [c for c in ids if "/" in text and problem_of.get(c) == text.split("/", 1)[0]]
    order = {c: i for i, c in enumerate(ids)}
    near = difflib.get_close_matches(text, ids, n=len(ids), cutoff=0.7)
    # equally close ids in the suite's order (get_close_matches puts the larger string first)
    near.sort(key=lambda c: (-difflib.SequenceMatcher(None, text, c).ratio(), order[c]))
    close = list(dict.fromkeys(same[:3] + near))[:3]
    return f" (did you mean {', '.join(close)}?)" if close else ""


def select_cases(suite: Suite, problems: list[str] | None) -> list[Case]:
    """Cases whose problem id (or full case id) is in ``problems`` (all if None).

    An unknown id is refused (`HarnessArgumentError`) with the valid ids in the form it was
    given: case ids for one that looks like a case id (it contains "/"), problem ids
    otherwise, with the closest ones as a "did you mean"."""
    cases = list(suite.cases())
    if not problems:
        return cases
    problem_ids = list(suite.problem_ids())
    case_ids = [c.case_id for c in cases]
    valid = set(problem_ids) | set(case_ids)
    unknown = [p for p in problems if p not in valid]
    if unknown:
        problem_of = {c.case_id: c.problem_id for c in cases}
        parts = []
        for what, ids, given in (("problem(s)", problem_ids, [p for p in unknown if "/" not in p]),
                                 ("case id(s)", case_ids, [p for p in unknown if "/" in p])):
            if given:
                named = ", ".join(p + _did_you_mean(p, ids, problem_of) for p in given)
                parts.append(f"unknown {what} {named} in suite {suite.name}; valid {what[:-3]}s: {_listed(ids)}")
        raise HarnessArgumentError("; ".join(parts))
    want = set(problems)
    return [c for c in cases if c.problem_id in want or c.case_id in want]


def plan_runs(ref: SuiteRef, suite: Suite, solver_specs: list[str], problems: list[str] | None,
              timeout: float, modules: tuple[str, ...] = ()) -> list[RunSpec]:
    """Every (case, solver) run, with options, settings hash and key computed up front."""
    parsed = [parse_solver_spec(s) for s in solver_specs]
    classes: dict[str, Any] = {}
    unavailable: dict[str, str] = {}
    for name, _ in parsed:
        try:
            classes[name] = get_solver_class(name)
        except KeyError as exc:  # UnknownSolver lists the valid names
            raise HarnessArgumentError(str(exc)) from None
        except Exception as exc:  # noqa: BLE001 - a known solver that fails to import: error rows
            unavailable[name] = f"solver {name} unavailable: {type(exc).__name__}: {exc}"
    parsed = [(name, normalized_options(classes[name], over) if name in classes else over) for name, over in parsed]
    seen: dict[tuple[str, str], int] = {}
    for i, ((name, over), spec_str) in enumerate(zip(parsed, solver_specs)):
        first = seen.setdefault((name, overrides_text(over)), i)
        if first != i:
            raise HarnessArgumentError(f"solver {spec_str!r} is given twice (as {solver_specs[first]!r}): the same "
                                       "solver with the same options is one run per case")
    for (name, over), spec_str in zip(parsed, solver_specs):  # the user's options: checked before any work
        if over and name in classes:
            try:
                make_solver(name, **over)
            except (ValueError, TypeError) as exc:
                raise HarnessArgumentError(f"invalid options in {spec_str!r}: {exc}") from None
    cases = select_cases(suite, problems)
    suite_module = None if ref.file else SUITE_REGISTRY.module_of(ref.name)
    files = (ref.file,) if ref.file else ()
    cv = {name: _solver_code(name, classes.get(name), suite_module, files) for name, _ in parsed}
    specs = []
    for case in cases:
        f_ref = case.problem.f_ref
        only = case.meta.get("solvers")  # a case meant for some solvers only (e.g. a14's rho=10 SQSD variant)
        for (name, over), spec_str in zip(parsed, solver_specs):
            if only and name not in only:
                continue
            valid = [o["name"] for o in classes[name].options()] if name in classes else []
            opts = {**case.options_for(name, valid), **over}
            reason = err = None
            try:
                if name in unavailable:
                    raise ValueError(unavailable[name])
                inst = make_solver(name, **opts)
                settings = _jsonable(inst.settings())
                reason = inst.can_solve(case.problem)
            except (ValueError, TypeError) as exc:  # bad options for this case: an error row
                settings = _jsonable(opts)
                err = unavailable.get(name) or f"invalid options for {spec_str}: {exc}"
            specs.append(RunSpec(
                suite_ref=ref, case_id=case.case_id, problem=case.problem_id, n=case.n,
                start=case.start, variant=case.variant,
                f_ref=float("nan") if f_ref is None else float(f_ref),
                solver=name, options=opts, settings=json.dumps(settings, sort_keys=True),
                settings_hash=settings_hash(settings), code_version=cv[name], timeout=float(timeout),
                modules=modules, overrides=overrides_text(over), not_applicable=reason,
                plan_error=err))
    return specs
