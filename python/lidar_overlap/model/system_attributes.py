"""A lidar system as flat, numeric file attributes (SI units in the names) and back: what result
files carry. Its ``fit_bounds`` are numbered entries ``fit_bound_<i>_path``, ``_low``, ``_high``
(the path's SI unit); a file without them reads as a system without."""

from __future__ import annotations

from typing import Any, Dict, Optional, cast

import numpy as np

from .aberrations import SEIDEL_TERMS, Aberrations
from .aperture_mask import ApertureMask, Sector
from .field_beam import FieldBeam
from .flat_top import FlatTopBeam
from .mixture_beam import BeamComponent, GaussianMixtureBeam
from .system import Detector, GaussianBeam, LidarSystem, Telescope, WidthLaw


def _pair_attributes(prefix: str, pair, unit: str) -> Dict[str, float]:
    return {f"{prefix}_x_{unit}": float(pair[0]), f"{prefix}_y_{unit}": float(pair[1])}


def system_attributes(system: LidarSystem) -> Dict[str, Any]:
    """The system as a flat dict of numbers (and a few type names); keys end in their unit."""
    beam, tel, det = system.beam, system.telescope, system.detector
    a: Dict[str, Any] = {}
    if isinstance(beam, GaussianBeam):
        a.update(
            beam_type="gaussian",
            beam_wavelength_m=beam.wavelength,
            beam_waist_radius_m=beam.waist_radius,
        )
        if beam.divergence is not None:
            a["beam_divergence_rad"] = beam.divergence
        a["beam_half_angle_divergence_rad"] = float(beam.half_angle_divergence)
        a["beam_width_law"] = beam.width_law
    elif isinstance(beam, GaussianMixtureBeam):
        a.update(
            beam_type="gaussian_mixture",
            beam_wavelength_m=beam.wavelength,
            beam_width_law=beam.width_law,
            beam_component_count=len(beam.components),
        )
        for i, c in enumerate(beam.components):
            a[f"beam_component_{i}_weight"] = c.weight
            a[f"beam_component_{i}_waist_radius_m"] = c.waist_radius
            if c.divergence is not None:
                a[f"beam_component_{i}_divergence_rad"] = c.divergence
    elif isinstance(beam, FieldBeam):
        a.update(
            beam_type="flat_top" if isinstance(beam, FlatTopBeam) else "field",
            beam_wavelength_m=beam.wavelength,
        )
        if isinstance(beam, FlatTopBeam):
            a.update(
                beam_waist_radius_m=beam.waist_radius,
                beam_angular_diameter_rad=beam.angular_diameter,
                beam_edge_width_rad=float(beam.edge_width),
                beam_efficiency=float(beam.efficiency),
                beam_uniformity_rms=float(beam.uniformity_rms),
            )
        a.update(
            beam_grid_size=int(beam.field.n),
            beam_grid_spacing_m=float(beam.field.spacing),
            beam_second_moment_radius_m=float(beam.field.beam_radius),
        )
    a.update(_pair_attributes("beam_offset", beam.offset, "m"))
    a.update(_pair_attributes("beam_tilt", beam.tilt, "rad"))
    a.update(
        telescope_diameter_m=tel.diameter,
        telescope_focal_length_m=tel.focal_length,
        telescope_obstruction_radius_m=tel.obstruction_radius,
        telescope_obstruction_distance_m=tel.obstruction_distance,
        detector_radius_m=det.radius,
        detector_defocus_m=det.defocus,
    )
    a.update(_pair_attributes("detector_offset", det.offset, "m"))
    if det.numerical_aperture is not None:
        a["detector_numerical_aperture"] = det.numerical_aperture
    if det.stop_radius is not None:
        a["detector_stop_radius_m"] = det.stop_radius
        a["detector_stop_distance_m"] = det.stop_distance
    a["detector_fov_rad"] = float(system.fov)
    if tel.aberrations is not None:
        a.update({f"aberration_zernike_{j}_m": c for j, c in tel.aberrations.zernike.items()})
        a.update(
            {
                f"aberration_{name}_m": getattr(tel.aberrations, name)
                for name in SEIDEL_TERMS
                if getattr(tel.aberrations, name) != 0.0
            }
        )
        if tel.aberrations.field_radius:
            a["aberration_field_radius_rad"] = tel.aberrations.field_radius
    if tel.mask is not None:
        for i, (sector, name) in enumerate(zip(tel.mask.sectors, tel.mask.names)):
            a.update(
                {
                    f"mask_sector_{i}_name": name,
                    f"mask_sector_{i}_start_angle_rad": sector.start_angle,
                    f"mask_sector_{i}_stop_angle_rad": sector.stop_angle,
                    f"mask_sector_{i}_inner_radius_m": sector.inner_radius,
                }
            )
            if sector.outer_radius is not None:
                a[f"mask_sector_{i}_outer_radius_m"] = sector.outer_radius
    for i, (path, (low, high)) in enumerate((system.fit_bounds or {}).items()):
        a.update(
            {f"fit_bound_{i}_path": path, f"fit_bound_{i}_low": low, f"fit_bound_{i}_high": high}
        )
    return {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in a.items()}


def _aberrations_from_attributes(attrs: Dict[str, Any]) -> Optional[Aberrations]:
    if not any(k.startswith("aberration_") for k in attrs):
        return None
    zernike = {
        int(k.split("_")[2]): v for k, v in attrs.items() if k.startswith("aberration_zernike_")
    }
    seidel = {name: attrs.get(f"aberration_{name}_m", 0.0) for name in SEIDEL_TERMS}
    return Aberrations(
        zernike=zernike, field_radius=attrs.get("aberration_field_radius_rad", 0.0), **seidel
    )


