"""The result of ``lo.fit_joint`` (:mod:`lidar_overlap.analysis.fitting.joint`): the shared and
per-curve parameters with one covariance, one fit result per curve and the joint verdict."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Dict, Optional, Tuple

import numpy as np

from ... import _checks, _values
from ..._pickling import ByValue
from ...model import parameters as _parameters
from . import multi_result
from .global_result import SearchReport
from .ladder import runs_p_value
from .multi_curve import MultiCurveFit
from .multi_inputs import path_of
from .multi_result import reduced, verdict_lines
from .result import FitResult


@dataclass(frozen=True, eq=False)
class JointFitResult(ByValue):
    """A joint fit of several curves (SI units).

    Attributes
    ----------
    curves : one :class:`FitResult` per curve (a ``RelativeFitResult`` for normalised data): its
        own paths at the joint solution and their covariance, its ``fitted`` curve (relative
        data), ``measured``, ``residuals``; its degrees of freedom are its independent points
        less the parameters only it sets.
    parameters, uncertainties, start : name -> value, 1-sigma uncertainty, start (module docstring:
        shared by path, per-curve as ``path@i``).
    covariance, correlation : (K, K) in the order of ``parameters``.
    chi_square, reduced_chi_square, degrees_of_freedom : over all curves (independent points - K).
    shared, per_curve : the paths fitted as shared and as each curve's own.
    degenerate_pairs : (name, name, correlation) with ``|correlation|`` > 0.95.
    at_bounds : the parameters that end on a bound.
    evaluations, jacobian_evaluations, converged, message : the optimiser's (evaluations count a
        search's candidates).
    search : the global search's report, or None. family : with ``free="auto"``, the family
        chosen; choices : what the choice tried, one line each (empty otherwise).
    """

    curves: Tuple[FitResult, ...]
    parameters: Dict[str, float]
    uncertainties: Dict[str, float]
    start: Dict[str, float]
    covariance: np.ndarray
    correlation: np.ndarray
    chi_square: float
    reduced_chi_square: float
    degrees_of_freedom: int
    shared: Tuple[str, ...]
    per_curve: Tuple[str, ...]
    degenerate_pairs: Tuple[Tuple[str, str, float], ...]
    at_bounds: Tuple[str, ...]
    evaluations: int
    jacobian_evaluations: int
    converged: bool
    message: str
    search: Optional[SearchReport] = None
    family: Optional[str] = None
    choices: Tuple[str, ...] = ()

    FIELDS: ClassVar[Dict[str, Any]] = multi_result.FIELDS

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        k = len(self.parameters)
        if not (
            isinstance(self.curves, tuple)
            and len(self.curves) >= 2
            and all(isinstance(c, FitResult) for c in self.curves)
        ):
            raise ValueError(
                f"curves = {_checks.shown(self.curves)} is invalid: expected a tuple of at least "
                "two FitResults"
            )
        if set(self.uncertainties) != set(self.parameters) or set(self.start) != set(
            self.parameters
        ):
            raise ValueError("uncertainties and start are invalid: expected one per parameter")
        if self.covariance.shape != (k, k) or self.correlation.shape != (k, k):
            raise ValueError(
                f"covariance has shape {self.covariance.shape}: expected ({k}, {k}), as correlation"
            )
        for name in ("shared", "per_curve", "at_bounds", "degenerate_pairs", "choices"):
            if not isinstance(getattr(self, name), tuple):
                raise ValueError(f"{name} = {_checks.shown(getattr(self, name))}: expected a tuple")

    @property
    def runs_p(self) -> Tuple[float, ...]:
        """Each curve's one-sided runs-test p-value of its residuals' signs (small: structure)."""
        return tuple(runs_p_value(c.residuals) for c in self.curves)

    def value(self, path: str, curve: int) -> float:
        """``path``'s fitted value for curve ``curve`` (shared or its own)."""
        return self.curves[curve].parameters[_parameters.canonical(path)]

    def summary(self) -> str:
        """The parameters with uncertainties, each curve's chi-square and runs test, one line
        each."""
        lines = [
            f"joint fit of {len(self.curves)} curves: "
            f"{'converged' if self.converged else 'NOT converged'} after {self.evaluations} model "
            f"and {self.jacobian_evaluations} Jacobian evaluations"
            + (f"; family '{self.family}'" if self.family else "")
        ]
        for name, value in self.parameters.items():
            unit = _parameters.unit(path_of(name))
            lines.append(
                f"  {name:<24} {value:+.6g} ± {self.uncertainties[name]:.3g} {unit}  (start "
                f"{self.start[name]:+.6g})"
            )
        for i, (fit, p) in enumerate(zip(self.curves, self.runs_p)):
            lines.append(
                f"  curve {i}: chi-square {fit.chi_square:.4g}, reduced "
                f"{fit.reduced_chi_square:.4g}, runs test p {p:.3g}"
            )
        lines.extend(verdict_lines(self))
        return "\n".join(lines)

    __str__ = summary


def joint_result(fit: MultiCurveFit, family=None, choices=()) -> JointFitResult:
    """The :class:`JointFitResult` of the driver's fit."""
    names = fit.problem.names
    shared = tuple(n for n in names if path_of(n) == n)
    own = tuple(dict.fromkeys(path_of(n) for n in names if path_of(n) != n))
    dof = fit.degrees_of_freedom
    return JointFitResult(
        curves=fit.fits,
        parameters=dict(zip(names, fit.values.tolist())),
        uncertainties=dict(zip(names, fit.uncertainties.tolist())),
        start=dict(zip(names, fit.problem.start.tolist())),
        covariance=fit.covariance,
        correlation=fit.correlation,
        chi_square=fit.chi_square,
        reduced_chi_square=reduced(fit.chi_square, dof),
        degrees_of_freedom=dof,
        shared=shared,
        per_curve=own,
        degenerate_pairs=fit.degenerate_pairs,
        at_bounds=fit.at_bounds,
        evaluations=fit.evaluations,
        jacobian_evaluations=fit.jacobian_evaluations,
        converged=fit.converged,
        message=fit.message,
        search=fit.search,
        family=family,
        choices=tuple(choices),
    )
