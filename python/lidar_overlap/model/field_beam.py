"""Any sampled transmitted field as the lidar's beam (Fourier optics only; SI units)."""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from dataclasses import field as dataclass_field
from typing import ClassVar, Optional, Tuple

from .. import _checks, _core
from .._pickling import ByArguments, ByValue
from .field import Field

Pair = Tuple[float, float]

#: Least power (W) of a transmitted field: much weaker fields make the FO path's products of
#: irradiances underflow (a 1e-165 W Gaussian of 1 mm gave G = 0 at 1 km); 1e-100 W keeps 1e-150
#: W/m² on any grid the length limits allow.
MIN_BEAM_POWER = 1e-100


@dataclass(frozen=True, eq=False, repr=False)
class FieldBeam(ByValue, ByArguments):
    """A transmitted beam given by its complex field at z = 0; immutable (:meth:`with_pointing` or
    :func:`dataclasses.replace` give a re-pointed copy).

    Parameters
    ----------
    field : :class:`Field` at the transmitting plane, centred on the beam axis (index n//2 is the
        axis). Its grid is also the grid it is propagated on: leave room for the beam to spread to
        the angular spectrum's critical distance n dx²/λ, beyond which Fresnel's growing output grid
        takes over. Its power must be at least 1e-100 W and spread over more than one sample.
    offset : (x, y) in m, beam axis at z = 0 relative to the telescope axis.
    tilt : (x, y) in rad, beam axis angle relative to the telescope axis.

    Only ``lo.overlap(..., method="fo")`` accepts it: ray tracing models Gaussian beams only.
    """

    #: What the parameter paths may address (:mod:`lidar_overlap.model.parameters`):
    #: ``field_given`` (only offset and tilt vary: the field is data), ``has_components`` (its
    #: ``beam.components[i]`` scalars; ``beam.divergence`` is component 0's).
    field_given: ClassVar[bool] = True
    has_components: ClassVar[bool] = False

    field: Field
    offset: Pair = (0.0, 0.0)
    tilt: Pair = (0.0, 0.0)
    _native: _core.GaussianBeam = dataclass_field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        field = self.field
        if not isinstance(field, Field):
            raise ValueError(
                f"field = {_checks.shown(field)} is invalid: expected a lidar_overlap.Field"
            )
        power, _, radius = field._moments()
        if not MIN_BEAM_POWER <= power < math.inf:
            raise ValueError(
                f"field = {field!r} is invalid: its power is {power:.4g} W; expected a finite "
                f"transmitted power of at least {MIN_BEAM_POWER:g} W"
            )
        if not radius >= _core.MIN_LENGTH:
            raise ValueError(
                f"field = {field!r} is invalid: its second-moment radius is {radius:.4g} m (the "
                f"power sits in one sample); expected a beam of at least {_core.MIN_LENGTH:g} m "
                "sampled over several points"
            )
        set_ = object.__setattr__
        set_(self, "offset", _checks.pair("beam.offset", self.offset))
        set_(self, "tilt", _checks.pair("beam.tilt", self.tilt))
        # The system model carries the pointing and wavelength in a Gaussian beam of the field's
        # second-moment radius; the FO path propagates the field itself.
        set_(
            self,
            "_native",
            _core.GaussianBeam(field.wavelength, radius, None, self.offset, self.tilt, "gaussian"),
        )

    @property
    def wavelength(self) -> float:
        """m."""
        return self.field.wavelength

    def center(self, z: float) -> Pair:
        """Beam axis (x, y) in m at range z (m): offset + tilt·z (paraxial)."""
        return (self.offset[0] + self.tilt[0] * z, self.offset[1] + self.tilt[1] * z)

    def with_pointing(
        self, offset: Optional[Pair] = None, tilt: Optional[Pair] = None
    ) -> "FieldBeam":
        """A copy of this beam (of its own type, a :class:`FlatTopBeam` too) with ``offset`` (m) and
        ``tilt`` (rad) replaced where given, checked as in the constructor."""
        beam = copy.copy(self)
        FieldBeam.__init__(
            beam,
            self.field,
            self.offset if offset is None else offset,
            self.tilt if tilt is None else tilt,
        )
        return beam

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.field!r}, offset={self.offset}, tilt={self.tilt})"
