"""Fitting a lidar system to a measured overlap curve: the free scalars (paths of
:mod:`lidar_overlap.model.parameters`) by weighted least squares (``scipy.optimize.least_squares``,
trust-region reflective with bounds).

Model. Planned once, on the starting system: auto's choice (RT or FO, and RT's quadrature tolerance)
holds for the whole fit, so the model cannot switch between RT and FO while the parameters move (a
switch would put a step of the size of the model error into the cost). Each evaluation runs that
plan with the trial system.

Jacobian. Central differences with the step rule of :mod:`lidar_overlap.analysis.sensitivity` (h = s
(3 tolerance)^(1/3), s the parameter's natural scale); on ray tracing all 2 k shifted systems go
through one ``overlap_rt_batch`` call, so one Jacobian is one core call. The optimiser works on p /
s, so a tilt (1e-4 rad) and a defocus (1e-3 m) are of one order for it. (One-sided differences, k
curves instead of 2 k, were tried: the fits then stopped in worse valleys of real curves, the
PollyNET chain's default overlap curve (examples/data/pollynet_default_overlap.txt) at chi²/dof
3.9 instead of 0.89.)

Covariance. (Jᵀ J)⁻¹ of the sigma-normalised residuals at the solution (Gauss-Newton). With
``sigma=None`` the points have unit weights and the covariance is scaled by the reduced chi-square:
the noise is then estimated from the scatter of the residuals. With a robust loss it is the same
form with every point counted (outliers included): an approximation, on the large side.

Driver. :func:`solve` is shared by the fits (:func:`fit_local` here, the relative fit, the telecover
fit): each gives its :class:`FitProblem` and a :class:`Model` (its vector and Jacobian as functions
of a trial system); the optimiser, covariance, degeneracy warnings and convergence error are the
same. The optimiser stops when a step lowers the
cost by less than ``COST_TOLERANCE`` of it: gains below that are noise for any verdict on the fit.

Default bounds, natural scales: the parameter table (:mod:`lidar_overlap.model.parameters`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Optional, Tuple

import numpy as np

from ... import _checks
from ...forward.compute import run
from ...forward.planning import Plan, plan, resolve
from ...model import parameters as _parameters
from ...model.system import LidarSystem
from ..sensitivity import jacobian
from . import verdict
from .problem import FitProblem
from .result import DegeneracyWarning, FitResult, covariance, step_tolerance

#: |correlation| above which a pair of parameters is reported as degenerate.
DEGENERATE_CORRELATION = 0.95
#: The optimiser stops when a step lowers the cost by less than this fraction of it (scipy's ftol):
#: on a fit that reaches the noise (chi² ~ n) a step then gains less than 1e-5 n in chi², far below
#: its scatter sqrt(2 n) and any information criterion's resolution. scipy's default, 1e-8, let the
#: fits crawl along degenerate valleys (a tilt against a detector radius) for 100-180 Jacobians to
#: gain 0.1-0.5 in chi².
COST_TOLERANCE = 1e-5
#: A fitted value within this fraction of its bounds' width from one of them ends on that bound.
ON_BOUND = 1e-6
#: The model's tolerance must stay below this fraction of the median sigma (else it adds to the
#: noise).
TOLERANCE_FRACTION = 0.1


def fit_local(problem: FitProblem) -> FitResult:
    """:func:`lidar_overlap.fit` of absolute data from the start (no normalisation, no global
    search): the free scalars of ``problem`` by weighted least squares."""
    curve, paths = problem.curve, problem.paths
    p = fit_plan(problem, problem.start, curve.ranges)
    h_tolerance = step_tolerance(p, problem.tolerance)

    last = last_curve(p)

    def result(trial):
        c = last(trial)
        return c, c.overlap

    model = Model(
        evaluate=lambda trial: result(trial)[1],
        jacobian=lambda trial: jacobian(p, trial, paths, h_tolerance),
        result=result,
        target=curve.measured,
        weights=curve.sigma,
        sigma_given=curve.sigma_given,
        plan=p,
        step_tolerance=h_tolerance,
        tolerance=p.tolerance,
    )
    return solve(problem, model)


@dataclass(frozen=True, eq=False)
class Model:
    """What :func:`solve` fits: ``evaluate(system)`` -> the model vector, one entry per point of
    ``target``; ``jacobian(system)`` -> d(vector)/dp (point, path) per SI unit; ``result(system)``
    -> (the result kept as ``FitResult.result``, the vector). ``target``: the data the vector is
    fitted to, with 1-sigma ``weights`` (given by the caller when ``sigma_given``, else ones);
    ``independent``: the number of independent points (None: ``target.size``), which sets the
    degrees of freedom. ``plan`` and ``step_tolerance`` are kept by the FitResult; ``tolerance`` is
    the model's error on the vector (compared with sigma)."""

    evaluate: Callable[[LidarSystem], np.ndarray]
    jacobian: Callable[[LidarSystem], np.ndarray]
    result: Callable[[LidarSystem], Tuple[Any, np.ndarray]]
    target: np.ndarray
    weights: np.ndarray
    sigma_given: bool
    plan: Plan
    step_tolerance: float
    tolerance: float
    independent: Optional[int] = None


