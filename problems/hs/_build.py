"""Build `Problem` objects from the vendored Hock–Schittkowski JSON.

Each problem's expression strings are parsed once (`_expr.parse`), turned into CasADi
SX expressions, and compiled into CasADi Functions for f, grad f, g, its Jacobian, h,
its Jacobian and the Hessian of the Lagrangian. The compiled set is cached at module
level per problem id, so building the suite twice (or every harness worker rebuilding
its case) costs nothing extra. The Problem's callables are thin NumPy wrappers around
those Functions; ``Problem.symbolic`` exposes the same functions to CasADi so Ipopt can
use exact second derivatives.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import threading
from importlib import resources
from typing import Any

import casadi as ca
import numpy as np

from .._problem import Problem
from ._convention import hs_to_ours
from ._expr import parse, to_casadi

__all__ = ["load_data", "compiled", "build_problem", "HSFunctions"]

JSON_NAME = "hock_schittkowski.json"


@functools.cache
def load_data() -> dict[str, dict[str, Any]]:
    """The vendored JSON (problem id -> entry), read once."""
    with resources.files(__package__).joinpath(JSON_NAME).open("r", encoding="utf-8") as fh:
        return json.load(fh)


@dataclasses.dataclass(frozen=True)
class HSFunctions:
    """Compiled CasADi Functions of one problem, in OUR convention (g <= 0).

    ``f(x)``, ``grad(x)``, ``g(x)``/``g_jac(x)`` (absent when m = 0), ``h(x)``/``h_jac(x)``
    (absent when q = 0), ``hess_lag(x, sigma, lam_g, lam_h)`` = Hessian of
    sigma f + lam_g^T g + lam_h^T h (lower and upper triangle, dense).
    """

    n: int
    m: int
    q: int
    f: ca.Function
    grad: ca.Function
    g: ca.Function | None
    g_jac: ca.Function | None
    h: ca.Function | None
    h_jac: ca.Function | None
    hess_lag: ca.Function


@functools.cache
def compiled(pid: str) -> HSFunctions:
    """Parse problem ``pid`` once and compile its CasADi Functions (cached)."""
    data = load_data()
    if pid not in data:
        raise KeyError(f"unknown Hock-Schittkowski problem {pid!r}; valid: {', '.join(data)}")
    e = data[pid]
    n = int(e["n"])
    x = ca.SX.sym("x", n)
    f = to_casadi(parse(e["objective"], n), x)
    g_list = [hs_to_ours(to_casadi(parse(s, n), x)) for s in e["ineq"]]
    h_list = [to_casadi(parse(s, n), x) for s in e["eq"]]
    g = ca.vertcat(*g_list) if g_list else ca.SX(0, 1)
    h = ca.vertcat(*h_list) if h_list else ca.SX(0, 1)
    m, q = len(g_list), len(h_list)
    sigma = ca.SX.sym("sigma")
    lam_g = ca.SX.sym("lam_g", m)
    lam_h = ca.SX.sym("lam_h", q)
    lag = sigma * f + ca.dot(lam_g, g) + ca.dot(lam_h, h)
    hess = ca.densify(ca.hessian(lag, x)[0])

    def fn(name: str, ins: list, out: Any, names: list[str]) -> ca.Function:
        return ca.Function(f"{pid}_{name}", ins, [ca.densify(out)], names, [name])

    return HSFunctions(
        n=n, m=m, q=q,
        f=fn("f", [x], f, ["x"]),
        grad=fn("grad", [x], ca.gradient(f, x), ["x"]),
        g=fn("g", [x], g, ["x"]) if m else None,
        g_jac=fn("g_jac", [x], ca.jacobian(g, x), ["x"]) if m else None,
        h=fn("h", [x], h, ["x"]) if q else None,
        h_jac=fn("h_jac", [x], ca.jacobian(h, x), ["x"]) if q else None,
        hess_lag=fn("hess_lag", [x, sigma, lam_g, lam_h], hess, ["x", "sigma", "lam_g", "lam_h"]),
    )


_F64 = np.dtype(float)


class _Numeric:
    """Numeric evaluation of a one-input dense CasADi Function through its buffer interface.

    ``Function.__call__`` converts the NumPy input to a DM and the DM result back to NumPy on
    every call (~50 us, most of an HS problem's cost inside LFOPC); ``Function.buffer()``
    evaluates the same compiled expression graph on preallocated arrays (~2 us), with the
    same floating-point operations, so the values are bitwise those of ``fun(x)``.  One
    buffer per thread: a buffer holds its input and output between calls.
    """

    def __init__(self, fun: ca.Function, rows: int, cols: int) -> None:
        self.fun, self.rows, self.cols = fun, rows, cols
        self.n = fun.size1_in(0)
        self._shape = (self.n,)
        self._local = threading.local()

    def _buffers(self) -> tuple[np.ndarray, np.ndarray, Any, Any]:
        b = getattr(self._local, "b", None)
        if b is None:
            buf, run = self.fun.buffer()
            xin, out = np.zeros(self.n), np.zeros(self.rows * self.cols)
            buf.set_arg(0, memoryview(xin))
            buf.set_res(0, memoryview(out))
            b = self._local.b = (xin, out, buf, run)
        return b

    def _run(self, x: Any) -> np.ndarray:
        """Evaluate at ``x``; the result is the buffer itself (column-major), valid until the next call."""
        try:
            xin, out, _, run = self._local.b
        except AttributeError:
            xin, out, _, run = self._buffers()
        if type(x) is np.ndarray and x.dtype is _F64 and x.shape == self._shape:  # the usual case
            xin[:] = x
        else:
            x = np.asarray(x, dtype=float)
            if x.size != self.n:
                raise ValueError(f"{self.fun.name()}: x must have {self.n} entries, got shape {x.shape}")
            xin[:] = x if x.ndim == 1 else x.reshape(-1)
        run()
        return out

    def __call__(self, x: np.ndarray) -> np.ndarray:
        return self._run(x).copy()  # column-major values


def _vec(fun: ca.Function):
    run = _Numeric(fun, fun.size1_out(0), 1)._run

    def call(x: np.ndarray) -> np.ndarray:
        return run(x).copy()

    return call


@functools.cache
def _transposed(pid: str, which: str) -> ca.Function:
    """The Jacobian ``which`` ("g_jac", "h_jac") of problem ``pid`` with its output transposed.

    CasADi stores a matrix column-major, so the column-major (n, rows) transpose is the
    row-major (rows, n) Jacobian: one contiguous copy instead of a strided one.  Its entries
    are the same expression nodes (the Jacobian Function called on a symbol replays its
    operations), so the values are bitwise those of the Jacobian Function.
    """
    fun = getattr(compiled(pid), which)
    x = ca.SX.sym("x", fun.size1_in(0))
    return ca.Function(f"{fun.name()}_t", [x], [ca.densify(fun(x).T)], ["x"], [f"{which}_t"])


def _mat(fun: ca.Function, rows: int, cols: int):
    """Row-major (rows, cols) values of ``fun``, a Function whose output is the (cols, rows) transpose."""
    run = _Numeric(fun, cols, rows)._run

    def call(x: np.ndarray) -> np.ndarray:
        return run(x).copy().reshape(rows, cols)  # column-major transpose = row-major matrix

    return call


def _scalar(fun: ca.Function):
    run = _Numeric(fun, 1, 1)._run

    def call(x: np.ndarray) -> float:
        return float(run(x)[0])

    return call


def _bounds(values: list[Any], fill: float) -> np.ndarray:
    return np.array([fill if v is None else float(v) for v in values], dtype=float)


def build_problem(pid: str) -> Problem:
    """The `Problem` for HS problem ``pid`` (e.g. ``"hs071"``), from x0 of the HS book."""
    e = load_data()[pid]
    fs = compiled(pid)

    def symbolic(x: Any) -> dict[str, Any]:
        """CasADi expressions of f, g (ours, <= 0) and h in the symbol x (SX or MX)."""
        return {
            "f": fs.f(x),
            "ineq": fs.g(x) if fs.g is not None else None,
            "eq": fs.h(x) if fs.h is not None else None,
        }

    return Problem(
        name=pid,
        x0=np.asarray(e["x0"], dtype=float),
        objective=_scalar(fs.f),
        gradient=_vec(fs.grad),
        ineq=_vec(fs.g) if fs.m else None,
        ineq_jacobian=_mat(_transposed(pid, "g_jac"), fs.m, fs.n) if fs.m else None,
        eq=_vec(fs.h) if fs.q else None,
        eq_jacobian=_mat(_transposed(pid, "h_jac"), fs.q, fs.n) if fs.q else None,
        lower=_bounds(e["lower"], -np.inf),
        upper=_bounds(e["upper"], np.inf),
        f_ref=float(e["f_star"]),
        x_ref=np.asarray(e["x_star"], dtype=float),
        source=f"Hock & Schittkowski (1981) problem {e['hs_number']}; f*: {e['f_star_source']}",
        symbolic=symbolic,
        tags=("hs", "constrained") if (fs.m or fs.q) else ("hs",),
        meta={"hs_number": int(e["hs_number"]), "thesis_f_act": e.get("thesis_f_act"),
              "other_published_values": e.get("other_published_values", []), "notes": e.get("notes", "")},
        n_ineq=fs.m,
        n_eq=fs.q,
    )
