"""pytest-benchmark benchmarks of the spatial cable-robot workspace (disabled by default;
``python -m pytest tests/manipulators/test_benchmarks_spatial.py --benchmark-enable``).

The same 8-cable robot and load: the vectorized exact l1 feasibility on a 30^3 grid, and
the per-point LP path (one HiGHS LP per grid point through `solvers.convex`) on a 6^3
grid; the per-point cost ratio is the speed-up (docs/spatial.md).
"""

import itertools

import numpy as np
import pytest

from manipulators import SpatialCableRobot
from manipulators.spatial._cable import grid_points
from solvers.convex import solve_lp

CORNERS = np.array(list(itertools.product((-1.0, 1.0), repeat=3)))
W = np.array([0.0, 0.0, -10.0, 0.5, -0.3, 0.2])
BOX = [[-1.5] * 3, [1.5] * 3]


@pytest.fixture(scope="module")
def robot():
    rng = np.random.default_rng(7)
    frame = 2.0 * CORNERS + rng.normal(0, 0.15, (8, 3))
    plat = 0.2 * CORNERS[rng.permutation(8)] + rng.normal(0, 0.03, (8, 3))
    return SpatialCableRobot(frame, plat, t_min=1.0, t_max=120.0)


def test_grid_30_cubed_l1_vectorized(benchmark, robot):
    ws = benchmark(lambda: robot.workspace(np.zeros(3), W, BOX, resolution=30))
    assert ws.mask.size == 27_000 and 0 < ws.mask.sum() < 27_000


def test_grid_6_cubed_per_point_lp(benchmark, robot):
    _, pts = grid_points(BOX, 6)
    lb, ub = np.full(8, robot.t_min), np.full(8, robot.t_max)

    def per_point():
        return np.array([solve_lp(np.ones(8), robot.structure_matrix(p, np.zeros(3)), -W, lb, ub,
                                  backend="highs").feasible is True for p in pts])

    mask = benchmark(per_point)
    np.testing.assert_array_equal(mask, robot.workspace(np.zeros(3), W, BOX, resolution=6).mask.ravel())
