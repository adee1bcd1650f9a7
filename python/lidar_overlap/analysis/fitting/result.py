"""The result of :func:`lidar_overlap.analysis.fitting.fit` (and
:func:`lidar_overlap.analysis.studies.telecover_fit`): the parameters, their covariance, the fitted
curve, and the model's prediction at other ranges with its 1-sigma band (the covariance propagated
through the Jacobian)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, ClassVar, Dict, List, Optional, Tuple, Union

import numpy as np

from ... import _checks, _values
from ..._pickling import ByValue
from ...forward.compute import run
from ...forward.planning import plan
from ...forward.result import OverlapResult
from ...model.parameters import unit
from ..sensitivity import jacobian
from .diffraction import at_diffraction_limit

#: Singular values of the normalised Jacobian below this fraction of the largest count as zero.
RANK_TOLERANCE = 1e-10


class DegeneracyWarning(RuntimeWarning):
    """The data cannot tell some free parameters apart (``|correlation|`` > 0.95, or a singular
    Jacobian)."""


def covariance(j: np.ndarray, scale: float) -> np.ndarray:
    """scale x (Jᵀ J)⁻¹ from the SVD of J (range, parameter); infinite where J is rank deficient."""
    _, s, vt = np.linalg.svd(j, full_matrices=False)
    if s.size == 0 or not s[-1] > RANK_TOLERANCE * s[0]:
        return np.full((j.shape[1],) * 2, np.inf)
    return scale * (vt.T / s**2) @ vt


def step_tolerance(p, tolerance: float) -> float:
    """The tolerance that sets the central-difference steps: RT's quadrature tolerance, else the
    fit's."""
    return p.rt_quadrature_tolerance if p.plain_rt else tolerance


@dataclass(frozen=True, eq=False)
class Prediction(ByValue):
    """The fitted model at ``ranges`` (m): ``overlap`` and its 1-sigma band ``sigma`` (from the
    covariance; inf where it is unbounded, NaN where rounding left no variance to take the root
    of)."""

    ranges: np.ndarray
    overlap: np.ndarray
    sigma: np.ndarray

    def __post_init__(self) -> None:
        _values.check(
            self,
            {
                "ranges": _values.array(low=0.0),
                "overlap": _values.array(),
                "sigma": _values.array(low=0.0, inf=True, nan=True),
            },
        )
        if not self.overlap.shape == self.sigma.shape == self.ranges.shape:
            raise ValueError(
                f"overlap and sigma have shapes {self.overlap.shape} and {self.sigma.shape}: "
                f"expected one value per range, {self.ranges.size}"
            )


