"""The result of an overlap computation and the ranges derived from it."""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import Any, Dict, Optional

import numpy as np

from . import _checks, _files
from .system import LidarSystem
from .system_attributes import system_attributes, system_from_attributes

CSV_COLUMNS = ("range_m", "overlap", "error_estimate")
#: Smallest allowance for G outside [0, 1] (the round-off of a sum of order-one terms), used where the
#: result states neither an error estimate nor a tolerance.
ROUND_OFF = 1e-12
#: full_overlap_range warns when G still rises at the end of the ranges by more than this fraction of its
#: maximum per decade of range.
FAR_SLOPE = 0.01
#: What ``error_estimate`` means: a bound from the quadrature (RT, plus auto's model error), the measured
#: accuracy of a path (FO), or the standard error of a mean over random draws (turbulence).
ERROR_KINDS = ("bound", "nominal", "standard_error")
_IO_HINT = "reading and writing NetCDF needs xarray and h5netcdf (with h5py): pip install 'lidar-overlap[io]'"


@dataclass(frozen=True, eq=False)
class OverlapResult:
    """Overlap function G(z) on a range grid.

    Attributes
    ----------
    ranges : m, the ranges asked for.
    overlap : G at each range (dimensionless, 0..1).
    method : the model that computed it (``"rt"`` or ``"fo"``).
    error_estimate : estimated absolute error of each G value (NaN where the method gives none), of the kind
        ``error_kind`` says.
    system : the lidar it describes (``None`` for a result read from a file whose beam is not Gaussian).
    tolerance : the absolute tolerance that was asked for (NaN where none was).
    error_kind : ``"bound"`` (RT: the adaptive quadrature's error bound, plus the model error ``method="auto"``
        estimated for ray tracing), ``"nominal"`` (FO: the path's measured accuracy, the same at every range) or
        ``"standard_error"`` (turbulence: the standard error of the mean over the draws).

    Two results are equal (``==``) when every field is: arrays element by element (NaN equal to NaN), and the
    systems. :meth:`allclose` compares the curves within a tolerance.

    Checked on construction, so that no computation failure can pass as a result: ``ranges`` finite, > 0 and
    strictly increasing; ``overlap`` and ``error_estimate`` one value per range; ``error_estimate`` >= 0 or
    NaN; every G finite and within [0, 1] up to its slack, max(error_estimate, tolerance, 1e-12) (each
    where finite). G outside that is a ValueError naming the range, the value and the method; G within it
    (round-off) is clipped into [0, 1].
    """

    ranges: np.ndarray
    overlap: np.ndarray
    method: str
    error_estimate: np.ndarray
    system: Optional[LidarSystem]
    tolerance: float
    error_kind: str = "bound"

    def __post_init__(self) -> None:
        for name, value in zip(("ranges", "overlap", "error_estimate", "tolerance"),
                               _checked(self.ranges, self.overlap, self.method, self.error_estimate, self.tolerance,
                                        self._upper_bound())):
            object.__setattr__(self, name, value)
        _checks.choice("error_kind", self.error_kind, ERROR_KINDS)

    def _upper_bound(self) -> float:
        """Largest G the result may hold: 1 (power on the detector over the power into the aperture), more only
        where physics allows it (two-way turbulence, :class:`lidar_overlap.turbulence.TurbulentOverlapResult`)."""
        return 1.0

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return all(_same(getattr(self, f.name), getattr(other, f.name)) for f in dataclasses.fields(self))

    __hash__ = None  # type: ignore[assignment]  # results hold arrays

    def allclose(self, other: "OverlapResult", atol: float = 1e-12) -> bool:
        """True when ``other`` has the same ranges and its G is within ``atol`` (absolute) of this one's at every
        range (methods, errors and systems may differ: this compares curves)."""
        if not isinstance(other, OverlapResult):
            raise ValueError(f"other = {_checks.shown(other)} is invalid: expected an OverlapResult")
        atol = _checks.real("atol", atol)
        if not atol >= 0.0:
            raise ValueError(f"atol = {atol!r} is invalid: expected a value >= 0")
        return bool(np.array_equal(self.ranges, other.ranges)
                    and np.all(np.abs(self.overlap - other.overlap) <= atol))

    def full_overlap_range(self, threshold: float = 0.99) -> float:
        """First range (m) of the grid where G >= threshold · max G; NaN if G is zero everywhere.

        Relative to the maximum, so an obstructed system (max G = 1 - (r_obs/R)²) has one too. That is the
        full-overlap range only when max G is the curve's far-range limit, which the grid must reach.

        Warns (RuntimeWarning), and :meth:`reaches_far_range` is False, when G still rises at the end of the
        ranges by more than 1 % of max G per decade (from z_last / 2, or the first range, to z_last, less the
        two values' error estimates), or for a single range: extend the ranges. Why: G nears its limit as
        gap(z) ~ z^-k, k >= 1 (offsets, tilts, image sizes scale as 1/z), so it rises by k ln(10) gap >= 2.3
        gap per decade, and a curve rising by less than 1 % per decade ends within 0.43 % of its limit. A
        curve that peaks and falls (defocus) does not warn; where the maximum sits is no test (a converged,
        rising curve has it at the last range too).
        """
        threshold = _checks.unit_interval("threshold", threshold, include_one=True)
        peak = float(np.max(self.overlap))
        if peak <= 0.0:
            return float("nan")
        reason = _still_rising(self.ranges, self.overlap, self.error_estimate, peak)
        if reason:
            warnings.warn(f"full_overlap_range: {reason}", RuntimeWarning, stacklevel=2)
        return float(self.ranges[np.argmax(self.overlap >= threshold * peak)])

    def reaches_far_range(self) -> bool:
        """False when :meth:`full_overlap_range` would warn that G is still rising at the end of the ranges
        (or there is only one range), True otherwise: a caller can test it instead of catching the warning."""
        return _still_rising(self.ranges, self.overlap, self.error_estimate, float(np.max(self.overlap))) is None

    def first_signal_range(self, threshold: float = 1e-3) -> float:
        """First range (m) of the grid where G >= threshold (absolute fraction); NaN if never."""
        threshold = _checks.unit_interval("threshold", threshold)
        hit = self.overlap >= threshold
        return float(self.ranges[np.argmax(hit)]) if hit.any() else float("nan")

    def plot(self, ax=None, **line_kwargs):
        """Plot G(z) on a logarithmic range axis, with the full-overlap and first-signal ranges marked.
        Returns the matplotlib Axes (needs ``pip install lidar-overlap[plot]``)."""
        from .plotting import plot_overlap

        return plot_overlap(self, ax=ax, **line_kwargs)

    # ------------------------------------------------------------------ files
    def attributes(self) -> Dict[str, Any]:
        """Metadata written to files: method, tolerance and the system, flattened (SI units in the names)."""
        from ._core import __version__

        attrs: Dict[str, Any] = {"method": self.method, "tolerance": float(self.tolerance),
                                 "error_kind": self.error_kind, "lidar_overlap_version": __version__}
        if self.system is not None:
            attrs.update(system_attributes(self.system))
        return attrs

    def to_csv(self, path, attrs: Optional[Dict[str, Any]] = None) -> None:
        """Write ``# key: value`` header lines (method, tolerance, system), then the columns
        ``range_m,overlap,error_estimate``. Numbers are written with ``repr``, so they read back exactly.
        The file appears under ``path`` only once complete (written beside it, then renamed)."""
        header = {"format": "lidar-overlap result", **self.attributes(), **(attrs or {})}
        if self.system is not None:
            header["system"] = repr(self.system)
        lines = [f"# {key}: {_csv_value(value)}" for key, value in header.items()]
        lines.append(",".join(CSV_COLUMNS))
        for row in zip(self.ranges.tolist(), self.overlap.tolist(), self.error_estimate.tolist()):
            lines.append(",".join(repr(float(v)) for v in row))
        with _files.replacing(path, "w", encoding="utf-8", newline="\n") as f:
            f.write("\n".join(lines) + "\n")

    @classmethod
    def from_csv(cls, path) -> "OverlapResult":
        """Read a result written by :meth:`to_csv`. ``system`` is rebuilt from the header for a Gaussian beam,
        else ``None``. A file that is not such a result, or whose values break the class's checks (a NaN or
        out-of-range G), is a ValueError naming the file."""
        try:
            with open(path, encoding="utf-8") as f:
                attrs, rows = _read_csv(path, f)
        except UnicodeDecodeError as exc:
            raise ValueError(f"{path}: not a file written by OverlapResult.to_csv: byte {exc.start} is not UTF-8 "
                             "text") from None
        data = np.array(rows, dtype=float).reshape(-1, len(CSV_COLUMNS))
        return _read(cls, path, attrs, data[:, 0].copy(), data[:, 1].copy(), data[:, 2].copy())

    def to_xarray(self, attrs: Optional[Dict[str, Any]] = None):
        """An ``xarray.Dataset`` with coordinate ``range`` (m), variables ``overlap`` and ``error_estimate``,
        CF-1.10 global attributes and the system as flattened numeric attributes (needs ``[io]``)."""
        xr = _xarray()
        from ._core import __version__

        now = datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
        tolerance = "" if math.isnan(self.tolerance) else f", tolerance={self.tolerance!r}"
        glob = {"Conventions": "CF-1.10", "title": "Lidar overlap function G(z)",
                "source": f"lidar_overlap {__version__}",
                "history": f"{now}: computed by lidar_overlap {__version__}, "
                           f"overlap(method={self.method!r}{tolerance})",
                "references": "Extended overlap function computation method for atmospheric lidars",
                **self.attributes()}
        if self.system is not None:
            glob["system"] = repr(self.system)
        glob.update(attrs or {})
        coord = {"units": "m", "long_name": "range from the transmitting plane", "axis": "X"}
        return xr.Dataset(
            {"overlap": ("range", np.asarray(self.overlap, dtype=float),
                         {"units": "1", "long_name": "lidar overlap function",
                          "comment": "power reaching the detector over the power entering the full aperture"}),
             "error_estimate": ("range", np.asarray(self.error_estimate, dtype=float),
                                {"units": "1", "long_name": "estimated absolute error of the overlap function",
                                 "comment": "NaN where the method gives no estimate"})},
            coords={"range": ("range", np.asarray(self.ranges, dtype=float), coord)},
            attrs=glob)

    def to_netcdf(self, path, attrs: Optional[Dict[str, Any]] = None, engine: Optional[str] = None) -> None:
        """Write :meth:`to_xarray` to a NetCDF file. ``engine=None``: ``"h5netcdf"`` (NetCDF-4) when h5netcdf
        and its h5py backend are installed, else ``"scipy"`` (NetCDF-3, same variables and attributes).
        The file appears under ``path`` only once complete (written beside it, then renamed)."""
        ds = self.to_xarray(attrs)
        encoding = {name: {"_FillValue": None} for name in ("range", "overlap", "error_estimate")}
        engine = engine or _netcdf_engine()
        with _files.replacing_path(path) as temporary:
            ds.to_netcdf(temporary, engine=engine, encoding=encoding)

    @classmethod
    def from_netcdf(cls, path, engine: Optional[str] = None) -> "OverlapResult":
        """Read a result written by :meth:`to_netcdf`; ``system`` is rebuilt for a Gaussian beam, else ``None``.
        Values that break the class's checks (a NaN or out-of-range G) are a ValueError naming the file."""
        xr = _xarray()
        with xr.open_dataset(path, engine=engine) as ds:
            ds = ds.load()
        attrs = dict(ds.attrs)
        if "method" not in attrs or any(name not in ds.variables for name in ("range", "overlap", "error_estimate")):
            raise ValueError(f"{path}: not a file written by OverlapResult.to_netcdf (no 'method' attribute, or no "
                             "'range', 'overlap' or 'error_estimate')")
        return _read(cls, path, attrs, ds["range"].values, ds["overlap"].values, ds["error_estimate"].values)


