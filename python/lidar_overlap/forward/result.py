"""The result of an overlap computation and the ranges derived from it."""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass
from typing import Any, Dict, Optional

import numpy as np

from .. import _checks, _pickling
from .._core import __version__
from ..model.system import LidarSystem
from ..model.system_attributes import system_attributes
from ..model.turbulence import TWO_WAY_BOUND
from . import result_files
from .far_range import FAR_SLOPE, still_rising  # noqa: F401  (FAR_SLOPE re-exported)
from .result_checks import ROUND_OFF, checked_curve, frozen
from .result_files import CSV_COLUMNS  # noqa: F401  (re-exported)

#: What ``error_estimate`` means: a bound from the quadrature (RT, plus auto's model error), the
#: measured accuracy of a path (FO), or the standard error of a mean over random draws (turbulence).
ERROR_KINDS = ("bound", "nominal", "standard_error")


@dataclass(frozen=True, eq=False)
class OverlapResult:
    """Overlap function G(z) on a range grid.

    Attributes
    ----------
    ranges : m, the ranges asked for.
    overlap : G at each range (dimensionless, 0..1).
    method : the model that computed it (``"rt"`` or ``"fo"``).
    error_estimate : estimated absolute error of each G value (NaN where the method gives none), of
        the kind ``error_kind`` says.
    system : the lidar it describes (``None`` for a result read from a file whose beam is not
        Gaussian).
    tolerance : the absolute tolerance that was asked for (NaN where none was).
    error_kind : ``"bound"`` (RT: the adaptive quadrature's error bound, plus the model error
        ``method="auto"`` estimated for ray tracing), ``"nominal"`` (FO: the path's measured
        accuracy, the same at every range) or ``"standard_error"`` (turbulence: the standard error
        of the mean over the draws).

    Two results are equal (``==``) when every field is: arrays element by element (NaN equal to
    NaN), and the systems. :meth:`allclose` compares the curves within a tolerance.

    Checked on construction, so that no computation failure can pass as a result: ``ranges`` finite,
    > 0 and strictly increasing; ``overlap`` and ``error_estimate`` one value per range;
    ``error_estimate`` >= 0 or NaN; every G finite and within [0, 1] up to round-off
    (:data:`ROUND_OFF`, a fixed 1e-9, not the stated error). G outside that is a ValueError naming
    the range, the value and the method; G within it is clipped into [0, 1]. The arrays are
    read-only copies, and a pickle is rebuilt through the constructor, so a result is a value: it
    cannot be changed after its checks.
    """

    ranges: np.ndarray
    overlap: np.ndarray
    method: str
    error_estimate: np.ndarray
    system: Optional[LidarSystem]
    tolerance: float
    error_kind: str = "bound"

    def __post_init__(self) -> None:
        for name, value in zip(
            ("ranges", "overlap", "error_estimate", "tolerance"),
            checked_curve(
                self.ranges,
                self.overlap,
                self.method,
                self.error_estimate,
                self.tolerance,
                self._upper_bound(),
            ),
        ):
            object.__setattr__(self, name, value)
        _checks.choice("error_kind", self.error_kind, ERROR_KINDS)
        if self.system is not None:
            if not isinstance(self.system, LidarSystem):
                raise ValueError(
                    f"system = {_checks.shown(self.system)} is invalid: expected a LidarSystem, "
                    "or None for a curve read from a file without one"
                )
            self.system._native.validate_ranges(self.ranges)

    def _upper_bound(self) -> float:
        """Largest G the result may hold: 1 (power on the detector over the power into the
        aperture), more only where physics allows it (two-way turbulence,
        :class:`TurbulentOverlapResult`)."""
        return 1.0

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return all(
            _same(getattr(self, f.name), getattr(other, f.name)) for f in dataclasses.fields(self)
        )

    __hash__ = None  # type: ignore[assignment]  # results hold arrays

    def allclose(self, other: "OverlapResult", atol: float = 1e-12) -> bool:
        """True when ``other`` has the same ranges and its G is within ``atol`` (absolute) of this
        one's at every range (methods, errors and systems may differ: this compares curves)."""
        if not isinstance(other, OverlapResult):
            raise ValueError(
                f"other = {_checks.shown(other)} is invalid: expected an OverlapResult"
            )
        atol = _checks.real("atol", atol)
        if not atol >= 0.0:
            raise ValueError(f"atol = {atol!r} is invalid: expected a value >= 0")
        return bool(
            np.array_equal(self.ranges, other.ranges)
            and np.all(np.abs(self.overlap - other.overlap) <= atol)
        )

    def full_overlap_range(self, threshold: float = 0.99) -> float:
        """First range (m) of the grid where G >= threshold · max G; NaN if G is zero everywhere.

        Relative to the maximum, so an obstructed system (max G = 1 - (r_obs/R)²) has one too. That
        is the full-overlap range only when max G is the curve's far-range limit, which the grid
        must reach.

        Warns (RuntimeWarning), and :meth:`reaches_far_range` is False, when G still rises at the
        end of the ranges by more than 1 % of max G per decade (from z_last / 2, or the first range,
        to z_last, less the two values' error estimates), or for a single range: extend the ranges.
        Why: G nears its limit as gap(z) ~ z^-k, k >= 1 (offsets, tilts, image sizes scale as 1/z),
        so it rises by k ln(10) gap >= 2.3 gap per decade, and a curve rising by less than 1 % per
        decade ends within 0.43 % of its limit. A curve that peaks and falls (defocus) does not
        warn; where the maximum sits is no test (a converged, rising curve has it at the last range
        too).
        """
        threshold = _checks.unit_interval("threshold", threshold, include_one=True)
        peak = float(np.max(self.overlap))
        if peak <= 0.0:
            return float("nan")
        reason = still_rising(self.ranges, self.overlap, self.error_estimate, peak)
        if reason:
            warnings.warn(f"full_overlap_range: {reason}", RuntimeWarning, stacklevel=2)
        return float(self.ranges[np.argmax(self.overlap >= threshold * peak)])

    def reaches_far_range(self) -> bool:
        """False when :meth:`full_overlap_range` would warn that G is still rising at the end of the
        ranges (or there is only one range), True otherwise: a caller can test it instead of
        catching the warning."""
        return (
            still_rising(
                self.ranges, self.overlap, self.error_estimate, float(np.max(self.overlap))
            )
            is None
        )

    def first_signal_range(self, threshold: float = 1e-3) -> float:
        """First range (m) of the grid where G >= threshold (absolute fraction); NaN if never."""
        threshold = _checks.unit_interval("threshold", threshold)
        hit = self.overlap >= threshold
        return float(self.ranges[np.argmax(hit)]) if hit.any() else float("nan")

    def plot(self, ax=None, **line_kwargs):
        """Plot G(z) on a logarithmic range axis, with the full-overlap and first-signal ranges
        marked. Returns the matplotlib Axes (needs ``pip install lidar-overlap[plot]``)."""
        from ..views.plotting import plot_overlap

        return plot_overlap(self, ax=ax, **line_kwargs)

    # ------------------------------------------------------------------ files
    def attributes(self) -> Dict[str, Any]:
        """Metadata written to files: method, tolerance and the system, flattened (SI units in the
        names)."""
        attrs: Dict[str, Any] = {
            "method": self.method,
            "tolerance": float(self.tolerance),
            "error_kind": self.error_kind,
            "lidar_overlap_version": __version__,
        }
        if self.system is not None:
            attrs.update(system_attributes(self.system))
        return attrs

    def to_csv(self, path, attrs: Optional[Dict[str, Any]] = None) -> None:
        """Write ``# key: value`` header lines (method, tolerance, system), then the columns
        ``range_m,overlap,error_estimate``. Numbers are written with ``repr``, so they read back
        exactly. ``attrs`` adds header keys (numbers, or one-line text that does not read as a
        number); a key the result writes itself (method, tolerance, error_kind, format, system and
        its ``beam_``, ``telescope_``, ``detector_``, ``aberration_``, ``mask_`` keys) is a
        ValueError. The result's values are checked again before writing. The file appears under
        ``path`` only once complete (written beside it, then renamed)."""
        _recheck(self)
        result_files.write_csv(self, path, attrs)

    @classmethod
    def from_csv(cls, path) -> "OverlapResult":
        """Read a result written by :meth:`to_csv`. ``system`` is rebuilt from the header for a
        Gaussian beam, else ``None``. Header lines count only before the columns, each key once. A
        file that is not such a result (or not a regular file), whose system header is corrupt, or
        whose values break the class's checks (a NaN or out-of-range G) is a ValueError naming the
        file."""
        return result_files.read_csv(
            cls, path, TurbulentOverlapResult if cls is OverlapResult else None
        )

    def to_xarray(self, attrs: Optional[Dict[str, Any]] = None):
        """An ``xarray.Dataset`` with coordinate ``range`` (m), variables ``overlap`` and
        ``error_estimate``, CF-1.10 global attributes and the system as flattened numeric attributes
        (needs ``[io]``). ``attrs`` as in :meth:`to_csv` (nor may it replace the CF attributes)."""
        _recheck(self)
        return result_files.to_xarray(self, attrs)

    def to_netcdf(
        self, path, attrs: Optional[Dict[str, Any]] = None, engine: Optional[str] = None
    ) -> None:
        """Write :meth:`to_xarray` to a NetCDF file. ``engine=None``: ``"h5netcdf"`` (NetCDF-4) when
        h5netcdf and its h5py backend are installed, else ``"scipy"`` (NetCDF-3, same variables and
        attributes). The file appears under ``path`` only once complete (written beside it, then
        renamed)."""
        _recheck(self)
        result_files.write_netcdf(self, path, attrs, engine)

    @classmethod
    def from_netcdf(cls, path, engine: Optional[str] = None) -> "OverlapResult":
        """Read a result written by :meth:`to_netcdf`; ``system`` is rebuilt for a Gaussian beam,
        else ``None``. A file that is not such a result (text, truncated, not a regular file), a
        corrupt system attribute or values that break the class's checks are a ValueError naming the
        file."""
        return result_files.read_netcdf(
            cls, path, engine, TurbulentOverlapResult if cls is OverlapResult else None
        )

    def __reduce__(self):
        # Unpickled through the constructor, so a tampered pickle is checked like any new value.
        return _pickling.rebuild, (
            type(self),
            {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.init},
        )


