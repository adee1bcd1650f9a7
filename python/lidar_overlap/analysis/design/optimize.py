"""Design optimisation: the values of free parameters that answer a design question
(:mod:`lidar_overlap.analysis.design.objectives`).

Search. Every candidate is ray traced at the objective's ranges; many candidates at once go through
one parallel core call (an alignment grid for one or two tilts, offsets or defocus, else
``overlap_rt_batch``). A grid over the bounds comes first (G need not be unimodal: a biaxial lidar,
a plateau), then a local refine from its best point:
``scipy.optimize.minimize_scalar(method="bounded")`` for one parameter, Nelder-Mead with bounds for
several, COBYLA when a generic objective has constraints. :class:`SmallestFieldOfView` minimises the
detector radius by bisection, valid because G grows with the radius at every range (the objective's
docstring), for each grid point of the other free parameters at once, then refines those others.

A target no candidate within the bounds meets is a ValueError that says so, with the best value
found; a search that stops on its evaluation budget returns ``converged=False`` with scipy's
message.
"""

from __future__ import annotations

import dataclasses
import itertools
from typing import ClassVar, Dict, List, Mapping, Optional, Sequence

import numpy as np

from ... import _checks, _values
from ..._pickling import ByValue
from ...forward.backends import many
from ...forward.compute import run
from ...forward.planning import plan
from ...forward.result import OverlapResult
from ...forward.validity import warn_if_rt_invalid
from ...model import parameters as _parameters
from ...model.system import LidarSystem
from ..method_choice import ray_tracing, requested
from .alignment import AXES
from .objectives import MaximumOverlapAt, Objective, SmallestFieldOfView
from .search import axis_points, grid_points, refine, refine_tolerance
from .smallest_fov import search as smallest_fov_search

#: Most free parameters (a grid of 3 per axis then has 729 points).
MAX_FREE = 6
_PATH_OF_AXIS = {path: name for name, (path, _) in AXES.items()}


@dataclasses.dataclass(frozen=True, eq=False)
class OptimizeResult(ByValue):
    """The answer of :func:`optimize`.

    Attributes
    ----------
    values : best value of each free parameter path (SI units).
    objective : the objective's value there, in ``unit`` (the radius for SmallestFieldOfView, G for
        MaximumOverlapAt).
    constraints : each constraint's value there (>= 0: met).
    system : the optimised system; result : its OverlapResult (at ``ranges``, else the objective's).
    evaluations : candidate systems ray traced; core_calls : the parallel calls they took.
    converged : the search reached its tolerance; message : how it ended.
    """

    values: Dict[str, float]
    objective: float
    unit: str
    constraints: Dict[str, float]
    system: LidarSystem
    result: OverlapResult
    evaluations: int
    core_calls: int
    converged: bool
    message: str

    FIELDS: ClassVar = {
        "values": _values.reals(),
        "objective": _values.real(),
        "unit": _values.text,
        "constraints": _values.reals(),
        "evaluations": _values.count(0),
        "core_calls": _values.count(0),
        "converged": _values.flag,
        "message": _values.text,
    }

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        if not isinstance(self.system, LidarSystem) or not isinstance(self.result, OverlapResult):
            raise ValueError(
                "system and result are invalid: expected the optimised LidarSystem and its "
                "OverlapResult"
            )


class Problem:
    """Candidates of one search (rows of values of the free paths), ray traced and counted."""

    def __init__(self, system, objective, paths, lower, upper, model, ranges):
        self.system, self.objective, self.paths = system, objective, paths
        self.lower, self.upper = lower, upper
        self.plan = plan(system, ranges, model)
        if not self.plan.batched:
            raise ValueError(
                f"optimize ray traces the plain receiver; this system needs {self.plan.backend!r} "
                "(receiver aberrations or a mask), which has no batched core call yet"
            )
        self.constrained = isinstance(objective, Objective) and bool(objective.constraints)
        self.evaluations = self.core_calls = 0

    def results(self, x: np.ndarray) -> List[OverlapResult]:
        """The OverlapResult of each row of ``x`` (m x free), in one parallel core call."""
        x = np.atleast_2d(x)
        systems = [
            _parameters.replace(self.system, dict(zip(self.paths, map(float, row)))) for row in x
        ]
        p = self.plan
        axes = [_PATH_OF_AXIS.get(path) for path in self.paths]
        if None not in axes and len(axes) <= 2 and len(x) > 1 and _is_grid(x):
            base = [_parameters.get(self.system, path) for path in self.paths]
            grid = [(a, np.unique(x[:, i]) - base[i]) for i, a in enumerate(axes)]
            mapped = many.grid(p, grid)
            shape = (len(x), p.ranges.size)
            curves = many.Curves(
                mapped.overlap.reshape(shape),
                mapped.error_estimate.reshape(shape),
                mapped.converged.reshape(shape),
            )
        else:
            curves = many.systems(p, systems)
        self.evaluations += len(x)
        self.core_calls += 1
        return many.results(p, systems, curves)

    def feasible(self, r: OverlapResult) -> bool:
        return all(v >= 0 for v in self.objective.constraint_values(r).values())