def _mask_from_attributes(attrs: Dict[str, Any]) -> Optional[ApertureMask]:
    n = sum(1 for k in attrs if k.startswith("mask_sector_") and k.endswith("_start_angle_rad"))
    if n == 0:
        return None
    keys = [f"mask_sector_{i}_" for i in range(n)]
    return ApertureMask(
        tuple(
            Sector(
                attrs[k + "start_angle_rad"],
                attrs[k + "stop_angle_rad"],
                attrs[k + "inner_radius_m"],
                attrs.get(k + "outer_radius_m"),
            )
            for k in keys
        ),
        tuple(str(attrs[k + "name"]) for k in keys),
    )


def _fit_bounds_from_attributes(attrs: Dict[str, Any], get) -> Optional[Dict[str, Any]]:
    n = sum(1 for k in attrs if k.startswith("fit_bound_") and k.endswith("_path"))
    keys = [f"fit_bound_{i}_" for i in range(n)]
    return {str(get(k + "path")): (get(k + "low"), get(k + "high")) for k in keys} or None


#: Prefixes of the keys :func:`system_attributes` writes.
SYSTEM_PREFIXES = ("beam_", "telescope_", "detector_", "aberration_", "mask_", "fit_bound_")
#: Beam types a file may name whose system is not rebuilt (the field is not stored).
UNSTORED_BEAMS = ("flat_top", "field")


def system_from_attributes(attrs: Dict[str, Any]) -> Optional[LidarSystem]:
    """Rebuild a Gaussian-beam system from :func:`system_attributes`; ``None`` when the attributes
    hold no system or one whose beam is a field (not stored). Attributes that name a system which
    cannot be rebuilt (a missing key, a value out of range, an unknown beam type) are a ValueError
    naming the attribute: never a silent ``None``."""
    kind = attrs.get("beam_type")
    if kind is None:
        stray = sorted(k for k in attrs if k.startswith(SYSTEM_PREFIXES))
        if stray:
            raise ValueError(
                f"system attributes without 'beam_type' (such as {stray[0]!r}): expected the "
                "complete set a result writes, or none"
            )
        return None
    if kind in UNSTORED_BEAMS:
        return None
    if kind not in ("gaussian", "gaussian_mixture"):
        raise ValueError(
            f"beam_type = {kind!r} is invalid: expected 'gaussian', 'gaussian_mixture', 'flat_top' "
            "or 'field'"
        )

    def get(key: str, default=_REQUIRED):
        if key not in attrs:
            if default is _REQUIRED:
                raise ValueError(f"system attribute {key!r} is missing: the header is incomplete")
            return default
        value = attrs[key]
        if key.endswith(("_name", "_law", "_path")) or value is None:
            return value
        if isinstance(value, (bool, str)) or not isinstance(value, (int, float, np.number)):
            raise ValueError(f"system attribute {key} = {value!r} is invalid: expected a number")
        return float(value)

    def pair(prefix: str, unit: str):
        return (get(f"{prefix}_x_{unit}"), get(f"{prefix}_y_{unit}"))

    try:
        beam: GaussianBeam | GaussianMixtureBeam
        if kind == "gaussian_mixture":
            count = get("beam_component_count")
            if not (count == int(count) and 1 <= count <= 10_000):
                raise ValueError(
                    f"system attribute beam_component_count = {count!r} is invalid: expected a "
                    "whole number from 1 to 10000"
                )
            beam = GaussianMixtureBeam(
                tuple(
                    BeamComponent(
                        get(f"beam_component_{i}_weight"),
                        get(f"beam_component_{i}_waist_radius_m"),
                        get(f"beam_component_{i}_divergence_rad", None),
                    )
                    for i in range(int(count))
                ),
                wavelength=get("beam_wavelength_m"),
                offset=pair("beam_offset", "m"),
                tilt=pair("beam_tilt", "rad"),
                width_law=cast(WidthLaw, str(get("beam_width_law", "gaussian"))),
            )
        else:
            beam = GaussianBeam(
                wavelength=get("beam_wavelength_m"),
                waist_radius=get("beam_waist_radius_m"),
                divergence=get("beam_divergence_rad", None),
                offset=pair("beam_offset", "m"),
                tilt=pair("beam_tilt", "rad"),
                width_law=cast(WidthLaw, str(get("beam_width_law", "gaussian"))),
            )
        telescope = Telescope(
            diameter=get("telescope_diameter_m"),
            focal_length=get("telescope_focal_length_m"),
            obstruction_radius=get("telescope_obstruction_radius_m"),
            obstruction_distance=get("telescope_obstruction_distance_m"),
            aberrations=_aberrations_from_attributes(attrs),
            mask=_mask_from_attributes(attrs),
        )
        detector = Detector(
            radius=get("detector_radius_m"),
            defocus=get("detector_defocus_m"),
            offset=pair("detector_offset", "m"),
            numerical_aperture=get("detector_numerical_aperture", None),
            stop_radius=get("detector_stop_radius_m", None),
            stop_distance=get("detector_stop_distance_m", 0.0),
        )
        return LidarSystem(
            beam=beam,
            telescope=telescope,
            detector=detector,
            fit_bounds=_fit_bounds_from_attributes(attrs, get),
        )
    except (KeyError, TypeError) as exc:
        raise ValueError(f"system attributes are invalid: {exc}") from None
    except ValueError as exc:
        raise ValueError(f"system attributes are invalid: {exc}") from None


_REQUIRED = object()
