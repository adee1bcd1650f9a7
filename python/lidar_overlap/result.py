"""The result of an overlap computation and the ranges derived from it."""

from __future__ import annotations

import math
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import Any, Dict, Optional

import numpy as np

from . import _checks, _files
from .aberrations import SEIDEL_TERMS, Aberrations
from .system import Detector, GaussianBeam, LidarSystem, Telescope

CSV_COLUMNS = ("range_m", "overlap", "error_estimate")
_IO_HINT = "reading and writing NetCDF needs xarray and h5netcdf (with h5py): pip install 'lidar-overlap[io]'"


@dataclass(frozen=True)
class OverlapResult:
    """Overlap function G(z) on a range grid.

    Attributes
    ----------
    ranges : m, the ranges asked for.
    overlap : G at each range (dimensionless, 0..1).
    method : the model that computed it (``"rt"`` or ``"fo"``).
    error_estimate : estimated absolute error of each G value (NaN where the method gives none).
    system : the lidar it describes (``None`` for a result read from a file whose beam is not Gaussian).
    tolerance : the absolute tolerance that was asked for.
    """

    ranges: np.ndarray
    overlap: np.ndarray
    method: str
    error_estimate: np.ndarray
    system: Optional[LidarSystem]
    tolerance: float

    def full_overlap_range(self, threshold: float = 0.99) -> float:
        """First range (m) of the grid where G >= threshold · max G; NaN if G is zero everywhere.

        Relative to the maximum, so an obstructed system (max G = 1 - (r_obs/R)²) has one too."""
        threshold = _checks.unit_interval("threshold", threshold, include_one=True)
        peak = float(np.max(self.overlap))
        if peak <= 0.0:
            return float("nan")
        return float(self.ranges[np.argmax(self.overlap >= threshold * peak)])

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
                                 "lidar_overlap_version": __version__}
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
        else ``None``."""
        attrs: Dict[str, Any] = {}
        rows, columns = [], False
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
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
                        raise ValueError(f"{path}: line {number} = {line!r} is invalid: expected "
                                         f"{len(CSV_COLUMNS)} numbers ({','.join(CSV_COLUMNS)})")
                    rows.append(values)
        if not columns:
            raise ValueError(f"{path}: no columns {','.join(CSV_COLUMNS)}: not a file written by OverlapResult.to_csv")
        data = np.array(rows, dtype=float).reshape(-1, len(CSV_COLUMNS))
        return cls(ranges=data[:, 0].copy(), overlap=data[:, 1].copy(), method=str(attrs["method"]),
                   error_estimate=data[:, 2].copy(), system=system_from_attributes(attrs),
                   tolerance=float(attrs.get("tolerance", math.nan)))

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
        """Read a result written by :meth:`to_netcdf`; ``system`` is rebuilt for a Gaussian beam, else ``None``."""
        xr = _xarray()
        with xr.open_dataset(path, engine=engine) as ds:
            ds = ds.load()
        attrs = dict(ds.attrs)
        if "method" not in attrs or "overlap" not in ds:
            raise ValueError(f"{path}: not a file written by OverlapResult.to_netcdf (no 'method' or 'overlap')")
        return cls(ranges=np.asarray(ds["range"].values, dtype=float),
                   overlap=np.asarray(ds["overlap"].values, dtype=float), method=str(attrs["method"]),
                   error_estimate=np.asarray(ds["error_estimate"].values, dtype=float),
                   system=system_from_attributes(attrs), tolerance=float(attrs.get("tolerance", math.nan)))


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


def _pair_attributes(prefix: str, pair, unit: str) -> Dict[str, float]:
    return {f"{prefix}_x_{unit}": float(pair[0]), f"{prefix}_y_{unit}": float(pair[1])}


def system_attributes(system: LidarSystem) -> Dict[str, Any]:
    """The system as a flat dict of numbers (and a few type names); keys end in their unit."""
    from .field_beam import FieldBeam
    from .flat_top import FlatTopBeam

    beam, tel, det = system.beam, system.telescope, system.detector
    a: Dict[str, Any] = {}
    if isinstance(beam, GaussianBeam):
        a.update(beam_type="gaussian", beam_wavelength_m=beam.wavelength, beam_waist_radius_m=beam.waist_radius)
        if beam.divergence is not None:
            a["beam_divergence_rad"] = beam.divergence
        a["beam_half_angle_divergence_rad"] = float(beam.half_angle_divergence)
        a["beam_width_law"] = beam.width_law
    elif isinstance(beam, FieldBeam):
        a.update(beam_type="flat_top" if isinstance(beam, FlatTopBeam) else "field", beam_wavelength_m=beam.wavelength)
        if isinstance(beam, FlatTopBeam):
            a.update(beam_waist_radius_m=beam.waist_radius, beam_angular_diameter_rad=beam.angular_diameter,
                     beam_edge_width_rad=float(beam.edge_width), beam_efficiency=float(beam.efficiency),
                     beam_uniformity_rms=float(beam.uniformity_rms))
        a.update(beam_grid_size=int(beam.field.n), beam_grid_spacing_m=float(beam.field.spacing),
                 beam_second_moment_radius_m=float(beam.field.beam_radius()))
    a.update(_pair_attributes("beam_offset", beam.offset, "m"))
    a.update(_pair_attributes("beam_tilt", beam.tilt, "rad"))
    a.update(telescope_diameter_m=tel.diameter, telescope_focal_length_m=tel.focal_length,
             telescope_obstruction_radius_m=tel.obstruction_radius,
             telescope_obstruction_distance_m=tel.obstruction_distance,
             detector_radius_m=det.radius, detector_defocus_m=det.defocus)
    a.update(_pair_attributes("detector_offset", det.offset, "m"))
    if det.numerical_aperture is not None:
        a["detector_numerical_aperture"] = det.numerical_aperture
    a["detector_fov_rad"] = float(system.fov)
    if tel.aberrations is not None:
        a.update({f"aberration_zernike_{j}_m": c for j, c in tel.aberrations.zernike.items()})
        a.update({f"aberration_{name}_m": getattr(tel.aberrations, name) for name in SEIDEL_TERMS
                  if getattr(tel.aberrations, name) != 0.0})
        if tel.aberrations.field_radius:
            a["aberration_field_radius_rad"] = tel.aberrations.field_radius
    return {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in a.items()}


def _aberrations_from_attributes(attrs: Dict[str, Any]) -> Optional[Aberrations]:
    if not any(k.startswith("aberration_") for k in attrs):
        return None
    zernike = {int(k.split("_")[2]): v for k, v in attrs.items() if k.startswith("aberration_zernike_")}
    seidel = {name: attrs.get(f"aberration_{name}_m", 0.0) for name in SEIDEL_TERMS}
    return Aberrations(zernike=zernike, field_radius=attrs.get("aberration_field_radius_rad", 0.0), **seidel)


def system_from_attributes(attrs: Dict[str, Any]) -> Optional[LidarSystem]:
    """Rebuild a Gaussian-beam system from :func:`system_attributes`; ``None`` for other beams or
    incomplete attributes."""
    if attrs.get("beam_type") != "gaussian":
        return None

    def pair(prefix: str, unit: str):
        return (attrs[f"{prefix}_x_{unit}"], attrs[f"{prefix}_y_{unit}"])

    try:
        beam = GaussianBeam(wavelength=attrs["beam_wavelength_m"], waist_radius=attrs["beam_waist_radius_m"],
                            divergence=attrs.get("beam_divergence_rad"), offset=pair("beam_offset", "m"),
                            tilt=pair("beam_tilt", "rad"), width_law=str(attrs.get("beam_width_law", "gaussian")))
        telescope = Telescope(diameter=attrs["telescope_diameter_m"], focal_length=attrs["telescope_focal_length_m"],
                              obstruction_radius=attrs["telescope_obstruction_radius_m"],
                              obstruction_distance=attrs["telescope_obstruction_distance_m"],
                              aberrations=_aberrations_from_attributes(attrs))
        detector = Detector(radius=attrs["detector_radius_m"], defocus=attrs["detector_defocus_m"],
                            offset=pair("detector_offset", "m"),
                            numerical_aperture=attrs.get("detector_numerical_aperture"))
        return LidarSystem(beam=beam, telescope=telescope, detector=detector)
    except (KeyError, ValueError):
        return None
