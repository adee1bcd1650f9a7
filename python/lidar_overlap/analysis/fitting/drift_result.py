"""The result of ``lo.fit_drift`` (:mod:`lidar_overlap.analysis.fitting.drift`): the fixed and
drifting parameters with one covariance, the overlap predicted (with its 1-sigma band) for any
covariate value, and the drift in physical units."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar, Dict, Optional, Tuple

import numpy as np

from ... import _checks, _values
from ...model import parameters as _parameters
from . import drift_prediction, multi_result
from .drift_basis import DriftBasis, warn_outside
from .drift_names import OFFSET, REFERENCE, SLOPE, knot_name
from .drift_reference import checked_reference
from .global_result import SearchReport
from .multi_result import MultiFitResult, verdict_lines
from .relative_result import RelativeFitResult

#: Units the summary shows the drifts in: SI unit -> (factor, unit).
SHOWN = {"rad": (1e6, "µrad"), "m": (1e3, "mm"), "1": (1.0, "")}


@dataclass(frozen=True, eq=False)
class DriftFitResult(MultiFitResult):
    """A drift fit of a series of curves against a covariate (SI units per covariate unit).

    Attributes
    ----------
    parameters, uncertainties, start : name -> value, 1-sigma uncertainty, start: each free path's
        value at the reference covariate, and for each drifting path ``path@slope``, its slope
        (SI unit per covariate unit; a spline's mean slope over the covariate's span), then for a
        spline ``path@knot[j]``, its departure at interior knot j from the chord through its end
        values (SI unit; :mod:`lidar_overlap.analysis.fitting.drift_basis`).
    covariance, correlation : (K, K) in the order of ``parameters``.
    chi_square, reduced_chi_square, degrees_of_freedom : over all curves.
    free, drifting : the free paths and those of them that drift.
    covariate : one value per curve; covariate_reference : c_ref, the covariate's mean, where the
        free paths take their ``parameters`` values; covariate_unit : its unit's name.
    curves : one :class:`FitResult` per curve (its paths at its covariate, their covariance; with
        a reference, its residuals the differential ones and its fitted curve the model's alone).
    reference, reference_ranges : the reference curve as given and the fitted ranges (m) it is
        on, or None; reference_offsets : the paths with their own offset at the reference
        (:mod:`lidar_overlap.analysis.fitting.drift_reference`).
    degenerate_pairs, at_bounds, evaluations, jacobian_evaluations, converged, message : as in
        :class:`JointFitResult` (at_diffraction_limit too); search : the global search's report or
        None; choices : with ``drifting="auto"`` (or ``free="auto"``), what the choice tried, one
        line each; splines : the drifting paths that are splines (the others linear); knots : their
        knots (covariate values; empty without a spline). The fields from ``parameters`` to
        ``message`` are :class:`MultiFitResult`'s.
    """

    free: Tuple[str, ...]
    drifting: Tuple[str, ...]
    covariate: np.ndarray
    covariate_reference: float
    covariate_unit: str
    search: Optional[SearchReport] = None
    choices: Tuple[str, ...] = ()
    splines: Tuple[str, ...] = ()
    knots: np.ndarray = field(default_factory=lambda: np.empty(0))
    reference: Optional[np.ndarray] = None
    reference_ranges: Optional[np.ndarray] = None
    reference_offsets: Tuple[str, ...] = ()

    FIELDS: ClassVar[Dict[str, Any]] = {
        **multi_result.FIELDS,
        "covariate": _values.array(),
        "covariate_reference": _values.real(),
        "covariate_unit": _values.text,
        "knots": _values.array(),
    }
    TUPLES: ClassVar[Tuple[str, ...]] = MultiFitResult.TUPLES + (
        "free",
        "drifting",
        "choices",
        "splines",
        "reference_offsets",
    )

    def __post_init__(self) -> None:
        super().__post_init__()
        if not set(self.splines) <= set(self.drifting):
            raise ValueError(
                f"splines = {self.splines} is invalid: expected drifting paths ({self.drifting})"
            )
        few = bool(self.splines) and self.knots.size < 3
        if bool(self.splines) != bool(self.knots.size) or few or np.any(np.diff(self.knots) <= 0):
            raise ValueError(
                f"knots = {_checks.shown(self.knots)} is invalid: expected strictly increasing "
                "covariate values with a spline drift, none without"
            )
        names = list(self.free) + self.basis.names
        if self.reference is not None:
            names += [REFERENCE] + [p + OFFSET for p in self.reference_offsets]
        if list(self.parameters) != names:
            raise ValueError(
                "parameters and uncertainties are invalid: expected the free paths, then each "
                "drifting path's slope (a spline's departures at its knots; with a reference, its "
                "covariate and offsets)"
            )
        if len(self.curves) != self.covariate.size:
            raise ValueError(
                "curves is invalid: expected a tuple of one FitResult per covariate value"
            )

    @property
    def basis(self) -> DriftBasis:
        """How the drifting paths depend on the covariate (their columns of ``parameters``)."""
        return DriftBasis(self.drifting, self.covariate_reference, self.splines, self.knots)

    @property
    def drift(self) -> Dict[str, Tuple[float, float]]:
        """{path: (slope, its 1-sigma uncertainty)} of each drifting path, SI unit per covariate
        unit: a linear drift's slope; a spline's mean slope over the covariate's span, (p(c_max) -
        p(c_min)) / (c_max - c_min), its own parameter (``path@slope``), so that its uncertainty
        is that parameter's in the covariance."""
        return {
            p: (self.parameters[p + SLOPE], self.uncertainties[p + SLOPE]) for p in self.drifting
        }

    @property
    def coefficients(self) -> int:
        """The numbers a prediction needs beside the start system and the reference curve: every
        fitted parameter (values, slopes, the reference's covariate and offsets)."""
        return len(self.parameters)

    @property
    def reference_covariate(self) -> Tuple[float, float]:
        """(c_ref, its 1-sigma uncertainty): the covariate value at which the reference lies on
        the drift line (covariate unit); NaN without a reference."""
        if self.reference is None:
            return (float("nan"), float("nan"))
        return (self.parameters[REFERENCE], self.uncertainties[REFERENCE])

    def matrix(self, covariate: float) -> np.ndarray:
        """M (free paths, K): the free paths' values at ``covariate`` are M @ parameters."""
        k, names = len(self.free), list(self.parameters)
        m = np.zeros((k, len(names)))
        m[:, :k] = np.eye(k)
        owners = [self.free.index(p) for p in self.basis.owners]
        m[owners, k + np.arange(len(owners))] = self.basis.columns(covariate)[0]
        return m

    def drift_curve(self, path: str, covariate) -> Tuple[np.ndarray, np.ndarray]:
        """(value, its 1-sigma uncertainty) of the free ``path`` at each ``covariate`` value (SI
        unit): a + b (c - c_ref) for a linear drift, the spline for a spline drift, a constant for
        a path that does not drift; the uncertainty sqrt(m C mᵀ) from the covariance. Outside the
        fitted span a warning says it is extrapolated (linearly)."""
        if path not in self.free:
            raise ValueError(
                f"path = {_checks.shown(path)} is invalid: expected a free path "
                f"({', '.join(self.free)})"
            )
        c = _checks.finite_array("covariate", np.atleast_1d(covariate), ndim=1)
        warn_outside(c, self.span, self.covariate_unit)
        rows = np.array([self.matrix(ci)[self.free.index(path)] for ci in c])
        value = rows @ np.array(list(self.parameters.values()))
        with np.errstate(invalid="ignore"):
            var = np.einsum("ij,jk,ik->i", rows, self.covariance, rows)
        return value, np.sqrt(np.maximum(var, 0.0))

    @property
    def span(self) -> Tuple[float, float]:
        """The fitted covariate span (smallest, largest value)."""
        return float(self.covariate.min()), float(self.covariate.max())

    def system_at(self, covariate: float):
        """The fitted system at ``covariate`` (beyond the fitted span every drift continues
        linearly)."""
        values = self.matrix(covariate) @ np.array(list(self.parameters.values()))
        return _parameters.replace(self.curves[0].system, dict(zip(self.free, values.tolist())))

    def predict(self, ranges, covariate, band: bool = False, reference=None):
        """The fitted overlap at ``ranges`` (m) for each value of ``covariate``: shape
        (len(covariate), len(ranges)); relative like the data when they were normalised (each
        curve divided by its mean over the measured ranges of the normalisation interval, or by
        its far-range limit; the retrieval's extinction bias, not the instrument's, is left out).
        ``band=True``: (overlap, its 1-sigma band from the covariance, sqrt(diag(J M C Mᵀ Jᵀ)) of
        the normalised model).

        With a reference (``lo.fit_drift(..., reference=)``): the model plus the reference's
        residual G_ref - M(θ_ref), normalised like the data; ``reference``: the reference curve at
        ``ranges`` (e.g. at gates between the fitted ones), None: the fit's own, interpolated
        linearly between the fitted ranges, the residual taken as 0 (the model alone) outside
        them."""
        z = _checks.ranges("ranges", ranges)
        c = _checks.finite_array("covariate", np.atleast_1d(covariate), ndim=1)
        warn_outside(c, self.span, self.covariate_unit)
        given = None
        if reference is not None:
            if self.reference is None:
                raise ValueError(
                    f"reference = {_checks.shown(reference)} is invalid: this drift fit has no "
                    "reference; leave it out"
                )
            given = checked_reference(reference, z, False)
        first = self.curves[0]
        normalizing = first.normalizing_ranges if isinstance(first, RelativeFitResult) else None
        return self.prediction(z, c, normalizing, band, given)

    def prediction(self, z, c, normalizing, band: bool, reference=None):
        """:meth:`predict` at checked ranges ``z`` and covariates ``c``, divided by the mean over
        ``normalizing`` ranges (m; None: absolute, or with a reference on the data's scale);
        ``reference`` at ``z`` or None (:func:`.drift_prediction.prediction`)."""
        self.curves[0].system._native.validate_ranges(z)
        return drift_prediction.prediction(self, z, c, normalizing, band, reference)

    def summary(self) -> str:
        """The parameters, the drifts in physical units per covariate unit, one line each."""
        unit_c = self.covariate_unit
        lines = [
            f"drift fit of {len(self.curves)} curves against the covariate ({unit_c}; reference "
            f"{self.covariate_reference:.4g}): "
            f"{'converged' if self.converged else 'NOT converged'} after {self.evaluations} model "
            f"and {self.jacobian_evaluations} Jacobian evaluations"
        ]
        for p in self.free:
            lines.append(
                f"  {p:<24} {self.parameters[p]:+.6g} ± {self.uncertainties[p]:.3g} "
                f"{_parameters.unit(p)} at {self.covariate_reference:.4g} {unit_c}"
            )
        for p, (slope, sd) in self.drift.items():
            factor, shown = SHOWN.get(_parameters.unit(p), (1.0, _parameters.unit(p)))
            mean = " (spline: mean over the span)" if p in self.splines else ""
            lines.append(
                f"  drift of {p:<15} {factor * slope:+.4g} ± {factor * sd:.2g} {shown}/{unit_c}"
                + mean
            )
            for j in range(1, self.knots.size - 1) if p in self.splines else ():
                name = knot_name(p, j)
                lines.append(
                    f"    off the chord at {self.knots[j]:.4g} {unit_c}: "
                    f"{factor * self.parameters[name]:+.4g} ± "
                    f"{factor * self.uncertainties[name]:.2g} {shown}"
                )
        if not self.drifting:
            lines.append("  no parameter drifts")
        if self.reference is not None:
            c_ref, sd = self.reference_covariate
            lines.append(
                f"  reference on the drift line at {c_ref:.4g} ± {sd:.2g} {unit_c}"
                + "".join(
                    f", {p} offset {self.parameters[p + OFFSET]:+.4g} ± "
                    f"{self.uncertainties[p + OFFSET]:.2g} {_parameters.unit(p)}"
                    for p in self.reference_offsets
                )
                + f"; {self.coefficients} coefficients"
            )
        lines.extend(verdict_lines(self))
        return "\n".join(lines)

    __str__ = summary
