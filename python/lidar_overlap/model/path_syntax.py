"""The syntax of parameter paths (``"beam.tilt[0]"``, ``"beam.components[1].divergence"``,
``"telescope.aberrations.zernike[11]"``): parsing, the one spelling of each, the expansion of a bare
pair, and maps of paths to bounds by scalar path (:func:`by_scalar`, what every fit matches bounds
with), without a system (what the system itself checks its ``fit_bounds`` with). Reading and
replacing values: :mod:`lidar_overlap.model.parameter_paths`.
"""

from __future__ import annotations

import math
import re
from typing import Any, Dict, Iterable, List, Mapping, Optional, Tuple

from .. import _checks
from .._values import FrozenMap
from .aberrations import SEIDEL_TERMS

PAIRS = {"beam": ("offset", "tilt"), "detector": ("offset",)}
SCALARS = {
    "beam": ("wavelength", "waist_radius", "divergence"),
    "telescope": ("diameter", "focal_length", "obstruction_radius", "obstruction_distance"),
    "detector": ("radius", "defocus", "numerical_aperture", "stop_radius", "stop_distance"),
}
# ASCII only and anchored at the very end (\Z, not $, which also matches before a final newline): a
# path is one spelling of one scalar, so that duplicates can be found (see canonical()).
_PATH = re.compile(r"(beam|telescope|detector)\.([A-Za-z_0-9]+)(?:\[([0-9]+)\])?\Z")
_COMPONENT = re.compile(r"beam\.components\[([0-9]{1,4})\]\.(weight|waist_radius|divergence)\Z")
COMPONENT_SCALARS = ("weight", "waist_radius", "divergence")
_ABERRATION = re.compile(r"telescope\.aberrations\.(?:zernike\[([0-9]+)\]|([A-Za-z_0-9]+))\Z")


def valid_paths() -> List[str]:
    """Every path form :func:`get` and :func:`replace` accept (``zernike[j]`` for any Noll index
    j)."""
    paths = [f"{part}.{name}" for part, names in SCALARS.items() for name in names]
    paths += [
        f"{part}.{name}[{i}]" for part, names in PAIRS.items() for name in names for i in (0, 1)
    ]
    return (
        paths
        + [f"beam.components[i].{name}" for name in COMPONENT_SCALARS]
        + ["telescope.aberrations.zernike[j]"]
        + [f"telescope.aberrations.{t}" for t in SEIDEL_TERMS]
    )


def expand(paths: Iterable[str]) -> List[str]:
    """``paths`` with each bare pair (``"beam.tilt"``) replaced by its two scalars; each path
    checked."""
    if isinstance(paths, str):
        paths = [paths]
    if paths is None or not isinstance(paths, Iterable):
        raise ValueError(
            f"parameters = {_checks.shown(paths)} is invalid: expected a list of parameter paths, "
            "e.g. ['beam.tilt', 'detector.defocus']"
        )
    paths = list(paths)
    out: List[str] = []
    for path in paths:
        m = _PATH.match(path) if isinstance(path, str) else None
        if m and m.group(3) is None and m.group(2) in PAIRS.get(m.group(1), ()):
            out += [f"{path}[0]", f"{path}[1]"]
        else:
            out.append(canonical(path))
    twice = sorted({p for p in out if out.count(p) > 1})
    if twice:
        raise ValueError(
            f"parameters = {_checks.shown(paths)} is invalid: {twice[0]} is named twice (paths are "
            "compared in their plain form: no leading zeros in an index)"
        )
    return out


class CheckedBounds(FrozenMap):
    """A map of bounds :func:`checked_bounds` made: taken as it is when it comes again (every new
    system of a fit, ``parameters.replace``, carries its start's); pickled as a FrozenMap, so an
    unpickled one is checked again."""

    __slots__ = ()


