"""``lo.fit_drift``: a series of curves of one instrument with a covariate per curve (its internal
temperature, the time): the fixed parameters shared by all curves, each drifting one linear in the
covariate, a + b (c - c_ref), with c_ref the covariate's mean (so a is the value at the series'
mean and a and b are nearly uncorrelated), or a natural cubic spline in it with the same a and b
(its value at c_ref and its mean slope over the span) and K - 2 more coefficients
(:mod:`lidar_overlap.analysis.fitting.drift_basis`). One fit of all curves
(:mod:`lidar_overlap.analysis.fitting.multi_curve`), one covariance.

``drifting="auto"``: forward selection by BIC = chi² + K ln n (n independent points of all curves):
from no drift, the free paths not yet drifting are ranked by the chi-square drop of one
Gauss-Newton step from the current solution with that path's slope freed as well (one Jacobian
ranks them all; a path held by its bound is not a candidate), the best is fitted (a local fit from
the current solution, its slope starting at 0) and taken when it lowers the BIC by more than
``BIC_TIE``, else the next best (``TRIED`` per round at most, and only while the one step's drop
exceeds the BIC's penalty); until none is taken. At most ``TRIED`` k local fits and k Jacobians for
k free paths. The drifts it chooses are linear; ask for a spline by name (a mapping).
``free="auto"``: the model ladder (``lo.fit(..., free="auto")``) on the series' median curve
chooses the family (its paths become ``free``) and its fit the start.
"""

from __future__ import annotations

import math
import warnings
from typing import List, Optional, Tuple

import numpy as np

from ... import _checks
from ...model import parameters as _parameters
from ...model.path_syntax import by_scalar
from .curve_set import CurveSet
from .drift_basis import DEFAULT_KNOTS, DriftBasis, checked_drifting, knots_at_quantiles
from .drift_inputs import (
    among_free,
    checked_covariate,
    checked_offsets,
    checked_series,
    checked_sigma,
)
from .drift_names import OFFSET, REFERENCE, SLOPE
from .drift_reference import checked_reference, reference_bounds, reference_state
from .drift_result import DriftFitResult
from .fit import fit as single_fit
from .ladder import BIC_TIE
from .multi_curve import CurveMap, MultiCurveFit, MultiCurveProblem, solve_curves
from .multi_inputs import (
    checked_bounds,
    checked_curve,
    checked_paths,
    is_interval,
    multi_settings,
    path_bounds,
    search_box,
)
from .multi_result import bic_of, fit_fields
from .multi_search import fit_curves
from .normalization import normalization
from .problem import GENERATIONS, MINIMA

#: drifting="auto" fits at most this many of the best-ranked candidates per round.
TRIED = 2


