"""Writing a scenario file (TOML): the writer beside its reader (:mod:`.scenario`), so that a system
saved from the interactive view reads back, value for value, as ``lidar-overlap run`` reads it."""

from __future__ import annotations


def _toml_value(value) -> str:
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, (tuple, list)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return repr(float(value))  # repr: read back exactly


def scenario_toml(system, ranges, name: str, tolerance: float) -> str:
    """``system`` (a GaussianBeam) at ``ranges`` (m) as a scenario file (TOML, SI units) for ray
    tracing; the values are written with repr, so the file reads back to the same system. A
    telescope's aperture mask has no place in a scenario and is left out (said in a comment); the
    system's ``fit_bounds`` are its ``[fit_bounds]`` table."""
    beam, tel, det = system.beam, system.telescope, system.detector
    sections = {
        "beam": {
            "type": "gaussian",
            "wavelength": beam.wavelength,
            "waist_radius": beam.waist_radius,
            "divergence": beam.divergence,
            "offset": beam.offset,
            "tilt": beam.tilt,
            "width_law": beam.width_law,
        },
        "telescope": {
            "diameter": tel.diameter,
            "focal_length": tel.focal_length,
            "obstruction_radius": tel.obstruction_radius,
            "obstruction_distance": tel.obstruction_distance,
        },
        "detector": {
            "radius": det.radius,
            "defocus": det.defocus,
            "offset": det.offset,
            "numerical_aperture": det.numerical_aperture,
            "stop_radius": det.stop_radius,
            "stop_distance": det.stop_distance if det.stop_radius is not None else None,
        },
        "ranges": {"values": [float(z) for z in ranges]},
        "run": {"method": "rt", "tolerance": tolerance},
    }
    lines = [
        "# Written by the lidar_overlap view: the system as its sliders stood (SI units: m, rad).",
        f"name = {_toml_value(name)}",
        'description = "Saved from the interactive view"',
    ]
    if tel.mask is not None:
        lines.insert(
            1, "# The telescope's aperture mask is not part of a scenario and is left out."
        )
    for section, table in sections.items():
        lines.append(f"\n[{section}]")
        lines += [
            f"{key} = {_toml_value(value)}" for key, value in table.items() if value is not None
        ]
    ab = tel.aberrations
    if ab is not None:
        lines.append("\n[telescope.aberrations]")
        lines += [
            f"{key} = {getattr(ab, key)!r}"
            for key in ("w040", "w131", "w222", "w220", "w311", "field_radius")
            if getattr(ab, key)
        ]
        if ab.zernike:
            lines.append("\n[telescope.aberrations.zernike]")
            lines += [f'"{j}" = {float(c)!r}' for j, c in sorted(ab.zernike.items())]
    if system.fit_bounds:
        lines.append("\n[fit_bounds]")
        lines += [f"{_toml_value(p)} = {_toml_value(b)}" for p, b in system.fit_bounds.items()]
    return "\n".join(lines) + "\n"
