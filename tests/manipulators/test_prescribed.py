"""Prescribed workspaces P1-P3 (eq. 4.11 as corrected, ellipse, eq. 4.25 / Table 4.8)."""

import numpy as np
import pytest

from manipulators.prescribed import P1, P2, P3, P3_ARCS, chapter5_workspaces, get_prescribed
from problems.reference import thesis_table


def test_p1_is_four_arcs_with_corners_at_pm1():
    corners = P1.points_at(np.pi / 4 * np.array([1, 3, 5, 7]))
    assert np.allclose(np.abs(corners - [0, 3]), 1.0, atol=1e-4)
    # convex (the printed cos^2 reading is not: r = 0.631 at pi/2, ERRATA)
    assert P1.radius(np.pi / 2) > 1.0
    assert P1.polygon().convex_hull.area == pytest.approx(P1.area(), rel=1e-6)


def test_p2_ellipse():
    assert P2.radius(0.0) == pytest.approx(1.75)
    assert P2.radius(np.pi / 2) == pytest.approx(1.0)
    assert P2.area() == pytest.approx(np.pi * 1.75, rel=1e-5)


def test_p3_arcs_join_continuously_and_match_table_4_8():
    t = thesis_table("table_4_8_P3_prescribed_workspace_arcs")
    for arc, row in zip(P3_ARCS, t.itertuples()):
        assert arc[2:5] == (float(row.dx), float(row.dy), float(row.R))
        assert arc[5] == (1 if row.sign_inferred == "+" else -1)
    eps = 1e-9
    for lo, *_ in P3_ARCS[1:]:
        assert abs(P3.radius(lo - eps) - P3.radius(lo + eps)) < 3e-3  # rounded table values
    assert P3.polygon().is_valid


def test_scaling_and_moving():
    q = P1.scaled(0.2).moved(to=(1.0, 1.5))
    assert q.centre == (1.0, 1.5)
    assert q.area() == pytest.approx(0.04 * P1.area(), rel=1e-9)
    about = P2.scaled(0.5, about=(0.0, 0.0))
    assert about.centre == (0.0, 1.5)
    assert np.allclose(P2.moved((1.0, -1.0)).points(8) - P2.points(8), [1.0, -1.0])
    c5 = chapter5_workspaces()
    assert c5["P3"].scale == pytest.approx(1 / 7) and c5["P1"].centre == (1.0, 1.5)
    with pytest.raises(ValueError):
        P1.moved()


def test_unknown_name():
    assert get_prescribed("p2") is P2
    with pytest.raises(KeyError, match="valid"):
        get_prescribed("P9")