def last_curve(p) -> Callable:
    """``curve(trial)`` -> the result of plan ``p`` run on ``trial``, remembering the last one: the
    optimiser asks for the Jacobian where it has just evaluated the model, and a normalised model's
    Jacobian needs that curve again."""
    last: list = [None, None]

    def curve(trial):
        if last[0] is None or last[0] != trial:
            last[:] = [trial, run(p.with_system(trial))]
        return last[1]

    return curve


def solve(problem: FitProblem, model: Model) -> FitResult:
    """The least-squares driver shared by the fits: the free paths of ``problem`` (its start,
    bounds, loss, most evaluations, whether an unconverged result is returned) so that ``model``'s
    vector matches its target (module docstring)."""
    optimize = _scipy()
    system, paths, y, w = problem.start, problem.paths, model.target, model.weights
    sigma_given, loss = model.sigma_given, problem.loss
    max_evaluations, allow_unconverged = problem.max_evaluations, problem.allow_unconverged
    k = len(paths)
    n = y.size if model.independent is None else model.independent
    if n <= k:  # n == k leaves no degrees of freedom: chi²/dof would be 0/0
        kind = "" if model.independent is None else " independent"
        raise ValueError(
            f"measured has {n}{kind} points for {k} free parameters: expected more points than "
            "parameters; measure more ranges or free fewer"
        )
    start = np.array([_parameters.get(system, path) for path in paths])
    low, high = parameter_bounds(system, paths, start, problem.bounds)
    scale = np.array([_parameters.step_scale(system, path) for path in paths])
    tolerance = model.tolerance
    if sigma_given and math.isfinite(tolerance) and tolerance > TOLERANCE_FRACTION * np.median(w):
        _checks.warn(
            f"fit: the model's tolerance {tolerance:g} exceeds {TOLERANCE_FRACTION:g} x the median "
            f"sigma ({np.median(w):.3g}): its error adds to the noise; lower tolerance"
        )
    counts = {"model": 0, "jacobian": 0}

    def system_at(u):
        return _parameters.replace(system, dict(zip(paths, (u * scale).tolist())))

    def residuals(u):
        counts["model"] += 1
        return (model.evaluate(system_at(u)) - y) / w

    def normalised_jacobian(u):
        counts["jacobian"] += 1
        return model.jacobian(system_at(u)) * scale / w[:, None]

    solution = verdict.least_squares(
        optimize,
        residuals,
        start / scale,
        jac=normalised_jacobian,
        bounds=(low / scale, high / scale),
        method="trf",
        loss=loss,
        max_nfev=max_evaluations,
        ftol=COST_TOLERANCE,
    )
    converged = solution.status > 0
    if not converged and not allow_unconverged:
        raise RuntimeError(
            f"fit did not converge: {solution.message} (status {solution.status}, "
            f"{counts['model']} model evaluations, max_evaluations={max_evaluations}); raise "
            "max_evaluations, start closer, or pass allow_unconverged=True to get the last point"
        )
    result, vector = model.result(system_at(solution.x))
    counts["model"] += 1
    r = (vector - y) / w
    j = normalised_jacobian(solution.x) / scale  # per SI unit of each parameter
    with np.errstate(over="ignore", invalid="ignore"):
        chi_square, dof = float(r @ r), n - k
    cov, corr = parameter_covariance(j, chi_square, dof, sigma_given)
    sd = np.sqrt(np.diag(cov))
    pairs = degeneracies(paths, corr, sd)
    # A robust loss expects outliers, which the chi-square and the runs test would count as misfit.
    exact = loss == "linear" and verdict.check_quality("fit", r, y, w, dof, sigma_given, tolerance)
    noise = math.sqrt(chi_square / dof)
    if (
        not sigma_given
        and not exact
        and math.isfinite(tolerance)
        and tolerance > TOLERANCE_FRACTION * noise
    ):
        _checks.warn(
            f"fit: the model's tolerance {tolerance:g} exceeds {TOLERANCE_FRACTION:g} x the "
            f"scatter of the residuals ({noise:.3g}): its error adds to the noise; lower tolerance"
        )
    return FitResult(
        parameters={path: float(v) for path, v in zip(paths, solution.x * scale)},
        uncertainties={path: float(v) for path, v in zip(paths, sd)},
        start={path: float(v) for path, v in zip(paths, start)},
        covariance=cov,
        correlation=corr,
        residuals=r,
        chi_square=chi_square,
        reduced_chi_square=chi_square / dof,
        degrees_of_freedom=dof,
        result=result,
        measured=y,
        sigma=w if sigma_given else None,
        covariance_scaled=not sigma_given,
        degenerate_pairs=pairs,
        evaluations=counts["model"],
        jacobian_evaluations=counts["jacobian"],
        status=int(solution.status),
        message=str(solution.message),
        converged=bool(converged),
        loss=loss,
        plan=model.plan,
        step_tolerance=model.step_tolerance,
        at_bounds=on_bounds(paths, solution.x * scale, low, high),
    )


