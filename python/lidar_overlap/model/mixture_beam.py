"""A transmitted beam with wings: mutually incoherent Gaussian components (SI units).

A laser's beam often carries, besides its main mode, a weak and more divergent part (higher-order
modes, scattered light off the beam expander). When the parts are mutually incoherent their
irradiances add, and since the overlap function is linear in the transmitted irradiance (paper Eq.
(3): the received power is the irradiance weighted by the receiver's coupling), G of the whole beam
is exactly the power-weighted mean of the components' G:

    G(z) = Σ_i w_i G_i(z) / Σ_i w_i,

each G_i that of a :class:`~lidar_overlap.GaussianBeam` of the component's waist and divergence
sharing the beam's wavelength, offset, tilt and width law. Ray tracing and Fourier optics both model
it (each component by its own path).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import ClassVar, Literal, Optional, Tuple

from .. import _checks, _core
from .._pickling import ByArguments

Pair = Tuple[float, float]
#: Most components of a beam: each is planned and run on its own (a beam and its wings need a few).
MAX_COMPONENTS = 64


@dataclass(frozen=True)
class BeamComponent(ByArguments):
    """One incoherent part of a :class:`GaussianMixtureBeam`.

    Parameters
    ----------
    weight : its share of the transmitted power, relative to the other components' (> 0; the
        weights need not sum to 1: each is divided by their sum).
    waist_radius : m, its 1/e² irradiance radius at z = 0.
    divergence : rad, its 1/e² far-field half-angle; ``None`` means diffraction-limited.
    """

    weight: float = 1.0
    waist_radius: float = 1e-3
    divergence: Optional[float] = None

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "weight", _checks.real("component.weight", self.weight))
        set_(self, "waist_radius", _checks.positive("component.waist_radius", self.waist_radius))
        if self.divergence is not None:
            set_(self, "divergence", _checks.positive("component.divergence", self.divergence))
        if not (self.weight > 0 and math.isfinite(self.weight)):
            raise ValueError(
                f"component.weight = {self.weight!r} is invalid: expected a finite relative power "
                "> 0"
            )


@dataclass(frozen=True)
class GaussianMixtureBeam(ByArguments):
    """A radially symmetric transmitted beam made of mutually incoherent Gaussian components
    (module docstring): a main mode and its wings.

    Parameters
    ----------
    components : sequence of :class:`BeamComponent` (at least one; their relative powers, waists and
        divergences).
    wavelength : m, shared by every component.
    offset : (x, y) in m, the common centroid at z = 0 relative to the telescope axis.
    tilt : (x, y) in rad, the common pointing relative to the telescope axis.
    width_law : as :class:`GaussianBeam` (``"gaussian"`` or ``"linear"``).

    Each component is checked as a :class:`GaussianBeam` would be; an error names it as
    ``beam.components[i].<name>``.
    """

    #: What the parameter paths may address (:mod:`lidar_overlap.model.parameters`):
    #: ``field_given`` (only offset and tilt vary: the field is data), ``has_components`` (its
    #: ``beam.components[i]`` scalars; ``beam.divergence`` is component 0's).
    field_given: ClassVar[bool] = False
    has_components: ClassVar[bool] = True

    components: Tuple[BeamComponent, ...] = (BeamComponent(),)
    wavelength: float = 355e-9
    offset: Pair = (0.0, 0.0)
    tilt: Pair = (0.0, 0.0)
    width_law: Literal["gaussian", "linear"] = "gaussian"
    _natives: Tuple[_core.GaussianBeam, ...] = field(init=False, repr=False, compare=False)
    _native: _core.GaussianBeam = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        parts = self.components
        if isinstance(parts, (str, bytes)) or not hasattr(parts, "__len__"):
            raise ValueError(
                f"beam.components = {_checks.shown(parts)} is invalid: expected a sequence of "
                "BeamComponent"
            )
        if not 1 <= len(parts) <= MAX_COMPONENTS:
            raise ValueError(
                f"beam.components has {len(parts)} components: expected 1 to {MAX_COMPONENTS} "
                "BeamComponent"
            )
        for i, c in enumerate(parts):
            if not isinstance(c, BeamComponent):
                raise ValueError(
                    f"beam.components[{i}] = {_checks.shown(c)} is invalid: expected a "
                    "BeamComponent"
                )
        set_(self, "components", tuple(parts))
        total = sum(c.weight for c in parts)
        if not (total > 0 and math.isfinite(total)):
            raise ValueError(
                f"beam.components: the weights sum to {total!r}; expected a finite total > 0"
            )
        set_(self, "wavelength", _checks.real("beam.wavelength", self.wavelength))
        set_(self, "offset", _checks.pair("beam.offset", self.offset))
        set_(self, "tilt", _checks.pair("beam.tilt", self.tilt))
        _checks.choice("beam.width_law", self.width_law, ("gaussian", "linear"))
        natives = []
        for i, c in enumerate(parts):
            try:
                natives.append(
                    _core.GaussianBeam(
                        self.wavelength,
                        c.waist_radius,
                        c.divergence,
                        self.offset,
                        self.tilt,
                        self.width_law,
                    )
                )
            except ValueError as exc:
                text = str(exc)
                # the component's own parameters are named by its index
                if text.startswith(("beam.waist_radius", "beam.divergence")):
                    text = f"beam.components[{i}].{text[len('beam.') :]}"
                raise ValueError(text) from None
        set_(self, "_natives", tuple(natives))
        # The system model (validation, pointing) carries the dominant component.
        set_(self, "_native", natives[self.dominant])

    @property
    def weights(self) -> Tuple[float, ...]:
        """The components' shares of the power (summing to 1)."""
        total = sum(c.weight for c in self.components)
        return tuple(c.weight / total for c in self.components)

    @property
    def dominant(self) -> int:
        """Index of the component carrying the most power (the first of equals)."""
        w = [c.weight for c in self.components]
        return w.index(max(w))

    @property
    def divergences(self) -> Tuple[float, ...]:
        """rad, each component's far-field 1/e² half-angle (its diffraction limit where
        ``divergence`` is None)."""
        return tuple(n.half_angle_divergence() for n in self._natives)

    @property
    def waist_radius(self) -> float:
        """m, the main beam's (component 0's) 1/e² waist radius, as the path
        ``"beam.waist_radius"`` reads it."""
        return self.components[0].waist_radius

    @property
    def divergence(self) -> Optional[float]:
        """rad, the main beam's (component 0's) divergence as given (None: diffraction-limited)."""
        return self.components[0].divergence

    @property
    def half_angle_divergence(self) -> float:
        """rad, the main beam's (component 0's) far-field 1/e² half-angle."""
        return self._natives[0].half_angle_divergence()

    @property
    def rms_divergence(self) -> float:
        """rad, the power-weighted RMS far-field half-angle sqrt(Σ w_i θ_i²): that of the
        irradiance's second moment."""
        return math.sqrt(sum(w * d**2 for w, d in zip(self.weights, self.divergences)))

    def radius(self, z):
        """The power-weighted RMS 1/e² radius (m) at range(s) z (m): the irradiance's second-moment
        radius, sqrt(Σ w_i w_i(z)²)."""
        return sum(w * n.radius(z) ** 2 for w, n in zip(self.weights, self._natives)) ** 0.5

    def center(self, z: float) -> Tuple[float, float]:
        """Beam centroid (x, y) in m at range z (m): offset + tilt·z (paraxial)."""
        return (self.offset[0] + self.tilt[0] * z, self.offset[1] + self.tilt[1] * z)

    def with_component(self, index: int, **changes) -> "GaussianMixtureBeam":
        """A copy with component ``index``'s ``weight``, ``waist_radius`` or ``divergence``
        replaced."""
        n = len(self.components)
        index = _checks.count("index", index, -n, n - 1)
        unknown = sorted(set(changes) - {"weight", "waist_radius", "divergence"})
        if unknown:
            raise ValueError(
                f"with_component: {unknown[0]!r} is invalid: expected weight, waist_radius or "
                "divergence"
            )
        parts = list(self.components)
        parts[index] = dataclasses.replace(parts[index], **changes)
        return dataclasses.replace(self, components=tuple(parts))

    @classmethod
    def with_wings(
        cls,
        beam,
        weight: float,
        divergence: float,
        waist_radius: Optional[float] = None,
    ) -> "GaussianMixtureBeam":
        """``beam`` (a :class:`~lidar_overlap.GaussianBeam`) as the main component (weight 1) plus a
        wing of relative power ``weight`` and half-angle ``divergence`` (rad), of the main's waist
        unless ``waist_radius`` (m) is given."""
        if not all(hasattr(beam, a) for a in ("waist_radius", "divergence", "width_law")) or (
            isinstance(beam, GaussianMixtureBeam)
        ):
            raise ValueError(f"beam = {_checks.shown(beam)} is invalid: expected a GaussianBeam")
        main = BeamComponent(1.0, beam.waist_radius, beam.divergence)
        wing = BeamComponent(
            weight, beam.waist_radius if waist_radius is None else waist_radius, divergence
        )
        return cls((main, wing), beam.wavelength, beam.offset, beam.tilt, beam.width_law)
