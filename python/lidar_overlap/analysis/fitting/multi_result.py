"""What the results of fits of several curves (:class:`~.joint_result.JointFitResult`,
:class:`~.drift_result.DriftFitResult`) share: their checked fields, their verdict lines and the
information criterion their choices compare."""

from __future__ import annotations

import math
from typing import Any, Dict, List

from ... import _values
from .multi_curve import MultiCurveFit

#: The fields every multi-curve result checks on construction (beside its own).
FIELDS: Dict[str, Any] = {
    "parameters": _values.reals(),
    "uncertainties": _values.reals(inf=True),
    "start": _values.reals(),
    "covariance": _values.array(2, square=True, inf=True),
    "correlation": _values.array(2, square=True, nan=True),
    "chi_square": _values.real(low=0.0),
    "reduced_chi_square": _values.real(low=0.0, nan=True, inf=True),
    "degrees_of_freedom": _values.count(0),
    "evaluations": _values.count(0),
    "jacobian_evaluations": _values.count(0),
    "converged": _values.flag,
    "message": _values.text,
}


def reduced(chi_square: float, dof: int) -> float:
    """chi²/dof, NaN without degrees of freedom."""
    return chi_square / dof if dof else math.nan


def bic_of(fit: MultiCurveFit) -> float:
    """BIC = chi² + K ln n of a multi-curve fit (n independent points of all curves)."""
    n = fit.degrees_of_freedom + len(fit.values)
    return fit.chi_square + len(fit.values) * math.log(n)


def verdict_lines(result) -> List[str]:
    """The chi-square, degeneracy, bound and choice lines of a result's summary."""
    lines = [
        f"  chi-square {result.chi_square:.4g} for {result.degrees_of_freedom} degrees of "
        f"freedom, reduced {result.reduced_chi_square:.4g}"
    ]
    for a, b, c in result.degenerate_pairs:
        lines.append(f"  degenerate: {a} and {b} (correlation {c:+.3f})")
    if result.at_bounds:
        lines.append(f"  on a bound (set by it, not by the data): {', '.join(result.at_bounds)}")
    lines.extend(f"  {line}" for line in result.choices)
    return lines
