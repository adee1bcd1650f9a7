"""Any sampled transmitted field as the lidar's beam (Fourier optics only; SI units)."""

from __future__ import annotations

import math
from typing import Tuple

from . import _checks, _core
from .fields import Field

Pair = Tuple[float, float]

#: Least power (W) of a transmitted field: much weaker fields make the FO path's products of irradiances
#: underflow (a 1e-165 W Gaussian of 1 mm gave G = 0 at 1 km); 1e-100 W keeps 1e-150 W/m² on any grid
#: the length limits allow.
MIN_BEAM_POWER = 1e-100


class FieldBeam:
    """A transmitted beam given by its complex field at z = 0.

    Parameters
    ----------
    field : :class:`Field` at the transmitting plane, centred on the beam axis (index n//2 is the axis).
        Its grid is also the grid it is propagated on: leave room for the beam to spread to the angular
        spectrum's critical distance n dx²/λ, beyond which Fresnel's growing output grid takes over. Its power
        must be at least 1e-100 W and spread over more than one sample.
    offset : (x, y) in m, beam axis at z = 0 relative to the telescope axis.
    tilt : (x, y) in rad, beam axis angle relative to the telescope axis.

    Only ``lo.overlap(..., method="fo")`` accepts it: ray tracing models Gaussian beams only.
    """

    def __init__(self, field: Field, offset: Pair = (0.0, 0.0), tilt: Pair = (0.0, 0.0)) -> None:
        if not isinstance(field, Field):
            raise ValueError(f"field = {_checks.shown(field)} is invalid: expected a lidar_overlap.Field")
        power, _, radius = field._moments()
        if not MIN_BEAM_POWER <= power < math.inf:
            raise ValueError(f"field = {field!r} is invalid: its power is {power:.4g} W; expected a finite transmitted "
                             f"power of at least {MIN_BEAM_POWER:g} W")
        if not radius >= _core.MIN_LENGTH:
            raise ValueError(f"field = {field!r} is invalid: its second-moment radius is {radius:.4g} m (the power sits "
                             f"in one sample); expected a beam of at least {_core.MIN_LENGTH:g} m sampled over "
                             "several points")
        self._field = field
        self._offset = _checks.pair("beam.offset", offset)
        self._tilt = _checks.pair("beam.tilt", tilt)
        # The system model carries the pointing and wavelength in a Gaussian beam of the field's
        # second-moment radius; the FO path propagates the field itself.
        self._native = _core.GaussianBeam(field.wavelength, radius, None, self._offset, self._tilt, "gaussian")

    @property
    def field(self) -> Field:
        """The transmitted field at z = 0."""
        return self._field

    @property
    def wavelength(self) -> float:
        """m."""
        return self._field.wavelength

    @property
    def offset(self) -> Pair:
        return self._offset

    @property
    def tilt(self) -> Pair:
        return self._tilt

    def center(self, z: float) -> Pair:
        """Beam axis (x, y) in m at range z (m): offset + tilt·z (paraxial)."""
        return (self._offset[0] + self._tilt[0] * z, self._offset[1] + self._tilt[1] * z)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._field!r}, offset={self._offset}, tilt={self._tilt})"
