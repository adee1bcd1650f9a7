"""One driver for fits of several curves at once: ``lo.fit_joint`` (channels that share the optics)
and ``lo.fit_drift`` (days that share all but what drifts) are this driver with different parameter
maps.

Parameter map. The fit's vector θ (K global parameters) sets each curve's system linearly: curve i's
free scalars (``CurveMap.paths``) are ``CurveMap.matrix`` @ θ. A parameter shared by all curves is a
column with a 1 in every curve's row of that path; a per-curve one a column with a single 1; a
linear drift a + b (c_i - c_ref) two columns, 1 and c_i - c_ref. The chain rule then gives the
Jacobian in θ from each curve's own Jacobian (J_i M_i).

Residuals. Each curve is compared as a single fit compares it
(:mod:`lidar_overlap.analysis.fitting.normalization`): its own system, normalisation, sigma and
whitening, its own retrieval extinction bias profiled out; the whitened residuals of all curves are
stacked and solved by the least-squares driver's optimiser, scaling and checks
(:mod:`lidar_overlap.analysis.fitting.solve`), so one covariance holds every parameter. Curves that
share a start system and ranges are evaluated together: one batched core call for the curves, one
for all their Jacobians (on ray tracing; :mod:`lidar_overlap.analysis.fitting.curve_set`).

Search. ``search="global"``: :mod:`lidar_overlap.analysis.fitting.multi_search`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any, Optional, Tuple

import numpy as np

from ... import _checks
from ...forward.compute import run
from ...model import parameters as _parameters
from . import verdict
from .curve_set import CurveSet
from .drift_reference import ReferenceState
from .global_result import SearchReport
from .problem import FitProblem
from .relative import relative_result
from .result import FitResult
from .solve import (
    COST_TOLERANCE,
    DEGENERATE_CORRELATION,
    TOLERANCE_FRACTION,
    degeneracies,
    on_bounds,
    parameter_covariance,
)


@dataclass(frozen=True, eq=False)
class CurveMap:
    """How θ sets one curve's system: its start ``system``, the scalar ``paths`` θ sets, and
    ``matrix`` (len(paths), K): their values are ``matrix`` @ θ."""

    system: Any
    paths: Tuple[str, ...]
    matrix: np.ndarray

    def at(self, theta):
        """The curve's system at θ."""
        values = (self.matrix @ np.asarray(theta, dtype=float)).tolist()
        return _parameters.replace(self.system, dict(zip(self.paths, values)))


@dataclass(frozen=True, eq=False)
class MultiCurveProblem:
    """A fit of several curves: ``settings`` (a :class:`FitProblem` holding the curves and the
    method, tolerance, loss, evaluations and search), the global ``names``, one :class:`CurveMap`
    per curve, θ's ``start``, bounds ``low`` and ``high``, natural ``scale`` and, for a search,
    its box (``search_low``, ``search_high``) and which parameters it takes in their logarithm;
    ``reference``: a drift fit's reference state (:mod:`.drift_reference`), whose normalised model
    less the reference curve every curve's residual subtracts (None: no reference)."""

    settings: FitProblem
    names: Tuple[str, ...]
    maps: Tuple[CurveMap, ...]
    start: np.ndarray
    low: np.ndarray
    high: np.ndarray
    scale: np.ndarray
    search_low: np.ndarray
    search_high: np.ndarray
    logs: np.ndarray
    reference: Optional[ReferenceState] = None


@dataclass(frozen=True, eq=False)
class MultiCurveFit:
    """What the driver found: θ (``values``), its ``covariance``, ``correlation`` and
    ``uncertainties``; ``chi_square`` over all curves and its ``degrees_of_freedom`` (independent
    points of all curves - K); one :class:`FitResult` per curve (``fits``: its own paths, their
    covariance M C Mᵀ, its residuals and fitted curve); ``degenerate_pairs``, ``at_bounds``,
    model and Jacobian ``evaluations``, the optimiser's ``status``, ``message``, ``converged``;
    ``search`` (the global search's report, or None)."""

    problem: MultiCurveProblem
    values: np.ndarray
    covariance: np.ndarray
    correlation: np.ndarray
    uncertainties: np.ndarray
    chi_square: float
    degrees_of_freedom: int
    fits: Tuple[FitResult, ...]
    degenerate_pairs: Tuple[Tuple[str, str, float], ...]
    at_bounds: Tuple[str, ...]
    evaluations: int
    jacobian_evaluations: int
    status: int
    message: str
    converged: bool
    search: Optional[SearchReport] = None