def fit_drift(
    system,
    ranges,
    curves,
    covariate,
    *,
    sigma,
    free,
    drifting,
    reference=None,
    reference_offsets=(),
    normalize=None,
    extinction_bias=False,
    method="auto",
    tolerance: Optional[float] = None,
    search: Optional[str] = None,
    seed: Optional[int] = None,
    bounds=None,
    covariate_unit: str = "K",
    spline_knots: int = DEFAULT_KNOTS,
    loss: str = "linear",
    max_evaluations: int = 200,
    allow_unconverged: bool = False,
    threads: int = 0,
    population: Optional[int] = None,
    generations: int = GENERATIONS,
    minima: int = MINIMA,
) -> DriftFitResult:
    """Fit a series of curves with parameters that drift with a covariate, linearly or as a
    spline (module docstring).

    system : the start (its values start every curve). ranges : m, strictly increasing, shared by
    the curves. curves : (n_curves, n_ranges), G or relative G, at least two. covariate : one
    finite value per curve, not all equal (in ``covariate_unit``, e.g. K). sigma : 1-sigma error:
    a scalar, one per range, or (n_curves, n_ranges); required. free : paths fitted (a list, or
    ``"auto"``: the model ladder on the median curve chooses them, its global searches run with
    this call's seed, population, generations and minima); drifting : those of them that drift
    (a list, possibly empty, each linear; a mapping {path: "linear" | "spline"}; or ``"auto"``,
    linear drifts chosen by BIC). spline_knots : the number of a spline drift's knots, at the
    covariate's quantiles (>= 3, at most the covariate's distinct values): K - 2 coefficients
    beyond the linear drift's.
    reference : None, or a curve on ``ranges`` (G, relative like the curves: the factory curve)
    the curves differ from by what the model changes: the differential anchor of
    :mod:`lidar_overlap.analysis.fitting.drift_reference`, one more coefficient (the covariate
    value c_ref of the reference, ``covariate@reference``); reference_offsets : free paths whose
    value at the reference also takes its own offset (``path@reference_offset``).
    normalize : None, "far" or (z_low, z_high) in m, for every curve; extinction_bias : each
    curve's retrieval extinction bias profiled (with an interval). bounds : {path: (low, high)}
    for the paths' values (the slopes' bounds: ± that width per covariate span). method,
    tolerance, loss, max_evaluations, allow_unconverged, threads, search, seed, population,
    generations, minima : as in :func:`lidar_overlap.fit`. Returns a :class:`DriftFitResult`.
    """
    if not isinstance(covariate_unit, str):
        raise ValueError(f"covariate_unit = {_checks.shown(covariate_unit)}: expected a text")
    z = _checks.ranges("ranges", ranges)
    y = checked_series(curves, z)
    c = checked_covariate(covariate, y.shape[0])
    anchor = None if reference is None else checked_reference(reference, z, extinction_bias)
    if anchor is not None and search not in (None, "local"):
        raise ValueError(
            f"search = {_checks.shown(search)} with a reference is not supported: expected None "
            "or 'local' (start from a fit of the reference, e.g. free='auto')"
        )
    w = checked_sigma(sigma, y.shape)
    if not is_interval(normalize):
        raise ValueError(
            f"normalize = {_checks.shown(normalize)} is invalid: expected None, 'far' or (z_low, "
            "z_high) in m, one for every curve"
        )
    data = tuple(
        checked_curve(i, z, y[i], w[i], normalize, extinction_bias) for i in range(y.shape[0])
    )
    if anchor is not None:  # normalised as the days are: its errors name it
        try:
            normalization(checked_curve(0, z, anchor, w[0], normalize, False).normalize, z,
                          anchor, w[0], False)  # fmt: skip
        except ValueError as exc:
            raise ValueError(
                f"reference: {exc}".replace("curves[0]: ", "").replace("curve 0: ", "")
            ) from None
    settings = multi_settings(
        system, data, method=method, tolerance=tolerance, loss=loss,
        max_evaluations=max_evaluations, allow_unconverged=allow_unconverged, threads=threads,
        search=search, seed=seed, population=population, generations=generations, minima=minima,
    )  # fmt: skip
    # the drifts' kinds and knots before any ladder runs (the ladder's system has the same paths)
    auto = isinstance(drifting, str) and drifting == "auto"
    moving, splines = ((), ()) if auto else checked_drifting(drifting, [system])
    knots = knots_at_quantiles(spline_knots, c, splines)
    if anchor is not None and splines:
        raise ValueError(
            f"drifting: {', '.join(splines)} as a spline with a reference is not supported: the "
            "reference's state is taken on a linear drift line; give linear drifts or no reference"
        )
    choices: List[str] = []
    chosen = isinstance(free, str) and free == "auto"
    if chosen:
        if anchor is None:  # the median curve, its error the median's
            shape, error, what = (
                np.median(y, axis=0),
                np.median(w, axis=0) / math.sqrt(len(y)),
                "median curve",
            )
        else:
            shape, error, what = anchor, np.median(w, axis=0), "reference"
        system, free, line = _ladder_start(
            system, z, shape, error, what, normalize, extinction_bias, settings, bounds
        )
        choices.append(line)
    paths = checked_paths("free", free, [system])
    among_free("drifting", moving, paths, "drifting paths")
    offsets = checked_offsets(reference_offsets, anchor, system, paths)
    pair = None if anchor is None else (anchor, offsets)
    if chosen and isinstance(bounds, dict):  # those of the family's paths (the ladder took all)
        bounds = {k: v for k, v in by_scalar("bounds", bounds, paths).items() if k in paths}
    given = checked_bounds(bounds, paths)
    settings = settings.derived(start=system, free=paths)
    basis = DriftBasis(moving, float(c.mean()), splines, knots)
    problem = drift_problem(settings, system, paths, moving, c, given, basis=basis, anchor=pair)
    if auto:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the model without drift: its BIC is its verdict
            fit = fit_curves(_quiet(problem))
        fit, moving = _select(fit, settings, system, paths, c, given, choices, pair)
    else:
        fit = fit_curves(problem)
    return drift_result(fit, paths, moving, c, covariate_unit, choices, z, splines, knots)


