"""Figures of thesis Chapter 4 from stored rpr2 runs (matplotlib Agg, PNG).

Workspaces (Figs. 4.4, 4.9, 4.10, 4.12, 4.13) with kappa^-1 contours for P synthesis, and
convergence histories f against N^fg (Figs. 4.5-4.8, 4.11, 4.14).
"""

from __future__ import annotations

import json
import pathlib

import numpy as np
import pandas as pd

from harness._styles import solver_order, solver_styles
from harness.figures import save_figure

__all__ = ["figures"]


def _x(v):
    if isinstance(v, str):
        v = json.loads(v)
    return np.asarray(list(v) if v is not None else [], dtype=float)


def _hist(v):
    h = json.loads(v) if isinstance(v, str) else v
    return np.asarray(h, dtype=float).reshape(-1, 3) if h is not None and len(h) else np.zeros((0, 3))


def _draw_ws(ax, m, chord=0.1, **kw):
    if m is None:
        return
    ws = m.workspace(chord)
    if ws.n_boundary >= 3:
        b = np.vstack((ws.boundary, ws.boundary[:1]))
        ax.plot(b[:, 0], b[:, 1], **kw)


def _draw_p(ax, P, **kw):
    b = P.points(720)
    b = np.vstack((b, b[:1]))
    ax.plot(b[:, 0], b[:, 1], **{"color": "k", "lw": 1.6, **kw})


def _kinv_contours(ax, d):
    from manipulators.rpr2 import inverse_condition

    X, Y = np.meshgrid(np.linspace(-6, 6, 241), np.linspace(d[1], 9, 181))
    K = inverse_condition(d[0], d[1], d[2], np.column_stack((X.ravel(), Y.ravel()))).reshape(X.shape)
    cs = ax.contour(X, Y, K, levels=[0.2, 0.4, 0.6, 0.8, 0.9, 0.95], colors="0.6", linewidths=0.6)
    ax.clabel(cs, fontsize=6)


def _finish(fig, ax, path, title):
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=6, loc="upper right")
    return save_figure(fig, path)[0]


