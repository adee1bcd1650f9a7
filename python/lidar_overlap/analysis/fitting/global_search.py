"""``lo.fit(..., search="global")``: a seeded differential-evolution search over the bounds, each
generation's candidates in one batched core call, then the local least-squares fit from the best
distinct minima (the best becomes the result, with its covariance; the others are reported).

Why: the cost of an overlap fit is multimodal (a tilt that brings the beam into the field of view
from the other side, a defocus that trades against the detector radius), so a local fit from a
design value can stop in the wrong valley.

Search space. Tilt, offset and defocus are searched linearly, every other (positive) scalar in its
logarithm (a divergence between a tenth and ten times the start is as likely to be 3x smaller as 3x
larger): the parameter table's ``search`` (:mod:`lidar_overlap.model.parameters`). The bounds given
are searched whole. Without them the bounds are the fit's except the beam tilt: the start ±
``TILT_FIELDS`` half fields of view r_d / f (wider tilts put the beam out of the field of view at
every range, where the cost is flat and tells the search nothing), unless the start itself sees no
light at any fitted range: then the fit's bounds (±MAX_TILT). The report names the bounds searched,
which of them the search chose, and whether the start was dark.

Stop. After at most ``generations``, or when the population has gathered in one valley (every
unit-cube coordinate within ``SPREAD``), not when the candidates' costs agree: over a dark region
they agree from the first generation on.

Model. A fit planned on Fourier optics of a system ray tracing models (auto's choice for a receiver
whose diffraction matters) compares its candidates and polishes its minima on ray tracing at the
fit's tolerance, a generation then being one batched call instead of one FO curve per candidate;
the best minimum is then polished on the fit's own plan, which gives the result.

Candidates. scipy's ``differential_evolution`` (``vectorized=True``, ``updating="deferred"``), its
first population a Latin hypercube with the start as one member (a good start is never lost), so a
generation is one call of :func:`lidar_overlap.analysis.batch_curves.curves`. The minima: every
candidate evaluated is kept; the best one, then the next best whose coordinates (scaled to the unit
cube) differ from every one kept by more than ``DISTINCT`` in some parameter, up to ``minima`` of
them; each is polished by the local fit.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass
from typing import Any, Dict, List, Tuple

import numpy as np

from ...forward.methods import RT
from ...model import parameters as _parameters
from ..batch_curves import curves, variants
from .global_result import SearchMinimum, SearchReport, with_search
from .normalization import extended_plan, normalization
from .problem import Curve, FitProblem, Search
from .relative import polish
from .solve import fit_plan, parameter_bounds

#: Two candidates are distinct minima when some unit-cube coordinate differs by more than this.
DISTINCT = 0.1
#: Default population: this many candidates per free parameter (at least MIN_POPULATION).
POPULATION_PER_PARAMETER, MIN_POPULATION = 5, 15
#: The search stops before its most generations (:data:`.problem.GENERATIONS` by default) when the
#: population has gathered in one valley: every unit-cube coordinate of its members within SPREAD
#: (half the distance of distinct minima; the polish finds the valley's bottom). Not when their
#: costs agree: over a dark region (no candidate's beam in the field of view) they agree at once.
SPREAD = DISTINCT / 2
#: The search compares candidates on at most this many of the measured ranges (evenly thinned: a
#: valley's place does not need every point, its polish uses them all).
SEARCH_POINTS = 60


def fit_global(problem: FitProblem):
    """The global fit of ``problem`` (module docstring), its search as ``problem.search`` says
    (``population`` candidates per generation, at most ``generations``, ``minima`` distinct
    candidates polished, >= 1; those that end in one valley are reported once). Returns a
    ``GlobalFitResult`` (or ``GlobalRelativeFitResult`` with a normalised curve): the best local fit
    and its ``search`` report (candidates, generations, core calls, and every distinct polished
    minimum with its chi-square)."""
    system, paths, curve, settings = problem.start, problem.paths, problem.curve, problem.search
    searched = ray_traced(problem)
    norm, p = thinned(fit_plan(searched, system, curve.ranges), curve)
    start = np.array([_parameters.get(system, path) for path in paths])
    dark = not np.any(curves(p, [system])[0][: norm.ranges.size] > 0)
    box = search_bounds(system, paths, start, problem.bounds, dark)
    low, high = parameter_bounds(system, paths, start, box)
    logs = np.array([_parameters.searched_in_log(path, lo) for path, lo in zip(paths, low)])
    cube = UnitCube(low, high, logs)

    def cost(x):  # parameter values (S, k) -> each candidate's cost
        return norm.whitened_cost(curves(p, variants(system, paths, x)))

    solution, u_all, c_all, calls = population_search(cost, cube, start, settings)
    a, b, values = cube.a, cube.b, cube.values
    starts = distinct_minima(u_all, c_all, settings.minima)
    given = {path: (float(lo), float(hi)) for path, lo, hi in zip(paths, low, high)}
    fits, caught = [], []
    for i in starts:
        trial = _parameters.replace(system, dict(zip(paths, values(u_all[i][None])[0].tolist())))
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            local = polish(searched.derived(start=trial, bounds=given, allow_unconverged=True))
        fits.append((local, float(c_all[i])))
        caught.append(record)
    order = _distinct_fits(fits, paths, a, b, logs)
    best, record = fits[order[0]][0], caught[order[0]]
    refined = 0
    if searched is not problem:  # the best valley, polished on the fit's own model
        trial = _parameters.replace(system, best.parameters)
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            best = polish(problem.derived(start=trial, bounds=given, allow_unconverged=True))
        refined = best.evaluations
    for item in record:
        warnings.warn_explicit(item.message, item.category, item.filename, item.lineno)
    if not best.converged and not problem.allow_unconverged:
        raise RuntimeError(
            "fit did not converge: the local fit from the global search's best candidate stopped "
            f"short ({best.message}); raise max_evaluations or pass allow_unconverged=True"
        )
    report = SearchReport(
        method="differential evolution"
        + ("" if searched is problem else ", candidates ray traced (the best refined on FO)"),
        seed=settings.seed,
        population=int(np.asarray(solution.population).shape[0]),
        generations=int(solution.nit),
        candidates=int(c_all.size),
        core_calls=calls,
        local_evaluations=sum(f.evaluations for f, _ in fits) + refined,
        minima=tuple(
            SearchMinimum(f.parameters, f.chi_square, candidate, f.converged, f.evaluations)
            for f, candidate in (fits[j] for j in order)
        ),
        bounds={path: given[path] for path in paths},
        chosen=tuple(path for path in paths if not _named(path, problem.bounds)),
        dark_start=dark,
    )
    evaluations = int(c_all.size) + sum(f.evaluations for f, _ in fits) + refined
    return with_search(best, report, evaluations)


def ray_traced(problem: FitProblem) -> FitProblem:
    """The problem the search and the polish of its candidates run: ``problem`` itself, or the same
    on ray tracing at its tolerance when its plan is Fourier optics of a system ray tracing models
    (a valley's place does not need diffraction's percent of G, and a generation is then one
    batched call; the best valley is then polished on the plan's own model)."""
    if fit_plan(problem, problem.start, problem.curve.ranges).method != "fo":
        return problem
    traced = problem.derived(method=RT(tolerance=problem.tolerance))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # RT's validity: the refinement on FO answers it
            plan = fit_plan(traced, problem.start, problem.curve.ranges)
    except ValueError:  # a system only Fourier optics models
        return problem
    return traced if plan.method == "rt" else problem


@dataclass(frozen=True, eq=False)
class UnitCube:
    """The search space as the unit cube: parameter bounds ``low``, ``high`` (k,), each taken in its
    logarithm where ``logs`` (module docstring); ``a``, ``b`` the ends of each axis (a value or its
    logarithm)."""

    low: np.ndarray
    high: np.ndarray
    logs: np.ndarray

    @property
    def a(self) -> np.ndarray:
        return np.where(self.logs, np.log(np.where(self.logs, self.low, 1.0)), self.low)

    @property
    def b(self) -> np.ndarray:
        return np.where(self.logs, np.log(np.where(self.logs, self.high, 1.0)), self.high)

    def values(self, u):
        """Unit-cube points (S, k) -> parameter values, within the bounds (exp(log(high)) may
        exceed high by a rounding: a start on a bound, a preset's, stays on it)."""
        x = self.a + u * (self.b - self.a)
        return np.clip(
            np.where(self.logs, np.exp(np.where(self.logs, x, 0.0)), x), self.low, self.high
        )

    def unit(self, x):
        """Parameter values (k,) -> their unit-cube point, clipped to the cube."""
        a, b = self.a, self.b
        return np.clip((np.where(self.logs, np.log(np.abs(x) + (x == 0)), x) - a) / (b - a), 0, 1)


def population_search(cost, cube: UnitCube, start, settings: Search):
    """Differential evolution over ``cube`` (module docstring) with the candidates' ``cost(values)``
    ((S, k) parameter values -> (S,) costs, one batched evaluation per generation), ``start`` one
    member of the first population. Returns (scipy's solution, every candidate evaluated (unit
    cube), their costs, the number of cost calls)."""
    optimize = _scipy()
    k = cube.low.size
    population = settings.population or max(MIN_POPULATION, POPULATION_PER_PARAMETER * k)
    seen_u, seen_cost, calls = [], [], [0]

    def unit_cost(u_columns):  # scipy passes (k, S)
        u = np.atleast_2d(np.asarray(u_columns, dtype=float).T)
        c = cost(cube.values(u))
        calls[0] += 1
        seen_u.append(u)
        seen_cost.append(c)
        return c

    def gathered(intermediate_result) -> bool:  # scipy's population, in the unit cube
        return bool(np.all(np.ptp(intermediate_result.population, axis=0) <= SPREAD))

    solution = optimize.differential_evolution(
        unit_cost,
        [(0.0, 1.0)] * k,
        popsize=max(1, math.ceil(population / k)),
        maxiter=settings.generations,
        # scipy's own test (the costs' spread below atol + tol x their mean) never passes: the
        # population's spread decides, in gathered
        tol=0.0,
        atol=-math.inf,
        callback=gathered,
        seed=settings.seed,
        polish=False,
        init="latinhypercube",
        x0=cube.unit(np.asarray(start, dtype=float)),
        updating="deferred",
        vectorized=True,
    )
    return solution, np.vstack(seen_u), np.concatenate(seen_cost), calls[0]


def thinned(p0, curve: Curve):
    """(Normalization, plan) of the search: on every j-th measured range so that at most
    SEARCH_POINTS remain (all of them when thinning would leave fewer than 2 in the interval)."""
    y, w, normalize, bias = curve.measured, curve.sigma, curve.normalize, curve.extinction_bias
    step = max(1, math.ceil(y.size / SEARCH_POINTS))
    keep = np.unique(np.append(np.arange(0, y.size, step), y.size - 1))
    if keep.size == y.size:
        norm = normalization(normalize, p0.ranges, y, w, bias)
        return norm, extended_plan(p0, norm)
    normalization(normalize, p0.ranges, y, w, bias)  # the argument's errors name the data as given
    try:
        norm = normalization(normalize, p0.ranges[keep], y[keep], w[keep], bias)
    except ValueError:
        keep = np.arange(y.size)
        norm = normalization(normalize, p0.ranges, y, w, bias)
    p = dataclasses.replace(p0, ranges=p0.ranges[keep]) if keep.size < y.size else p0
    return norm, extended_plan(p, norm)


def search_bounds(
    system, paths, start, bounds, dark: bool = False
) -> Dict[str, Tuple[float, float]]:
    """The bounds the search uses: those given, else the parameter table's search box where it has
    one (the tilt: start ± TILT_FIELDS r_d / f, within the fit's ±MAX_TILT), else the fit's
    defaults. From a ``dark`` start (its model zero at every fitted range) no box about it: the
    fit's defaults, since no candidate near a start that sees no light tells the search anything."""
    out = dict(bounds or {})
    for path, x0 in zip(paths, start):
        if not dark and not _named(path, out) and _parameters.describe(path).search_bounds:
            out[path] = _parameters.search_bounds(system, path, x0)
    return out


def _named(path: str, bounds) -> bool:
    """Whether ``bounds`` (as given to the fit) name ``path``, or the pair it belongs to."""
    return bool(bounds) and (path in bounds or path.split("[")[0] in bounds)


def _distinct_fits(fits, paths, a, b, logs) -> list:
    """Indices of the polished fits, best first, without those that ended within DISTINCT / 10 (unit
    cube) of a better one: two candidates of one valley are one minimum."""
    kept: List[Any] = []
    for j in sorted(range(len(fits)), key=lambda j: fits[j][0].chi_square):
        x = np.array([fits[j][0].parameters[path] for path in paths])
        u = (np.where(logs, np.log(np.abs(x) + (x == 0)), x) - a) / (b - a)
        if all(np.max(np.abs(u - v)) > DISTINCT / 10 for _, v in kept):
            kept.append((j, u))
    return [j for j, _ in kept]


def distinct_minima(u: np.ndarray, cost: np.ndarray, count: int) -> list:
    """Indices of up to ``count`` candidates, best first, each differing from every earlier one by
    more than DISTINCT in some unit-cube coordinate (finite costs only)."""
    chosen: List[int] = []
    for i in np.argsort(cost, kind="stable"):
        if not math.isfinite(cost[i]):
            break
        if all(np.max(np.abs(u[i] - u[j])) > DISTINCT for j in chosen):
            chosen.append(int(i))
            if len(chosen) == count:
                break
    if not chosen:
        raise ValueError(
            "search: every candidate's model vanishes where the data are normalised or leaves the "
            "model's range; widen or move the bounds"
        )
    return chosen


def _scipy():
    try:
        from scipy import optimize
    except ImportError:
        raise ImportError("lo.fit needs scipy: pip install 'lidar-overlap[fit]'") from None
    return optimize