def solve_curves(problem: MultiCurveProblem) -> MultiCurveFit:
    """The local fit of ``problem`` from its start (module docstring)."""
    try:
        from scipy import optimize
    except ImportError:
        raise ImportError("lo.fit_joint needs scipy: pip install 'lidar-overlap[fit]'") from None
    settings, names, scale = problem.settings, problem.names, problem.scale
    model = CurveSet(problem)
    counts = {"model": 0, "jacobian": 0}
    k = len(names)
    n = sum(model.independent())
    if n <= k:
        raise ValueError(
            f"curves hold {n} independent points for {k} parameters: expected more points than "
            "parameters; measure more ranges or free fewer"
        )
    sigmas = np.concatenate([c.sigma for c in settings.curves])
    tolerance = min(p.tolerance for p in model.base)
    if math.isfinite(tolerance) and tolerance > TOLERANCE_FRACTION * np.median(sigmas):
        _checks.warn(
            f"fit: the model's tolerance {tolerance:g} exceeds {TOLERANCE_FRACTION:g} x the median "
            f"sigma ({np.median(sigmas):.3g}): its error adds to the noise; lower tolerance"
        )

    def residuals(u):
        counts["model"] += 1
        return model.residuals(u * scale)

    def jacobian(u):
        counts["jacobian"] += 1
        return model.jacobian(u * scale) * scale

    solution = verdict.least_squares(
        optimize,
        residuals,
        problem.start / scale,
        jac=jacobian,
        bounds=(problem.low / scale, problem.high / scale),
        method="trf",
        loss=settings.loss,
        max_nfev=settings.max_evaluations,
        ftol=COST_TOLERANCE,
    )
    converged = solution.status > 0
    if not converged and not settings.allow_unconverged:
        raise RuntimeError(
            f"fit did not converge: {solution.message} (status {solution.status}, "
            f"{counts['model']} model evaluations, max_evaluations={settings.max_evaluations}); "
            "raise max_evaluations, start closer, or pass allow_unconverged=True"
        )
    theta = solution.x * scale
    local: list = []
    r = model.residuals(theta)
    j = model.jacobian(theta, local)
    with np.errstate(over="ignore", invalid="ignore"):
        chi_square, dof = float(r @ r), n - k
    # in the solver's units (θ / scale): in SI units a drift's slope column is the covariate's
    # spread times its value's (1e9 for seconds over years), past the SVD's rank tolerance
    scaled, corr = parameter_covariance(j * scale, chi_square, dof, True)
    with np.errstate(over="ignore", invalid="ignore"):
        cov = scaled * np.outer(scale, scale)
    sd = np.sqrt(np.diag(cov))
    pairs = degeneracies(list(names), corr, sd)
    if settings.loss == "linear":
        verdict.check_quality("fit", r, r, np.ones_like(r), dof, True, tolerance)
    fits = _curve_fits(problem, model, theta, cov, local, counts, solution)
    return MultiCurveFit(
        problem=problem,
        values=theta,
        covariance=cov,
        correlation=corr,
        uncertainties=sd,
        chi_square=chi_square,
        degrees_of_freedom=dof,
        fits=fits,
        degenerate_pairs=pairs,
        at_bounds=on_bounds(names, theta, problem.low, problem.high),
        evaluations=counts["model"] + 1,
        jacobian_evaluations=counts["jacobian"],
        status=int(solution.status),
        message=str(solution.message),
        converged=bool(converged),
    )