def figures(runs: pd.DataFrame, outdir: pathlib.Path) -> list[pathlib.Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from manipulators.prescribed import P1, PRESCRIBED
    from manipulators.synthesis.rpr2_suite import P_START, STARTS, design_o, design_p

    outdir = pathlib.Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    out: list[pathlib.Path] = []
    ok = runs[runs["status"] != "not_applicable"] if len(runs) else runs

    # Fig. 4.4: prescribed workspace and the starting designs' workspaces
    fig, ax = plt.subplots(figsize=(6, 5))
    _draw_p(ax, P1, label="P1")
    for sp, d in STARTS.items():
        _draw_ws(ax, design_o(d), 0.1, lw=0.8, label=sp)
    out.append(_finish(fig, ax, outdir / "fig_4_4_o_starts.png", "Fig. 4.4: P1 and the workspaces of SP1-SP4"))

    # Figs. 4.9 / 4.10: optimal O and E workspaces (best and worst of ours per problem)
    for prob, num, title in (("rpr2-o", "4_9", "O synthesis"), ("rpr2-e", "4_10", "E synthesis")):
        sub = ok[(ok["problem"] == prob)] if len(ok) else ok
        if not len(sub):
            continue
        fig, ax = plt.subplots(figsize=(6, 5))
        _draw_p(ax, P1, label="P1")
        sub = sub[np.isfinite(sub["f"].astype(float))].sort_values("f")
        # Fig. 4.10 is the thesis's Dynamic-Q designs from SP1-SP4 (E synthesis is Dynamic-Q only there)
        picks = (sub[sub["solver"] == "dynamic-q"].sort_values("start") if prob == "rpr2-e"
                 else pd.concat([sub.head(1), sub.tail(1)]))
        for _, r in picks.iterrows():
            x = _x(r["x"])
            if x.size == 5:
                _draw_ws(ax, design_o(x), 0.1, lw=0.8, label=f"{r['solver']} {r['start']} f={r['f']:.3f}")
        out.append(
            _finish(
                fig,
                ax,
                outdir / f"fig_{num}_{prob[-1]}_workspaces.png",
                f"Fig. {num.replace('_', '.')}: {title} optima",
            )
        )

    # Figs. 4.12 / 4.13: P synthesis workspaces with kappa^-1 contours (start and Dynamic-Q optima)
    fig, ax = plt.subplots(figsize=(6, 5))
    for P in PRESCRIBED.values():
        _draw_p(ax, P, lw=1.0, label=P.name)
    _draw_ws(ax, design_p(P_START), 0.1, color="C0", label="d0")
    _kinv_contours(ax, P_START)
    out.append(_finish(fig, ax, outdir / "fig_4_12a_p_start.png", "Fig. 4.12(a): P1-P3, d0 workspace, kappa^-1"))
    for name, P in PRESCRIBED.items():
        sub = ok[(ok["problem"] == f"rpr2-p{name[-1]}")] if len(ok) else ok
        if not len(sub):
            continue
        best = (
            sub[sub["solver"] == "dynamic-q"] if (sub["solver"] == "dynamic-q").any() else sub.sort_values("f").head(1)
        )
        x = _x(best.iloc[0]["x"])
        if x.size != 3:
            continue
        fig, ax = plt.subplots(figsize=(6, 5))
        _draw_p(ax, P, label=name)
        _draw_ws(ax, design_p(x), 0.1, color="C0", label=f"{best.iloc[0]['solver']} d*")
        _kinv_contours(ax, x)
        out.append(_finish(fig, ax, outdir / f"fig_4_13_p_{name.lower()}_optimum.png",
                           f"Figs. 4.12(b)/4.13: {name}, optimal workspace, kappa^-1"))

    # Convergence histories: Figs. 4.5-4.8 (O per start), 4.11 (E), 4.14 (P)
    groups: list[tuple[str, str | None, str]] = [("rpr2-o", sp, f"4_{5 + i}") for i, sp in enumerate(STARTS)]
    groups += [
        ("rpr2-e", None, "4_11"),
        ("rpr2-p1", None, "4_14a"),
        ("rpr2-p2", None, "4_14b"),
        ("rpr2-p3", None, "4_14c"),
    ]
    for prob, start, num in groups:
        sub = ok[(ok["problem"] == prob)] if len(ok) else ok
        if start is not None and len(sub):
            sub = sub[sub["start"] == start]
        if prob == "rpr2-e" and len(sub):  # Fig. 4.11: the thesis's Dynamic-Q histories from SP1-SP4
            sub = sub[sub["solver"] == "dynamic-q"].sort_values("start")
        if not len(sub):
            continue
        fig, ax = plt.subplots(figsize=(6, 4))
        look = solver_styles(sub["solver"])
        # one solver, several starts (Fig. 4.11): a colour per start instead
        by_start = start is None and sub["solver"].nunique() == 1
        sub = sub.assign(_order=[solver_order(v) for v in sub["solver"]]).sort_values(["_order", "start"])
        for k, (_, r) in enumerate(sub.iterrows()):
            h = _hist(r["history"])
            if h.shape[0]:
                y = -h[:, 1] if prob.startswith("rpr2-p") else h[:, 1]
                kw = {"color": f"C{k % 10}"} if by_start else look[r["solver"]]
                ax.plot(h[:, 0], y, lw=0.9, label=f"{r['solver']}" + ("" if start else f" {r['start']}"), **kw)
        ax.set_xlabel("N^fg")
        ax.set_ylabel("min kappa^-1" if prob.startswith("rpr2-p") else "f")
        ax.set_title(f"Fig. {num.replace('_', '.')}: convergence, {prob} {start or ''}", fontsize=9)
        ax.legend(fontsize=6)
        path = outdir / f"fig_{num}_{prob}{'_' + start if start else ''}_history.png"
        out += save_figure(fig, path)
    return out
