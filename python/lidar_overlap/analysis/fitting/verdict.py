"""What a finished fit found: whether its numbers are usable, and how well the model fits the data.

A least-squares optimiser reports convergence when its steps stop shrinking the cost, which says
nothing about whether the minimum is the right one or the model fits. The checks here turn what the
statistics show into a named warning or an error, never a NaN returned as a number:

- non-finite statistics (chi-square, covariance) are an error: the fit has no meaning;
- with sigma given, chi²/dof far above 1 (a chi-square p-value below :data:`P_VALUE`, and chi²/dof
  above :data:`CHI2_RATIO`) warns: the minimum may be local or the model inadequate;
- residuals larger than the model's own tolerance whose signs come in too few runs (a Wald–Wolfowitz
  runs test, z below -:data:`RUNS_Z`) warn the same way: noise alternates, a wrong curve does not;
- a zero-residual fit without sigma warns: the noise is estimated from the residuals, so the
  uncertainties are 0 and mean nothing.

The goodness-of-fit checks apply to the linear loss: a robust loss expects outliers, which they
would count as misfit.
"""

from __future__ import annotations

import math
from typing import Optional

import numpy as np

from ... import _checks

#: A chi-square this improbable for the degrees of freedom counts as far above 1.
P_VALUE = 1e-6
#: ... and only when chi²/dof is also above this (large dof make small excesses improbable).
CHI2_RATIO = 2.0
#: Runs-test z-score below which the residuals' signs count as structured (one-sided p ~ 2e-4).
RUNS_Z = 3.5
#: The runs test needs at least this many residuals of each sign to mean anything.
RUNS_MIN = 10
#: Residuals count as zero below this many times the round-off of the measured values.
ZERO_RESIDUAL = 1e3


class FitQualityWarning(RuntimeWarning):
    """The fit converged, but its residuals say the minimum may be local or the model inadequate
    (chi²/dof far above 1 with sigma given, or residuals with structure), or, without sigma, that
    its uncertainties mean nothing (zero residuals)."""


def check_usable(what: str, chi_square: float, covariance: np.ndarray) -> None:
    """ValueError when the fit's statistics are not finite numbers (a NaN covariance from
    overflowing weights, an infinite chi-square). An infinite covariance of a singular Jacobian is
    the degeneracy the caller warns about, and passes."""
    if not math.isfinite(chi_square):
        raise ValueError(
            f"{what}: the chi-square at the solution is {chi_square!r}: the residuals overflow; "
            "check measured (G, of order 0 to 1) and sigma (the 1-sigma error of each point)"
        )
    if np.isnan(covariance).any():
        raise ValueError(
            f"{what}: the covariance at the solution is not a number: the weights 1/sigma overflow "
            "or underflow; give sigma of the order of the measurement error"
        )


def runs_z(residuals: np.ndarray) -> Optional[float]:
    """z-score of the number of sign runs in ``residuals`` (zeros left out) against its expectation
    for random signs; None when too few of either sign for the test."""
    signs = np.sign(residuals[residuals != 0.0])
    n1, n2 = int(np.sum(signs > 0)), int(np.sum(signs < 0))
    if min(n1, n2) < RUNS_MIN:
        return None
    n = n1 + n2
    runs = 1 + int(np.count_nonzero(signs[1:] != signs[:-1]))
    mean = 2.0 * n1 * n2 / n + 1.0
    variance = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n - 1.0))
    return (runs - mean) / math.sqrt(variance)


def check_quality(
    what: str,
    residuals: np.ndarray,
    measured: np.ndarray,
    weights: np.ndarray,
    dof: int,
    sigma_given: bool,
    model_tolerance: float,
) -> bool:
    """Warn :class:`FitQualityWarning` by the rules of the module docstring. ``residuals`` are
    (model - measured) / ``weights``; ``model_tolerance`` is the model's absolute error on G (NaN if
    unknown). True when the fit is exact without sigma (no noise to compare anything with)."""
    r = np.asarray(residuals, dtype=float)
    chi_square = float(r @ r)
    raw = r * weights  # in units of G
    floor = ZERO_RESIDUAL * np.finfo(float).eps * max(float(np.max(np.abs(measured))), 1e-300)
    if not sigma_given and float(np.max(np.abs(raw), initial=0.0)) <= floor:
        _checks.warn(
            f"{what}: the model fits the data exactly (residuals at round-off) and sigma is not "
            "given, so the noise estimated from the residuals is 0 and so are the uncertainties; "
            "give sigma, the 1-sigma error of each point",
            FitQualityWarning,
        )
        return True
    if sigma_given and dof > 0:
        ratio = chi_square / dof
        if ratio > CHI2_RATIO and _chi2_p_value(chi_square, dof) < P_VALUE:
            _checks.warn(
                f"{what}: chi²/dof = {ratio:.3g} for {dof} degrees of freedom is far above 1: the "
                "minimum may be local (start closer, or from several starts) or the model "
                "inadequate (free other parameters), or sigma too small",
                FitQualityWarning,
            )
            return False
    above_model = not math.isfinite(model_tolerance) or (
        float(np.sqrt(np.mean(raw**2))) > 3.0 * model_tolerance
    )
    z = runs_z(r) if above_model else None
    if z is not None and z < -RUNS_Z:
        _checks.warn(
            f"{what}: the residuals are structured (their signs form too few runs, z = {z:.2g}): "
            "the minimum may be local (start closer, or from several starts) or the model "
            "inadequate (free other parameters)",
            FitQualityWarning,
        )
    return False


def _chi2_p_value(chi_square: float, dof: int) -> float:
    from scipy import stats

    return float(stats.chi2.sf(chi_square, dof))


def least_squares(optimize, residuals, start, **options):
    """``optimize.least_squares``, with the residuals and the Jacobian it is given checked at the
    start, where scipy refuses non-finite values in words that name no parameter: refused in the
    fit's words instead (no extra evaluation: each function checks its own first result)."""
    options = dict(options)
    if callable(options.get("jac")):
        options["jac"] = _FiniteAtStart(options["jac"], "Jacobian of the weighted residuals")
    return optimize.least_squares(_FiniteAtStart(residuals, "weighted residuals"), start, **options)


class _FiniteAtStart:
    """``function`` whose first result (at the start) must be finite."""

    def __init__(self, function, what: str) -> None:
        self.function, self.what, self.first = function, what, True

    def __call__(self, x, *args, **kwargs):
        values = self.function(x, *args, **kwargs)
        if self.first:
            self.first = False
            if not np.all(np.isfinite(values)):
                raise ValueError(
                    f"fit: the {self.what} are not finite at the start: sigma is too small or "
                    "measured too large for double precision; give measured G (of order 0 to 1) "
                    "and sigma of the order of its error"
                )
        return values
