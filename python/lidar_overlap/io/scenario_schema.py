"""The keys a scenario file may hold (:data:`SCHEMA`: each key's kind; :data:`INTEGER_LIMITS`: the
bounds of the keys that size work or memory) and the checks of a table against them, each failure a
:class:`ScenarioError` naming the file, the section and the key; the [fit_bounds] table, whose keys
are parameter paths, read by :func:`fit_bounds_table`."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, Optional, Tuple

from .. import _checks
from ..forward.methods import RECEIVER_FIELDS

METHODS = ("rt", "fo", "auto")
#: [beam] type: a Gaussian beam, a flat-top phase plate's field, a super-Gaussian field.
BEAM_TYPES = ("gaussian", "flat_top", "super_gaussian")
OUTPUTS = ("csv", "netcdf", "plot", "scene")
#: The most ranges one scenario may ask for (``count``, or the length of ``values``).
MAX_RANGES = 100_000
#: The largest scenario file read (bytes).
MAX_FILE_BYTES = 10_000_000
#: The longest ``name`` (it names the output files, whose names the file system limits to 255
#: bytes).
MAX_NAME_LENGTH = 100


@dataclass(frozen=True)
class IntegerKey:
    """An integer key's valid range and why it ends there."""

    low: int
    high: int
    why: str = ""

    def __str__(self) -> str:
        return f"an integer from {self.low} to {self.high}" + (f" ({self.why})" if self.why else "")


