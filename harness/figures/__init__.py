"""Thesis figures: per-suite plug-ins, declared by the suite (``Suite(..., figures="harness.figures.rpr2")``).

A plug-in defines ``figures(runs: pandas.DataFrame, outdir: pathlib.Path) -> list[Path]``
drawing the thesis's figures for that suite from stored runs (no solver re-runs).
`thesis_figures` is the dispatcher behind ``python -m harness plot --kind thesis``.
"""

from __future__ import annotations

import importlib
import pathlib

import pandas as pd

__all__ = ["NoFigurePlugin", "thesis_figures", "finish"]


class NoFigurePlugin(LookupError):
    """The suite has no thesis-figure plug-in."""


def thesis_figures(suite: str, runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    from problems import UnknownSuite, get_suite

    try:
        modname = get_suite(suite).figures
    except UnknownSuite:
        modname = ""
    if not modname:
        raise NoFigurePlugin(f"suite {suite!r} has no thesis-figure plug-in (Suite(..., figures='module') with "
                             "figures(runs, outdir) -> list[Path])")
    module = importlib.import_module(modname)
    import matplotlib

    matplotlib.use("Agg")
    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return [pathlib.Path(p) for p in module.figures(runs, outdir)]


def finish(fig, title: str, path: pathlib.Path) -> list[pathlib.Path]:
    """Title, lay out, write (120 dpi) and close a plug-in's figure; returns ``[path]``."""
    import matplotlib.pyplot as plt

    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return [pathlib.Path(path)]
