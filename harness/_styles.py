"""One look per solver in every figure: the same colour and line style for a solver in a
profile, a convergence history and a thesis figure, whatever the order of the stored rows.

* The built-in solvers each own a colour (`COLOURS`); the line style says the solver's
  family (its class's ``family``): the thesis's algorithms solid, our extensions dash-dot,
  the established solvers dashed.
* A label with command-line options (``sqsd[rho=0.1]``) keeps its solver's colour and takes
  a dotted or dash pattern of its own.
* Any other solver (a user's, ``--solver-module``) takes the colours of `PALETTE`, in
  sorted order of the labels drawn together, then repeats them with further dash patterns.

`solver_order` sorts labels as the registry lists the solvers (``python -m harness list
solvers``), so legends list them alike everywhere.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from solvers import solver_names
from solvers._registry import get_solver_class

__all__ = ["COLOURS", "PALETTE", "solver_order", "solver_styles"]

_FAMILY_STYLE = {"thesis": "-", "own": "-.", "established": "--"}
#: each built-in solver's colour (hex: this module needs no matplotlib). The solvers drawn
#: together most (the constrained ones of hs, hs-all, cutest and the syntheses; the unconstrained
#: ones of appendix-a) have colours far apart within their group; Dynamic-Q+ is the red line.
COLOURS: dict[str, str] = {
    # constrained
    "dynamic-q": "#1f77b4", "dynamic-q-plus": "#d62728", "multistart": "#9467bd", "lfopc": "#2ca02c",
    "etopc": "#8c564b", "scipy-slsqp": "#ff7f0e", "ipopt": "#000000", "nlopt-slsqp": "#e6ab02",
    "nlopt-mma": "#a6761d", "scipy-trust-constr": "#e7298a", "scipy-cobyla": "#555555",
    # unconstrained
    "sqsd": "#17becf", "sd": "#7f7f7f", "fletcher-reeves": "#bcbd22", "polak-ribiere": "#e377c2",
    "scipy-cg": "#1b9e77", "scipy-bfgs": "#7570b3", "scipy-lbfgsb": "#66a61e",
}
#: colours of other solvers (a user's), in turn
PALETTE: tuple[str, ...] = ("#377eb8", "#4daf4a", "#984ea3", "#ff7f00", "#a65628", "#f781bf", "#999999", "#e41a1c")
#: line styles of option variants and of colours used a second time
_PATTERNS: tuple[Any, ...] = (":", (0, (5, 1)), (0, (3, 1, 1, 1)), (0, (1, 3)), (0, (5, 3, 1, 3, 1, 3)))


def _base(label: str) -> str:
    return label.split("[", 1)[0]


def solver_order(label: str) -> tuple[int, str]:
    """Sort key: registered solvers in the registry's order, then every other label
    alphabetically (an option variant right after its solver)."""
    names = solver_names()
    base = _base(label)
    return (names.index(base) if base in names else len(names), label)


def _family_style(name: str) -> str:
    try:
        return _FAMILY_STYLE.get(get_solver_class(name).family, "-")
    except KeyError:  # runs of a solver not registered in this process
        return "-"


def solver_styles(labels: Iterable[str]) -> dict[str, dict[str, Any]]:
    """``{label: {"color": ..., "linestyle": ...}}`` for the labels drawn together.

    A built-in solver's style depends on its name only; a variant's on the variants drawn
    with it; another solver's on the other such solvers drawn with it (its colour is the
    next unused one of `PALETTE` in sorted order).
    """
    look: dict[str, tuple[str, Any]] = {}  # solver -> (colour, line style)
    n_other = 0
    n_variants: dict[str, int] = {}
    styles: dict[str, dict[str, Any]] = {}
    for lab in sorted(set(labels), key=solver_order):
        base = _base(lab)
        if base not in look:
            if base in COLOURS:
                look[base] = (COLOURS[base], _family_style(base))
            else:  # the next free colour; once all are used, again with a dash pattern
                rounds, k = divmod(n_other, len(PALETTE))
                look[base] = (PALETTE[k], "-" if rounds == 0 else _PATTERNS[(rounds - 1) % len(_PATTERNS)])
                n_other += 1
        color, style = look[base]
        if lab != base:  # an option variant: its solver's colour, a pattern of its own
            style = _PATTERNS[n_variants.get(base, 0) % len(_PATTERNS)]
            n_variants[base] = n_variants.get(base, 0) + 1
        styles[lab] = {"color": color, "linestyle": style}
    return styles
