"""The overlap a fit gives for correcting a signal (``lo.correct(ranges, signal, fit)``): the fitted
curve at the signal's ranges and its 1-sigma band from the fit's covariance.

Absolute fits give G as fitted. Relative fits (``normalize=``) know G only up to a factor, and a
signal is corrected to the far-range level: their curve is the fitted instrument's G divided by its
far-range limit (G at ``FAR_FACTOR`` x the last range), which tends to 1 where the signal needs no
correction; when a defocused curve peaks above its far limit, by that peak instead (G stays in [0,
1], and the corrected signal is low by peak / far limit, which the fit states). The band covers the
parameters' uncertainty, not the model's own error.
"""

from __future__ import annotations

import numpy as np

from .normalization import FAR_FACTOR
from .relative_result import RelativeFitResult, normalised_prediction


def fitted_overlap(fit, ranges):
    """(G, its 1-sigma band) of ``fit`` at ``ranges`` (m) for a correction (module docstring)."""
    z = np.asarray(ranges, dtype=float)
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
