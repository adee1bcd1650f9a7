"""Fits to relative overlap curves: data normalised to about 1 in the far range, as overlap curves
retrieved from real signals are (the Raman or near/far method gives G only up to a factor).

``normalize=(z_low, z_high)``: the model and the data are each divided by their own mean over the
measured ranges in [z_low, z_high], so the fit compares shapes and no scale is fitted.
``normalize="far"``: the model is divided by its far-range limit, G at ``FAR_FACTOR`` x the last
measured range; the data are taken as they are (already normalised to their far level).

Covariance. Dividing the data by their own mean Ȳ correlates the points: to first order ỹ = A y with
A = (I - ỹ e_Iᵀ / n_I) / Ȳ (e_I marks the n_I points of the interval), so cov(ỹ) = A diag(σ²) Aᵀ. It
has rank n - 1: the mean of ỹ over the interval is exactly 1, and so is the normalised model's, so
the residual has no component along e_I. The fit minimises rᵀ C⁺ r (C⁺ the pseudo-inverse) by
whitening: r is mapped to W r with Wᵀ W = C⁺ (W has n - 1 rows), and the fit's degrees of freedom
are n - 1 - k. ``"far"`` leaves the points independent (W = 1/σ). The Jacobian of the normalised
model follows from the quotient rule, so the covariance of the parameters is the Gauss-Newton one of
the normalised problem (:mod:`lidar_overlap.analysis.fit`).
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from .. import _checks
from .fit_result import step_tolerance
from .fit_solve import (
    Model,
    fit_plan,
    free_paths,
    last_curve,
    measured_values,
    sigma_weights,
    solve,
)
from .relative_result import RelativeFitResult
from .sensitivity import jacobian

#: normalize="far" divides by G at this multiple of the last measured range.
FAR_FACTOR = 100.0
#: Eigenvalues of cov(ỹ) below this fraction of the largest are its null direction (dropped).
RANK_TOLERANCE = 1e-12
#: The fewest measured points an interval must hold.
MIN_INTERVAL_POINTS = 2


@dataclass(frozen=True, eq=False)
class Normalization:
    """How model and data are normalised (module docstring). ``kind``: ``"interval"``, ``"far"`` or
    ``"none"``; ``extra_ranges``: ranges (m) the model needs beyond the measured ones (the far
    point); ``inside``: the measured points in the interval; ``data``, ``sigma``: the normalised
    data and their 1-sigma errors; ``data_scale``: Ȳ (1 for "far" and "none"); ``whitening``: W,
    (rows, n)."""

    kind: str
    interval: Optional[Tuple[float, float]]
    ranges: np.ndarray
    extra_ranges: np.ndarray
    inside: np.ndarray
    data: np.ndarray
    sigma: np.ndarray
    data_scale: float
    whitening: np.ndarray

    @property
    def model_ranges(self) -> np.ndarray:
        """Where the model is computed: the measured ranges, then ``extra_ranges``."""
        return np.concatenate([self.ranges, self.extra_ranges])

    def scale(self, g):
        """The model's normaliser for curves ``g`` (..., model_ranges): mean over the interval, G at
        the far point, or 1."""
        g = np.asarray(g)
        n = self.ranges.size
        if self.kind == "interval":
            return g[..., :n][..., self.inside].mean(axis=-1)
        if self.kind == "far":
            return g[..., n]
        return np.ones(g.shape[:-1])

    def model(self, g):
        """The normalised model at the measured ranges for curves ``g`` (..., model_ranges)."""
        g = np.asarray(g)
        with np.errstate(divide="ignore", invalid="ignore"):
            return g[..., : self.ranges.size] / self.scale(g)[..., None]

    def model_jacobian(self, g, j):
        """d(normalised model)/dp, (n, k), from the curve ``g`` and its Jacobian ``j``
        (model_ranges, k): the quotient rule."""
        n, s = self.ranges.size, self.scale(g)
        if self.kind == "none":
            return j[:n]
        ds = j[:n][self.inside].mean(axis=0) if self.kind == "interval" else j[n]
        return j[:n] / s - np.outer(g[:n], ds) / s**2

    def whitened_cost(self, g) -> np.ndarray:
        """rᵀ C⁺ r of curves ``g`` (S, model_ranges): the cost of each candidate (inf where the
        model vanishes over the interval or at the far point)."""
        with np.errstate(invalid="ignore", over="ignore"):
            r = (self.model(g) - self.data) @ self.whitening.T
            cost = np.einsum("...i,...i->...", r, r)
        return np.where(np.isfinite(cost), cost, np.inf)


def normalization(normalize, ranges, measured, sigma) -> Normalization:
    """The :class:`Normalization` for ``normalize`` (None, ``"far"`` or (z_low, z_high) in m) of
    data ``measured`` at ``ranges`` with errors ``sigma`` (one per point); ValueError naming
    ``normalize`` and its valid range otherwise."""
    z = np.asarray(ranges, dtype=float)
    y = np.asarray(measured, dtype=float)
    w = np.asarray(sigma, dtype=float)
    if normalize is None:
        return Normalization(
            "none", None, z, np.empty(0), np.zeros(z.size, bool), y, w, 1.0, np.diag(1.0 / w)
        )
    if isinstance(normalize, str):
        if normalize != "far":
            raise ValueError(
                f"normalize = {normalize!r} is invalid: expected None, 'far' or (z_low, z_high) in "
                "m"
            )
        far = np.array([FAR_FACTOR * z[-1]])
        return Normalization(
            "far", None, z, far, np.zeros(z.size, bool), y, w, 1.0, np.diag(1.0 / w)
        )
    try:
        z_low, z_high = _checks.pair("normalize", normalize)
    except ValueError:
        raise ValueError(
            f"normalize = {_checks.shown(normalize)} is invalid: expected None, 'far' or (z_low, "
            "z_high) in m"
        ) from None
    if not (z_low < z_high and z_low >= z[0] and z_high <= z[-1]):
        raise ValueError(
            f"normalize = ({z_low:g}, {z_high:g}) m is invalid: expected z_low < z_high within the "
            f"measured ranges [{z[0]:g}, {z[-1]:g}] m"
        )
    inside = (z >= z_low) & (z <= z_high)
    if inside.sum() < MIN_INTERVAL_POINTS:
        raise ValueError(
            f"normalize = ({z_low:g}, {z_high:g}) m holds {int(inside.sum())} measured points: "
            f"expected at least {MIN_INTERVAL_POINTS}; widen the interval"
        )
    mean = float(y[inside].mean())
    if not mean > 0:
        raise ValueError(
            f"normalize = ({z_low:g}, {z_high:g}) m: the data's mean there is {mean:g}: expected > "
            "0 (choose an interval where the signal is in the field of view)"
        )
    data = y / mean
    whitening = _whitening(data.tobytes(), inside.tobytes(), w.tobytes(), mean)
    return Normalization(
        "interval", (z_low, z_high), z, np.empty(0), inside, data, w / mean, mean, whitening
    )


@functools.lru_cache(maxsize=8)
def _whitening(data: bytes, inside: bytes, sigma: bytes, mean: float) -> np.ndarray:
    """W of the interval normalisation (module docstring), read-only. Cached: the model ladder and
    the global search fit the same data many times (each family, each polished minimum), and the
    eigendecomposition of the n x n covariance is the costliest step of setting up a fit."""
    y = np.frombuffer(data)
    e = np.frombuffer(inside, dtype=bool)
    w = np.frombuffer(sigma)
    a = (np.eye(y.size) - np.outer(y, e / e.sum())) / mean
    cov = (a * w**2) @ a.T
    values, vectors = np.linalg.eigh(cov)
    keep = values > RANK_TOLERANCE * values[-1]
    out = (vectors[:, keep] / np.sqrt(values[keep])).T
    out.setflags(write=False)
    return out


def fit_relative(
    system,
    ranges,
    measured,
    sigma,
    free,
    bounds,
    method,
    tolerance,
    loss,
    max_evaluations,
    allow_unconverged,
    threads,
    normalize,
) -> RelativeFitResult:
    """:func:`lidar_overlap.fit` with ``normalize`` given (arguments as there)."""
    paths = free_paths(free)
    p0 = fit_plan(system, ranges, method, tolerance, threads)
    y = measured_values(measured, p0.ranges)
    w = sigma_weights(sigma, y)
    norm = normalization(normalize, p0.ranges, y, w)
    p, h_tolerance = extended_plan(p0, norm), step_tolerance(p0, tolerance)
    white = norm.whitening

    curve = last_curve(p)

    def result(trial):
        c = curve(trial)
        return c, white @ norm.model(c.overlap)

    def model_jacobian(trial):
        g = curve(trial).overlap  # the curve the optimiser has just evaluated
        return white @ norm.model_jacobian(g, jacobian(p, trial, paths, h_tolerance))

    model = Model(
        lambda trial: result(trial)[1], model_jacobian, result, p, h_tolerance, p.tolerance
    )
    raw = solve(
        system,
        paths,
        model,
        white @ norm.data,
        np.ones(white.shape[0]),
        sigma is not None,
        bounds,
        loss,
        max_evaluations,
        allow_unconverged,
    )
    return relative_result(raw, norm, sigma is not None)


def extended_plan(p, norm: Normalization):
    """Plan ``p`` on the ranges the normalised model needs (the measured ones and the far point),
    its system's range limits checked there."""
    if norm.extra_ranges.size == 0:
        return p
    return p.at(norm.model_ranges)


def relative_result(raw, norm: Normalization, sigma_given: bool) -> RelativeFitResult:
    """The :class:`RelativeFitResult` of a solve on the whitened problem: chi-square and the
    covariance as solved; residuals, measured and sigma per measured range on the normalised scale
    (for plots and tables)."""
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
    return RelativeFitResult(**fields)
