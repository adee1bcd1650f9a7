"""The overlap a fit gives for correcting a signal (``lo.correct(ranges, signal, fit)``): the fitted
curve at the signal's ranges and its 1-sigma band from the fit's covariance.

Absolute fits give G as fitted. Relative fits (``normalize=``) know G only up to a factor, and a
signal is corrected to the far-range level: their curve is the fitted instrument's G divided by its
far-range limit (G at ``FAR_FACTOR`` x the last range), which tends to 1 where the signal needs no
correction; when a defocused curve peaks above its far limit, by that peak instead (G stays in [0,
1], and the corrected signal is low by peak / far limit, which the fit states). The band covers the
parameters' uncertainty, not the model's own error.

A drift fit (``lo.fit_drift``) gives the curve of the instrument at the signal's covariate value
(``covariate=``, e.g. the day's internal temperature), in the same way: absolute as fitted, relative
divided by its far-range limit (or its peak), with the band of the drift fit's covariance; a
covariate outside the fitted span is warned about (the drift is extrapolated there).
"""

from __future__ import annotations

import numpy as np

from ... import _checks
from .drift_basis import warn_outside
from .drift_result import DriftFitResult
from .normalization import FAR_FACTOR
from .relative_result import RelativeFitResult, normalised_prediction


def fitted_overlap(fit, ranges, covariate=None):
    """(G, its 1-sigma band) of ``fit`` at ``ranges`` (m) for a correction (module docstring);
    ``covariate``: the signal's covariate value, for a drift fit only."""
    z = np.asarray(ranges, dtype=float)
    if isinstance(fit, DriftFitResult):
        return _drift_overlap(fit, z, covariate)
    if covariate is not None:
        raise ValueError(
            f"covariate = {_checks.shown(covariate)} is invalid here: only a drift fit's overlap "
            "(lo.fit_drift) depends on a covariate; leave it out"
        )
    if isinstance(fit, RelativeFitResult):
        far = np.array([FAR_FACTOR * z[-1]])
        g = fit.absolute(np.append(z, far)).overlap
        peak = far if g[-1] >= g[:-1].max() else z[[int(np.argmax(g[:-1]))]]
        pred = normalised_prediction(fit, z, peak)
    else:
        pred = fit.predict(z)
    return pred.overlap, pred.sigma


def is_fit(value) -> bool:
    """Whether ``value`` is a fit result (it has a covariance to give a band)."""
    return hasattr(value, "predict") and hasattr(value, "covariance")


def _drift_overlap(fit: DriftFitResult, z, covariate):
    """(G, its band) of a drift fit at ``covariate`` (module docstring)."""
    if covariate is None:
        raise ValueError(
            "covariate is missing: a drift fit's overlap depends on it; give the signal's value "
            f"(in {fit.covariate_unit}), e.g. covariate=the day's temperature"
        )
    c = _checks.real("covariate", covariate)
    if not np.isfinite(c):
        raise ValueError(f"covariate = {c!r} is invalid: expected a finite value")
    warn_outside(c, fit.span, fit.covariate_unit)
    if not isinstance(fit.curves[0], RelativeFitResult):
        g, band = fit.prediction(z, np.array([c]), None, True)
        return g[0], band[0]
    far = np.array([FAR_FACTOR * z[-1]])
    g = fit.prediction(np.append(z, far), np.array([c]), None, False)[0]
    peak = far if g[-1] >= g[:-1].max() else z[[int(np.argmax(g[:-1]))]]
    g, band = fit.prediction(z, np.array([c]), peak, True)
    return g[0], band[0]
