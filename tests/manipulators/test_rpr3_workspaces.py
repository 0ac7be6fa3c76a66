"""3-RPR workspaces by the chord method against exact (shapely) geometry.

Constant orientation (Section 5.4): the upper-branch component of the intersection of the
three leg annuli.  Dextrous (Algorithm 5.1): the intersection of 200 evenly spaced
constant-orientation slices.
"""

import math

import numpy as np
import pytest
import shapely

from manipulators import RPR3
from manipulators._rpr3_workspaces import EmptyWorkspace

QUAD = 1024  # shapely circle resolution (area error ~ 1e-6 relative)


def exact_constant_orientation(m, phi, upper=True, quad=QUAD):
    e = np.array([math.cos(phi), math.sin(phi)])
    sign = [-1.0, -1.0, 1.0]
    region = None
    for i in range(3):
        c = shapely.Point(m.base[i] - sign[i] * m.r * e)
        ann = c.buffer(m.lmax[i], quad_segs=quad).difference(c.buffer(m.lmin[i], quad_segs=quad))
        region = ann if region is None else region.intersection(ann)
    if upper:
        region = region.intersection(shapely.box(-50, m.yC, 50, 50))
    return region


def component_at(region, point):
    for g in getattr(region, "geoms", [region]):
        if g.area > 0 and g.buffer(1e-9).contains(shapely.Point(point)):
            return g
    raise AssertionError("no exact component contains the interior point")


RANDOM = [
    RPR3(*d) for d in np.random.default_rng(11).uniform([-1.2, -0.2, 0.6, 1.5, 0.5], [-0.8, 0.3, 1.3, 2.1, 1.0], (3, 5))
]
CASES = [(RPR3.named(n), p) for n in ("M1", "M2", "M3") for p in (-5.0, 0.0, 5.0)] + [
    (m, p) for m in RANDOM for p in (-4.0, 3.0)
]


@pytest.mark.parametrize("m,phi_deg", CASES)
def test_constant_orientation_workspace_exact(m, phi_deg):
    phi = math.radians(phi_deg)
    ws = m.workspace(phi, chord=0.02)
    assert ws.info["closed"] and ws.boundary.shape[0] > 20
    exact = component_at(exact_constant_orientation(m, phi), ws.info["interior"])
    assert ws.area == pytest.approx(exact.area, rel=5e-3)
    # every boundary point lies on the exact boundary: one constraint active, none violated
    C = m.constraints(ws.boundary, phi)
    assert np.all(C <= 1e-6)
    assert np.all(np.abs(C.max(axis=1)) <= 1e-6)
    # bifurcation points have two active constraints
    Cb = m.constraints(ws.bifurcations, phi)
    assert np.all(np.sort(np.abs(Cb), axis=1)[:, :2] <= 1e-6)


def exact_dextrous(m, a, b, n=200):
    region = None
    for phi in np.linspace(a, b, n):
        e = exact_constant_orientation(m, phi, quad=256)
        region = e if region is None else region.intersection(e)
    return region


@pytest.mark.parametrize("name", ["M1", "M2", "M3"])
@pytest.mark.parametrize("deg", [5.0, 10.0])
def test_dextrous_workspace_against_slices(name, deg):
    m = RPR3.named(name)
    a, b = math.radians(-deg), math.radians(deg)
    ws = m.dextrous_workspace(a, b, chord=0.02)
    assert ws.info["closed"]
    exact = component_at(exact_dextrous(m, a, b), ws.info["interior"])
    assert ws.area == pytest.approx(exact.area, rel=1e-2)
    C = m.dextrous_constraints(ws.boundary, a, b)
    assert np.all(C <= 1e-6) and np.all(np.abs(C.max(axis=1)) <= 1e-6)
    assert set(ws.info["bifurcation_types"]) <= {"I", "II"}
    assert len(ws.info["bifurcation_types"]) == ws.bifurcations.shape[0]


def test_dextrous_orientation_form_same_as_leg_form():
    """The thesis's c1, c2 form (5.30)-(5.31) traces the same workspace."""
    m = RPR3.named("M2")
    a, b = math.radians(-5), math.radians(5)
    w1 = m.dextrous_workspace(a, b, chord=0.05)
    w2 = m.dextrous_workspace(a, b, chord=0.05, constraints="orientation")
    assert w2.area == pytest.approx(w1.area, rel=2e-3)


def test_dextrous_zero_width_equals_constant_orientation():
    m = RPR3.named("M1")
    w0 = m.workspace(0.0, chord=0.02)
    wd = m.dextrous_workspace(0.0, 0.0, chord=0.02)
    assert wd.area == pytest.approx(w0.area, rel=1e-3)


def test_maximal_workspace_contains_constant_orientation_slices():
    m = RPR3.named("M3")
    wm = m.maximal_workspace(chord=0.05)
    assert wm.info["closed"]
    from manipulators.workspace import to_shapely

    pm = to_shapely(wm.boundary).buffer(0.01)
    for phi in (-0.2, 0.0, 0.2):
        assert pm.contains(to_shapely(m.workspace(phi, chord=0.05).boundary))


def test_empty_workspace_and_bad_input():
    far = RPR3(-10.0, 0.0, 10.0, 30.0, 0.5)
    with pytest.raises(EmptyWorkspace, match="empty"):
        far.workspace(0.0)
    m = RPR3.named("M1")
    with pytest.raises(ValueError, match="phi_min <= phi_max"):
        m.dextrous_workspace(0.2, 0.1)
    with pytest.raises(ValueError, match="finite"):
        m.workspace(float("nan"))


def test_benchmark_constant_orientation(benchmark):
    m = RPR3.named("M1")
    ws = benchmark(m.workspace, 0.0, 0.02)
    assert ws.info["closed"]


def test_benchmark_dextrous(benchmark):
    m = RPR3.named("M2")
    ws = benchmark(m.dextrous_workspace, math.radians(-5), math.radians(5), 0.02)
    assert ws.info["closed"]


def test_traces_are_simple_curves_at_sharp_corners():
    """The chord method's corner fix (docs/manipulators.md) for the 3-RPR: before it, 100 of
    445 constant-orientation traces and 14 of 50 dextrous traces of these random designs
    doubled back over a corner (self-overlapping boundary)."""
    rng = np.random.default_rng(2)
    n_co = n_dx = 0
    for k in range(60):
        d = [rng.uniform(-1.6, -0.4), rng.uniform(-0.2, 0.6), rng.uniform(0.5, 1.8), rng.uniform(1.2, 2.4),
             rng.uniform(0.4, 1.2)]
        m = RPR3(*d)
        try:
            ws = m.workspace(0.087 * (k % 3 - 1), chord=0.02)
        except EmptyWorkspace:
            continue
        if ws.n_boundary >= 3:
            n_co += 1
            assert shapely.LinearRing(ws.boundary).is_simple, d
        if k % 6 == 0:
            try:
                wd = m.dextrous_workspace(-0.087, 0.087, chord=0.02)
            except EmptyWorkspace:
                continue
            if wd.n_boundary >= 3:
                n_dx += 1
                assert shapely.LinearRing(wd.boundary).is_simple, d
    assert n_co > 40 and n_dx > 5