def drift_problem(
    settings, system, paths, moving, c, bounds, start=None, basis=None, anchor=None
) -> MultiCurveProblem:
    """The multi-curve problem of free ``paths``, ``moving`` of them drifting with ``c`` as
    ``basis`` says (None: each linear; module docstring); ``start`` {name: value} overrides the
    system's values (slopes: 0, the reference's covariate: the mean); ``anchor`` (reference curve,
    offset paths) or None (with a reference, drifts are linear)."""
    k = len(paths)
    basis = basis or DriftBasis(tuple(moving), float(c.mean()))
    names = list(paths) + basis.names
    if anchor is not None:
        names += [REFERENCE] + [p + OFFSET for p in anchor[1]]
    owners = [paths.index(p) for p in basis.owners]
    span = float(np.ptp(c))
    maps = []
    for row in basis.columns(c):
        m = np.zeros((k, len(names)))
        m[:, :k] = np.eye(k)
        m[owners, k + np.arange(len(owners))] = row
        maps.append(CurveMap(system, tuple(paths), m))
    x0, low, high, scale, s_low, s_high, logs = (np.zeros(len(names)) for _ in range(7))
    for a, path in enumerate(paths):
        x0[a] = _parameters.get(system, path)
        low[a], high[a] = path_bounds([system], path, bounds)
        scale[a] = _parameters.step_scale(system, path)
        s_low[a], s_high[a] = search_box(system, path, x0[a], low[a], high[a])
        logs[a] = _parameters.searched_in_log(path, s_low[a])
    for b, (a, name) in enumerate(zip(owners, basis.names), start=k):
        # a slope: ± the value's width per span; a spline's departure at a knot: ± that width
        per = span if name.endswith(SLOPE) else 1.0
        low[b], high[b] = -(high[a] - low[a]) / per, (high[a] - low[a]) / per
        s_low[b], s_high[b] = (
            -(s_high[a] - s_low[a]) / (2 * per),
            (s_high[a] - s_low[a]) / (2 * per),
        )
        scale[b] = scale[a] / per
    state = None
    if anchor is not None:
        reference_bounds(names, paths, anchor[1], c, x0, low, high, scale, s_low, s_high)
        state = reference_state(system, paths, names, moving, anchor[1], c, anchor[0])
    if start is not None:
        x0 = np.array([start.get(name, x0[i] if name == REFERENCE else 0.0)
                       for i, name in enumerate(names)])  # fmt: skip
    return MultiCurveProblem(
        settings, tuple(names), tuple(maps), x0, low, high, scale, s_low, s_high, logs.astype(bool),
        state,
    )  # fmt: skip


def _quiet(problem: MultiCurveProblem) -> MultiCurveProblem:
    settings = problem.settings.derived(allow_unconverged=True)
    return MultiCurveProblem(**{**problem.__dict__, "settings": settings})


def _select(
    fit, settings, system, paths, c, bounds, choices, anchor
) -> Tuple[MultiCurveFit, tuple]:
    """Forward selection of the drifting paths by BIC (module docstring): the chosen fit and its
    drifting paths."""
    moving: List[str] = []
    best, best_bic, said = fit, bic_of(fit), []
    choices.append(f"no drift: chi-square {fit.chi_square:.4g}, BIC {best_bic:.2f}")
    local = settings.derived(allow_unconverged=True)
    while len(moving) < len(paths):
        start = dict(zip(best.problem.names, best.values.tolist()))
        pinned = set(best.at_bounds)  # a value held by its bound cannot follow a drift
        drops = _linear_drops(local, system, paths, moving, c, bounds, start, anchor)
        ranked = sorted((q for q in drops if q not in pinned), key=lambda q: -drops[q])
        shown = ", ".join(f"{q} {drops[q]:.4g}" for q in ranked)
        choices.append(f"one step's chi-square drop per candidate (not on a bound): {shown}")
        penalty = math.log(best.degrees_of_freedom + len(best.values)) + BIC_TIE
        taken = None
        for p in ranked[:TRIED]:
            if not drops[p] > penalty:  # not even its linear step pays for the parameter
                break
            problem = drift_problem(
                local, system, paths, moving + [p], c, bounds, start, anchor=anchor
            )
            with warnings.catch_warnings(record=True) as record:
                warnings.simplefilter("always")  # said below for the chosen one only
                trial = solve_curves(problem)
            bic = bic_of(trial)
            choices.append(
                f"drifting {', '.join(moving + [p])}: chi-square {trial.chi_square:.4g}, BIC "
                f"{bic:.2f}"
            )
            if bic < best_bic - BIC_TIE:
                taken = (p, trial, bic, record)
                break
        if taken is None:
            break
        p, trial, bic, record = taken
        moving.append(p)
        best, best_bic, said = trial, bic, record
    choices.append(f"chosen: {', '.join(moving) if moving else 'no drift'} (BIC {best_bic:.2f})")
    if moving:  # the chosen model's verdicts and convergence, said once
        for item in said:
            warnings.warn_explicit(item.message, item.category, item.filename, item.lineno)
        if not best.converged and not settings.allow_unconverged:
            raise RuntimeError(
                f"fit did not converge: the drift fit with {', '.join(moving)} drifting stopped "
                f"short ({best.message}); raise max_evaluations or pass allow_unconverged=True"
            )
    return best, tuple(moving)


