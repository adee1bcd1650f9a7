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
outside the model's range is refused naming the path. The paths' syntax (parsing, :func:`expand`,
:func:`canonical`) lives in :mod:`lidar_overlap.model.path_syntax`, which the system reads too.
"""

from __future__ import annotations

import dataclasses
from typing import Any, Dict, Mapping

from .. import _checks
from .aberrations import Aberrations
from .mixture_beam import GaussianMixtureBeam
from .path_syntax import (  # noqa: F401 (handed on: parameters and callers read them here)
    COMPONENT_SCALARS,
    PAIRS,
    SCALARS,
    canonical,
    checked_bounds,
    expand,
    parse,
    valid_paths,
)
from .system import LidarSystem


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
        return LidarSystem(**parts, fit_bounds=system.fit_bounds)
    except ValueError as exc:
        raise ValueError(
            f"{', '.join(values)} = {_shown(values)} makes an invalid system: {exc}"
        ) from None


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