#: Bounds of the integer keys: each sizes work or memory (grid sides are squared, threads are
#: started).
INTEGER_LIMITS: Dict[str, IntegerKey] = {
    "ranges.count": IntegerKey(2, MAX_RANGES, "the most ranges one scenario may ask for"),
    "run.threads": IntegerKey(0, 256, "0 uses all cores"),
    "run.max_segments": IntegerKey(1, 100_000, "adaptive subdivisions per integral"),
    "run.beam_grid": IntegerKey(16, 8192, "samples per side of the beam's grid"),
    "run.max_spectrum_grid": IntegerKey(16, 8192, "samples per side of the spectrum's grid"),
    "flat_top.grid": IntegerKey(64, 4096, "samples per side of the phase plate"),
    "flat_top.max_iterations": IntegerKey(1, 10_000, "iterations of the plate's design"),
    "super_gaussian.grid": IntegerKey(8, 4096, "samples per side of the field, even"),
    "turbulence.realizations": IntegerKey(1, 100_000, "draws of the atmosphere"),
    "turbulence.screens": IntegerKey(1, 1000, "phase screens of the Fourier-optics path"),
    "turbulence.receiver_fields": IntegerKey(
        *RECEIVER_FIELDS, "random-phase fields of the detector"
    ),
    "turbulence.seed": IntegerKey(0, 2**63 - 1, "the draws' seed"),
}
NUMBER, STRING, BOOL, PAIR = "a finite real number", "a string", "true or false", "pair"
CN2 = "a finite Cn² in m^-2/3 or 'hv57' (Hufnagel-Valley 5/7)"
SCHEMA: Dict[str, Dict[str, Any]] = {
    "gaussian": {
        "wavelength": NUMBER,
        "waist_radius": NUMBER,
        "divergence": NUMBER,
        "offset": PAIR,
        "tilt": PAIR,
        "width_law": STRING,
        "type": STRING,
    },
    "flat_top": {
        "wavelength": NUMBER,
        "waist_radius": NUMBER,
        "angular_diameter": NUMBER,
        "offset": PAIR,
        "tilt": PAIR,
        "grid": INTEGER_LIMITS["flat_top.grid"],
        "samples_per_waist": NUMBER,
        "edge_width": NUMBER,
        "max_iterations": INTEGER_LIMITS["flat_top.max_iterations"],
        "tolerance": NUMBER,
        "max_error": NUMBER,
        "power": NUMBER,
        "type": STRING,
    },
    "super_gaussian": {
        "wavelength": NUMBER,
        "radius": NUMBER,
        "order": NUMBER,
        "grid": INTEGER_LIMITS["super_gaussian.grid"],
        "spacing": NUMBER,
        "power": NUMBER,
        "offset": PAIR,
        "tilt": PAIR,
        "type": STRING,
    },
    "telescope": {
        "diameter": NUMBER,
        "focal_length": NUMBER,
        "obstruction_radius": NUMBER,
        "obstruction_distance": NUMBER,
        "aberrations": "table",
    },
    "telescope.aberrations": {
        "zernike": "table",
        "w040": NUMBER,
        "w131": NUMBER,
        "w222": NUMBER,
        "w220": NUMBER,
        "w311": NUMBER,
        "field_radius": NUMBER,
    },
    "detector": {
        "fov": NUMBER,
        "radius": NUMBER,
        "defocus": NUMBER,
        "offset": PAIR,
        "numerical_aperture": NUMBER,
        "stop_radius": NUMBER,
        "stop_distance": NUMBER,
    },
    "ranges": {
        "start": NUMBER,
        "stop": NUMBER,
        "count": INTEGER_LIMITS["ranges.count"],
        "spacing": STRING,
        "values": "values",
    },
    "run": {
        "method": STRING,
        "tolerance": NUMBER,
        "beam_window": NUMBER,
        **{
            key: INTEGER_LIMITS[f"run.{key}"]
            for key in ("threads", "max_segments", "beam_grid", "max_spectrum_grid")
        },
    },
    "output": {name: BOOL for name in OUTPUTS},
    "turbulence": {
        "cn2": CN2,
        "elevation": NUMBER,
        "altitude": NUMBER,
        "outer_scale": NUMBER,
        "inner_scale": NUMBER,
        "hv_ground": NUMBER,
        "hv_wind": NUMBER,
        "paths": STRING,
        **{
            key: INTEGER_LIMITS[f"turbulence.{key}"]
            for key in ("realizations", "screens", "receiver_fields", "seed")
        },
    },
}
#: The [turbulence] keys that describe the atmosphere (lo.Turbulence); the others are the draws'
#: (lo.Turbulent).
TURBULENCE_PROFILE_KEYS = (
    "cn2",
    "elevation",
    "altitude",
    "outer_scale",
    "inner_scale",
    "hv_ground",
    "hv_wind",
)
TOP_KEYS = {
    "name": STRING,
    "description": STRING,
    "beam": "table",
    "telescope": "table",
    "detector": "table",
    "ranges": "table",
    "run": "table",
    "output": "table",
    "turbulence": "table",
    "fit_bounds": "table",
}
REQUIRED = {
    "gaussian": ("wavelength", "waist_radius"),
    "flat_top": ("wavelength", "waist_radius", "angular_diameter"),
    "super_gaussian": ("wavelength", "radius", "order", "grid", "spacing"),
    "telescope": ("diameter", "focal_length"),
}


class ScenarioError(ValueError):
    """A scenario that cannot be used (or whose computation the library refused); the message names
    the file, section and key."""


def checked_keys(
    source: str, section: Optional[str], table: Any, schema: Dict[str, Any], required=()
) -> Dict[str, Any]:
    """Check a table against ``schema`` (key -> expected kind): unknown keys, missing keys and
    types."""
    where = f"{source}: [{section}]" if section else f"{source}:"
    if not isinstance(table, dict):
        raise ScenarioError(
            f"{where} is {short(table)}: expected a table of keys ({', '.join(schema)})"
        )
    for key, value in table.items():
        if key not in schema:
            raise ScenarioError(
                f"{where} unknown key {short(key, 40)} (valid: {', '.join(schema)})"
            )
        kind = schema[key]
        if isinstance(kind, IntegerKey):
            ok = (
                isinstance(value, int)
                and not isinstance(value, bool)
                and kind.low <= value <= kind.high
            )
        elif kind == PAIR:
            ok = isinstance(value, list) and len(value) == 2 and all(is_number(v) for v in value)
            kind = "an (x, y) pair of two finite numbers, e.g. [0.0, 0.0]"
        elif kind == "values":
            ok = isinstance(value, list) and all(is_number(v) for v in value)
            kind = "a list of finite numbers (m)"
        elif kind == "table":
            ok = isinstance(value, dict)
            kind = f"a table [{key}]"
        else:
            ok = {
                CN2: lambda v: is_number(v) or v == "hv57",
                NUMBER: is_number,
                STRING: lambda v: isinstance(v, str),
                BOOL: lambda v: isinstance(v, bool),
            }[kind](value)
        if not ok:
            raise ScenarioError(f"{where} {key} = {short(value)} is invalid: expected {kind}")
    require(where, table, required)
    return table