def optimize(
    system,
    objective,
    free,
    bounds,
    *,
    method="rt",
    tolerance: Optional[float] = None,
    ranges=None,
    x0=None,
) -> OptimizeResult:
    """The values of the ``free`` parameter paths (:mod:`lidar_overlap.model.parameters`;
    ``"beam.tilt"`` stands for both components) within ``bounds`` that answer ``objective``
    (:class:`SmallestFieldOfView`, :class:`MaximumOverlapAt` or :class:`Objective`).

    Parameters
    ----------
    bounds : one (low, high) per free path in order, or a mapping path -> (low, high) (SI units).
    method : ``"rt"`` or an :class:`lidar_overlap.RT`; tolerance : RT's absolute tolerance on each G
        (None: RT's default).
    ranges : m, where the returned ``result`` is computed (default: the objective's ranges); for an
        :class:`Objective` without ranges of its own, also where each candidate is evaluated.
    x0 : the start (mapping or sequence; default the system's values), which must lie within the
        bounds.
    """
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
    if not isinstance(objective, (SmallestFieldOfView, MaximumOverlapAt, Objective)):
        raise ValueError(
            f"objective = {_checks.shown(objective)} is invalid: expected SmallestFieldOfView, "
            "MaximumOverlapAt or Objective"
        )
    paths = _parameters.expand(free)
    if not 1 <= len(paths) <= MAX_FREE:
        raise ValueError(
            f"free = {_checks.shown(free)} is invalid: expected 1 to {MAX_FREE} parameter paths"
        )
    if isinstance(objective, SmallestFieldOfView) and "detector.radius" not in paths:
        raise ValueError(
            f"free = {paths!r} is invalid for SmallestFieldOfView: it minimises detector.radius, "
            "which must be one of the free parameters"
        )
    lower, upper = _bounds(paths, bounds)
    start = _start(system, paths, x0, lower, upper)
    if tolerance is not None:
        _checks.tolerance("tolerance", tolerance)
    model = ray_tracing(
        requested(method, tolerance),
        "for optimize: its candidates are ray traced in parallel batches; use method='rt'",
    )
    eval_ranges = objective.ranges if objective.ranges is not None else ranges
    if eval_ranges is None:
        raise ValueError(
            "ranges is required: the Objective has no ranges of its own to evaluate G at"
        )
    problem = Problem(system, objective, paths, lower, upper, model, eval_ranges)
    search = smallest_fov_search if isinstance(objective, SmallestFieldOfView) else _search
    best, converged, message = search(problem, start)
    best = np.clip(best, lower, upper)
    best_result = problem.results(best)[0]
    if not problem.feasible(best_result):
        raise ValueError(
            f"objective {type(objective).__name__} is unreachable within the bounds: the best "
            f"candidate found, {_shown(paths, best)}, has constraints "
            f"{_rounded(objective.constraint_values(best_result))} (each must be >= 0)"
        )
    optimised = best_result.system
    assert optimised is not None  # a candidate's result carries its system
    if (
        ranges is None
    ):  # candidates at the bounds may leave RT's validity; only the answer's is said
        warn_if_rt_invalid(optimised, problem.plan.ranges)
    out = best_result if ranges is None else run(plan(optimised, ranges, model))
    return OptimizeResult(
        values=dict(zip(paths, map(float, best))),
        objective=objective.value(best_result),
        unit=objective.unit,
        constraints=objective.constraint_values(best_result),
        system=optimised,
        result=out,
        evaluations=problem.evaluations,
        core_calls=problem.core_calls,
        converged=converged,
        message=message,
    )


