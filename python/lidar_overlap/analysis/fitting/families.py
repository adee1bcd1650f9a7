"""The model families of ``lo.fit(..., free="auto")``
(:mod:`lidar_overlap.analysis.fitting.ladder`), simplest first: each a physical explanation of an
overlap curve (where the beam enters the field of view, how fast it fills it, a field stop out of
focus, the acceptance cutting steep rays, a beam's wings, a second stop), the paths it frees, and
for the last two how the model is extended."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Callable, Dict, Optional, Tuple

from ...model import parameters as _parameters
from ...model.mixture_beam import GaussianMixtureBeam


@dataclass(frozen=True)
class Family:
    """A model family: its ``name``, the ``paths`` it frees and the physical ``explanation``;
    ``extend`` makes the family's model from a system (adds a beam's wing, a second stop; None:
    the system as it is; applied to systems that lack it only), ``start_from`` names the family
    whose best it starts from (None: the one before), ``bounds`` are its default bounds (m, rad)
    as functions of the system, where the fit's defaults would leave the model's range."""

    name: str
    paths: Tuple[str, ...]
    explanation: str
    extend: Optional[Callable[[Any], Any]] = None
    start_from: Optional[str] = None
    bounds: Optional[Callable[[Any], Dict[str, Tuple[float, float]]]] = None

    def model(self, system):
        """``system`` as this family models it (:attr:`extend` applied)."""
        return system if self.extend is None else self.extend(system)


#: A beam's wing when the ladder adds one: this share of the main beam's power ...
WING_WEIGHT = 0.05
#: ... spreading this many times faster than the main beam.
WING_DIVERGENCE = 4.0
#: A second stop when the ladder adds one: at this fraction of the lens-detector distance, cutting
#: the far-range pupil to this fraction of its radius.
STOP_AT, STOP_CUT = 0.5, 0.95
#: The farthest a fitted second stop may lie, as a fraction of the lens-detector distance: the
#: Jacobian's steps (~3 %) and a fitted defocus must leave it before the detector plane.
STOP_FARTHEST = 0.85


def with_wing(system):
    """``system`` with a weak, more divergent wing added to its Gaussian beam (WING_WEIGHT of the
    power, WING_DIVERGENCE times the divergence, the same waist); other systems as they are."""
    beam = system.beam
    if beam.field_given or beam.has_components:  # a given field, or a mixture already
        return system
    wing = GaussianMixtureBeam.with_wings(
        beam, WING_WEIGHT, WING_DIVERGENCE * beam.half_angle_divergence
    )
    return dataclasses.replace(system, beam=wing)


def with_stop(system):
    """``system`` with a second, centred stop STOP_AT of the way from the lens to the detector
    plane, of a radius that leaves STOP_CUT of the far-range pupil's radius (it vignettes the
    steepest rays); a system that has one as it is."""
    det = system.detector
    if det.stop_radius is not None:
        return system
    s = STOP_AT * system.image_distance
    radius = (
        STOP_CUT * 0.5 * system.telescope.diameter * abs(1.0 - s / system.telescope.focal_length)
    )
    radius = radius if radius > 0 else 0.5 * system.telescope.diameter
    return dataclasses.replace(
        system, detector=dataclasses.replace(det, stop_radius=radius, stop_distance=s)
    )


def wing_bounds(system) -> Dict[str, Tuple[float, float]]:
    """Default bounds of the wing (a system with one): share 1e-3 to 1 of the main beam's power,
    1.2 to 30 times its divergence."""
    theta = _parameters.get(system, "beam.components[0].divergence")
    return {
        "beam.components[1].weight": (1e-3, 1.0),
        "beam.components[1].divergence": (1.2 * theta, 30.0 * theta),
    }


def stop_bounds(system) -> Dict[str, Tuple[float, float]]:
    """Default bounds of a second stop: 2 % to STOP_FARTHEST of the way to the detector plane, a
    radius up to the aperture's."""
    d, radius = system.image_distance, 0.5 * system.telescope.diameter
    return {
        "detector.stop_distance": (0.02 * d, STOP_FARTHEST * d),
        "detector.stop_radius": (1e-3 * radius, radius),
    }


_FOCUS = (
    "beam.offset[0]",
    "beam.tilt[0]",
    "beam.divergence",
    "detector.radius",
    "detector.defocus",
)
_ACCEPTANCE = "alignment + beam + focus + acceptance"


#: The default ladder for a biaxial lidar, simplest first (each adds to the one before).
LADDER = (
    Family(
        "alignment",
        ("beam.offset[0]", "beam.tilt[0]"),
        "where the beam enters the field of view: the axis separation and the beam's tilt",
    ),
    Family(
        "alignment + beam",
        ("beam.offset[0]", "beam.tilt[0]", "beam.divergence", "detector.radius"),
        "how fast the beam fills the field of view: its divergence and the field stop's size",
    ),
    Family(
        "alignment + beam + focus",
        (
            "beam.offset[0]",
            "beam.tilt[0]",
            "beam.divergence",
            "detector.radius",
            "detector.defocus",
        ),
        "the slow approach to full overlap: a field stop out of focus, so near-range light is "
        "blurred over its edge",
    ),
    Family(
        "alignment + beam + focus + acceptance",
        (
            "beam.offset[0]",
            "beam.tilt[0]",
            "beam.divergence",
            "detector.radius",
            "detector.defocus",
            "detector.numerical_aperture",
        ),
        "the relay's (or fibre's) acceptance cutting the steep rays of near scatterers",
    ),
    Family(
        "alignment + beam + focus + wings",
        _FOCUS + ("beam.components[1].weight", "beam.components[1].divergence"),
        "a beam with wings: a weak, more divergent part of the laser's light (higher-order modes, "
        "light scattered in the beam expander) entering the field of view before the main beam",
        extend=with_wing,
        start_from=_ACCEPTANCE,
        bounds=wing_bounds,
    ),
    Family(
        "alignment + beam + focus + second stop",
        _FOCUS + ("detector.stop_radius", "detector.stop_distance"),
        "a second stop behind the lens (a relay's or field lens's aperture, a vignetting mount) "
        "cutting rays the field stop alone would pass",
        extend=with_stop,
        start_from=_ACCEPTANCE,
        bounds=stop_bounds,
    ),
)
