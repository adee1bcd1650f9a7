"""The two stages of a design search over free parameters within bounds: a full grid (G need not be
unimodal: a biaxial lidar, a plateau), then a local refine from its best point (bounded Brent for
one parameter, Nelder-Mead for several, COBYLA with constraints; scipy, the ``[fit]`` extra)."""

from __future__ import annotations

import itertools
import math

import numpy as np

from ...model.parameters import step_scale

#: Grid points over the bounds before the local refine: about this many in all, at most 33 per axis.
GRID_POINTS, MAX_AXIS_POINTS = 300, 33


def refine(score, x, lower, upper, cell, xtol, fatol, constraints=()):
    """A local search for the minimum of ``score`` (a function of a parameter vector) from ``x``,
    within the bounds; ``cell`` is the grid's spacing about ``x`` (the first step), ``xtol`` the
    step per parameter and ``fatol`` the score change below which it stops; ``constraints`` are
    functions that must stay >= 0. Bounded Brent for one parameter, Nelder-Mead for several, COBYLA
    with constraints (in coordinates scaled to the bounds, so one step size fits all parameters).
    Returns (x, scipy's result)."""
    so = _scipy_optimize()

    n, span = len(x), upper - lower
    u0 = (x - lower) / span
    if n == 1 and not constraints:
        lo, hi = max(lower[0], x[0] - cell[0]), min(upper[0], x[0] + cell[0])
        res = so.minimize_scalar(
            lambda t: score(np.array([t])),
            bounds=(lo, hi),
            method="bounded",
            options={"xatol": xtol[0]},
        )
        return np.array([res.x]), res

    def scaled(f):
        return lambda u: f(lower + u * span)

    if not constraints:
        simplex = np.vstack(
            [u0]
            + [
                np.clip(u0 + np.eye(n)[k] * cell[k] / span[k] * (1 if u0[k] < 0.5 else -1), 0, 1)
                for k in range(n)
            ]
        )
        res = so.minimize(
            scaled(score),
            u0,
            method="Nelder-Mead",
            bounds=[(0, 1)] * n,
            options={
                "initial_simplex": simplex,
                "xatol": float(np.min(xtol / span)),
                "fatol": fatol,
                "maxfev": 200 * n,
            },
        )
    else:
        res = so.minimize(
            scaled(score),
            u0,
            method="COBYLA",
            bounds=[(0, 1)] * n,
            constraints=[{"type": "ineq", "fun": scaled(c)} for c in constraints],
            options={
                "rhobeg": float(np.max(cell / span)),
                "tol": float(np.min(xtol / span)),
                "maxiter": 200 * n,
            },
        )
    return lower + res.x * span, res


def axis_points(n: int) -> int:
    """Grid points per axis for ``n`` free parameters: about GRID_POINTS in all, 3 to
    MAX_AXIS_POINTS each."""
    return int(min(MAX_AXIS_POINTS, max(3, math.floor(GRID_POINTS ** (1.0 / n) + 1e-9))))


def grid_points(lower: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """The full grid over the bounds (rows of values; the last axis fastest, as alignment_map orders
    it)."""
    axes = [np.linspace(lo, hi, axis_points(len(lower))) for lo, hi in zip(lower, upper)]
    return np.array(list(itertools.product(*axes)), dtype=float)


def refine_tolerance(problem) -> np.ndarray:
    """Per free path, the step below which G cannot tell two candidates apart: near a maximum G
    falls as (dx / s)² for a parameter of natural scale s
    (:func:`lidar_overlap.model.parameters.step_scale`), so by the quadrature tolerance at dx = s
    sqrt(tolerance). A path without a natural scale uses its bounds' span."""
    out = []
    for path, lo, hi in zip(problem.paths, problem.lower, problem.upper):
        try:
            s = step_scale(problem.system, path)
        except ValueError:
            s = hi - lo
        out.append(min(s, hi - lo) * math.sqrt(problem.plan.tolerance))
    return np.array(out)


def _scipy_optimize():
    try:
        from scipy import optimize
    except ImportError:
        raise ImportError("lo.optimize needs scipy: pip install 'lidar-overlap[fit]'") from None
    return optimize