def on_bounds(names, values, low, high) -> Tuple[str, ...]:
    """The ``names`` whose fitted ``values`` end on their bound (within ``ON_BOUND`` of the
    interval's width): the data would take them further, so the bound, not the data, set them."""
    width = np.asarray(high) - np.asarray(low)
    x = np.asarray(values)
    near = (x - low <= ON_BOUND * width) | (high - x <= ON_BOUND * width)
    return tuple(name for name, hit in zip(names, near) if hit)


def parameter_covariance(j, chi_square: float, dof: int, sigma_given: bool):
    """(covariance, correlation) of the parameters from J (point, parameter) per SI unit at the
    solution: Gauss-Newton, scaled by chi²/dof without sigma (module docstring)."""
    with np.errstate(over="ignore", invalid="ignore"):
        unscaled = covariance(j, 1.0)
        # inf (singular J) stays inf when scaled by a zero chi-square (inf x 0 would be NaN)
        scale_by = chi_square / dof if not sigma_given else 1.0
        cov = np.where(np.isinf(unscaled), unscaled, unscaled * scale_by)
    verdict.check_usable("fit", chi_square, cov)
    unit_sd = np.sqrt(np.diag(unscaled))
    with np.errstate(invalid="ignore", divide="ignore"):
        # The correlation does not depend on the scale (so a zero-residual fit has one). Singular J
        # (infinite covariance): -cos of the angle between two columns is their correlation when
        # only they are free, and +-1 names the pair that cannot be told apart.
        corr = (
            unscaled / np.outer(unit_sd, unit_sd) if np.all(np.isfinite(unit_sd)) else -_cosines(j)
        )
        np.fill_diagonal(corr, 1.0)  # -cos gives -1 there
    return cov, corr


def degeneracies(paths, corr, sd) -> tuple:
    """The pairs (path, path, correlation) the data cannot tell apart, warned (with a singular
    Jacobian's infinite uncertainties) as a DegeneracyWarning."""
    k = len(paths)
    pairs = tuple(
        (paths[a], paths[b], float(corr[a, b]))
        for a in range(k)
        for b in range(a + 1, k)
        if abs(corr[a, b]) > DEGENERATE_CORRELATION
    )
    if pairs:
        _checks.warn(
            "fit: degenerate parameters, the data cannot tell them apart: "
            + ", ".join(f"{a} and {b} (correlation {c:+.3f})" for a, b, c in pairs)
            + "; fix one, or measure other ranges",
            DegeneracyWarning,
        )
    if not np.all(np.isfinite(sd)):
        _checks.warn(
            "fit: the Jacobian is singular at the solution, so the data do not constrain every "
            "free parameter (say a tilt at exactly 0 in a coaxial lidar, where G is even in it, or "
            "a beam tilt and a detector offset along one axis, which move the field of view "
            "alike); uncertainties are infinite",
            DegeneracyWarning,
        )
    return pairs


def _cosines(j: np.ndarray) -> np.ndarray:
    """Cosines of the angles between J's columns; 0 with a column of zeros (a parameter G does
    not depend on has no angle: 0/0 would be NaN)."""
    norms = np.linalg.norm(j, axis=0)
    outer = np.outer(norms, norms)
    cos = np.where(outer > 0, j.T @ j / np.where(outer > 0, outer, 1.0), 0.0)
    return np.clip(cos, -1.0, 1.0)


def _scipy():
    try:
        from scipy import optimize
    except ImportError:
        raise ImportError("lo.fit needs scipy: pip install 'lidar-overlap[fit]'") from None
    return optimize


def fit_plan(problem: FitProblem, system, ranges):
    """The plan every evaluation of a fit of ``problem`` runs on ``system`` (its start, or a part of
    it) at ``ranges``: made once, with every decision taken (auto's choice kept for the whole fit;
    no turbulence)."""
    method = problem.method
    shortcuts = {"tolerance": problem.tolerance} if isinstance(method, str) else {}
    return resolve(plan(system, ranges, method, threads=problem.threads, **shortcuts))


def parameter_bounds(system, paths, start, bounds):
    given = {}
    if bounds is not None:
        for key, value in bounds.items():
            keys = _parameters.expand([key]) if isinstance(key, str) else [key]
            for path in keys:
                if path not in paths:
                    raise ValueError(
                        f"bounds: {_checks.shown(key)} is not a free parameter: expected one of "
                        f"{', '.join(paths)}"
                    )
                given[path] = value
    low, high = np.empty(len(paths)), np.empty(len(paths))
    for i, (path, x0) in enumerate(zip(paths, start)):
        if path in given:
            lo, hi = _checks.pair(f"bounds[{path!r}]", given[path])
        else:
            lo, hi = _parameters.default_bounds(system, path, x0)
        if not lo < hi:
            raise ValueError(f"bounds[{path!r}] = ({lo:g}, {hi:g}) is invalid: expected low < high")
        if not lo <= x0 <= hi:
            raise ValueError(
                f"bounds[{path!r}] = ({lo:g}, {hi:g}) excludes the start {x0:g}: widen the bounds "
                "(given, or the system's fit_bounds) or start the system within them"
            )
        low[i], high[i] = lo, hi
    return low, high
