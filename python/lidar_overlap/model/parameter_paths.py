"""Scalars of a :class:`LidarSystem` addressed by path (SI units): parsing, reading and replacing
them (:mod:`lidar_overlap.model.parameters` says what each one is).

A path names one scalar: ``"beam.tilt[0]"`` (rad), ``"beam.offset[1]"`` (m), ``"beam.divergence"``
(rad, the 1/e² half-angle; read as the actual divergence when the beam is diffraction-limited),
``"beam.waist_radius"``, ``"beam.wavelength"``, ``"telescope.diameter"``,
``"telescope.focal_length"``, ``"telescope.obstruction_radius"``,
``"telescope.obstruction_distance"``, ``"detector.radius"``, ``"detector.defocus"``,
``"detector.offset[0]"``, ``"detector.numerical_aperture"``, ``"detector.stop_radius"``,
``"detector.stop_distance"``, ``"telescope.aberrations.zernike[11]"``
(m RMS, Noll index), ``"telescope.aberrations.w040"`` (and the other Seidel terms) and, for a
:class:`GaussianMixtureBeam`, ``"beam.components[i].weight"`` (relative power),
``"beam.components[i].waist_radius"`` (m) and ``"beam.components[i].divergence"`` (rad), whose
``"beam.waist_radius"`` and ``"beam.divergence"`` are those of component 0 (the main beam). A pair
without an index (``"beam.tilt"``) stands for both of its scalars where a list of parameters is
asked for (:func:`expand`).

Systems are immutable: :func:`replace` builds a new one, validated like any other, so a value
outside the model's range is refused naming the path.
"""

from __future__ import annotations

import dataclasses
import re
from typing import Any, Dict, Iterable, List, Mapping, Optional, Tuple

from .. import _checks
from .aberrations import SEIDEL_TERMS, Aberrations
from .mixture_beam import GaussianMixtureBeam
from .system import LidarSystem

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


def get(system: LidarSystem, path: str) -> float:
    """The value of the scalar at ``path`` in ``system`` (SI units)."""
    kind, part, name, index = _main_component(system, *parse(path))
    if kind == "zernike":
        ab = system.telescope.aberrations
        return float(ab.zernike.get(index or 0, 0.0)) if ab is not None else 0.0
    if kind == "seidel":
        ab = system.telescope.aberrations
        return float(getattr(ab, name)) if ab is not None else 0.0
    if kind == "component":
        beam = _mixture(system, path, index)
        i = index or 0
        if name == "divergence":
            return float(beam.divergences[i])
        return float(getattr(beam.components[i], name))
    owner = getattr(system, part)
    if part == "beam" and name == "divergence" and not (owner.field_given or owner.has_components):
        return float(owner.half_angle_divergence)
    _check_owner(owner, part, name, path)
    value = getattr(owner, name)
    if value is None:
        raise ValueError(
            f"{path} is not set in this system (None): give it a value before varying it"
        )
    return float(value[index] if index is not None else value)


def replace(system: LidarSystem, values: Mapping[str, float]) -> LidarSystem:
    """A new system with each path in ``values`` set to its value (SI units); refused naming the
    path when a value is not a real number or the system it makes is invalid."""
    changes: Dict[str, Dict[str, Any]] = {"beam": {}, "telescope": {}, "detector": {}}
    aberrations: Dict[str, Any] = {}
    components: Dict[int, Dict[str, float]] = {}
    for path, value in values.items():
        kind, part, name, index = _main_component(system, *parse(path))
        value = _checks.real(path, value)
        if kind == "component":
            _mixture(system, path, index)
            components.setdefault(index or 0, {})[name] = value
        elif kind == "zernike":
            current = aberrations.get("zernike", dict(_aberrations(system).zernike))
            aberrations["zernike"] = {**current, index: value}
        elif kind == "seidel":
            aberrations[name] = value
        elif index is not None:
            pair = list(changes[part].get(name, getattr(getattr(system, part), name)))
            pair[index] = value
            changes[part][name] = tuple(pair)
        else:
            _check_owner(getattr(system, part), part, name, path)
            changes[part][name] = value
    try:
        if aberrations:
            changes["telescope"]["aberrations"] = dataclasses.replace(
                _aberrations(system), **aberrations
            )
        parts = {part: _replaced(getattr(system, part), part, c) for part, c in changes.items()}
        for i, c in components.items():
            parts["beam"] = parts["beam"].with_component(i, **c)
        return LidarSystem(**parts)
    except ValueError as exc:
        raise ValueError(
            f"{', '.join(values)} = {_shown(values)} makes an invalid system: {exc}"
        ) from None


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


def _main_component(system, kind: str, part: str, name: str, index):
    """A mixture's ``beam.waist_radius`` and ``beam.divergence`` as its component 0's."""
    if (
        kind == "plain"
        and part == "beam"
        and name in ("waist_radius", "divergence")
        and system.beam.has_components
    ):
        return "component", part, name, 0
    return kind, part, name, index


def _mixture(system, path: str, index) -> GaussianMixtureBeam:
    """``system``'s beam when it has a component ``index``; refused naming ``path`` otherwise."""
    beam = system.beam
    if not beam.has_components:
        raise ValueError(
            f"{path} is invalid for a {type(beam).__name__}: only a GaussianMixtureBeam has "
            "components"
        )
    if not 0 <= index < len(beam.components):
        raise ValueError(
            f"{path} is invalid: the beam has {len(beam.components)} components (index 0 to "
            f"{len(beam.components) - 1})"
        )
    return beam


def _check_owner(owner, part: str, name: str, path: str) -> None:
    if part == "beam" and owner.field_given and name not in ("offset", "tilt"):
        raise ValueError(
            f"{path} is invalid for a {type(owner).__name__}: only its offset and tilt can vary "
            "(its field is given)"
        )


def _aberrations(system) -> Aberrations:
    return (
        system.telescope.aberrations if system.telescope.aberrations is not None else Aberrations()
    )


def _replaced(owner, part: str, changes: Dict[str, Any]):
    if not changes:
        return owner
    if part == "beam" and owner.field_given:
        return owner.with_pointing(changes.get("offset"), changes.get("tilt"))
    return dataclasses.replace(owner, **changes)


def _shown(values: Mapping[str, float]) -> str:
    return ", ".join(repr(v) for v in values.values())
