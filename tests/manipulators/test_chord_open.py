"""A chord trace that does not close is never silent: it warns (default), raises or passes
by ``on_open``, on every public workspace method and on `chord_boundary` itself."""

import warnings

import numpy as np
import pytest

from manipulators import RPR2, RPR3, chord_boundary
from manipulators.workspace import ChordError, OpenBoundary, OpenBoundaryWarning, Workspace, check_closed

# a chord far longer than the workspace: the trace is lost after its first point
RPR2_COARSE = (RPR2(-4.0, -0.1, 4.0, l_min=(4, 4), l_max=(7, 7)), 100.0)
RPR3_DESIGN = RPR3(-1, 0, 1, 2, 1)


def _disk(U):
    return (np.hypot(U[:, 0], U[:, 1]) - 1.0)[:, None]


def test_chord_boundary_warns_raises_or_ignores_an_open_trace():
    with pytest.warns(OpenBoundaryWarning, match=r"did not close: max_points = 5 reached"):
        ws = chord_boundary(_disk, (0.0, 0.0), 0.05, max_points=5)
    assert not ws.info["closed"] and ws.n_boundary == 5
    with pytest.raises(OpenBoundary, match="open polyline of 5 points"):
        chord_boundary(_disk, (0.0, 0.0), 0.05, max_points=5, on_open="raise")
    assert issubclass(OpenBoundary, ChordError)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ws = chord_boundary(_disk, (0.0, 0.0), 0.05, max_points=5, on_open="ignore")
        closed = chord_boundary(_disk, (0.0, 0.0), 0.05)  # a closed trace never warns
    assert not ws.info["closed"] and closed.info["closed"]
    assert abs(closed.area - np.pi) < 0.01


def test_rpr2_workspace_judges_the_last_refined_trace():
    m, chord = RPR2_COARSE
    with pytest.warns(OpenBoundaryWarning, match=r"chord d = 12.5, refined from 100.0"):
        ws = m.workspace(chord)
    assert ws.area == 0.0 and not ws.info["closed"]
    with pytest.raises(OpenBoundary):
        m.workspace(chord, on_open="raise")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m.workspace(chord, on_open="ignore")
        assert m.workspace(0.1).info["closed"]  # the refinement's open traces are not reported


@pytest.mark.parametrize("method, args", [("workspace", (0.0,)), ("dextrous_workspace", (-0.1, 0.1))])
def test_rpr3_workspaces_warn_or_raise(method, args):
    with pytest.warns(OpenBoundaryWarning, match="lost the boundary"):
        ws = getattr(RPR3_DESIGN, method)(*args, chord=2.0)
    assert not ws.info["closed"]
    with pytest.raises(OpenBoundary):
        getattr(RPR3_DESIGN, method)(*args, chord=2.0, on_open="raise")


@pytest.mark.parametrize("call", [
    lambda: RPR2_COARSE[0].workspace(0.1, on_open="quiet"),
    lambda: RPR3_DESIGN.workspace(0.0, on_open="quiet"),
    lambda: chord_boundary(_disk, (0.0, 0.0), 0.05, on_open="quiet"),
])
def test_unknown_policy_is_refused_before_tracing(call):
    with pytest.raises(ValueError, match=r"on_open must be one of \('warn', 'raise', 'ignore'\), got 'quiet'"):
        call()


def test_untraced_workspaces_pass_the_check():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_closed(Workspace.empty(reason="none"))
        check_closed(Workspace(boundary=[[0, 0], [1, 0], [0, 1]], method="grid"))
