"""What the library knows about each scalar of a :class:`LidarSystem` it addresses by path (the
paths themselves: :mod:`lidar_overlap.model.parameter_paths`, whose names this module hands on, so
``lidar_overlap.parameters.get`` and ``.replace`` work as before).

:data:`TABLE` holds each form of path once, as a :class:`Parameter`: its SI unit, its physical
meaning, the part of the instrument it belongs to (the model families group by it), its natural
scale s (G changes by O(1) over s: the steps of sensitivities and fit Jacobians, and the fit's
parameter scaling), its default bounds in a fit, and whether a global search takes it linearly or
in its logarithm. The scales:

- ``beam.tilt[i]``: the receiver's half field of view r_d / f (rad);
- ``beam.offset[i]``: the aperture radius D/2; ``detector.offset[i]``: the detector radius r_d;
- ``detector.defocus``: 2 r_d f / D, the defocus whose blur circle is the detector's size;
- every other (positive) scalar: its own value (a relative step).

Default bounds: ``beam.tilt[i]`` ±``MAX_TILT`` (10 mrad, far beyond any lidar whose beam still
meets the field of view; a search: the start ± ``TILT_FIELDS`` half fields of view, within that);
``beam.offset[i]`` the start ± the aperture diameter D; ``detector.offset[i]`` the start ± 10
detector radii; ``detector.defocus`` the start ± f / 10; a divergence (a Gaussian width law's) from
a tenth of its start, but not below ``DIFFRACTION_MARGIN`` times the diffraction limit (nor above
the start), to ten times its start; any other (positive) scalar from a tenth to ten times its start.
A one-parameter scan (:func:`lidar_overlap.realign`) has a default interval for the tilt (the start
± ``MAX_TILT`` / 2) and the beam offset (± D) only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Tuple

from .parameter_paths import (
    COMPONENT_SCALARS,
    PAIRS,
    SCALARS,
    canonical,
    expand,
    get,
    parse,
    replace,
    valid_paths,
)
from .system import LidarSystem

__all__ = [
    "COMPONENT_SCALARS",
    "PAIRS",
    "SCALARS",
    "Parameter",
    "TABLE",
    "canonical",
    "default_bounds",
    "describe",
    "expand",
    "get",
    "plain_paths",
    "replace",
    "scan_bounds",
    "search_bounds",
    "searched_in_log",
    "step_scale",
    "unit",
    "valid_paths",
]

#: A divergence's default lower bound stays this factor above the diffraction limit λ/(π w0) (width
#: law "gaussian"): below the limit there is no such beam (within a step of it the Jacobian takes
#: the one-sided difference, :func:`lidar_overlap.analysis.sensitivity.jacobian`).
DIFFRACTION_MARGIN = 1.05
#: Largest |beam tilt| of the default bounds (rad): 10 mrad, far beyond any lidar whose beam still
#: meets the field of view.
MAX_TILT = 1e-2
#: A search's default tilt bounds: the start ± this many half fields of view r_d / f (wider tilts
#: put the beam out of the field of view at every range, where a cost is flat).
TILT_FIELDS = 4.0


@dataclass(frozen=True)
class Parameter:
    """What the library knows about one form of path (module docstring's table): ``form`` (the
    path with ``i`` for an index), ``unit`` (SI), ``meaning``, ``family`` (the part of the
    instrument it describes: ``"alignment"``, ``"beam"``, ``"field of view"``, ``"focus"``,
    ``"acceptance"``, ``"second stop"``, ``"beam wings"``, ``"receiver"``, ``"aberrations"``),
    ``search`` (``"linear"``, or ``"log"`` for a positive scalar searched in its logarithm),
    ``scale`` ((system, value) -> the natural step scale s: G changes by O(1) over s) and
    ``bounds`` ((system, path, start) -> default (low, high)); ``search_bounds``, where given, the
    narrower box a global search uses by default; ``scan``, where given, the interval a
    one-parameter scan searches by default."""

    form: str
    unit: str
    meaning: str
    family: str
    search: str
    scale: Callable[[Any, str], float]
    bounds: Callable[[Any, str, float], Tuple[float, float]]
    search_bounds: Optional[Callable[[Any, float], Tuple[float, float]]] = None
    scan: Optional[Callable[[Any, float], Tuple[float, float]]] = None


def _field(system, path) -> float:  # the receiver's half field of view r_d / f (rad)
    return system.detector.radius / system.telescope.focal_length


def _half_aperture(system, path) -> float:
    return 0.5 * system.telescope.diameter


def _detector_radius(system, path) -> float:
    return system.detector.radius


def _blur_defocus(system, path) -> float:  # the defocus whose blur circle is the detector's size
    return 2.0 * system.detector.radius * system.telescope.focal_length / system.telescope.diameter


def _own_value(system, path) -> float:
    value = abs(get(system, path))
    if not value > 0:
        raise ValueError(
            f"parameters: {path} = 0 is at the edge of its valid range (it cannot be negative), so "
            "no central difference can be taken there"
        )
    return value


def _tilt_bounds(system, path, start):
    return -MAX_TILT, MAX_TILT


def _tilt_search(system, start):
    field = TILT_FIELDS * system.detector.radius / system.telescope.focal_length
    return max(-MAX_TILT, start - field), min(MAX_TILT, start + field)


def _tilt_scan(system, start):
    return start - MAX_TILT / 2, start + MAX_TILT / 2


def _offset_scan(system, start):
    return start - system.telescope.diameter, start + system.telescope.diameter


def _aperture_bounds(system, path, start):
    return start - system.telescope.diameter, start + system.telescope.diameter


def _detector_bounds(system, path, start):
    return start - 10 * system.detector.radius, start + 10 * system.detector.radius


def _defocus_bounds(system, path, start):
    return (
        start - 0.1 * system.telescope.focal_length,
        start + 0.1 * system.telescope.focal_length,
    )


def _relative_bounds(system, path, start):
    return start / 10, start * 10


def _divergence_bounds(system, path, start):
    """A tenth to ten times the start, the lower bound not below DIFFRACTION_MARGIN times the
    diffraction limit (nor above the start) for a Gaussian width law."""
    if getattr(system.beam, "width_law", "") == "gaussian":
        waist = get(system, path[: -len("divergence")] + "waist_radius")
        limit = DIFFRACTION_MARGIN * system.beam.wavelength / (math.pi * waist)
        return min(start, max(start / 10, limit)), start * 10
    return start / 10, start * 10


def _scalar(form, unit, meaning, family, search="log", scale=_own_value, bounds=_relative_bounds):
    return Parameter(form, unit, meaning, family, search, scale, bounds)


#: Every form of path, once.
TABLE: Dict[str, Parameter] = {
    p.form: p
    for p in (
        Parameter(
            "beam.tilt[i]", "rad", "the beam's tilt from the telescope axis", "alignment",
            "linear", _field, _tilt_bounds, _tilt_search, _tilt_scan,
        ),
        Parameter(
            "beam.offset[i]", "m", "the beam axis's offset from the telescope axis", "alignment",
            "linear", _half_aperture, _aperture_bounds, scan=_offset_scan,
        ),
        Parameter(
            "detector.offset[i]", "m", "the field stop's offset from the telescope axis",
            "alignment", "linear", _detector_radius, _detector_bounds,
        ),
        Parameter(
            "detector.defocus", "m", "the field stop's distance behind the image plane", "focus",
            "linear", _blur_defocus, _defocus_bounds,
        ),
        _scalar("beam.wavelength", "m", "the laser's wavelength", "beam"),
        _scalar("beam.waist_radius", "m", "the beam's 1/e² waist radius", "beam"),
        _scalar(
            "beam.divergence", "rad", "the beam's 1/e² half-angle divergence", "beam",
            bounds=_divergence_bounds,
        ),
        _scalar("telescope.diameter", "m", "the telescope's aperture diameter", "receiver"),
        _scalar("telescope.focal_length", "m", "the telescope's focal length", "receiver"),
        _scalar(
            "telescope.obstruction_radius", "m", "the central obstruction's radius", "receiver"
        ),
        _scalar(
            "telescope.obstruction_distance", "m", "the obstruction's distance before the lens",
            "receiver",
        ),
        _scalar("detector.radius", "m", "the field stop's radius", "field of view"),
        _scalar(
            "detector.numerical_aperture", "1", "the relay's (or fibre's) acceptance",
            "acceptance",
        ),
        _scalar("detector.stop_radius", "m", "a second stop's radius", "second stop"),
        _scalar(
            "detector.stop_distance", "m", "a second stop's distance behind the lens",
            "second stop",
        ),
        _scalar(
            "beam.components[i].weight", "1", "a beam component's share of power", "beam wings"
        ),
        _scalar(
            "beam.components[i].waist_radius", "m", "a beam component's waist radius", "beam wings"
        ),
        _scalar(
            "beam.components[i].divergence", "rad", "a beam component's half-angle divergence",
            "beam wings", bounds=_divergence_bounds,
        ),
        _scalar(
            "telescope.aberrations.zernike[j]", "m", "a Zernike term's RMS wavefront error "
            "(Noll j)", "aberrations",
        ),
        _scalar(
            "telescope.aberrations.seidel", "m", "a Seidel term's wavefront coefficient (or the "
            "field radius)", "aberrations",
        ),
    )
}  # fmt: skip


def describe(path: str) -> Parameter:
    """The :class:`Parameter` of the scalar ``path`` (any spelling :func:`canonical` accepts)."""
    kind, part, name, index = parse(path)
    if kind == "zernike":
        return TABLE["telescope.aberrations.zernike[j]"]
    if kind == "seidel":
        return TABLE["telescope.aberrations.seidel"]
    if kind == "component":
        return TABLE[f"beam.components[i].{name}"]
    return TABLE[f"{part}.{name}" + ("" if index is None else "[i]")]


def step_scale(system: LidarSystem, path: str) -> float:
    """The natural scale s of ``path`` in ``system`` (its unit): G changes by O(1) over s."""
    return describe(path).scale(system, path)


def default_bounds(system: LidarSystem, path: str, start: float) -> Tuple[float, float]:
    """(low, high) of ``path`` when a fit is given none, in SI units."""
    return describe(path).bounds(system, path, start)


def unit(path: str) -> str:
    """The SI unit of the scalar at ``path``."""
    return describe(path).unit


def search_bounds(system: LidarSystem, path: str, start: float) -> Tuple[float, float]:
    """(low, high) of ``path`` in a global search when none is given: the fit's default bounds, or
    the table's narrower search box where it has one."""
    p = describe(path)
    return p.search_bounds(system, start) if p.search_bounds else p.bounds(system, path, start)