def _recheck(result: "OverlapResult") -> None:
    """The construction checks again on the stored values: a result whose arrays were made writable
    and changed is not written."""
    checked = checked_curve(
        result.ranges,
        result.overlap,
        result.method,
        result.error_estimate,
        result.tolerance,
        result._upper_bound(),
    )
    if not all(
        np.array_equal(a, b, equal_nan=True)
        for a, b in zip(checked[:3], (result.ranges, result.overlap, result.error_estimate))
    ):
        raise ValueError("the result's arrays were changed after construction: not written")


def _same(a: Any, b: Any) -> bool:
    """Equality of two field values: arrays element by element with NaN equal to NaN, floats with
    NaN equal to NaN, anything else by ==."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        try:
            return bool(np.array_equal(a, b, equal_nan=True))
        except TypeError:  # arrays without a NaN (bools, objects)
            return bool(np.array_equal(a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


#: Percentiles of the spread band a turbulent result reports per range.
BAND = (5.0, 95.0)
#: Realisations one turbulent overlap may draw (the core's bound on the FO path).
MAX_REALIZATIONS = 1_000_000


@dataclass(frozen=True, eq=False)
class TurbulentOverlapResult(OverlapResult):
    """An :class:`OverlapResult` whose ``overlap`` is the mean over ``realizations`` (K × N array,
    one row per draw of the atmosphere), with ``std`` and the 5–95 % percentile band ``low``,
    ``high``; ``error_estimate`` is the standard error of the mean (``error_kind``
    ``"standard_error"``).

    ``paths`` says which paths crossed the turbulence. With ``"both"``: ``amplification`` (N), the
    backscatter amplification, mean G over the mean G with uncorrelated paths; ``uncorrelated`` (K ×
    N, Fourier optics) each draw's beam with an independent draw's receiver, whose mean that is
    (ray tracing computes that mean exactly and gives no rows: None); and the mean G may exceed 1
    (up to :data:`~lidar_overlap.model.turbulence.TWO_WAY_BOUND`, docs/turbulence.md). A single
    draw's G (and so ``realizations``, ``low``, ``high``, ``uncorrelated``) may exceed that bound: a
    bright spot shared by both paths, or the speckle of few receiver fields."""

    realizations: Optional[np.ndarray] = None
    std: Optional[np.ndarray] = None
    low: Optional[np.ndarray] = None
    high: Optional[np.ndarray] = None
    paths: str = "transmit"
    uncorrelated: Optional[np.ndarray] = None
    amplification: Optional[np.ndarray] = None

    def _upper_bound(self) -> float:
        return TWO_WAY_BOUND if self.paths == "both" else 1.0

    def _no_light_where_nan(self, amplification: np.ndarray) -> None:
        """An amplification is NaN only where no light comes back (a ratio 0/0): where the mean G,
        or the mean of the ``uncorrelated`` rows, is 0."""
        dark = self.overlap == 0.0
        if self.uncorrelated is not None:
            dark |= np.asarray(self.uncorrelated, dtype=float).mean(axis=0) == 0.0
        bad = np.isnan(amplification) & ~dark
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(
                f"amplification[{i}] = nan at range {float(self.ranges[i])!r} m is invalid: NaN "
                f"only where no light comes back, but the mean G there is {self.overlap[i]!r}"
            )

    def attributes(self) -> Dict[str, Any]:
        """As :meth:`OverlapResult.attributes`, and which paths crossed the turbulence and over
        how many draws the mean was taken (a file read back is then a mean through turbulence, whose
        two-way values may exceed 1)."""
        attrs = super().attributes()
        attrs["turbulence_paths"] = self.paths
        if self.realizations is not None:
            attrs["turbulence_realizations"] = int(self.realizations.shape[0])
        return attrs

    def __post_init__(self) -> None:
        _checks.choice("paths", self.paths, ("transmit", "both"))
        super().__post_init__()
        n = self.ranges.size
        if self.paths == "transmit" and (
            self.uncorrelated is not None or self.amplification is not None
        ):
            raise ValueError(
                "uncorrelated and amplification are given for paths = 'transmit': expected them "
                "only with turbulence on both paths"
            )
        for name in ("realizations", "std", "low", "high", "uncorrelated", "amplification"):
            value = getattr(self, name)
            if value is None:
                continue
            if name == "amplification":  # a ratio of means, NaN where no light comes back
                values = _checks.real_array(name, value, ndim=1)
                if values.shape != (n,) or np.any(values[np.isfinite(values)] < 0.0):
                    raise ValueError(
                        f"amplification has shape {values.shape} or a negative value: expected one "
                        f"ratio >= 0 (or NaN) per range, N = {n}"
                    )
                self._no_light_where_nan(values)
                object.__setattr__(self, name, frozen(values))
                continue
            ndim = 2 if name in ("realizations", "uncorrelated") else 1
            values = _checks.real_array(name, value, ndim=ndim)
            if values.shape[-1] != n or (ndim == 2 and values.shape[0] == 0):
                raise ValueError(
                    f"{name} has shape {values.shape}: expected "
                    + ("K x N, one row per draw" if ndim == 2 else "one value per range")
                    + f" for N = {n} ranges"
                )
            upper = self._upper_bound()
            if self.paths == "both" and name != "std":  # one draw's G, not the mean: >= 0 only
                upper = math.inf
            bad = ~np.isfinite(values)
            if name != "std":
                bad |= ~((values >= -ROUND_OFF) & (values <= upper + ROUND_OFF))
            elif not bad.any():
                bad = values < 0.0
            if bad.any():
                raise ValueError(
                    f"{name} holds {float(values[bad].flat[0])!r}: expected finite values"
                    + (" >= 0" if name == "std" else f" within [0, {upper:g}]")
                )
            if name != "std":
                values = np.clip(values, 0.0, upper)
            object.__setattr__(self, name, frozen(values))
