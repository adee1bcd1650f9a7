"""The search behind :class:`SmallestFieldOfView`: bisection on the detector radius, nested in a
grid and a local refine over the other free parameters.

Bisection is valid because every constraint is monotone in the radius: G at each range grows with it
(a larger detector disc about the same centre contains the smaller one). The radius is bisected to a
relative width of ``tolerance`` (RT's absolute tolerance on G: near the edge G changes by O(1) over
a relative change of O(1) of the radius, so narrower brackets would be decided by quadrature error).
Every grid point is bisected at once, each bisection step one parallel core call.
"""

from __future__ import annotations

import numpy as np

from .search import axis_points, grid_points, refine, refine_tolerance

RADIUS = "detector.radius"


def search(problem, start: np.ndarray):
    """(best values of the free paths, converged, message) for SmallestFieldOfView."""
    paths = problem.paths
    k = paths.index(RADIUS)
    others = [i for i in range(len(paths)) if i != k]

    def full(points: np.ndarray, radii: np.ndarray) -> np.ndarray:
        x = np.empty((len(points), len(paths)))
        x[:, others], x[:, k] = points, radii
        return x

    if not others:
        radius, _ = smallest(problem, np.empty((1, 0)), full)
        return full(np.empty((1, 0)), radius)[0], True, "bisection on the detector radius converged"
    lower, upper = problem.lower[others], problem.upper[others]
    grid = np.vstack([grid_points(lower, upper), start[others]])
    radii, _ = smallest(problem, grid, full)
    i = int(np.argmin(radii))

    def score(point):
        return float(smallest(problem, point[None, :], full)[0][0])

    sub = _Sub(problem, others)
    x, res = refine(
        score,
        grid[i],
        lower,
        upper,
        (upper - lower) / (axis_points(len(others)) - 1),
        refine_tolerance(sub),
        problem.upper[k] * problem.plan.tolerance,
    )
    radius = score(x)
    if not radius <= radii[i]:
        x, radius = grid[i], radii[i]
    return (
        full(x[None, :], np.array([radius]))[0],
        bool(res.success),
        str(getattr(res, "message", "")),
    )


def smallest(problem, points: np.ndarray, full):
    """The smallest feasible radius for each row of ``points`` (the other free parameters), and
    whether it was feasible at all. Where even the upper bound fails, the upper bound times (1 + the
    constraints' deficit), so an outer search still sees which way is better."""
    rk = problem.paths.index(RADIUS)
    m = len(points)
    lo, hi = np.full(m, problem.lower[rk]), np.full(m, problem.upper[rk])
    at_hi = problem.results(full(points, hi))
    ok_hi = np.array([problem.feasible(r) for r in at_hi])
    deficit = np.array(
        [max(0.0, -min(problem.objective.constraint_values(r).values())) for r in at_hi]
    )
    ok_lo = np.zeros(m, bool)
    if ok_hi.any():
        ok_lo[ok_hi] = [
            problem.feasible(r) for r in problem.results(full(points[ok_hi], lo[ok_hi]))
        ]
    active = ok_hi & ~ok_lo
    while True:
        active &= hi - lo > problem.plan.tolerance * hi
        if not active.any():
            break
        mid = 0.5 * (lo + hi)
        ok = np.array(
            [problem.feasible(r) for r in problem.results(full(points[active], mid[active]))]
        )
        idx = np.flatnonzero(active)
        hi[idx[ok]], lo[idx[~ok]] = mid[idx[ok]], mid[idx[~ok]]
    radius = np.where(ok_lo, lo, np.where(ok_hi, hi, problem.upper[rk] * (1.0 + deficit)))
    return radius, ok_hi


class _Sub:
    """The view of a problem on some of its free paths (for refine_tolerance)."""

    def __init__(self, problem, index):
        self.system, self.plan = problem.system, problem.plan
        self.paths = [problem.paths[i] for i in index]
        self.lower, self.upper = problem.lower[index], problem.upper[index]
