"""Selecting S2MPJ instances by what users filter on (docs/cutest.md, "Selection").

A selection is a comma-separated list of conditions, all of which must hold:

==========================  ====================================================
``type=u`` / ``type=bl``    S2MPJ type: u(nconstrained), b(ounds only), l(inear
                            constraints), n(onlinear constraints); letters = any of
``n<=100``, ``n>=2``        dimension (``<``, ``<=``, ``=``, ``!=``, ``>=``, ``>``)
``m<=10``                   constraints (linear + nonlinear; bounds not counted);
                            also ``m_ineq``, ``m_eq``, ``m_linear``, ``m_nonlinear``,
                            ``bounds``
``name=HS71|ROSENBR``       problem names (instance names of extra sizes too)
``name~^HS\\d+$``            problem name matches a regular expression
``size=default``            the default size of variable-dimension problems (the
                            default); ``size=all`` adds every size S2MPJ lists
``feasibility=0``           leave out (``1``: only) feasibility problems, whose
                            objective is 0
==========================  ====================================================
"""

from __future__ import annotations

import operator
import re

import pandas as pd

from ._catalogue import catalogue

__all__ = ["select", "SelectionError", "NUMERIC"]

NUMERIC = ("n", "m", "m_ineq", "m_eq", "m_linear", "m_nonlinear", "bounds")
OPS = {"<=": operator.le, ">=": operator.ge, "!=": operator.ne, "<": operator.lt, ">": operator.gt,
       "=": operator.eq}
TERM = re.compile(r"^\s*([a-z_]+)\s*(<=|>=|!=|<|>|=|~)\s*(.+?)\s*$")
KEYS = ("type", *NUMERIC, "name", "size", "feasibility")


class SelectionError(ValueError):
    """A selection that cannot be read: names the term and what is valid."""


def _split(expr: str) -> list[str]:
    return [t for t in (s.strip() for s in expr.split(",")) if t]


def select(expr: str | None = None) -> pd.DataFrame:
    """The catalogue rows (`catalogue()`) of the instances ``expr`` selects."""
    cat = catalogue()
    keep = pd.Series(True, index=cat.index)
    size = "default"
    for term in _split(expr or ""):
        m = TERM.match(term)
        if not m:
            raise SelectionError(f"cannot read selection term {term!r}; write key<op>value with keys "
                                 f"{', '.join(KEYS)} (docs/cutest.md)")
        key, op, value = m.groups()
        if key not in KEYS:
            raise SelectionError(f"unknown selection key {key!r} in {term!r}; valid keys: {', '.join(KEYS)}")
        if key == "type":
            if op != "=" or not value or set(value) - set("ubln"):
                raise SelectionError(f"type must be type=<letters of u, b, l, n>, got {term!r}")
            keep &= cat["type"].isin(list(value))
        elif key in NUMERIC:
            if op == "~":
                raise SelectionError(f"{key} takes <, <=, =, !=, >=, >, not ~ ({term!r})")
            try:
                num = int(float(value))
            except ValueError:
                raise SelectionError(f"{key} needs a number, got {value!r} in {term!r}") from None
            keep &= OPS[op](cat[key], num)
        elif key == "name":
            if op == "~":
                try:
                    rx = re.compile(value)
                except re.error as exc:
                    raise SelectionError(f"bad regular expression in {term!r}: {exc}") from None
                def matches(name: str, rx: re.Pattern[str] = rx) -> bool:
                    return bool(rx.search(name))

                hit = cat["problem"].map(matches) | cat["instance"].map(matches)
            elif op in ("=", "!="):
                names = {v.strip() for v in value.split("|") if v.strip()}
                unknown = sorted(names - set(cat["problem"]) - set(cat["instance"]))
                if unknown and op == "=":
                    raise SelectionError(f"unknown S2MPJ problem(s) {', '.join(unknown)}; list them with "
                                         "`python -m harness list problems --suite cutest --select size=all`")
                hit = cat["problem"].isin(names) | cat["instance"].isin(names)
                hit = hit if op == "=" else ~hit
            else:
                raise SelectionError(f"name takes =, != or ~, got {term!r}")
            keep &= hit
        elif key == "size":
            if op != "=" or value not in ("default", "all"):
                raise SelectionError(f"size must be size=default or size=all, got {term!r}")
            size = value
        elif key == "feasibility":
            if op != "=" or value not in ("0", "1"):
                raise SelectionError(f"feasibility must be feasibility=0 or feasibility=1, got {term!r}")
            keep &= cat["feasibility"] == (value == "1")
    if size == "default":
        keep &= cat["default"]
    return cat[keep].reset_index(drop=True)