@dataclass(frozen=True, eq=False)
class FitResult(ByValue):
    """A fit of free parameters of a lidar system to a measured overlap (SI units).

    Attributes
    ----------
    parameters, uncertainties, start : path -> best value, its 1-sigma uncertainty, the start.
    covariance, correlation : (k, k) in the order of ``parameters``.
    residuals : (model - measured) / sigma per range.
    chi_square, reduced_chi_square, degrees_of_freedom : of those residuals (n - k).
    result : the fitted :class:`OverlapResult`.
    measured, sigma : the data (sigma None when unit weights were used; then
        ``covariance_scaled`` is True: the covariance is scaled by the reduced chi-square).
    degenerate_pairs : (path, path, correlation) with ``|correlation|`` > 0.95.
    evaluations, jacobian_evaluations : model curves and Jacobians computed (one core call each on
        ray tracing).
    status, message, converged : the optimiser's.
    at_bounds : the parameters that end on a bound of the fit (the bound, not the data, set them;
        a divergence's default lower bound is just above the diffraction limit).
    at_diffraction_limit : (property) the fitted divergences within a few % of λ/(π w0).
    """

    parameters: Dict[str, float]
    uncertainties: Dict[str, float]
    start: Dict[str, float]
    covariance: np.ndarray
    correlation: np.ndarray
    residuals: np.ndarray
    chi_square: float
    reduced_chi_square: float
    degrees_of_freedom: int
    result: Union[OverlapResult, Any]  # a telecover fit's: its TelecoverResult
    measured: np.ndarray
    sigma: Optional[np.ndarray]
    covariance_scaled: bool
    degenerate_pairs: Tuple[Tuple[str, str, float], ...]
    evaluations: int
    jacobian_evaluations: int
    status: int
    message: str
    converged: bool
    loss: str
    plan: Any
    step_tolerance: float
    at_bounds: Tuple[str, ...] = ()

    FIELDS: ClassVar[Dict[str, Any]] = {
        "parameters": _values.reals(),
        "uncertainties": _values.reals(inf=True),
        "start": _values.reals(),
        "covariance": _values.array(2, square=True, inf=True),
        "correlation": _values.array(2, square=True, nan=True),
        "residuals": _values.array(),
        "chi_square": _values.real(low=0.0),
        "reduced_chi_square": _values.real(low=0.0, nan=True, inf=True),
        "degrees_of_freedom": _values.count(0),
        "measured": _values.array(),
        "sigma": _values.array(low=0.0, optional=True),
        "covariance_scaled": _values.flag,
        "evaluations": _values.count(0),
        "jacobian_evaluations": _values.count(0),
        "status": _values.count(-10),
        "message": _values.text,
        "converged": _values.flag,
        "loss": _values.text,
        "step_tolerance": _values.real(low=0.0),
    }

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        k = len(self.parameters)
        if set(self.uncertainties) != set(self.parameters) or set(self.start) != set(
            self.parameters
        ):
            raise ValueError(
                "uncertainties and start are invalid: expected one value per fitted parameter"
            )
        if self.covariance.shape != (k, k) or self.correlation.shape != (k, k):
            raise ValueError(
                f"covariance has shape {self.covariance.shape}: expected ({k}, {k}), one row and "
                "column per fitted parameter, as correlation"
            )
        if self.residuals.shape != self.measured.shape or (
            self.sigma is not None and self.sigma.shape != self.measured.shape
        ):
            raise ValueError(
                f"residuals has shape {self.residuals.shape}: expected one residual (and sigma) "
                f"per measured value, {self.measured.size}"
            )
        if not (
            isinstance(self.at_bounds, tuple)
            and all(path in self.parameters for path in self.at_bounds)
        ):
            raise ValueError(
                f"at_bounds = {_checks.shown(self.at_bounds)} is invalid: expected a tuple of "
                "fitted parameters"
            )
        if not isinstance(self.degenerate_pairs, tuple):
            raise ValueError(
                f"degenerate_pairs = {_checks.shown(self.degenerate_pairs)} is invalid: expected a "
                "tuple of (path, path, correlation)"
            )

    def __reduce__(self):
        # The plan holds the core's option objects, which do not pickle: it travels as what made it
        # (start system, ranges, request, threads) and is made again, with the same decisions.
        state = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        p = state.pop("plan")
        recipe = (p.system, p.ranges, p.request, int(getattr(p.options, "threads", 0)))
        return _rebuild_fit, (type(self), state, recipe)

    @property
    def system(self):
        """The fitted system."""
        return self.result.system

    @property
    def ranges(self) -> np.ndarray:
        return self.result.ranges

    @property
    def at_diffraction_limit(self) -> Tuple[str, ...]:
        """The fitted divergences that end within 6 % of their beam's diffraction limit λ/(π w0)
        (:mod:`lidar_overlap.analysis.fitting.diffraction`); () for a fit without a system."""
        system = getattr(self.result, "system", None)
        return () if system is None else at_diffraction_limit(system, self.parameters)

    def predict(self, ranges) -> Prediction:
        """The fitted model at ``ranges`` (m) and its 1-sigma band, sqrt(diag(J C Jᵀ)) with J =
        dG/dp there: e.g. the near range of a curve measured only from 150 m. The fit's plan (model
        and options) is kept; the band covers the parameters' uncertainty, not the model's own error
        (``result.error_estimate``)."""
        p = self.plan.with_system(self.system).at(ranges)
        z = p.ranges
        g = run(p).overlap
        if not np.all(np.isfinite(self.covariance)):
            # inf x 0 would give NaN where G does not depend on the parameters: say it instead.
            _checks.warn(
                "predict: the fit's covariance is infinite (its Jacobian was singular), so the "
                "1-sigma band is unbounded (inf) at every range; fix a degenerate parameter and "
                "fit again",
                DegeneracyWarning,
            )
            return Prediction(z, g, np.full(z.shape, np.inf))
        j = jacobian(p, self.system, list(self.parameters), self.step_tolerance)
        band = np.sqrt(np.maximum(np.einsum("ij,jk,ik->i", j, self.covariance, j), 0.0))
        return Prediction(z, g, band)

    def summary(self) -> str:
        """The parameters with uncertainties, chi-square and degeneracies, one line each."""
        lines = [
            f"fit ({self.result.method}, loss {self.loss}): "
            f"{'converged' if self.converged else 'NOT converged'} after {self.evaluations} model "
            f"and {self.jacobian_evaluations} Jacobian evaluations"
        ]
        for path, value in self.parameters.items():
            lines.append(
                f"  {path:<22} {value:+.6g} ± {self.uncertainties[path]:.3g} {unit(path)}  (start "
                f"{self.start[path]:+.6g})"
            )
        scaled = " (unit weights: covariance scaled by it)" if self.covariance_scaled else ""
        lines.extend(verdict_lines(self, scaled))
        return "\n".join(lines)

    __str__ = summary

    def table(self):
        """Rows (path, value, uncertainty, unit, start) for files."""
        return [
            (path, v, self.uncertainties[path], unit(path), self.start[path])
            for path, v in self.parameters.items()
        ]

    def plot(self, ranges=None, fig=None):
        """Data with error bars, the fitted curve with its 1-sigma band over ``ranges`` (default:
        from a quarter of the first measured range, where valid, to the last) and the residuals
        below. Returns the matplotlib Figure (needs ``pip install 'lidar-overlap[plot]'``). A
        telecover fit: the measured and fitted deviations per sector (at the measured ranges) and
        the residuals."""
        from matplotlib.figure import Figure

        plot_fit = getattr(self.result, "plot_fit", None)  # a telecover fit's result plots it
        if plot_fit is not None:
            return plot_fit(self, fig or Figure(figsize=(7.0, 5.6), constrained_layout=True))
        z = self.ranges
        if ranges is None:
            ranges = np.geomspace(z[0] / 4, z[-1], 200)
            try:
                self.system._native.validate_ranges(ranges)
            except ValueError:
                ranges = np.geomspace(z[0], z[-1], 200)
        pred = self.predict(ranges)
        fig = fig or Figure(figsize=(7.0, 5.6), constrained_layout=True)
        top, bottom = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": (3, 1)})
        err = (
            self.sigma
            if self.sigma is not None
            else np.full(z.shape, math.sqrt(self.reduced_chi_square))
        )
        top.errorbar(z, self.measured, yerr=err, fmt=".", ms=3, lw=0.6, color="k", label="measured")
        top.plot(pred.ranges, pred.overlap, color="C0", label="fitted model")
        top.fill_between(
            pred.ranges,
            pred.overlap - pred.sigma,
            pred.overlap + pred.sigma,
            color="C0",
            alpha=0.3,
            label="1-sigma band (parameters)",
        )
        top.set_xscale("log")
        top.set_ylabel("overlap G")
        top.legend(fontsize=8, loc="lower right")
        top.set_title(
            "; ".join(
                f"{p} = {v:.4g} ± {self.uncertainties[p]:.2g} {unit(p)}"
                for p, v in self.parameters.items()
            ),
            fontsize=8,
        )
        bottom.axhline(0.0, color="0.5", lw=0.6)
        bottom.plot(z, self.residuals, ".", color="k", ms=3)
        bottom.set_xlabel("range (m)")
        bottom.set_ylabel("residual / sigma" if self.sigma is not None else "residual")
        return fig


def verdict_lines(result, scaled: str = "") -> List[str]:
    """The chi-square (``scaled``: a note after it), degeneracy, bound and diffraction-limit lines
    of a fit result's summary (single or of several curves)."""
    lines = [
        f"  chi-square {result.chi_square:.4g} for {result.degrees_of_freedom} degrees of freedom, "
        f"reduced {result.reduced_chi_square:.4g}{scaled}"
    ]
    for a, b, c in result.degenerate_pairs:
        lines.append(f"  degenerate: {a} and {b} (correlation {c:+.3f})")
    if result.at_bounds:
        lines.append(f"  on a bound (set by it, not by the data): {', '.join(result.at_bounds)}")
    if result.at_diffraction_limit:
        lines.append(f"  at the diffraction limit: {', '.join(result.at_diffraction_limit)}")
    return lines


def _rebuild_fit(cls, state, recipe):
    """A pickled :class:`FitResult`, its plan made again from its recipe."""
    import warnings

    system, ranges, request, threads = recipe
    with warnings.catch_warnings():  # said when the fit was planned
        warnings.simplefilter("ignore")
        return cls(**state, plan=plan(system, ranges, request, threads=threads))
