"""Thesis figures: per-suite plug-ins, declared by the suite (``Suite(..., figures="harness.figures.rpr2")``).

A plug-in defines ``figures(runs: pandas.DataFrame, outdir: pathlib.Path) -> list[Path]``
drawing the thesis's figures for that suite from stored runs (no solver re-runs).
`thesis_figures` is the dispatcher behind ``python -m harness plot --kind thesis``.
"""

from __future__ import annotations

import importlib
import pathlib

import pandas as pd

__all__ = ["NoFigurePlugin", "thesis_figures", "finish", "save_figure"]


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


def save_figure(fig, path: pathlib.Path, *, dpi: int = 120, tight: bool = True,
                svg: bool = False) -> list[pathlib.Path]:
    """Write ``fig`` as PNG at ``path`` (and as SVG beside it when ``svg``), close it, and return
    the paths.  The SVG carries no date and fixed ids, so the same runs draw the same bytes
    (PNG output of the Agg backend is deterministic already)."""
    import matplotlib.pyplot as plt

    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    kw = {"bbox_inches": "tight"} if tight else {}
    fig.savefig(path, dpi=dpi, **kw)
    paths = [path]
    if svg:
        with plt.rc_context({"svg.hashsalt": "haybench"}):
            fig.savefig(path.with_suffix(".svg"), metadata={"Date": None}, **kw)
        paths.append(path.with_suffix(".svg"))
    plt.close(fig)
    return paths


def finish(fig, title: str, path: pathlib.Path) -> list[pathlib.Path]:
    """Title, lay out, write (120 dpi) and close a plug-in's figure; returns ``[path]``."""
    fig.suptitle(title)
    fig.tight_layout()
    return save_figure(fig, path, tight=False)