def require(where: str, table: Dict[str, Any], required, alternative: str = "") -> None:
    for key in required:
        if key not in table:
            raise ScenarioError(
                f"{where} missing key {key!r} (required: {', '.join(required)}{alternative})"
            )


def choice(where: str, key: str, value: Any, valid) -> Any:
    if not isinstance(value, str) or value not in valid:
        raise ScenarioError(
            f"{where} {key} = {short(value)} is invalid: expected one of "
            f"{', '.join(map(repr, valid))}"
        )
    return value


def is_number(value: Any) -> bool:
    """A finite int or float (TOML also has nan, inf and integers beyond any float)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    try:
        return math.isfinite(value)
    except OverflowError:
        return False


def fit_bounds_table(source: str, table: Dict[str, Any]) -> Dict[str, Any]:
    """[fit_bounds]: "path" = [low, high]; a bare dotted key (beam.divergence) is a nested table in
    TOML, read back as its path. The paths and bounds are the system's to check."""
    out: Dict[str, Any] = {}
    pending = [("", table)]
    while pending:
        prefix, part = pending.pop()
        for key, value in part.items():
            if isinstance(value, dict):
                pending.append((f"{prefix}{key}.", value))
            elif isinstance(value, list) and len(value) == 2 and all(map(is_number, value)):
                out[prefix + key] = tuple(value)
            else:
                raise ScenarioError(
                    f"{source}: [fit_bounds] {short(prefix + key, 40)} = {short(value)} is "
                    "invalid: expected [low, high], two finite numbers in SI units"
                )
    return out


def short(value: Any, limit: int = 80) -> str:
    """repr(value), cut to ``limit`` characters so that a message stays one readable line."""
    text = repr(value)
    return text if len(text) <= limit else f"{text[: limit - 3]}..."


def prefixed(source: str, section: Optional[str], error: ValueError) -> str:
    """The library's ``error`` about ``beam.offset``, ``aberrations.zernike[11]``, ... as the
    file's section and key: ``[beam] offset``, ``[telescope.aberrations.zernike] 11`` (from the
    parameter a :class:`lidar_overlap.ParameterError` carries); any other error under
    ``section``."""
    message = str(error)
    parameter = error.parameter if isinstance(error, _checks.ParameterError) else ""
    place = file_key(parameter) if message.startswith(parameter) else None
    if place is not None:
        table, key, rest = place
        return f"{source}: [{table}] {key}{message[len(parameter) - len(rest) :]}"
    return f"{source}: [{section}] {message}" if section else f"{source}: {message}"


def file_key(parameter: str) -> Optional[Tuple[str, str, str]]:
    """(table, key, what follows the key) of a system's parameter path in a scenario file:
    ``beam.offset[0]`` -> (``beam``, ``offset``, ``[0]``), ``aberrations.zernike[11]`` ->
    (``telescope.aberrations.zernike``, ``11``, ``""``); None for a path of no file table."""
    head, _, tail = parameter.partition(".")
    if head == "aberrations" and tail.startswith("zernike[") and "]" in tail:
        index, _, rest = tail.removeprefix("zernike[").partition("]")
        return ("telescope.aberrations.zernike", index, rest) if index.isdigit() else None
    key = tail.split("[", 1)[0].split(".", 1)[0]
    if head not in ("aberrations", "beam", "telescope", "detector") or not key.isidentifier():
        return None
    table = "telescope.aberrations" if head == "aberrations" else head
    return table, key, tail[len(key) :]


def build(source: str, section: Optional[str], factory, *args, **kwargs):
    try:
        return factory(*args, **kwargs)
    except ValueError as exc:
        raise ScenarioError(prefixed(source, section, exc)) from None