def _read_csv(path, lines):
    """The ``# key: value`` header and the rows of numbers of a file written by :meth:`OverlapResult.to_csv`."""
    attrs: Dict[str, Any] = {}
    rows, columns = [], False
    for number, line in enumerate(lines, 1):
        line = line.strip()
        if not line:
            continue
        if line.startswith("#"):
            key, sep, value = line[1:].partition(":")
            if sep:
                attrs[key.strip()] = _parse_value(value.strip())
        elif not columns:
            if "method" not in attrs or line.replace(" ", "") != ",".join(CSV_COLUMNS):
                raise ValueError(f"{path}: not a file written by OverlapResult.to_csv: expected '# method:' "
                                 f"and the other header lines, then the columns {','.join(CSV_COLUMNS)}")
            columns = True
        else:
            try:
                values = [float(v) for v in line.split(",")]
            except ValueError:
                values = []
            if len(values) != len(CSV_COLUMNS):
                raise ValueError(f"{path}: line {number} = {_short(line)} is invalid: expected "
                                 f"{len(CSV_COLUMNS)} numbers ({','.join(CSV_COLUMNS)})")
            rows.append(values)
    if not columns:
        raise ValueError(f"{path}: no columns {','.join(CSV_COLUMNS)}: not a file written by OverlapResult.to_csv")
    return attrs, rows


