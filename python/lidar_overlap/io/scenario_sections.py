"""The sections of a scenario file, each checked and made the library's value: ``[beam]`` (a
GaussianBeam, or a FieldBeam for the types ``flat_top`` and ``super_gaussian``), ``[telescope]``
with its ``[telescope.aberrations]``, ``[detector]`` (by its field of view or its radius) and
``[ranges]`` (listed, or start, stop, count and spacing). Every error is a
:class:`~lidar_overlap.io.scenario_schema.ScenarioError` naming the file, the section and the
key."""

from __future__ import annotations

import math
from typing import Any, Dict

import numpy as np

from ..model.aberrations import Aberrations
from ..model.field_beam import FieldBeam
from ..model.flat_top import FlatTopBeam
from ..model.system import Detector, GaussianBeam, Telescope
from ..optics.beam_fields import super_gaussian_field
from .scenario_schema import (
    BEAM_TYPES,
    MAX_RANGES,
    REQUIRED,
    SCHEMA,
    ScenarioError,
    build,
    checked_keys,
    choice,
    is_number,
    require,
    short,
)


def beam_from_table(source: str, table: Dict[str, Any]) -> GaussianBeam | FieldBeam:
    kind = table.get("type", "gaussian") if isinstance(table, dict) else "gaussian"
    choice(f"{source}: [beam]", "type", kind, BEAM_TYPES)
    values = dict(checked_keys(source, "beam", table, SCHEMA[kind], REQUIRED[kind]))
    values.pop("type", None)
    for key in ("offset", "tilt"):
        if key in values:
            values[key] = tuple(values[key])
    if kind == "gaussian":
        return build(source, "beam", GaussianBeam, **values)
    if kind == "super_gaussian":  # a sampled field: the grid it is given on is n x spacing
        pointing = {key: values.pop(key) for key in ("offset", "tilt") if key in values}
        values["n"] = values.pop("grid")
        field = build(source, "beam", super_gaussian_field, **values)
        return build(source, "beam", FieldBeam, field, **pointing)
    args = [values.pop(key) for key in REQUIRED["flat_top"]]
    return build(source, "beam", FlatTopBeam, *args, **values)


def telescope_from_table(source: str, table: Dict[str, Any]) -> Telescope:
    values = dict(
        checked_keys(source, "telescope", table, SCHEMA["telescope"], REQUIRED["telescope"])
    )
    if "aberrations" in values:
        values["aberrations"] = _aberrations(source, values["aberrations"])
    return build(source, "telescope", Telescope, **values)


def _aberrations(source: str, table: Dict[str, Any]) -> Aberrations:
    """[telescope.aberrations]: Seidel coefficients (m), field_radius (rad) and a [..zernike] table
    of "Noll index" = m RMS."""
    values = dict(
        checked_keys(source, "telescope.aberrations", table, SCHEMA["telescope.aberrations"])
    )
    terms = {}
    for key, value in values.pop("zernike", {}).items():
        if not (key.isdigit() and len(key) <= 4 and 1 <= int(key) <= 1000) or not is_number(value):
            raise ScenarioError(
                f"{source}: [telescope.aberrations.zernike] {short(key, 40)[1:-1]} = "
                f'{short(value)} is invalid: expected "Noll index" (1-1000) = RMS wavefront in m, '
                'e.g. "11" = 5e-8'
            )
        terms[int(key)] = value
    return build(source, "telescope.aberrations", Aberrations, zernike=terms, **values)


def detector_from_table(source: str, table: Dict[str, Any], telescope: Telescope) -> Detector:
    values = dict(checked_keys(source, "detector", table, SCHEMA["detector"]))
    if ("fov" in values) == ("radius" in values):
        which = "both" if "fov" in values else "neither"
        raise ScenarioError(
            f"{source}: [detector] fov and radius: {which} given: expected exactly one (fov: full "
            "field of view in rad, radius: detector radius in m)"
        )
    if "offset" in values:
        values["offset"] = tuple(values["offset"])
    if "fov" in values:
        return build(
            source,
            "detector",
            Detector.from_fov,
            values.pop("fov"),
            telescope.focal_length,
            **values,
        )
    return build(source, "detector", Detector, **values)


def ranges_from_table(source: str, table: Dict[str, Any]) -> np.ndarray:
    t, where = checked_keys(source, "ranges", table, SCHEMA["ranges"]), f"{source}: [ranges]"
    if "values" in t:
        z = np.asarray(t["values"], dtype=float)
        if (
            len(t) > 1
            or not 0 < z.size <= MAX_RANGES
            or not np.all(z > 0)
            or np.any(np.diff(z) <= 0)
        ):
            raise ScenarioError(
                f"{where} values = {short(t['values'])} ({z.size} values) is invalid: expected a "
                f"strictly increasing list of 1 to {MAX_RANGES:,} ranges > 0 (m), and no start, "
                "stop, count"
            )
        return z
    require(where, t, ("start", "stop", "count"), " (or values = [...])")
    start, stop, count = t["start"], t["stop"], t["count"]
    for key, ok, rule in (
        ("start", 0 < start < math.inf, "a finite value > 0"),
        ("stop", start < stop < math.inf, f"a finite value > start = {start!r}"),
        ("count", count >= 2, "an integer >= 2"),
    ):
        if not ok:
            raise ScenarioError(f"{where} {key} = {t[key]!r} is invalid: expected {rule}")
    spacing = choice(where, "spacing", t.get("spacing", "linear"), ("linear", "log"))
    z = (np.geomspace if spacing == "log" else np.linspace)(float(start), float(stop), count)
    if not np.all(np.diff(z) > 0):
        raise ScenarioError(
            f"{where} start = {start!r}, stop = {stop!r}, count = {count} are invalid: {count} "
            "ranges between them are not distinct in double precision; expected fewer ranges or a "
            "wider span"
        )
    return z
