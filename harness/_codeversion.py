"""Code version of a run: a hash of exactly the project sources that can change its numbers.

The sources are the transitive closure of project-internal imports (read with `ast`, not
by importing) starting from the solver's module and the suite's module, plus the package
``__init__`` files on the way and the harness's row format.  Editing a cable-robot
module therefore does not invalidate stored Appendix A runs, while editing LFOPC does
invalidate Dynamic-Q runs (Dynamic-Q imports LFOPC).  The name registries (``REGISTRIES``)
are followed but not hashed: they map names to modules, and the modules a run uses are
hashed themselves, so registering a new suite or solver invalidates no stored run.
"""

from __future__ import annotations

import ast
import functools
import hashlib
import pathlib

__all__ = ["code_version", "module_closure"]

ROOT = pathlib.Path(__file__).resolve().parent.parent
PACKAGES = ("problems", "solvers", "manipulators", "harness")
ALWAYS = ("harness/_record.py", "harness/_worker.py")
REGISTRIES = ("problems/_catalog.py", "solvers/_catalog.py")  # name -> module maps: followed, not hashed


def _file_of(module: str) -> pathlib.Path | None:
    if module.split(".")[0] not in PACKAGES:
        return None
    base = ROOT.joinpath(*module.split("."))
    for cand in (base.with_suffix(".py"), base / "__init__.py"):
        if cand.is_file():
            return cand
    return None


def _module_of(path: pathlib.Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _executed_nodes(tree: ast.AST):
    """Every node of ``tree`` except the bodies of ``if TYPE_CHECKING:`` (imports for type
    checkers only: the module never runs them, so they cannot change a run's numbers)."""
    stack = [tree]
    while stack:
        node = stack.pop()
        yield node
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            stack += node.orelse
            continue
        stack += ast.iter_child_nodes(node)


@functools.cache
def _imports(path: pathlib.Path, mtime: float) -> tuple[str, ...]:
    """Project modules imported by ``path`` (absolute names)."""
    try:
        tree = ast.parse(path.read_bytes())
    except (OSError, SyntaxError):
        return ()
    here = _module_of(path)
    pkg = here if path.name == "__init__.py" else here.rpartition(".")[0]
    out: list[str] = []
    for node in _executed_nodes(tree):
        if isinstance(node, ast.Import):
            out += [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg.split(".")[: len(pkg.split(".")) - (node.level - 1)] if pkg else []
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            out.append(mod)
            out += [f"{mod}.{a.name}" for a in node.names]  # "from . import lfopc" imports a module
    return tuple(m for m in out if m and m.split(".")[0] in PACKAGES)


def module_closure(modules: tuple[str, ...]) -> list[pathlib.Path]:
    """Files of ``modules``, their parent packages and everything they import, transitively."""
    seen: dict[pathlib.Path, None] = {}
    stack = list(modules)
    while stack:
        mod = stack.pop()
        parts = mod.split(".")
        for i in range(1, len(parts) + 1):  # importing a.b.c runs a/__init__ and a/b/__init__
            f = _file_of(".".join(parts[:i]))
            if f is None or f in seen:
                continue
            seen[f] = None
            stack += _imports(f, f.stat().st_mtime)
    return sorted(seen)


@functools.lru_cache(maxsize=256)
def _hash(modules: tuple[str, ...], files: tuple[str, ...], stamp: tuple[float, ...]) -> str:
    h = hashlib.sha256()
    paths = module_closure(modules) + [ROOT / a for a in ALWAYS] + [pathlib.Path(f) for f in files]
    for p in sorted(set(paths)):
        if p.is_relative_to(ROOT) and p.relative_to(ROOT).as_posix() in REGISTRIES:
            continue
        try:
            data = p.read_bytes()
        except OSError:
            continue
        h.update(str(p.relative_to(ROOT) if p.is_relative_to(ROOT) else p.name).encode() + b"\0" + data)
    return h.hexdigest()[:12]


def code_version(modules: tuple[str, ...], files: tuple[str, ...] = ()) -> str:
    """Hash of the sources behind ``modules`` (dotted names) and extra ``files`` (user suite files)."""
    stamp = tuple(p.stat().st_mtime for p in module_closure(modules)) + tuple(
        pathlib.Path(f).stat().st_mtime for f in files if pathlib.Path(f).exists())
    return _hash(tuple(sorted(modules)), tuple(files), stamp)
