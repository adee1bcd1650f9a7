"""The result of ``lo.fit_joint`` (:mod:`lidar_overlap.analysis.fitting.joint`): the shared and
per-curve parameters with one covariance, one fit result per curve and the joint verdict."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Optional, Tuple

from ... import _checks
from ...model import parameters as _parameters
from .global_result import SearchReport
from .multi_curve import MultiCurveFit
from .multi_inputs import path_of
from .multi_result import MultiFitResult, fit_fields, verdict_lines


@dataclass(frozen=True, eq=False)
class JointFitResult(MultiFitResult):
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
    at_bounds : the parameters that end on a bound; at_diffraction_limit (property): those whose
        divergence ends within a few % of λ/(π w0).
    evaluations, jacobian_evaluations, converged, message : the optimiser's (evaluations count a
        search's candidates).
    search : the global search's report, or None. family : with ``free="auto"``, the family
        chosen; choices : what the choice tried, one line each (empty otherwise).
    The fields from ``parameters`` to ``message`` are :class:`MultiFitResult`'s.
    """

    shared: Tuple[str, ...]
    per_curve: Tuple[str, ...]
    search: Optional[SearchReport] = None
    family: Optional[str] = None
    choices: Tuple[str, ...] = ()

    TUPLES: ClassVar[Tuple[str, ...]] = MultiFitResult.TUPLES + ("shared", "per_curve", "choices")

    def __post_init__(self) -> None:
        super().__post_init__()
        if len(self.curves) < 2:
            raise ValueError(
                f"curves = {_checks.shown(self.curves)} is invalid: expected a tuple of at least "
                "two FitResults"
            )

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
    return JointFitResult(
        **fit_fields(fit),
        shared=tuple(n for n in names if path_of(n) == n),
        per_curve=tuple(dict.fromkeys(path_of(n) for n in names if path_of(n) != n)),
        family=family,
        choices=tuple(choices),
    )