def _search(problem: Problem, start: np.ndarray):
    """A grid in one core call and the start, then a local refine from the best feasible point."""
    n = len(problem.paths)
    grid = np.vstack([grid_points(problem.lower, problem.upper), start])
    results = problem.results(grid[:-1]) + problem.results(grid[-1:])
    scores = np.array(
        [problem.objective.score(r) if problem.feasible(r) else np.inf for r in results]
    )
    i = int(np.argmin(scores)) if np.isfinite(scores).any() else len(grid) - 1
    cell = (problem.upper - problem.lower) / (axis_points(n) - 1)
    cache: Dict[tuple, OverlapResult] = {}

    def evaluate(x):
        key = tuple(np.round(x, 15))
        if key not in cache:
            cache[key] = problem.results(np.clip(x, problem.lower, problem.upper))[0]
        return cache[key]

    def score(x):
        return problem.objective.score(evaluate(x))

    constraints = [
        lambda x, k=k: problem.objective.constraint_values(evaluate(x))[k]
        for k in (problem.objective.constraints if problem.constrained else ())
    ]
    x, res = refine(
        score,
        grid[i],
        problem.lower,
        problem.upper,
        cell,
        refine_tolerance(problem),
        problem.plan.tolerance,
        constraints,
    )
    # keep the grid's best if the refine did not improve on it (a plateau, or noise at the
    # tolerance)
    if not (problem.feasible(evaluate(x)) and score(x) <= scores[i]):
        x = grid[i]
    return (
        np.clip(x, problem.lower, problem.upper),
        bool(res.success),
        str(getattr(res, "message", "")),
    )


def _is_grid(x: np.ndarray) -> bool:
    """Whether the rows of ``x`` are exactly the full grid of their unique values per column, in
    product order."""
    axes = [np.unique(x[:, i]) for i in range(x.shape[1])]
    return len(x) == int(np.prod([a.size for a in axes])) and np.array_equal(
        x, np.array(list(itertools.product(*axes)), dtype=float)
    )


def _bounds(paths: List[str], bounds):
    """(lower, upper) arrays, one per path, finite with low < high; refused naming the path
    otherwise."""
    if isinstance(bounds, Mapping):
        given = {}
        for key, pair in bounds.items():
            for path in _parameters.expand([key]):
                given[path] = pair
        unknown = [k for k in given if k not in paths]
        missing = [p for p in paths if p not in given]
        if unknown or missing:
            raise ValueError(
                f"bounds is invalid: {'no free parameter ' + ', '.join(unknown) if unknown else ''}"
                f"{'; ' if unknown and missing else ''}"
                f"{'no bounds for ' + ', '.join(missing) if missing else ''}"
            )
        pairs = [given[p] for p in paths]
    elif _listlike(bounds, len(paths)):
        pairs = list(bounds)
    else:
        raise ValueError(
            f"bounds = {_checks.shown(bounds)} is invalid: expected one (low, high) pair per free "
            f"parameter ({', '.join(paths)}) or a mapping path -> (low, high)"
        )
    lower, upper = [], []
    for path, pair in zip(paths, pairs):
        lo, hi = _checks.pair(f"bounds[{path!r}]", pair)
        if not lo < hi:
            raise ValueError(f"bounds[{path!r}] = ({lo:g}, {hi:g}) is invalid: expected low < high")
        lower.append(lo)
        upper.append(hi)
    return np.array(lower), np.array(upper)


def _start(system, paths, x0, lower, upper) -> np.ndarray:
    """The start: x0 (mapping or sequence) or the system's values, each within its bounds."""
    if x0 is None:
        values = [_parameters.get(system, p) for p in paths]
    elif isinstance(x0, Mapping):
        values = [x0[p] if p in x0 else _parameters.get(system, p) for p in paths]
        unknown = [k for k in x0 if k not in paths]
        if unknown:
            raise ValueError(
                f"x0 is invalid: {', '.join(map(str, unknown))} is not a free parameter"
            )
    elif _listlike(x0, len(paths)):
        values = list(x0)
    else:
        raise ValueError(
            f"x0 = {_checks.shown(x0)} is invalid: expected one value per free parameter "
            f"({', '.join(paths)}) or a mapping path -> value"
        )
    out = np.array([_checks.real(f"x0[{p!r}]", v) for p, v in zip(paths, values)])
    if not np.isfinite(out).all():
        p = paths[int(np.argmin(np.isfinite(out)))]
        raise ValueError(f"x0[{p!r}] is invalid: expected a finite value")
    for p, v, lo, hi in zip(paths, out, lower, upper):
        if not lo <= v <= hi:
            raise ValueError(
                f"bounds[{p!r}] = ({lo:g}, {hi:g}) excludes the start {p} = {v:g} (x0, else the "
                "system's value): widen the bounds or give x0 inside them"
            )
    return out


def _listlike(value, n: int) -> bool:
    """A list, tuple or array of ``n`` items (a string is not)."""
    return (
        (isinstance(value, Sequence) and not isinstance(value, str))
        or (isinstance(value, np.ndarray) and value.ndim >= 1)
    ) and len(value) == n


def _shown(paths: Sequence[str], x: np.ndarray) -> str:
    return ", ".join(f"{p} = {v:.6g}" for p, v in zip(paths, x))


def _rounded(values: Mapping[str, float]) -> str:
    return "{" + ", ".join(f"{k}: {v:.4g}" for k, v in values.items()) + "}"
