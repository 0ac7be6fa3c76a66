"""One look per solver in every figure: the same colour and line style for a solver in a
profile, a convergence history and a thesis figure, whatever the order of the stored rows.

* The built-in solvers (`BUILTIN_ORDER`) each own a colour (`COLOURS`); their line style
  says the family: the thesis's algorithms solid, our extensions dash-dot, the established
  solvers dashed.
* A label with command-line options (``sqsd[rho=0.1]``) keeps its solver's colour and takes
  a dotted or dash pattern of its own.
* Any other solver (a user's, ``--solver-module``) takes the colours of `PALETTE`, in
  sorted order of the labels drawn together, then repeats them with further dash patterns.

`solver_order` sorts labels in that order, so legends list the solvers alike everywhere.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

__all__ = ["BUILTIN_ORDER", "COLOURS", "PALETTE", "solver_order", "solver_styles"]

#: the registry's built-in solvers, thesis family first (the order of `python -m harness list solvers`)
BUILTIN_ORDER: tuple[str, ...] = (
    "sqsd", "sd", "fletcher-reeves", "polak-ribiere", "lfopc", "dynamic-q", "etopc",
    "dynamic-q-plus", "multistart",
    "scipy-cg", "scipy-bfgs", "scipy-lbfgsb", "scipy-slsqp", "scipy-trust-constr", "scipy-cobyla", "ipopt",
    "nlopt-mma", "nlopt-slsqp",
)
_FAMILY_STYLE = {"thesis": "-", "own": "-.", "established": "--"}
_FAMILY = {**dict.fromkeys(BUILTIN_ORDER[:7], "thesis"), **dict.fromkeys(BUILTIN_ORDER[7:9], "own"),
           **dict.fromkeys(BUILTIN_ORDER[9:], "established")}
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
    """Sort key: built-in solvers in `BUILTIN_ORDER`, then every other label alphabetically
    (an option variant right after its solver)."""
    base = _base(label)
    return (BUILTIN_ORDER.index(base) if base in BUILTIN_ORDER else len(BUILTIN_ORDER), label)


def solver_styles(labels: Iterable[str]) -> dict[str, dict[str, Any]]:
    """``{label: {"color": ..., "linestyle": ...}}`` for the labels drawn together.

    A built-in solver's style depends on its name only; a variant's on the variants drawn
    with it; a user's solver's on the other user solvers drawn with it (its colour is the
    next unused one in sorted order).
    """
    free = PALETTE
    look: dict[str, tuple[str, Any]] = {}  # solver -> (colour, line style)
    n_variants: dict[str, int] = {}
    styles: dict[str, dict[str, Any]] = {}
    for lab in sorted(set(labels), key=solver_order):
        base = _base(lab)
        if base not in look:
            if base in BUILTIN_ORDER:
                look[base] = (COLOURS[base], _FAMILY_STYLE[_FAMILY[base]])
            else:  # the next free colour; once all are used, again with a dash pattern
                k = sum(b not in BUILTIN_ORDER for b in look)
                rounds = k // len(free)
                look[base] = (free[k % len(free)], "-" if rounds == 0 else _PATTERNS[(rounds - 1) % len(_PATTERNS)])
        color, style = look[base]
        if lab != base:  # an option variant: its solver's colour, a pattern of its own
            style = _PATTERNS[n_variants.get(base, 0) % len(_PATTERNS)]
            n_variants[base] = n_variants.get(base, 0) + 1
        styles[lab] = {"color": color, "linestyle": style}
    return styles
