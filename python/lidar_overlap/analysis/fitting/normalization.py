"""How relative overlap curves are compared with the model: data normalised to about 1 in the far
range, as overlap curves retrieved from real signals are (the Raman or near/far method gives G only
up to a factor); the fit itself is :mod:`lidar_overlap.analysis.fitting.relative`.

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
the normalised problem (:mod:`lidar_overlap.analysis.fitting.solve`).

Retrieval extinction bias (``extinction_bias=True``, interval normalisation only). An overlap curve
retrieved from real signals (the Raman method, Wandinger and Ansmann, Appl. Opt. 41, 511 (2002);
the near/far-range method) assumes an extinction profile; an error δα (1/m) in it, constant with
height, stays in the retrieved curve as the two-way transmission factor exp(-2 δα (z - z_ref)). The
model is then G(z) exp(-2 δα (z - z_ref)) before normalising (z_ref, the mean measured range of the
interval, only fixes the factor's scale, which the normalisation removes). δα describes the
retrieval, not the instrument. It is fitted by variable projection: for each model curve the 1-D
least-squares problem in δα is solved by Gauss-Newton on the whitened residual (no extra model
evaluations), within ±``EXTINCTION_BIAS_BOUND``; the optimiser sees the Jacobian with the δα
direction projected out (Kaufman's form), so the covariance of the system parameters is the marginal
one of the joint problem, and δα's variance follows from the block inverse
(:func:`bias_covariance`).
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from ... import _checks

#: normalize="far" divides by G at this multiple of the last measured range.
FAR_FACTOR = 100.0
#: Eigenvalues of cov(ỹ) below this fraction of the largest are its null direction (dropped).
RANK_TOLERANCE = 1e-12
#: The fewest measured points an interval must hold.
MIN_INTERVAL_POINTS = 2
#: |δα| (1/m) the retrieval extinction bias may reach: 0.1 /km, several times the aerosol
#: extinction of a clean boundary layer, so a larger trend is no extinction error.
EXTINCTION_BIAS_BOUND = 1e-4
#: The profile solve in δα stops when a step is below this (1/m): 1e-8 of the bound.
BIAS_STEP_TOLERANCE = 1e-12
#: Most Gauss-Newton steps of the profile solve (nearly linear: a few steps reach the tolerance).
BIAS_MAX_STEPS = 30


@dataclass(frozen=True, eq=False)
class Trend:
    """The retrieval extinction bias of a :class:`Normalization`: ``offsets`` z - z_ref (m) at the
    measured ranges, ``reference`` z_ref (m), ``bound`` on |δα| (1/m)."""

    offsets: np.ndarray
    reference: float
    bound: float


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
    trend: Optional[Trend] = None

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
        """The normalised model at the measured ranges for curves ``g`` (..., model_ranges), times
        the retrieval's transmission factor at the profiled δα when there is a trend."""
        g = np.asarray(g)
        if self.trend is not None:
            g = g[..., : self.ranges.size] * self.transmission(self.bias(g))
        with np.errstate(divide="ignore", invalid="ignore"):
            return g[..., : self.ranges.size] / self.scale(g)[..., None]

    def transmission(self, bias):
        """exp(-2 δα (z - z_ref)) at the measured ranges for δα ``bias`` (...,) in 1/m."""
        assert self.trend is not None
        return np.exp(-2.0 * np.asarray(bias)[..., None] * self.trend.offsets)

    def bias(self, g):
        """The δα (1/m) of least whitened cost for each curve ``g`` (..., model_ranges), within
        ±bound (Gauss-Newton in one variable, halving a step that raises the cost; 0 where the
        model vanishes over the interval)."""
        assert self.trend is not None
        u = np.asarray(g)[..., : self.ranges.size]
        bound = self.trend.bound
        a = np.zeros(u.shape[:-1])

        def cost_and_step(a):
            v = u * self.transmission(a)
            m = v / self.scale(v)[..., None]
            r = (m - self.data) @ self.whitening.T
            ja = self.bias_column(v) @ self.whitening.T
            return np.einsum("...i,...i->...", r, r), -np.einsum("...i,...i->...", ja, r) / (
                np.einsum("...i,...i->...", ja, ja)
            )

        with np.errstate(all="ignore"):
            cost, step = cost_and_step(a)
            for _ in range(BIAS_MAX_STEPS):
                trial = np.clip(a + np.where(np.isfinite(step), step, 0.0), -bound, bound)
                for _ in range(8):  # halve until the cost does not rise
                    new_cost, new_step = cost_and_step(trial)
                    worse = ~(new_cost <= cost) & np.isfinite(cost)
                    if not worse.any():
                        break
                    trial = np.where(worse, 0.5 * (a + trial), trial)
                else:  # still worse after the halvings: stay
                    trial = np.where(worse, a, trial)
                    new_cost, new_step = cost_and_step(trial)
                moved = np.abs(trial - a)
                a, cost, step = trial, new_cost, new_step
                if not np.any(moved > BIAS_STEP_TOLERANCE):
                    break
        return np.where(np.isfinite(a), a, 0.0)

    def bias_column(self, v):
        """d(normalised model)/dδα for the trended curves ``v`` (..., measured ranges): the
        normaliser moves too, so -2 m (z - z̄) with z̄ the v-weighted mean range over the
        interval."""
        assert self.trend is not None
        x = self.trend.offsets
        m = v / self.scale(v)[..., None]
        zbar = (v[..., self.inside] * x[self.inside]).sum(axis=-1) / v[..., self.inside].sum(
            axis=-1
        )
        return -2.0 * m * (x - zbar[..., None])

    def bias_parts(self, g, j):
        """(δα, d model/dp at fixed δα (n, k), d model/dδα (n,)) of the curve ``g`` and its
        Jacobian ``j`` (model_ranges, k)."""
        n = self.ranges.size
        a = float(self.bias(g))
        t = self.transmission(a)
        v, jv = g[:n] * t, j[:n] * t[:, None]
        s, ds = self.scale(v), jv[self.inside].mean(axis=0)
        return a, jv / s - np.outer(v, ds) / s**2, self.bias_column(v)

    def model_jacobian(self, g, j):
        """d(normalised model)/dp, (n, k), from the curve ``g`` and its Jacobian ``j``
        (model_ranges, k): the quotient rule; with a trend, its δα direction projected out in the
        whitened metric (variable projection) unless δα rests on its bound."""
        n = self.ranges.size
        if self.trend is not None:
            a, jp, ja = self.bias_parts(g, j)
            if abs(a) >= self.trend.bound:
                return jp
            wa, wp = self.whitening @ ja, self.whitening @ jp
            return jp - np.outer(ja, wa @ wp / (wa @ wa))
        s = self.scale(g)
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


