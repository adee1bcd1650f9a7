"""Fits to relative overlap curves (``lo.fit(..., normalize=...)``): the model and the data each
normalised (:mod:`lidar_overlap.analysis.fitting.normalization`: the whitening of the normalised
data, the retrieval's extinction bias profiled out), then the least-squares driver shared by every
fit (:func:`lidar_overlap.analysis.fitting.solve.solve`); and :func:`polish`, the local fit of a
problem, relative or absolute."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ... import _checks
from ..sensitivity import jacobian
from .normalization import Normalization, bias_covariance, extended_plan, normalization
from .problem import FitProblem
from .relative_result import RelativeFitResult
from .result import FitResult, step_tolerance
from .solve import Model, fit_local, fit_plan, last_curve, solve


def polish(problem: FitProblem) -> FitResult:
    """The local fit of ``problem`` from its start: relative when its curve is normalised, else
    absolute."""
    return fit_local(problem) if problem.curve.normalize is None else fit_relative(problem)


def fit_relative(problem: FitProblem) -> RelativeFitResult:
    """:func:`lidar_overlap.fit` of ``problem`` (its curve normalised)."""
    curve, paths = problem.curve, problem.paths
    p0 = fit_plan(problem, problem.start, curve.ranges)
    norm = normalization(
        curve.normalize, p0.ranges, curve.measured, curve.sigma, curve.extinction_bias
    )
    p, h_tolerance = extended_plan(p0, norm), step_tolerance(p0, problem.tolerance)
    white = norm.whitening

    last = last_curve(p)
    parts: list = [None]  # the bias split of the last Jacobian (the solution's, after the solve)

    def result(trial):
        c = last(trial)
        return c, white @ norm.model(c.overlap)

    def model_jacobian(trial):
        g = last(trial).overlap  # the curve the optimiser has just evaluated
        j = jacobian(p, trial, paths, h_tolerance)
        if norm.trend is not None:
            parts[0] = norm.bias_parts(g, j)
        return white @ norm.model_jacobian(g, j)

    model = Model(
        evaluate=lambda trial: result(trial)[1],
        jacobian=model_jacobian,
        result=result,
        target=white @ norm.data,
        weights=np.ones(white.shape[0]),
        sigma_given=curve.sigma_given,
        plan=p,
        step_tolerance=h_tolerance,
        tolerance=p.tolerance,
        # δα takes a degree of freedom
        independent=None if norm.trend is None else white.shape[0] - 1,
    )
    return relative_result(problem, solve(problem, model), norm, parts[0])


def relative_result(problem: FitProblem, raw, norm: Normalization, parts=None) -> RelativeFitResult:
    """The :class:`RelativeFitResult` of a solve on the whitened problem: chi-square and the
    covariance as solved; residuals, measured and sigma per measured range on the normalised scale
    (for plots and tables); with a trend, δα and its uncertainty from ``parts`` (the
    :meth:`Normalization.bias_parts` at the solution)."""
    sigma_given = problem.curve.sigma_given
    g = raw.result.overlap
    model = norm.model(g)
    residuals = (model - norm.data) / (norm.sigma if sigma_given else 1.0)
    fields = {f.name: getattr(raw, f.name) for f in dataclasses.fields(raw)}
    fields.update(
        residuals=residuals,
        measured=norm.data,
        sigma=norm.sigma if sigma_given else None,
        normalize=norm.kind if norm.kind != "interval" else norm.interval,
        normalizing_ranges=(
            norm.ranges[norm.inside] if norm.kind == "interval" else norm.extra_ranges
        ),
        model_scale=float(norm.scale(g)),
        data_scale=norm.data_scale,
        fitted=model,
    )
    if norm.trend is not None and parts is not None:
        bias, jp, ja = parts
        scale = raw.reduced_chi_square if raw.covariance_scaled else 1.0
        variance, cross = bias_covariance(norm, jp, ja, raw.covariance, scale)
        if abs(bias) >= norm.trend.bound:
            _checks.warn(
                f"fit: extinction_bias {bias:.3g} /m rests on its bound ±{norm.trend.bound:g} /m: "
                "the trend in the data is larger than an extinction error explains; its "
                "uncertainty is that of a free parameter there"
            )
        fields.update(
            extinction_bias=bias,
            # unbounded (inf) where the covariance is: as the warning of a singular fit says
            extinction_bias_uncertainty=math.sqrt(variance) if variance >= 0 else math.inf,
            extinction_bias_reference=norm.trend.reference,
            extinction_bias_covariance=cross,
        )
    return RelativeFitResult(**fields)
