"""``lo.empirical_drift``: the empirical temperature model of an overlap curve, range gate by range
gate (Hervo, M., Poltera, Y., and Haefele, A. (2016), An empirical method to correct for
temperature-dependent variations in the overlap function of CHM15k ceilometers, Atmos. Meas. Tech.
9, 2947-2959, doi:10.5194/amt-9-2947-2016).

At each gate z the log of a day's curve over a reference curve (the manufacturer's, say) is a
straight line in the day's covariate x (the instrument's internal temperature):

    ln(G(z, x) / G_ref(z)) = a(z) + b(z) (x - x0),

a and b fitted by least squares over the training curves, every gate at once (numpy), x0 the
training covariates' mean (so that a and b are uncorrelated). Two coefficients per gate: it predicts
the days it was trained on well, says nothing about which part of the instrument moves, and
extrapolates a straight line in ln G beyond the training covariates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, Dict

import numpy as np

from ... import _checks, _values
from ..._pickling import ByValue

#: Curves the fit needs: three give each gate's residual scatter one degree of freedom.
MIN_CURVES = 3
#: Two predicted gates are the same when they differ by less than this fraction of the range.
SAME_GATE = 1e-9


@dataclass(frozen=True, eq=False)
class EmpiricalDrift(ByValue):
    """The per-gate model ln(G / G_ref) = intercept + slope (x - center) (module docstring).

    ranges: the gates (m). reference: G_ref at each gate. intercept, slope: per gate (slope per
    unit of the covariate, e.g. 1/K), with their 1-sigma uncertainties intercept_sigma,
    slope_sigma from each gate's residual scatter (n_curves - 2 degrees of freedom). residual_rms:
    each gate's RMS residual in ln G. center: the training covariates' mean; covariate_range: their
    (min, max); n_curves: training curves.
    """

    ranges: np.ndarray
    reference: np.ndarray
    intercept: np.ndarray
    slope: np.ndarray
    intercept_sigma: np.ndarray
    slope_sigma: np.ndarray
    residual_rms: np.ndarray
    center: float
    covariate_range: tuple
    n_curves: int

    FIELDS: ClassVar[Dict[str, _values.Kind]] = {
        "ranges": _values.array(1, low=0.0),
        "reference": _values.array(1, low=0.0),
        "intercept": _values.array(1),
        "slope": _values.array(1),
        "intercept_sigma": _values.array(1, low=0.0),
        "slope_sigma": _values.array(1, low=0.0),
        "residual_rms": _values.array(1, low=0.0),
        "center": _values.real(),
        "covariate_range": _values.pair,
        "n_curves": _values.count(MIN_CURVES),
    }

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        n = self.ranges.size
        for name in ("reference", "intercept", "slope", "intercept_sigma", "slope_sigma"):
            if getattr(self, name).size != n:
                raise ValueError(
                    f"{name} has {getattr(self, name).size} values for {n} ranges: expected one "
                    "per range"
                )
        if self.residual_rms.size != n:
            raise ValueError(f"residual_rms has {self.residual_rms.size} values for {n} ranges")

    @property
    def coefficients(self) -> int:
        """Fitted coefficients: two per gate."""
        return 2 * int(self.ranges.size)

    def predict(self, ranges, covariate) -> np.ndarray:
        """G at ``ranges`` (m; each one of the fitted gates, any other refused: the model has no
        value between gates) for each ``covariate`` value: shape (len(covariate), len(ranges)),
        in the reference's units (relative when the reference is)."""
        z = _checks.ranges("ranges", ranges)
        x = _values.array(1)("covariate", np.atleast_1d(_checks.real_array("covariate", covariate)))
        index = np.searchsorted(self.ranges, z)
        index = np.clip(index, 0, self.ranges.size - 1)
        nearer = np.clip(index - 1, 0, None)
        use_left = np.abs(self.ranges[nearer] - z) < np.abs(self.ranges[index] - z)
        index = np.where(use_left, nearer, index)
        off = np.abs(self.ranges[index] - z) > SAME_GATE * z
        if off.any():
            i = int(np.argmax(off))
            raise ValueError(
                f"ranges[{i}] = {float(z[i])!r} m is invalid: expected one of the model's "
                f"{self.ranges.size} gates ({self.ranges[0]:g} to {self.ranges[-1]:g} m); the "
                "per-gate model is not interpolated"
            )
        with np.errstate(over="ignore", invalid="ignore"):
            log_ratio = self.intercept[index] + np.outer(x - self.center, self.slope[index])
            g = self.reference[index] * np.exp(log_ratio)
        if not np.all(np.isfinite(g)):
            i = int(np.argmax(~np.all(np.isfinite(g), axis=1)))
            raise _checks.refused(
                f"covariate[{i}]",
                float(x[i]),
                "a value at which the model's G is finite (the training covariates span "
                f"{self.covariate_range[0]:g} to {self.covariate_range[1]:g})",
            )
        return g