def _curve_fits(problem, model: CurveSet, theta, cov, local, counts, solution) -> tuple:
    """One FitResult per curve: its paths at θ, their covariance M C Mᵀ, its residuals; its degrees
    of freedom its independent points less the parameters only it sets."""
    settings, maps = problem.settings, problem.maps
    systems, _ = model.at(theta)
    own = [int(np.sum((np.abs(m.matrix).sum(axis=0) > 0) & (_users(maps) == 1))) for m in maps]
    out = []
    for i, (m, curve, norm) in enumerate(zip(maps, settings.curves, model.norms)):
        p = model.plans[i]
        kept = run(p.with_system(systems[i]))
        c_local = mapped_covariance(m.matrix, cov)
        sd = np.sqrt(np.diag(c_local))
        with np.errstate(invalid="ignore", divide="ignore"):
            corr = c_local / np.outer(sd, sd)
        np.fill_diagonal(corr, 1.0)
        shift = model.reference_term(theta)
        r = norm.whitening @ (norm.model(kept.overlap) - norm.data - shift)
        chi = float(r @ r)
        dof = max(model.independent()[i] - own[i], 0)
        paths = list(m.paths)
        raw = FitResult(
            parameters=dict(zip(paths, (m.matrix @ theta).tolist())),
            uncertainties=dict(zip(paths, sd.tolist())),
            start=dict(zip(paths, (m.matrix @ problem.start).tolist())),
            covariance=c_local,
            correlation=corr,
            residuals=r,
            chi_square=chi,
            reduced_chi_square=reduced(chi, dof),
            degrees_of_freedom=dof,
            result=kept,
            measured=norm.whitening @ norm.data,
            sigma=np.ones(r.size),
            covariance_scaled=False,
            degenerate_pairs=tuple(
                (paths[a], paths[b], float(corr[a, b]))
                for a in range(len(paths))
                for b in range(a + 1, len(paths))
                if abs(corr[a, b]) > DEGENERATE_CORRELATION
            ),
            evaluations=counts["model"] + 1,
            jacobian_evaluations=counts["jacobian"],
            status=int(solution.status),
            message=str(solution.message),
            converged=bool(solution.status > 0),
            loss=settings.loss,
            plan=p,
            step_tolerance=model.steps[i],
        )
        if curve.normalize is None:
            raw = _absolute(raw, curve)
            out.append(raw)
            continue
        parts = norm.bias_parts(kept.overlap, local[i]) if norm.trend is not None else None
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # a δα on its bound: said by the joint result
            out.append(relative_result(settings.derived(curves=(curve,)), raw, norm, parts))
    return tuple(out)


def mapped_covariance(matrix: np.ndarray, cov: np.ndarray) -> np.ndarray:
    """``matrix`` @ ``cov`` @ ``matrix``ᵀ with the terms of zero weight left out: a parameter the
    data leave unconstrained (infinite variance) makes infinite only the values that use it, not
    NaN (0 x inf) every value of the curve; a sum of unconstrained terms (inf - inf) is one too."""
    weights = matrix[:, None, :, None] * matrix[None, :, None, :]  # (P, P, K, K)
    with np.errstate(invalid="ignore"):
        terms = np.where(weights != 0.0, weights * cov[None, None], 0.0)
        out = terms.sum(axis=(2, 3))
    return np.where(np.isnan(out), np.inf, out)


def _absolute(raw: FitResult, curve) -> FitResult:
    """A curve's result on the scale of its absolute data: residuals (G - y) / sigma."""
    import dataclasses

    g = raw.result.overlap[: curve.measured.size]
    return dataclasses.replace(
        raw,
        residuals=(g - curve.measured) / curve.sigma,
        measured=curve.measured,
        sigma=curve.sigma,
    )


def _users(maps) -> np.ndarray:
    """How many curves each global parameter sets."""
    return np.sum([np.abs(m.matrix).sum(axis=0) > 0 for m in maps], axis=0)


def reduced(chi_square: float, dof: int) -> float:
    """chi²/dof, NaN without degrees of freedom."""
    return chi_square / dof if dof else math.nan