def _read(cls, path, attrs: Dict[str, Any], ranges, overlap, error_estimate):
    """``cls`` from what a file holds; a ValueError of the class's checks names the file."""
    try:
        method = str(attrs["method"])
        kind = str(attrs.get("error_kind", "nominal" if method == "fo" else "bound"))   # files written before the kind existed
        return cls(ranges=ranges, overlap=overlap, method=method, error_estimate=error_estimate,
                   system=system_from_attributes(attrs), tolerance=attrs.get("tolerance", math.nan), error_kind=kind)
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None


def _same(a: Any, b: Any) -> bool:
    """Equality of two field values: arrays element by element with NaN equal to NaN, floats with NaN equal to
    NaN, anything else by ==."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        try:
            return bool(np.array_equal(a, b, equal_nan=True))
        except TypeError:   # arrays without a NaN (bools, objects)
            return bool(np.array_equal(a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


def _checked(ranges, overlap, method, error_estimate, tolerance, upper=1.0):
    """The class's invariants (see :class:`OverlapResult`): the arrays as float arrays, G clipped within its
    slack, the tolerance as a float; ValueError naming what is wrong otherwise."""
    if not isinstance(method, str) or not method:
        raise ValueError(f"method = {method!r} is invalid: expected the name of the model, such as 'rt' or 'fo'")
    z, g, e = (_curve_array(name, value) for name, value in
               (("ranges", ranges), ("overlap", overlap), ("error_estimate", error_estimate)))
    if z.size == 0:
        raise ValueError("ranges is empty: expected at least one range (m)")
    for name, values in (("overlap", g), ("error_estimate", e)):
        if values.size != z.size:
            raise ValueError(f"{name} has {values.size} values for {z.size} ranges: expected one per range")
    _first_bad("ranges", z, ~(np.isfinite(z) & (z > 0)), "expected a finite range > 0 (m)")
    if z.size > 1 and not np.all(np.diff(z) > 0):
        i = int(np.argmax(~(np.diff(z) > 0))) + 1
        raise ValueError(f"ranges must be strictly increasing: ranges[{i}] = {float(z[i])!r} follows "
                         f"{float(z[i - 1])!r}")
    tolerance = _checks.real("tolerance", tolerance)
    if not (math.isnan(tolerance) or (math.isfinite(tolerance) and tolerance >= 0.0)):
        raise ValueError(f"tolerance = {tolerance!r} is invalid: expected a finite value >= 0, or NaN for none")
    _first_bad("error_estimate", e, ~(np.isnan(e) | (np.isfinite(e) & (e >= 0.0))),
               "expected a finite value >= 0, or NaN where the method gives none")
    slack = np.fmax(np.fmax(e, tolerance), ROUND_OFF)   # fmax: a NaN estimate or tolerance gives way
    outside = ~((g >= -slack) & (g <= upper + slack))  # NaN is outside too
    if outside.any():
        i = int(np.argmax(outside))
        raise ValueError(f"overlap[{i}] = {float(g[i])!r} at range {float(z[i])!r} m (method {method!r}) is invalid: "
                         "G must be "
                         f"finite and within [0, {upper:g}] up to its error estimate or tolerance ({slack[i]:.3g}); "
                         "the computation failed at this range")
    if g.min() < 0.0 or g.max() > upper:
        g = np.clip(g, 0.0, upper)
    return z, g, e, tolerance


def _curve_array(name: str, value) -> np.ndarray:
    try:
        values = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        values = None
    if values is None or values.ndim != 1:
        raise ValueError(f"{name} is invalid: expected a 1-D array of numbers, got {type(value).__name__} "
                         f"{_short(value)}")
    return values


def _first_bad(name: str, values: np.ndarray, bad: np.ndarray, expected: str) -> None:
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"{name}[{i}] = {float(values[i])!r} is invalid: {expected}")


def _short(value, limit: int = 80) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _still_rising(z: np.ndarray, g: np.ndarray, error: np.ndarray, peak: float) -> Optional[str]:
    """Why the curve has not shown its far-range limit, by the rule of :meth:`OverlapResult.full_overlap_range`;
    None when it has (or G is zero everywhere)."""
    if peak <= 0.0:
        return None
    if z.size == 1:
        return (f"one range ({z[0]:.4g} m) cannot show whether G has reached its far-range limit; compute more "
                "ranges, out to where G stops rising")
    start = max(z[-1] / 2.0, float(z[0]))
    log_z = np.log(z)
    g_start, e_start = (float(np.interp(np.log(start), log_z, values)) for values in (g, np.nan_to_num(error)))
    decades = math.log10(z[-1] / start)
    rise = float(g[-1]) - g_start - (float(np.nan_to_num(error[-1])) + e_start)
    if rise <= FAR_SLOPE * peak * decades:
        return None
    return (f"G is still rising at the end of the ranges: it gains {rise / peak:.2g} of its maximum {peak:.4g} from "
            f"{start:.4g} m to {z[-1]:.4g} m, more than {FAR_SLOPE:.0%} per decade of range, so max G may be short of "
            "its far-range limit and the range found too early; extend the ranges farther")


def _xarray():
    try:
        import xarray
    except ImportError as exc:
        raise ImportError(_IO_HINT) from exc
    return xarray


def _netcdf_engine() -> str:
    """h5netcdf with its h5py backend if installed, else scipy's NetCDF-3 writer."""
    import importlib.util

    if importlib.util.find_spec("h5netcdf") and importlib.util.find_spec("h5py"):
        return "h5netcdf"
    if importlib.util.find_spec("scipy"):
        return "scipy"
    raise ImportError(_IO_HINT)


def _csv_value(value: Any) -> str:
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    return " ".join(str(value).split())


def _parse_value(text: str) -> Any:
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text