def empirical_drift(ranges, curves, covariate, reference) -> EmpiricalDrift:
    """The per-gate log-linear model of ``curves`` (n_curves x n_ranges, G at ``ranges`` in m) in
    ``covariate`` (one finite value per curve, e.g. the internal temperature in K) over
    ``reference`` (G_ref at ``ranges``, e.g. the manufacturer's curve). Curves and reference must
    be > 0 at every range (the model is in ln G; choose ranges where they are). At least
    :data:`MIN_CURVES` curves, and covariates that are not all equal. Returns an
    :class:`EmpiricalDrift`; its ``predict`` gives the curve for any covariate."""
    z = _checks.ranges("ranges", ranges)
    g = _checks.real_array("curves", curves, ndim=2)
    if g.shape[1] != z.size:
        raise ValueError(
            f"curves has shape {g.shape}: expected (n_curves, {z.size}), one column per range"
        )
    if g.shape[0] < MIN_CURVES:
        raise ValueError(
            f"curves holds {g.shape[0]} curve(s): expected at least {MIN_CURVES} (a slope and an "
            "intercept per gate, and their scatter)"
        )
    x = _checks.real_array("covariate", covariate, ndim=1)
    if x.size != g.shape[0]:
        raise ValueError(
            f"covariate has {x.size} values for {g.shape[0]} curves: expected one per curve"
        )
    if not np.all(np.isfinite(x)):
        i = int(np.argmax(~np.isfinite(x)))
        raise ValueError(f"covariate[{i}] = {float(x[i])!r} is invalid: expected a finite value")
    reference = _checks.real_array("reference", reference, ndim=1)
    if reference.size != z.size:
        raise ValueError(
            f"reference has {reference.size} values for {z.size} ranges: expected one per range"
        )
    for name, values in (("curves", g), ("reference", reference)):
        bad = ~(np.isfinite(values) & (values > 0))
        if bad.any():
            where = np.unravel_index(int(np.argmax(bad)), values.shape)
            index = ", ".join(str(int(i)) for i in where)
            raise ValueError(
                f"{name}[{index}] = {float(values[where])!r} (range {z[where[-1]]:g} m) is "
                "invalid: expected finite values > 0 (the model is in ln G: leave out the ranges "
                "where a curve is 0 or negative)"
            )
    with np.errstate(over="ignore", invalid="ignore"):
        center = float(np.mean(x))
        dx = x - center
        sxx = float(dx @ dx)
    if not (sxx > 0 and math.isfinite(sxx) and math.isfinite(center)):
        why = "all values are equal" if sxx == 0 else "its spread overflows"
        raise ValueError(
            f"covariate is invalid: {why}; expected values that spread (and whose squares stay "
            "below 1e308) to fit a slope on"
        )
    y = np.log(g / reference)
    intercept = y.mean(axis=0)
    slope = dx @ (y - intercept) / sxx
    residuals = y - intercept - np.outer(dx, slope)
    n = x.size
    scatter = np.sqrt((residuals**2).sum(axis=0) / (n - 2))
    return EmpiricalDrift(
        ranges=z,
        reference=reference,
        intercept=intercept,
        slope=slope,
        intercept_sigma=scatter / math.sqrt(n),
        slope_sigma=scatter / math.sqrt(sxx),
        residual_rms=np.sqrt((residuals**2).mean(axis=0)),
        center=center,
        covariate_range=(float(x.min()), float(x.max())),
        n_curves=n,
    )
