"""The lidar system model: transmitted beam, receiving telescope, detector (SI units throughout).

Each dataclass is immutable and validated on construction by the C++ core, so an invalid system
cannot reach a computation. Use :func:`dataclasses.replace` to vary one parameter.

One rule across the public classes (these, :class:`Field`, :class:`FieldBeam`, :class:`FlatTopBeam`,
:class:`Turbulence`, :class:`Aberrations`, :class:`DetectorImage`): a derived quantity that needs no
argument is a property (``LidarSystem.fov``, ``Field.beam_radius``); one that needs an argument is a
method (``Detector.fov(focal_length)``, ``GaussianBeam.radius(z)``). Arguments go wavelength first,
then
beam sizes, then path length or range: ``(wavelength, waist_radius, path_length)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar, Literal, Mapping, Optional, Tuple

import numpy as np

from .. import _checks, _core
from .._pickling import ByArguments
from .aberrations import Aberrations
from .aperture_mask import ApertureMask
from .field_beam import FieldBeam
from .mixture_beam import GaussianMixtureBeam
from .path_syntax import checked_bounds

Pair = Tuple[float, float]
#: The width laws of a Gaussian beam (:class:`GaussianBeam`).
WidthLaw = Literal["gaussian", "linear"]


@dataclass(frozen=True)
class GaussianBeam(ByArguments):
    """Gaussian (TEM00-like) transmitted beam.

    Parameters
    ----------
    wavelength : m.
    waist_radius : m, 1/e² irradiance radius w0 at the transmitting plane z = 0.
    divergence : rad, 1/e² far-field *half*-angle θ; ``None`` means diffraction-limited λ/(π w0).
    offset : (x, y) in m, beam centroid at z = 0 relative to the telescope axis (biaxial systems).
    tilt : (x, y) in rad, centroid angle relative to the telescope axis (misalignment, paper B3-B4).
    width_law : ``"gaussian"``: w(z)² = w0² + (θz)²; ``"linear"``: w(z) = w0 + θz, the paper's
        marginal ray of Appendix B, kept to reproduce its figures.
    """

    #: What the parameter paths may address (:mod:`lidar_overlap.model.parameters`):
    #: ``field_given`` (only offset and tilt vary: the field is data), ``has_components`` (its
    #: ``beam.components[i]`` scalars; ``beam.divergence`` is component 0's).
    field_given: ClassVar[bool] = False
    has_components: ClassVar[bool] = False

    wavelength: float = 355e-9
    waist_radius: float = 1e-3
    divergence: Optional[float] = None
    offset: Pair = (0.0, 0.0)
    tilt: Pair = (0.0, 0.0)
    width_law: WidthLaw = "gaussian"
    _native: _core.GaussianBeam = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "wavelength", _checks.real("beam.wavelength", self.wavelength))
        set_(self, "waist_radius", _checks.real("beam.waist_radius", self.waist_radius))
        set_(self, "divergence", _checks.optional_real("beam.divergence", self.divergence))
        set_(self, "offset", _checks.pair("beam.offset", self.offset))
        set_(self, "tilt", _checks.pair("beam.tilt", self.tilt))
        _checks.choice("beam.width_law", self.width_law, ("gaussian", "linear"))
        set_(
            self,
            "_native",
            _core.GaussianBeam(
                self.wavelength,
                self.waist_radius,
                self.divergence,
                self.offset,
                self.tilt,
                self.width_law,
            ),
        )

    @classmethod
    def from_m_squared(
        cls,
        wavelength: float,
        waist_radius: float,
        m_squared: float,
        offset: Pair = (0.0, 0.0),
        tilt: Pair = (0.0, 0.0),
    ) -> "GaussianBeam":
        """A multimode beam of beam quality ``m_squared`` (M² >= 1) and 1/e² waist radius
        ``waist_radius`` (m): its divergence is the embedded Gaussian's M² λ / (π w0) (rad).

        Ray tracing traces its Gaussian irradiance w(z)² = w0² + (θz)²; Fourier optics takes it as
        a Gaussian Schell-model beam, whose incoherent modes add to that same Gaussian irradiance at
        every range (docs/beam_shapes.md). The overlap needs only the irradiance, so both are exact
        for any beam whose irradiance stays Gaussian of that second-moment radius; a real multimode
        beam's profile (flatter top, steeper edge) differs from it by what its mode content makes
        (a mixture of components, :class:`GaussianMixtureBeam`, models wings)."""
        lam = _checks.real("beam.wavelength", wavelength)
        w0 = _checks.real("beam.waist_radius", waist_radius)
        m2 = _checks.real("m_squared", m_squared)
        if not (1.0 <= m2 < math.inf):
            raise ValueError(
                f"m_squared = {m2!r} is invalid: expected a finite beam quality M^2 >= 1"
            )
        if not (lam > 0 and w0 > 0 and math.isfinite(lam) and math.isfinite(w0)):
            return cls(lam, w0, None, offset, tilt)  # the constructor names what is wrong
        return cls(lam, w0, m2 * lam / (math.pi * w0), offset, tilt)

    @property
    def m_squared(self) -> float:
        """Beam quality M² = θ π w0 / λ (1 for a diffraction-limited beam)."""
        return self.half_angle_divergence * math.pi * self.waist_radius / self.wavelength

    @property
    def half_angle_divergence(self) -> float:
        """Far-field 1/e² half-angle θ (rad)."""
        return self._native.half_angle_divergence()

    def radius(self, z):
        """1/e² irradiance radius w(z) (m) at range(s) z (m)."""
        return self._native.radius(z)

    def center(self, z: float) -> Tuple[float, float]:
        """Beam centroid (x, y) in m at range z (m): offset + tilt·z (paraxial)."""
        return (self.offset[0] + self.tilt[0] * z, self.offset[1] + self.tilt[1] * z)


@dataclass(frozen=True)
class Telescope(ByArguments):
    """Receiving telescope: ideal thin lens at the aperture stop (z = 0).

    Parameters
    ----------
    diameter : m, aperture stop diameter D.
    focal_length : m, effective focal length f.
    obstruction_radius : m, radius of the opaque central obstruction (secondary mirror), < D/2.
    obstruction_distance : m, its distance in front of the aperture stop, towards the sky.
    aberrations : :class:`Aberrations` of the receiver (Zernike and Seidel terms), or ``None``
        (ideal lens).
    mask : :class:`ApertureMask`, the open part of the aperture stop (the telecover test), or
        ``None`` (all of it). G stays normalised to the full aperture; ray tracing, or Fourier
        optics through the sampled pupil.
    """

    diameter: float = 0.15
    focal_length: float = 1.0
    obstruction_radius: float = 0.0
    obstruction_distance: float = 0.0
    aberrations: Optional[Aberrations] = None
    mask: Optional[ApertureMask] = None
    _native: _core.Telescope = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.mask is not None and not isinstance(self.mask, ApertureMask):
            raise ValueError(
                f"telescope.mask = {self.mask!r} is invalid: expected an ApertureMask or None"
            )
        if self.aberrations is not None and not isinstance(self.aberrations, Aberrations):
            raise ValueError(
                f"telescope.aberrations = {self.aberrations!r} is invalid: expected an Aberrations "
                "or None"
            )
        for name in ("diameter", "focal_length", "obstruction_radius", "obstruction_distance"):
            object.__setattr__(self, name, _checks.real(f"telescope.{name}", getattr(self, name)))
        object.__setattr__(
            self,
            "_native",
            _core.Telescope(
                self.diameter, self.focal_length, self.obstruction_radius, self.obstruction_distance
            ),
        )
        if self.mask is not None:
            self.mask._native.validate(self._native)


@dataclass(frozen=True)
class Detector(ByArguments):
    """Detector (fibre core or field stop) in a plane f + defocus behind the lens.

    Parameters
    ----------
    radius : m, detector radius r_d.
    defocus : m, displacement of the detector plane behind the focal plane (negative: in front).
    offset : (x, y) in m, detector centre in its plane.
    numerical_aperture : accepted sin(angle) of a fibre; rays steeper than it are rejected. ``None``
        accepts every ray.
    stop_radius : m, radius of a second, centred stop behind the lens (a relay's or field lens's
        aperture, a vignetting mount) that every ray must pass; ``None``: no such stop.
    stop_distance : m, its distance behind the lens, 0 < s < f + defocus (0 without a stop). In ray
        tracing a ray crosses its plane at A (1 + s/z - s/f) - P s/z, a circle in the pupil moving
        with the scatterer, exact as the detector's; Fourier optics keeps the circle's radius and
        neglects its motion, as for the NA cone (docs/receiver_stop.md).
    """

    radius: float = 0.45e-3
    defocus: float = 0.0
    offset: Pair = (0.0, 0.0)
    numerical_aperture: Optional[float] = None
    stop_radius: Optional[float] = None
    stop_distance: float = 0.0
    _native: _core.Detector = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "radius", _checks.real("detector.radius", self.radius))
        set_(self, "defocus", _checks.real("detector.defocus", self.defocus))
        set_(self, "offset", _checks.pair("detector.offset", self.offset))
        set_(
            self,
            "numerical_aperture",
            _checks.optional_real("detector.numerical_aperture", self.numerical_aperture),
        )
        set_(self, "stop_radius", _checks.optional_real("detector.stop_radius", self.stop_radius))
        set_(self, "stop_distance", _checks.real("detector.stop_distance", self.stop_distance))
        set_(
            self,
            "_native",
            _core.Detector(
                self.radius,
                self.defocus,
                self.offset,
                self.numerical_aperture,
                self.stop_radius,
                self.stop_distance,
            ),
        )

    @classmethod
    def from_fov(
        cls,
        fov: float,
        focal_length: float,
        defocus: float = 0.0,
        offset: Pair = (0.0, 0.0),
        numerical_aperture: Optional[float] = None,
        stop_radius: Optional[float] = None,
        stop_distance: float = 0.0,
    ) -> "Detector":
        """The detector that gives a full field of view ``fov`` (rad, full angle, as in the paper's
        Table 1) behind a lens of ``focal_length`` (m): radius = fov · f / 2."""
        native = _core.Detector.from_fov(
            _checks.real("fov", fov),
            _checks.real("focal_length", focal_length),
            _checks.real("defocus", defocus),
            _checks.pair("offset", offset),
            _checks.optional_real("numerical_aperture", numerical_aperture),
        )
        return cls(native.radius, defocus, offset, numerical_aperture, stop_radius, stop_distance)

    def fov(self, focal_length: float) -> float:
        """Full field of view (rad) behind a lens of ``focal_length`` (m)."""
        return 2.0 * self.radius / focal_length


@dataclass(frozen=True)
class LidarSystem(ByArguments):
    """A lidar: transmitted beam, receiving telescope and detector, validated together
    (obstruction inside the aperture, detector plane behind the lens). The beam is a
    :class:`GaussianBeam` (both methods) or a :class:`FieldBeam` / :class:`FlatTopBeam` (Fourier
    optics), or a :class:`GaussianMixtureBeam` of incoherent Gaussian components (both methods).

    ``fit_bounds``: {path: (low, high)} (SI units), the ranges the system's sources allow for some
    of its scalars (an instrument preset's divergence, its axis separation), or None. They change
    no overlap: every fit that frees one of those paths takes them as its default bounds, under
    the caller's ``bounds`` (the caller's win, path by path); ``dataclasses.replace(system,
    fit_bounds=None)`` switches them off. Paths as :mod:`lidar_overlap.model.parameters` names
    them (a bare pair, ``"beam.offset"``, stands for both scalars); kept read-only; written to
    result files and scenarios (``[fit_bounds]``) with the system.
    """

    beam: GaussianBeam | FieldBeam | GaussianMixtureBeam = field(default_factory=GaussianBeam)
    telescope: Telescope = field(default_factory=Telescope)
    detector: Detector = field(default_factory=Detector)
    fit_bounds: Optional[Mapping[str, Pair]] = None
    _native: _core.LidarSystem = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for name, kinds in (
            ("beam", (GaussianBeam, FieldBeam, GaussianMixtureBeam)),
            ("telescope", (Telescope,)),
            ("detector", (Detector,)),
        ):
            if not isinstance(getattr(self, name), kinds):
                expected = " or ".join(k.__name__ for k in kinds)
                raise ValueError(
                    f"{name} = {getattr(self, name)!r} is invalid: expected a {expected}"
                )
        object.__setattr__(self, "fit_bounds", checked_bounds("fit_bounds", self.fit_bounds))
        object.__setattr__(
            self,
            "_native",
            _core.LidarSystem(self.beam._native, self.telescope._native, self.detector._native),
        )

    @property
    def incoherent_parts(self) -> Tuple[Tuple[float, "LidarSystem"], ...]:
        """(power share, system) of each mutually incoherent part of the beam, whose G add with
        those shares: the components of a :class:`GaussianMixtureBeam` (each a
        :class:`GaussianBeam` in this receiver), or ``((1.0, self),)`` for any other beam."""
        beam = self.beam
        if not isinstance(beam, GaussianMixtureBeam):
            return ((1.0, self),)
        return tuple(
            (
                w,
                LidarSystem(
                    GaussianBeam(
                        beam.wavelength,
                        c.waist_radius,
                        c.divergence,
                        beam.offset,
                        beam.tilt,
                        beam.width_law,
                    ),
                    self.telescope,
                    self.detector,
                ),
            )
            for w, c in zip(beam.weights, beam.components)
        )

    @property
    def aberrated(self) -> bool:
        """True when the telescope carries aberrations with at least one term set."""
        a = self.telescope.aberrations
        return a is not None and not a.none

    @property
    def is_axisymmetric(self) -> bool:
        """True when beam and detector share the telescope axis."""
        return self._native.is_axisymmetric()

    @property
    def fov(self) -> float:
        """Full field of view (rad) of the receiver: 2 r_d / f."""
        return self.detector.fov(self.telescope.focal_length)

    @property
    def image_distance(self) -> float:
        """d = f + defocus (m): distance from the lens to the detector plane."""
        return self.telescope.focal_length + self.detector.defocus

    @property
    def diffraction_blur(self) -> float:
        """λ d / D (m): the diffraction blur of a point image on the detector plane."""
        return self.beam.wavelength * self.image_distance / self.telescope.diameter

    @property
    def airy_radius(self) -> float:
        """1.22 λ d / D (m): first dark ring of a point image focused on the detector plane."""
        return 1.22 * self.diffraction_blur

    def confusion_radius(self, z):
        """R ``|1 + d/z − d/f|`` (m) at range(s) z (m): the circle of confusion on the detector
        plane, the geometric image of a point at range z through the whole aperture R = D/2 (no
        obstruction, no NA)."""
        return 0.5 * self.telescope.diameter * _defocus_factor(self, z)

    def shadow_radius(self, z):
        """``|1 + d/z − d/f|`` r_obs z / (z − z_obs) (m) at range(s) z (m): the obstruction's shadow
        inside the circle of confusion of an on-axis point; 0 where z <= obstruction_distance."""
        t, z = self.telescope, np.asarray(z, dtype=float)
        behind = z > t.obstruction_distance
        r = np.where(
            behind,
            t.obstruction_radius * z / np.where(behind, z - t.obstruction_distance, 1.0),
            0.0,
        )
        return _scalar_or_array(_defocus_factor(self, z) * r)


def _defocus_factor(system: LidarSystem, z):
    """|1 + d/z − d/f| at range(s) z (m): the circle of confusion over the aperture radius."""
    d, f = system.image_distance, system.telescope.focal_length
    return _scalar_or_array(np.abs(1.0 + d / np.asarray(z, dtype=float) - d / f))


def _scalar_or_array(a: np.ndarray):
    return float(a) if a.ndim == 0 else a