def checked_bounds(name: str, bounds) -> Optional[FrozenMap]:
    """``bounds`` ({path: (low, high)}, SI units; None or empty: none) as a read-only map of scalar
    paths (a bare pair expanded to both) to finite pairs with low < high; ValueError naming
    ``name`` and the path otherwise."""
    if bounds is None or isinstance(bounds, CheckedBounds):
        return bounds
    if not isinstance(bounds, Mapping):
        raise ValueError(
            f"{name} = {_checks.shown(bounds)} is invalid: expected None or a dict path -> "
            "(low, high) in SI units"
        )
    out: Dict[str, Tuple[float, float]] = {}
    for path, value in by_scalar(name, bounds).items():
        low, high = _checks.pair(f"{name}[{path!r}]", value)
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise ValueError(
                f"{name}[{path!r}] = ({low!r}, {high!r}) is invalid: expected finite low < high"
            )
        out[path] = (low, high)
    return CheckedBounds(out) if out else None


def by_scalar(name: str, bounds: Mapping, free: Optional[Iterable[str]] = None) -> Dict[str, Any]:
    """``bounds`` ({path: value}, the values left to the caller to check) by scalar path in its one
    spelling: a bare pair's value for both its scalars, as everywhere a pair is named. With
    ``free`` (the fit's free scalars), a pair of which the fit frees one bounds that one only
    ("beam.offset" when only "beam.offset[0]" is free); other keys are kept for the fit to refuse.
    ValueError naming ``name`` for a key that is not a path and for a scalar named twice
    ("beam.offset" and "beam.offset[0]")."""
    chosen = None if free is None else set(free)
    out: Dict[str, Any] = {}
    whose: Dict[str, Any] = {}
    for key, value in bounds.items():
        try:
            paths = expand([key])
        except ValueError as exc:
            raise ValueError(f"{name}: {exc}") from None
        if chosen is not None and len(paths) == 2 and chosen & set(paths):
            paths = [p for p in paths if p in chosen]
        for path in paths:
            if path in out:
                raise ValueError(
                    f"{name}: {path} is bounded twice ({whose[path]!r} and {key!r}): expected one "
                    "bound per scalar (a bare pair bounds both of its scalars)"
                )
            out[path], whose[path] = value, key
    return out


def canonical(path) -> str:
    """The one spelling of the scalar ``path`` names (``"beam.tilt[00]"`` -> ``"beam.tilt[0]"``);
    ValueError for anything that is not a path."""
    kind, part, name, index = parse(path)
    if kind == "zernike":
        return f"telescope.aberrations.zernike[{index}]"
    if kind == "seidel":
        return f"telescope.aberrations.{name}"
    if kind == "component":
        return f"beam.components[{index}].{name}"
    return f"{part}.{name}" + ("" if index is None else f"[{index}]")


def parse(path) -> Tuple[str, str, str, Optional[int]]:
    """(kind, part, name, index) of a path: kind ``"plain"``, ``"zernike"`` or ``"seidel"``."""
    if isinstance(path, str):
        m = _COMPONENT.match(path)
        if m:
            return "component", "beam", m.group(2), int(m.group(1))
        m = _ABERRATION.match(path)
        if m and m.group(1) is not None and len(m.group(1)) <= 4:
            j = int(m.group(1))
            if 1 <= j <= 231:
                return "zernike", "telescope", "zernike", j
        elif m and m.group(2) in SEIDEL_TERMS + ("field_radius",):
            return "seidel", "telescope", m.group(2), None
        m = _PATH.match(path)
        if m:
            part, name, index = m.group(1), m.group(2), m.group(3)
            if index is None and name in SCALARS[part]:
                return "plain", part, name, None
            if (
                index is not None
                and name in PAIRS.get(part, ())
                and len(index) <= 4
                and int(index) in (0, 1)
            ):
                return "plain", part, name, int(index)
    raise _checks.refused(
        "parameter",
        path,
        f"one of {', '.join(valid_paths())}",
        f"parameter {_checks.shown(path)} is invalid: expected one of {', '.join(valid_paths())}",
    )
