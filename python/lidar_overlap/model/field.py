"""A sampled optical field: the complex amplitude of a beam on a square grid (paper Appendix A; SI
units).

A :class:`Field` is an (n, n) complex array U on a grid centred so that index n//2 is x = 0; |U|² is
the irradiance in W/m². It is immutable and checked on construction; :func:`lidar_overlap.propagate`
moves it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Tuple

import numpy as np

from .. import _checks, _core
from .._pickling import ByArguments, ByValue

#: Largest power (W) of a field, the core's bound for ``Field.gaussian``: irradiances stay far
#: inside double precision.
MAX_POWER = 1e30


@dataclass(frozen=True, eq=False, repr=False)
class Field(ByValue, ByArguments):
    """Complex scalar field on an (n, n) grid; immutable (``values`` is a read-only copy). Use
    :func:`dataclasses.replace` for a field with other values, spacing or wavelength.

    Parameters
    ----------
    values : (n, n) array of numbers (complex, real or integer; not strings, objects or bools), n
        even from 8 to 65536, finite; row index is y, column index is x; ``|values|²`` in W/m²,
        their power Σ|U|² spacing² at most 1e30 W.
    spacing : m, grid spacing, 1e-10 to 1e10 m.
    wavelength : m, 1e-10 to 1e10 m.
    """

    values: np.ndarray
    spacing: float
    wavelength: float

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "spacing", _checks.length("spacing", self.spacing))
        set_(self, "wavelength", _checks.length("wavelength", self.wavelength))
        arr = _complex_grid(self.values)
        with np.errstate(over="ignore"):
            power = float(np.sum(arr.real**2 + arr.imag**2)) * self.spacing**2
        if not power <= MAX_POWER:
            raise ValueError(
                f"values is invalid: its power Σ|U|² spacing² is {power:.4g} W; expected at most "
                f"{MAX_POWER:g} W"
            )
        arr.flags.writeable = False
        set_(self, "values", arr)

    @classmethod
    def _from_core(cls, values: np.ndarray, spacing: float, wavelength: float) -> "Field":
        """Wrap an array the core has just made (checked there), without another copy."""
        field = cls.__new__(cls)
        values.flags.writeable = False
        for name, value in (
            ("values", values),
            ("spacing", float(spacing)),
            ("wavelength", float(wavelength)),
        ):
            object.__setattr__(field, name, value)
        return field

    @classmethod
    def gaussian(
        cls,
        wavelength: float,
        waist_radius: float,
        n: int,
        spacing: float,
        center: Tuple[float, float] = (0.0, 0.0),
        power: float = 1.0,
    ) -> "Field":
        """TEM00 beam at its waist (flat phase): 1/e² irradiance radius ``waist_radius`` (m), total
        ``power`` (W), centred at ``center`` (m)."""
        n = _checks.count("n", n, 8)
        values = _core.gaussian_field(
            _checks.real("wavelength", wavelength),
            _checks.real("waist_radius", waist_radius),
            n,
            _checks.real("spacing", spacing),
            _checks.pair("center", center),
            _checks.real("power", power),
        )
        return cls._from_core(values, spacing, wavelength)

    @property
    def n(self) -> int:
        return self.values.shape[0]

    @property
    def x(self) -> np.ndarray:
        """Sample x coordinates (m); index n//2 is 0."""
        return (np.arange(self.n) - self.n // 2) * self.spacing

    @property
    def y(self) -> np.ndarray:
        """Sample y coordinates (m); index n//2 is 0."""
        return self.x

    @property
    def intensity(self) -> np.ndarray:
        """Irradiance ``|U|²`` (W/m²)."""
        return np.abs(self.values) ** 2

    def _moments(self):
        return _core.field_moments(self.values, self.spacing, self.wavelength)

    @property
    def power(self) -> float:
        """Total power Σ|U|² spacing² (W)."""
        return self._moments()[0]

    @property
    def centroid(self) -> Tuple[float, float]:
        """Irradiance-weighted centre (x, y) in m."""
        return tuple(self._moments()[1])

    @property
    def beam_radius(self) -> float:
        """Second-moment radius about the centroid, sqrt(2 (σx² + σy²)) (m): the 1/e² radius w of a
        TEM00 beam (D4σ/2)."""
        return self._moments()[2]

    def __repr__(self) -> str:
        return (
            f"Field(n={self.n}, spacing={self.spacing:.4g} m, wavelength={self.wavelength:.4g} m)"
        )


def _complex_grid(values) -> np.ndarray:
    """``values`` as a fresh (n, n) complex128 array, n even from 8 to MAX_GRID_SIDE, with finite
    numbers. Only
    numeric arrays are taken: strings, objects and bools are refused before any conversion."""
    try:
        raw = np.asarray(values)
    except (ValueError, TypeError, OverflowError) as exc:  # ragged nesting, unconvertible objects
        raise ValueError(
            f"values is invalid: expected a square (n, n) array of numbers ({exc})"
        ) from None
    if raw.dtype == np.bool_ or not np.issubdtype(raw.dtype, np.number):
        raise ValueError(
            f"values has dtype {raw.dtype}: expected an array of numbers (complex, real or integer)"
        )
    n_max = _core.MAX_GRID_SIDE
    if (
        raw.ndim != 2
        or raw.shape[0] != raw.shape[1]
        or not 8 <= raw.shape[0] <= n_max
        or raw.shape[0] % 2
    ):
        raise ValueError(
            f"values has shape {raw.shape}: expected a square (n, n) array with n even from 8 to "
            f"{n_max}"
        )
    with np.errstate(over="ignore"):  # long doubles beyond double range become inf
        arr = np.array(raw, dtype=np.complex128, copy=True)
    if not np.all(np.isfinite(arr)):
        raise ValueError("values contains NaN or infinity: expected finite complex numbers")
    return arr
