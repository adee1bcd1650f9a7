"""What the results of fits of several curves (:class:`~.joint_result.JointFitResult`,
:class:`~.drift_result.DriftFitResult`) share: one base value type with their common fields and
checks (:class:`MultiFitResult`), those fields taken from the driver's fit, their verdict lines and
the information criterion their choices compare."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar, Dict, List, Tuple

import numpy as np

from ... import _checks, _values
from ..._pickling import ByValue
from .diffraction import at_diffraction_limit
from .ladder import runs_p_value
from .multi_curve import MultiCurveFit, reduced
from .result import FitResult
from .result import verdict_lines as fit_verdict_lines

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


@dataclass(frozen=True, eq=False)
class MultiFitResult(ByValue):
    """The fields a fit of several curves reports (SI units): ``parameters``, ``uncertainties``,
    ``start`` (name -> value, 1-sigma uncertainty, start), ``covariance`` and ``correlation``
    (K, K) in the order of ``parameters``, ``chi_square``, ``reduced_chi_square`` and
    ``degrees_of_freedom`` over all curves (independent points - K), ``curves`` (one
    :class:`FitResult` per curve, its paths at the joint solution), ``degenerate_pairs`` ((name,
    name, correlation) with ``|correlation|`` > 0.95), ``at_bounds`` (the parameters that end on a
    bound), ``evaluations``, ``jacobian_evaluations`` (a search's candidates counted),
    ``converged``, ``message`` (the optimiser's). Subclasses add their own fields after these."""

    parameters: Dict[str, float]
    uncertainties: Dict[str, float]
    start: Dict[str, float]
    covariance: np.ndarray
    correlation: np.ndarray
    chi_square: float
    reduced_chi_square: float
    degrees_of_freedom: int
    curves: Tuple[FitResult, ...]
    degenerate_pairs: Tuple[Tuple[str, str, float], ...]
    at_bounds: Tuple[str, ...]
    evaluations: int
    jacobian_evaluations: int
    converged: bool
    message: str

    FIELDS: ClassVar[Dict[str, Any]] = FIELDS
    #: The fields that must be tuples (a subclass adds its own).
    TUPLES: ClassVar[Tuple[str, ...]] = ("at_bounds", "degenerate_pairs")

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        k = len(self.parameters)
        if set(self.uncertainties) != set(self.parameters) or set(self.start) != set(
            self.parameters
        ):
            raise ValueError("uncertainties and start are invalid: expected one per parameter")
        if self.covariance.shape != (k, k) or self.correlation.shape != (k, k):
            raise ValueError(
                f"covariance has shape {self.covariance.shape}: expected ({k}, {k}), as correlation"
            )
        if not (
            isinstance(self.curves, tuple) and all(isinstance(c, FitResult) for c in self.curves)
        ):
            raise ValueError(
                f"curves = {_checks.shown(self.curves)} is invalid: expected a tuple of one "
                "FitResult per curve"
            )
        for name in self.TUPLES:
            if not isinstance(getattr(self, name), tuple):
                raise ValueError(f"{name} = {_checks.shown(getattr(self, name))}: expected a tuple")

    @property
    def runs_p(self) -> Tuple[float, ...]:
        """Each curve's one-sided runs-test p-value of its residuals' signs (small: structure)."""
        return tuple(runs_p_value(c.residuals) for c in self.curves)

    @property
    def at_diffraction_limit(self) -> Tuple[str, ...]:
        """The parameters (names as in ``parameters``) whose divergence ends within a few % of its
        beam's diffraction limit λ/(π w0) for at least one curve
        (:mod:`lidar_overlap.analysis.fitting.diffraction`)."""
        found: set = set()
        for i, fit in enumerate(self.curves):
            for path in at_diffraction_limit(fit.system, fit.parameters):
                found.update(n for n in self.parameters if n in (path, f"{path}@{i}"))
        return tuple(n for n in self.parameters if n in found)


def fit_fields(fit: MultiCurveFit) -> Dict[str, Any]:
    """The :class:`MultiFitResult` fields of the driver's ``fit``."""
    names = fit.problem.names
    return dict(
        parameters=dict(zip(names, fit.values.tolist())),
        uncertainties=dict(zip(names, fit.uncertainties.tolist())),
        start=dict(zip(names, fit.problem.start.tolist())),
        covariance=fit.covariance,
        correlation=fit.correlation,
        chi_square=fit.chi_square,
        reduced_chi_square=reduced(fit.chi_square, fit.degrees_of_freedom),
        degrees_of_freedom=fit.degrees_of_freedom,
        curves=fit.fits,
        degenerate_pairs=fit.degenerate_pairs,
        at_bounds=fit.at_bounds,
        evaluations=fit.evaluations,
        jacobian_evaluations=fit.jacobian_evaluations,
        converged=fit.converged,
        message=fit.message,
        search=fit.search,
    )


def bic_of(fit: MultiCurveFit) -> float:
    """BIC = chi² + K ln n of a multi-curve fit (n independent points of all curves)."""
    n = fit.degrees_of_freedom + len(fit.values)
    return fit.chi_square + len(fit.values) * math.log(n)


def verdict_lines(result) -> List[str]:
    """The summary lines of a single fit's verdict (:func:`.result.verdict_lines`), then the
    choices the fit made (family, per-curve or drifting parameters)."""
    return fit_verdict_lines(result) + [f"  {line}" for line in result.choices]
