"""The result of a fit to a relative overlap curve
(:mod:`lidar_overlap.analysis.fitting.relative`): a :class:`FitResult` whose measured data,
residuals and predictions are on the normalised scale."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, ClassVar, Dict, Optional, Tuple, Union

import numpy as np

from ... import _checks, _values
from ...forward.compute import run
from ..sensitivity import jacobian
from .result import FitResult, Prediction


@dataclass(frozen=True, eq=False)
class RelativeFitResult(FitResult):
    """A :class:`FitResult` of ``lo.fit(..., normalize=...)``. Beyond its fields:

    normalize : ``"far"`` or the interval (z_low, z_high) in m. normalizing_ranges : the ranges (m)
    the model is normalised over (the measured ranges in the interval, or the far point).
    model_scale, data_scale : the model's normaliser at the solution (its mean over the interval or
    its far limit; the instrument's absolute G there) and the data's (their mean over the interval,
    1 for "far"). fitted : the normalised model at the measured ranges. ``measured``, ``sigma`` and
    ``residuals`` are per measured range on the normalised scale; ``chi_square`` is that of the
    whitened problem (n - 1 independent points for an interval).

    With ``extinction_bias=True``: extinction_bias, its 1-sigma extinction_bias_uncertainty (1/m):
    δα, the error of the extinction the retrieval of the data assumed (two-way: the data carry
    exp(-2 δα (z - z_ref))), a property of the retrieval, not of the instrument; δα = α_true -
    α_assumed, positive when the retrieval assumed too little extinction (see
    :mod:`lidar_overlap.analysis.fitting.relative`).
    extinction_bias_reference : z_ref (m). extinction_bias_covariance : cov(p, δα), one per
    parameter. All None without it."""

    normalize: Union[str, Tuple[float, float]] = "far"
    normalizing_ranges: np.ndarray = dataclasses.field(default_factory=lambda: np.empty(0))
    model_scale: float = 1.0
    data_scale: float = 1.0
    fitted: np.ndarray = dataclasses.field(default_factory=lambda: np.empty(0))
    extinction_bias: Optional[float] = None
    extinction_bias_uncertainty: Optional[float] = None
    extinction_bias_reference: Optional[float] = None
    extinction_bias_covariance: Optional[np.ndarray] = None

    RELATIVE_FIELDS: ClassVar[Dict[str, Any]] = {
        "normalizing_ranges": _values.array(low=0.0),
        "model_scale": _values.real(low=0.0),
        "data_scale": _values.real(low=0.0),
        "fitted": _values.array(),
        "extinction_bias_covariance": _values.array(optional=True, inf=True, nan=True),
    }

    def __post_init__(self) -> None:
        super().__post_init__()
        _values.check(self, self.RELATIVE_FIELDS)
        if not (
            self.normalize == "far"
            or (
                isinstance(self.normalize, tuple)
                and len(self.normalize) == 2
                and all(isinstance(v, float) for v in self.normalize)
            )
        ):
            raise ValueError(
                f"normalize = {_checks.shown(self.normalize)} is invalid: expected 'far' or "
                "(z_low, z_high) in m"
            )
        if self.fitted.shape != self.measured.shape:
            raise ValueError(
                f"fitted has shape {self.fitted.shape}: expected one value per measured value, "
                f"{self.measured.size}"
            )
        bias = (
            self.extinction_bias,
            self.extinction_bias_uncertainty,
            self.extinction_bias_reference,
        )
        if any(v is None for v in bias) and not all(v is None for v in bias):
            raise ValueError(
                "extinction_bias, its uncertainty and reference are invalid: expected all three "
                "or none"
            )
        if bias[0] is not None:
            kinds = (_values.real(), _values.real(low=0.0, inf=True), _values.real(low=0.0))
            names = ("extinction_bias", "extinction_bias_uncertainty", "extinction_bias_reference")
            for name, kind in zip(names, kinds):
                object.__setattr__(self, name, kind(name, getattr(self, name)))

    @property
    def ranges(self) -> np.ndarray:
        """The measured ranges (m) (the model's curve may hold the far point as well)."""
        return self.result.ranges[: self.measured.size]

    def predict(self, ranges) -> Prediction:
        """The fitted model at ``ranges`` (m) on the data's normalised scale, and its 1-sigma band
        from the covariance, sqrt(diag(J C Jᵀ)) with J the derivative of the normalised model (its
        normaliser moves with the parameters too)."""
        return normalised_prediction(self, ranges, self.normalizing_ranges, self._trend())

    def _trend(self):
        if self.extinction_bias is None:
            return None
        return (
            self.extinction_bias,
            self.extinction_bias_reference,
            self.extinction_bias_uncertainty,
            self.extinction_bias_covariance,
        )

    def absolute(self, ranges) -> Prediction:
        """The fitted instrument's absolute G at ``ranges`` (m) with its band (the model before
        normalising: what the instrument's geometry implies, e.g. for :func:`lo.correct`)."""
        return FitResult.predict(self, ranges)

    def table(self):
        """:meth:`FitResult.table`, then the extinction bias (1/m; start 0) when it was fitted."""
        rows = FitResult.table(self)
        if self.extinction_bias is not None:
            u = self.extinction_bias_uncertainty
            rows.append(("extinction_bias", self.extinction_bias, u, "1/m", 0.0))
        return rows

    def summary(self) -> str:
        """:meth:`FitResult.summary` with how the data were normalised."""
        how = (
            "by the model's far-range limit"
            if self.normalize == "far"
            else "each by its mean over {:g}-{:g} m".format(*self.normalize)
        )
        text = (
            FitResult.summary(self)
            + f"\n  relative data: model and data normalised {how}; the model's absolute G "
            f"there is {self.model_scale:.4g}"
        )
        if self.extinction_bias is not None:
            text += (
                "\n  retrieval extinction bias (two-way; the data's retrieval, not the "
                f"instrument): {1e3 * self.extinction_bias:.4g} +- "
                f"{1e3 * float(self.extinction_bias_uncertainty or 0.0):.2g} /km (z_ref "
                f"{self.extinction_bias_reference:.4g} m)"
            )
        return text

    __str__ = summary


def normalised_prediction(fit: FitResult, ranges, normalizing_ranges, trend=None) -> Prediction:
    """The fitted model of ``fit`` at ``ranges`` (m) divided by its mean over ``normalizing_ranges``
    (m), with the 1-sigma band of that ratio from the fit's covariance (the
    quotient rule on the Jacobian: the normaliser moves with the parameters too). ``trend``: None or
    (δα (1/m), z_ref (m), its uncertainty, cov(p, δα)): the model times exp(-2 δα (z - z_ref)), δα's
    variance and covariance in the band."""
    z = _checks.ranges("ranges", ranges)
    fit.system._native.validate_ranges(z)
    both = np.union1d(z, normalizing_ranges)
    p = fit.plan.with_system(fit.system).at(both)  # at: auto's RT model error for these ranges
    g = run(p).overlap
    j = jacobian(p, fit.system, list(fit.parameters), fit.step_tolerance)
    at, norm = np.searchsorted(both, z), np.searchsorted(both, normalizing_ranges)
    if trend is not None:
        t = np.exp(-2.0 * trend[0] * (both - trend[1]))
        g, j = g * t, j * t[:, None]
    s, ds = g[norm].mean(), j[norm].mean(axis=0)
    jn = j[at] / s - np.outer(g[at], ds) / s**2
    with np.errstate(invalid="ignore"):
        variance = np.einsum("ij,jk,ik->i", jn, fit.covariance, jn)
        if (
            trend is not None
        ):  # d(model)/dδα = -2 m (z - z̄), z̄ the g-weighted mean over the interval
            m = g[at] / s
            zbar = (g[norm] * both[norm]).sum() / g[norm].sum()
            ja = -2.0 * m * (both[at] - zbar)
            variance = variance + 2 * ja * (jn @ trend[3]) + ja**2 * trend[2] ** 2
        band = np.sqrt(variance)
    return Prediction(z, g[at] / s, band)