def searched_in_log(path: str, low: float) -> bool:
    """Whether a search takes ``path`` in its logarithm (a positive scalar whose bounds are
    positive) rather than linearly."""
    return describe(path).search == "log" and low > 0


def scan_bounds(system: LidarSystem, path: str, start: float) -> Tuple[float, float]:
    """The interval a one-parameter scan of ``path`` searches when none is given; ValueError naming
    ``bounds`` for a parameter without one."""
    p = describe(path)
    if p.scan is None:
        raise ValueError(f"bounds: give (low, high) for {path}: it has no default search interval")
    return p.scan(system, start)


def plain_paths(paths, name: str, why: str) -> List[str]:
    """:func:`expand` of ``paths`` (the argument ``name``), refused when empty or naming aberration
    terms (``why`` says why the caller cannot vary them)."""
    try:
        out = expand(paths)
    except ValueError as exc:
        text = str(exc)
        if text.startswith("parameters = "):  # the caller's word for the list
            raise ValueError(name + text[len("parameters") :]) from None
        raise
    if not out:
        raise ValueError(
            f"{name} = [] is invalid: expected at least one parameter path, e.g. ['beam.tilt']"
        )
    aberrations = [path for path in out if describe(path).family == "aberrations"]
    if aberrations:
        raise ValueError(f"{name}: {', '.join(aberrations)} is not available: {why}")
    return out