def _linear_drops(settings, system, paths, moving, c, bounds, start, anchor=None) -> dict:
    """{candidate: the chi-square drop of one Gauss-Newton step from the current solution with its
    slope freed as well, beyond the step's without it}: one Jacobian (all candidates' slope
    columns at once) ranks them."""
    candidates = [p for p in paths if p not in moving]
    problem = drift_problem(
        settings, system, paths, moving + candidates, c, bounds, start, anchor=anchor
    )
    model = CurveSet(problem)
    r = model.residuals(problem.start)
    j = model.jacobian(problem.start)
    names = problem.names
    current = [
        i for i, n in enumerate(names) if not n.endswith(SLOPE) or n[: -len(SLOPE)] in moving
    ]
    # the step without a new slope: what the current solution, short of its minimum along a
    # degenerate valley, would gain anyway (every candidate's drop counts from it)
    base = _step_drop(j[:, current], r)
    return {p: _step_drop(j[:, current + [names.index(p + SLOPE)]], r) - base for p in candidates}


def _step_drop(a, r) -> float:
    """The chi-square drop of the Gauss-Newton step in the columns ``a`` from residuals ``r``."""
    step = np.linalg.lstsq(a, -r, rcond=None)[0]
    after = r + a @ step
    return float(r @ r - after @ after)


def drift_result(
    fit: MultiCurveFit, paths, moving, c, unit: str, choices, z, splines=(), knots=None
) -> DriftFitResult:
    """The :class:`DriftFitResult` of the driver's fit of free ``paths``, ``moving`` of them
    drifting, ``splines`` of those on ``knots`` (the problem's names: those paths, then each
    drifting one's slope and a spline's departures at its knots, then the reference's), on
    ranges ``z``."""
    state = fit.problem.reference
    offsets = tuple(n[: -len(OFFSET)] for n in fit.problem.names if n.endswith(OFFSET))
    return DriftFitResult(
        reference=None if state is None else state.curve,
        reference_ranges=None if state is None else z,
        reference_offsets=offsets,
        **fit_fields(fit),
        free=tuple(paths),
        drifting=tuple(moving),
        covariate=c,
        covariate_reference=float(c.mean()),
        covariate_unit=unit,
        choices=tuple(choices),
        splines=tuple(splines),
        knots=np.empty(0) if knots is None else knots,
    )


def _ladder_start(system, z, y, w, what, normalize, extinction_bias, settings, bounds):
    """(the ladder's fitted system, its family's paths, a line saying so) on the curve ``y`` with
    1-sigma error ``w`` (``what``: the series' median curve or the reference), with
    the drift fit's method, tolerance, threads and search settings (seed, population, generations,
    minima: its families' global searches)."""
    search = settings.search
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the family's verdicts: the drift fit's own follow
        ladder = single_fit(
            system, z, y, w, free="auto", method=settings.method, tolerance=settings.tolerance,
            threads=settings.threads, normalize=normalize, extinction_bias=extinction_bias,
            seed=search.seed, population=search.population, generations=search.generations,
            minima=search.minima, bounds=bounds, allow_unconverged=True,
        )  # fmt: skip
    fit = ladder.chosen
    start = _parameters.replace(system, dict(fit.parameters))
    line = f"free='auto': family '{ladder.chosen_family.name}' chosen on the {what}"
    return start, tuple(fit.parameters), line