def bias_covariance(norm: Normalization, jp, ja, covariance, scale: float):
    """(var δα, cov(p, δα) (k,)) from the joint problem's block inverse: with A = JpᵀJp, b = Jpᵀja,
    c = jaᵀja (whitened), the parameters' block of the inverse is (A - b bᵀ/c)⁻¹ = ``covariance``
    (the projected fit's, times ``scale``), δα's is 1/c + bᵀ P b / c² and the cross term -P b / c.
    ``scale``: the factor the fit scaled its covariance by (chi²/dof without sigma, else 1)."""
    wa, wp = norm.whitening @ ja, norm.whitening @ jp
    c, b = float(wa @ wa), wp.T @ wa
    with np.errstate(invalid="ignore", over="ignore"):
        return float(scale / c + b @ covariance @ b / c**2), -(covariance @ b) / c


def normalization(
    normalize, ranges, measured, sigma, extinction_bias: bool = False
) -> Normalization:
    """The :class:`Normalization` for ``normalize`` (None, ``"far"`` or (z_low, z_high) in m) of
    data ``measured`` at ``ranges`` with errors ``sigma`` (one per point), with the retrieval's
    ``extinction_bias`` profiled when True (an interval only: :mod:`.problem` checks it); ValueError
    naming ``normalize`` and its valid range otherwise."""
    if extinction_bias:
        plain = normalization(normalize, ranges, measured, sigma)
        x = plain.ranges[plain.inside]
        reference = float(x.mean())
        trend = Trend(plain.ranges - reference, reference, EXTINCTION_BIAS_BOUND)
        return dataclasses.replace(plain, trend=trend)
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
    if not z_low < z_high:
        raise ValueError(
            f"normalize = ({z_low:g}, {z_high:g}) m is invalid: expected z_low < z_high"
        )
    # the interval selects the measured points within it: it may reach past the data's ends
    inside = (z >= z_low) & (z <= z_high)
    if inside.sum() < MIN_INTERVAL_POINTS:
        raise ValueError(
            f"normalize = ({z_low:g}, {z_high:g}) m holds {int(inside.sum())} measured points "
            f"(the data span [{z[0]:g}, {z[-1]:g}] m): expected at least {MIN_INTERVAL_POINTS}; "
            "widen or move the interval"
        )
    mean = float(y[inside].mean())
    if not mean > 0:
        raise ValueError(
            f"normalize = ({z_low:g}, {z_high:g}) m: the data's mean there is {mean:g}: expected > "
            "0 (choose an interval where the signal is in the field of view)"
        )
    data = y / mean
    try:
        whitening = _whitening(data.tobytes(), inside.tobytes(), w.tobytes(), mean)
    except FloatingPointError:
        raise _checks.refused(
            "measured",
            mean,
            "data and sigma on comparable scales",
            f"measured: the data's mean over normalize = ({z_low:g}, {z_high:g}) m is {mean:g} and "
            f"sigma reaches {float(w.max()):g}: the normalised errors sigma / mean overflow double "
            "precision; expected data and sigma on comparable scales (a relative curve is about 1 "
            "in the far range: rescale the data)",
        ) from None
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
    with np.errstate(over="raise", invalid="raise"):  # data of 1e-300 with unit weights
        cov = (a * w**2) @ a.T
    if not np.isfinite(cov).all():
        raise FloatingPointError("the normalised covariance overflows")
    values, vectors = np.linalg.eigh(cov)
    keep = values > RANK_TOLERANCE * values[-1]
    out = (vectors[:, keep] / np.sqrt(values[keep])).T
    out.setflags(write=False)
    return out


def extended_plan(p, norm: Normalization):
    """Plan ``p`` on the ranges the normalised model needs (the measured ones and the far point),
    its system's range limits checked there."""
    if norm.extra_ranges.size == 0:
        return p
    return p.at(norm.model_ranges)
