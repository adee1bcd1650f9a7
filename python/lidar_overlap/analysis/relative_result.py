"""The result of a fit to a relative overlap curve (:mod:`lidar_overlap.analysis.relative`): a
:class:`FitResult` whose measured data, residuals and predictions are on the normalised scale."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Tuple, Union

import numpy as np

from .. import _checks
from ..forward.compute import run
from .fit_result import FitResult, Prediction
from .sensitivity import jacobian


@dataclass(frozen=True, eq=False)
class RelativeFitResult(FitResult):
    """A :class:`FitResult` of ``lo.fit(..., normalize=...)``. Beyond its fields:

    normalize : ``"far"`` or the interval (z_low, z_high) in m. normalizing_ranges : the ranges (m)
    the model is normalised over (the measured ranges in the interval, or the far point).
    model_scale, data_scale : the model's normaliser at the solution (its mean over the interval or
    its far limit; the instrument's absolute G there) and the data's (their mean over the interval,
    1 for "far"). fitted : the normalised model at the measured ranges. ``measured``, ``sigma`` and
    ``residuals`` are per measured range on the normalised scale; ``chi_square`` is that of the
    whitened problem (n - 1 independent points for an interval)."""

    normalize: Union[str, Tuple[float, float]] = "far"
    normalizing_ranges: np.ndarray = dataclasses.field(default_factory=lambda: np.empty(0))
    model_scale: float = 1.0
    data_scale: float = 1.0
    fitted: np.ndarray = dataclasses.field(default_factory=lambda: np.empty(0))

    @property
    def ranges(self) -> np.ndarray:
        """The measured ranges (m) (the model's curve may hold the far point as well)."""
        return self.result.ranges[: self.measured.size]

    def predict(self, ranges) -> Prediction:
        """The fitted model at ``ranges`` (m) on the data's normalised scale, and its 1-sigma band
        from the covariance, sqrt(diag(J C Jᵀ)) with J the derivative of the normalised model (its
        normaliser moves with the parameters too)."""
        return normalised_prediction(self, ranges, self.normalizing_ranges)

    def absolute(self, ranges) -> Prediction:
        """The fitted instrument's absolute G at ``ranges`` (m) with its band (the model before
        normalising: what the instrument's geometry implies, e.g. for :func:`lo.correct`)."""
        return FitResult.predict(self, ranges)

    def summary(self) -> str:
        """:meth:`FitResult.summary` with how the data were normalised."""
        how = (
            "by the model's far-range limit"
            if self.normalize == "far"
            else "each by its mean over {:g}-{:g} m".format(*self.normalize)
        )
        return (
            FitResult.summary(self)
            + f"\n  relative data: model and data normalised {how}; the model's absolute G "
            f"there is {self.model_scale:.4g}"
        )

    __str__ = summary


def normalised_prediction(fit: FitResult, ranges, normalizing_ranges) -> Prediction:
    """The fitted model of ``fit`` at ``ranges`` (m) divided by its mean over ``normalizing_ranges``
    (m), with the 1-sigma band of that ratio from the fit's covariance (the
    quotient rule on the Jacobian: the normaliser moves with the parameters too)."""
    z = _checks.ranges("ranges", ranges)
    fit.system._native.validate_ranges(z)
    both = np.union1d(z, normalizing_ranges)
    p = dataclasses.replace(fit.plan, system=fit.system, ranges=both)
    g = run(p).overlap
    j = jacobian(p, fit.system, list(fit.parameters), fit.step_tolerance)
    at, norm = np.searchsorted(both, z), np.searchsorted(both, normalizing_ranges)
    s, ds = g[norm].mean(), j[norm].mean(axis=0)
    jn = j[at] / s - np.outer(g[at], ds) / s**2
    with np.errstate(invalid="ignore"):
        band = np.sqrt(np.einsum("ij,jk,ik->i", jn, fit.covariance, jn))
    return Prediction(z, g[at] / s, band)
