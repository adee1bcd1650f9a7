"""Receiver aberrations (paper Section 3, step 5): Zernike terms in the pupil and Seidel terms
across the field.

The wavefront W (m of optical path) is added to the pupil phase as exp(2πi W/λ), over the pupil
coordinate normalised to the telescope radius D/2. A ray through pupil point a is displaced on the
detector plane by d ∇_a W (d = f + defocus), which is how ray tracing sees it; Fourier optics puts W
into the pupil function.

- **Zernike** coefficients (Noll's index j ≥ 1, metres of RMS wavefront): the same for every
  scatterer, as for a misaligned or imperfect telescope. Both methods model them.
- **Seidel** coefficients W040, W131, W222, W220, W311 (metres, at the pupil edge and at the field
  edge H = 1, reached at the field angle ``field_radius``): they vary with each scatterer's field
  angle P/z, so only ray tracing models the field-dependent ones; W040 (spherical) is the same
  everywhere and both do.

:func:`seidel_to_zernike` gives the Zernike form of the Seidel terms at one field point (exact, for
the terms
they share: spherical, coma, astigmatism, field curvature, distortion, plus the defocus and tilt
they imply), and :func:`zernike_to_seidel` the reverse for a wavefront at H = 1 along +x.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Dict, Mapping, Tuple

import numpy as np

from .. import _checks, _core
from .._pickling import ByArguments
from .._values import FrozenMap

SEIDEL_TERMS = ("w040", "w131", "w222", "w220", "w311")

#: Highest Noll index (radial order 20); the Fourier-optics path takes up to 153 (radial order 16).
MAX_NOLL_INDEX = 231
#: Highest Noll index :func:`noll_index` and :func:`zernike` evaluate (the core's polynomials,
#: cpp/include/lidar_overlap/pupil/zernike.hpp).
MAX_POLYNOMIAL_INDEX = 1000


@dataclass(frozen=True)
class Aberrations(ByArguments):
    """Wavefront aberrations of the receiver.

    Parameters
    ----------
    zernike : {Noll index j: coefficient in m RMS}, j from 1 (piston) to 231 (radial order 20;
        Fourier optics takes up to 153, radial order 16); e.g. ``{11: 50e-9}`` is 50 nm RMS of
        primary spherical aberration.
    w040, w131, w222, w220, w311 : m, Seidel coefficients (spherical, coma, astigmatism, field
        curvature, distortion) at the pupil edge and at field height H = 1.
    field_radius : rad, the field angle at H = 1; required (> 0) when a field-dependent term is set.
    """

    zernike: Mapping[int, float] = field(default_factory=dict)
    w040: float = 0.0
    w131: float = 0.0
    w222: float = 0.0
    w220: float = 0.0
    w311: float = 0.0
    field_radius: float = 0.0
    _native: _core.Aberrations = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.zernike, Mapping):
            raise ValueError(
                f"aberrations.zernike = {self.zernike!r} is invalid: expected a mapping "
                "{Noll index: m RMS}"
            )
        terms: Dict[int, float] = {}
        for j, c in self.zernike.items():
            if (
                isinstance(j, bool)
                or not isinstance(j, (int, np.integer))
                or not 1 <= j <= MAX_NOLL_INDEX
            ):
                raise ValueError(
                    f"aberrations.zernike index {_checks.shown(j)} is invalid: expected a Noll "
                    f"index in [1, {MAX_NOLL_INDEX}] (radial order 20)"
                )
            terms[int(j)] = _checks.real(f"aberrations.zernike[{j}]", c)
        object.__setattr__(self, "zernike", FrozenMap(sorted(terms.items())))
        for name in SEIDEL_TERMS + ("field_radius",):
            object.__setattr__(self, name, _checks.real(f"aberrations.{name}", getattr(self, name)))
        dense = [0.0] * (max(terms) if terms else 0)
        for j, c in terms.items():
            dense[j - 1] = c
        object.__setattr__(
            self,
            "_native",
            _core.Aberrations(
                dense, self.w040, self.w131, self.w222, self.w220, self.w311, self.field_radius
            ),
        )

    @property
    def none(self) -> bool:
        """True when no term is set (the aberration-free receiver)."""
        return self._native.none()

    @property
    def field_dependent(self) -> bool:
        """True when W131, W222, W220 or W311 is set (ray tracing only)."""
        return self._native.field_dependent()

    def wavefront(self, x, y, field_angle: Tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
        """W (m) at normalised pupil points (x, y) (arrays of one shape) for a scatterer at
        ``field_angle`` (rad, x and y)."""
        x, y = _pupil_points(x, y)
        w = self._native.wavefront(x, y, _checks.pair("field_angle", field_angle))
        return _finite_values("wavefront", w, x, y)

    @property
    def rms(self) -> float:
        """RMS wavefront (m) of the Zernike terms over the pupil, piston excluded (their
        orthonormality)."""
        return math.sqrt(sum(c * c for j, c in self.zernike.items() if j > 1))


def noll_index(j: int) -> Tuple[int, int]:
    """(n, m) of Noll's Zernike index j (an integer from 1 to 1000): radial order n, signed
    azimuthal order m (m < 0: sin)."""
    n, m = _core.noll_index(_checks.count("j", j, 1, MAX_POLYNOMIAL_INDEX))
    return n, m


def zernike(j: int, x, y) -> np.ndarray:
    """Zernike polynomial Z_j (Noll, unit RMS over the unit disc; j an integer from 1 to 1000) at
    normalised pupil points (x, y): finite real arrays of one shape."""
    x, y = _pupil_points(x, y)
    z = _core.zernike(_checks.count("j", j, 1, MAX_POLYNOMIAL_INDEX), x, y)
    return _finite_values(f"Z_{j}", z, x, y)


def _pupil_points(x, y) -> Tuple[np.ndarray, np.ndarray]:
    """x and y as float arrays of finite real numbers; ValueError naming the one that is not (a
    NaN or infinite coordinate would give a NaN wavefront without a word)."""
    points = []
    for name, value in (("x", x), ("y", y)):
        v = _checks.real_array(name, value)
        if not np.all(np.isfinite(v)):
            raise ValueError(
                f"{name} = {_checks.shown(value)} is invalid: expected finite normalised pupil "
                "coordinates"
            )
        points.append(v)
    return points[0], points[1]


def _finite_values(what: str, values, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """``values`` when all are finite; else ValueError naming x and y: a point so far outside the
    unit pupil that the polynomial overflows double precision (|rho| ~ 1e300)."""
    bad = ~np.isfinite(np.asarray(values))
    if np.any(bad):
        k = np.flatnonzero(bad)[0]
        px, py = (float(np.broadcast_to(v, bad.shape).flat[k]) for v in (x, y))
        raise ValueError(
            f"x, y = ({px!r}, {py!r}) is invalid: {what} overflows there; expected normalised "
            "pupil coordinates (|rho| <= 1 on the pupil)"
        )
    return values


def seidel_to_zernike(aberrations: Aberrations, field_angle: Tuple[float, float]) -> Aberrations:
    """The Zernike form (terms 1-11) of ``aberrations``' Seidel terms at one field point (rad, x and
    y), added
    to its own Zernike terms: the pupil a scatterer at that field angle sees. Exact (the Seidel
    polynomials are sums of Zernike terms j <= 11), up to piston."""
    if not isinstance(aberrations, Aberrations):
        raise ValueError(f"aberrations = {aberrations!r} is invalid: expected an Aberrations")
    fx, fy = _checks.pair("field_angle", field_angle)
    a = aberrations
    h = math.hypot(fx, fy) / a.field_radius if a.field_radius > 0 else 0.0
    if h == 0.0 and (fx or fy) and a.field_dependent:
        raise ValueError("aberrations.field_radius must be > 0 to place a field angle")
    phi = math.atan2(fy, fx)
    c: Dict[int, float] = dict(a.zernike)

    def add(j: int, value: float) -> None:
        c[j] = c.get(j, 0.0) + value

    s3, s5, s6, s8 = math.sqrt(3), math.sqrt(5), math.sqrt(6), math.sqrt(8)
    add(11, a.w040 / (6 * s5))  # rho^4 = Z11/(6 sqrt5) + rho^2 - 1/6
    add(4, a.w040 / (2 * s3))  # rho^2 = Z4/(2 sqrt3) + 1/2
    coma, astig, curvature, distortion = a.w131 * h, a.w222 * h**2, a.w220 * h**2, a.w311 * h**3
    add(8, coma * math.cos(phi) / (3 * s8))  # rho^3 cos = Z8/(3 sqrt8) + Z2/3
    add(7, coma * math.sin(phi) / (3 * s8))
    add(2, coma * math.cos(phi) / 3 + distortion * math.cos(phi) / 2)  # rho cos = Z2/2
    add(3, coma * math.sin(phi) / 3 + distortion * math.sin(phi) / 2)
    add(
        6, astig * math.cos(2 * phi) / (2 * s6)
    )  # rho^2 cos^2 = rho^2/2 + (Z6 cos2phi + Z5 sin2phi)/(2 sqrt6)
    add(5, astig * math.sin(2 * phi) / (2 * s6))
    add(4, astig / (4 * s3) + curvature / (2 * s3))
    return Aberrations(zernike={j: v for j, v in c.items() if v != 0.0})


def zernike_to_seidel(aberrations: Aberrations, field_radius: float) -> Aberrations:
    """The Seidel form of a Zernike wavefront seen at the field edge H = 1 along +x
    (``field_radius`` rad): W040 = 6√5 c11, W131 = 3√8 c8, W222 = 2√6 c6, W311 = 2 c2 - 2√8 c8, W220
    = 2√3 c4 - W040 - W222/2. Raises ValueError for terms with no Seidel counterpart (y-oriented,
    trefoil, j > 11)."""
    if not isinstance(aberrations, Aberrations):
        raise ValueError(f"aberrations = {aberrations!r} is invalid: expected an Aberrations")
    if aberrations.w040 or aberrations.field_dependent:
        raise ValueError("aberrations already holds Seidel terms: expected Zernike terms only")
    c = aberrations.zernike
    foreign = sorted(j for j, v in c.items() if v != 0.0 and j not in (1, 2, 4, 6, 8, 11))
    if foreign:
        raise ValueError(
            f"aberrations.zernike terms {foreign} have no Seidel counterpart along +x: expected "
            "only Noll 1, 2, 4, 6, 8 and 11"
        )
    g = lambda j: c.get(j, 0.0)  # noqa: E731
    w040, w131, w222 = 6 * math.sqrt(5) * g(11), 3 * math.sqrt(8) * g(8), 2 * math.sqrt(6) * g(6)
    return Aberrations(
        w040=w040,
        w131=w131,
        w222=w222,
        w220=2 * math.sqrt(3) * g(4) - w040 - w222 / 2,
        w311=2 * g(2) - 2 * math.sqrt(8) * g(8),
        field_radius=_checks.real("field_radius", field_radius),
    )


def with_aberrations(system, aberrations):
    """``system`` with ``aberrations`` (an :class:`Aberrations` or None) on its telescope."""
    return dataclasses.replace(
        system, telescope=dataclasses.replace(system.telescope, aberrations=aberrations)
    )
