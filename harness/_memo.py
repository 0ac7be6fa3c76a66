"""An on-disk memo for expensive, deterministic inputs of the tables.

The 3-RPR tables carry an exact-model optimum per case (`rpr3_suite.exact_optimum`:
differential evolution plus multistart SLSQP, ~75 s for the nine cases); it depends only
on the code and its arguments, so it is computed once per code version and kept under
``$HAYBENCH_CACHE`` (default ``~/.cache/haybench``).  The key holds the code version of the
computing modules (`harness._codeversion`), the arguments, the NumPy and SciPy versions and
the BLAS kernels in force (`harness._blas`): any change recomputes.  Delete the folder to
clear it; an unwritable cache only costs the recomputation.
"""

from __future__ import annotations

import hashlib
import os
import pathlib
import pickle
from collections.abc import Callable
from typing import Any, TypeVar

from ._codeversion import code_version

__all__ = ["memo", "cache_dir"]

T = TypeVar("T")


def cache_dir() -> pathlib.Path:
    return pathlib.Path(os.environ.get("HAYBENCH_CACHE") or pathlib.Path.home() / ".cache" / "haybench")


def memo(name: str, modules: tuple[str, ...], args: tuple[Any, ...], compute: Callable[[], T]) -> T:
    """``compute()``, or its stored value for the same ``name``, ``args`` and sources of ``modules``."""
    import numpy
    import scipy

    key = repr((name, code_version(modules), args, numpy.__version__, scipy.__version__,
                os.environ.get("OPENBLAS_CORETYPE")))
    path = cache_dir() / f"{name}-{hashlib.sha256(key.encode()).hexdigest()[:20]}.pkl"
    try:
        return pickle.loads(path.read_bytes())
    except (OSError, pickle.PickleError, EOFError, AttributeError, ImportError):
        pass
    value = compute()
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_bytes(pickle.dumps(value))
        os.replace(tmp, path)
    except OSError:
        pass
    return value
