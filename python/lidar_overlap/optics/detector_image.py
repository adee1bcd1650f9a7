"""The detector-plane image of the scattering volume at one range, by geometric optics (paper
Section 4, the circles of confusion of Appendix B): the beam irradiance imaged by the lens
(magnification −d/z) and spread over each scatterer's circle of confusion, a uniform disc of radius
R|1 + d/z − d/f| (less the obstruction's shadow, taken for an on-axis scatterer). The detector disc
collects ``fraction`` of it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .. import _checks, _core, _values
from .._checks import check_memory
from .._checks import system_range as validate_range
from .._pickling import ByValue
from ..model.field_beam import FieldBeam
from ..model.system import LidarSystem
from .propagation import propagate

_erf = np.vectorize(math.erf, otypes=[float])

#: Peak bytes per image pixel (measured 168: the (4n)² sub-pixel kernel of the blur and the padded
#: FFTs).
BYTES_PER_PIXEL = 192
#: A field beam's propagated field (complex, its irradiance, normalised) per sample, and the
#: interpolation matrices and product per (image side x field side).
BYTES_PER_FIELD_SAMPLE = 48
BYTES_PER_WEIGHT = 32


@dataclass(frozen=True, eq=False)
class DetectorImage(ByValue):
    """``image`` (W/m² per W of backscatter entering the aperture) on the detector-plane grid ``u``
    (columns) by ``v`` (rows), m; the detector disc of ``detector_radius`` at ``detector_offset``;
    ``fraction``: the part of the image's power on the detector. A value: checked on construction,
    read-only arrays."""

    u: np.ndarray
    v: np.ndarray
    image: np.ndarray
    detector_radius: float
    detector_offset: tuple
    range: float

    FIELDS: ClassVar = {
        "u": _values.array(),
        "v": _values.array(),
        "image": _values.array(2, low=0.0),
        "detector_radius": _values.real(low=0.0),
        "range": _values.real(low=0.0),
    }

    def __post_init__(self) -> None:
        _values.check(self, self.FIELDS)
        if self.image.shape != (self.v.size, self.u.size):
            raise ValueError(
                f"image has shape {self.image.shape}: expected (len(v), len(u)) = "
                f"({self.v.size}, {self.u.size})"
            )
        offset = self.detector_offset
        if not isinstance(offset, tuple) or len(offset) != 2:
            raise ValueError(
                f"detector_offset = {_checks.shown(offset)} is invalid: expected (x, y) in m"
            )
        object.__setattr__(
            self,
            "detector_offset",
            tuple(_values.real()(f"detector_offset[{i}]", v) for i, v in enumerate(offset)),
        )

    @property
    def fraction(self) -> float:
        r = np.hypot(
            *np.meshgrid(self.u - self.detector_offset[0], self.v - self.detector_offset[1])
        )
        return float(self.image[r <= self.detector_radius].sum() / self.image.sum())


def detector_image(system, z: float, n: int = 192) -> DetectorImage:
    """Geometric detector-plane image at range ``z`` (m) on an n × n grid holding the beam image
    (2.5 w) spread by its circle of confusion and the detector disc. ``z`` is refused as the overlap
    refuses a range (outside 1e-10..1e10 m, or not beyond the obstruction), ``n`` (16 to 65536) when
    its arrays, ~192 n² bytes, exceed ``lo.max_memory()``."""
    if not isinstance(system, LidarSystem):
        raise ValueError(f"system = {_checks.shown(system)} is invalid: expected a LidarSystem")
    z = _checks.real("z", z)
    validate_range(system, z, "z")
    n = _checks.count("n", n, 16, _core.MAX_GRID_SIDE)
    check_memory("n", n, _bytes_needed(system, n), "use a smaller n")
    det, d = system.detector, system.image_distance
    blur = (
        system.confusion_radius(z) * z / d
    )  # the circle of confusion, back in the scattering plane
    shadow = system.shadow_radius(z) * z / d
    field = propagate(system.beam.field, z) if isinstance(system.beam, FieldBeam) else None
    c = np.array(system.beam.center(z))
    w = (
        float(field.beam_radius)
        if field is not None
        else float(np.asarray(system.beam.radius(np.array([z])))[0])  # type: ignore[union-attr]
    )
    o_back, r_back = -np.asarray(det.offset) * z / d, det.radius * z / d
    mid, half = window_about([(c, 2.5 * w + blur), (o_back, r_back)])
    h = 2 * half / n
    grid = np.arange(n) - n / 2 + 0.5
    x, y = (mid[k] + grid * h for k in (0, 1))
    img = blurred(beam_image(system, z, x, y, field), h, blur, min(shadow, blur))[
        ::-1, ::-1
    ]  # u = −x d/z
    scale = d / z
    u, v = (-(mid[k] + grid[::-1] * h) * scale for k in (0, 1))
    return DetectorImage(
        u=u,
        v=v,
        image=img / scale**2,
        detector_radius=det.radius,
        detector_offset=tuple(det.offset),
        range=z,
    )


def _bytes_needed(system, n: int) -> float:
    """Peak bytes of the arrays detector_image builds on an n x n image: the blur's sub-pixel kernel
    and FFTs (BYTES_PER_PIXEL, measured), and for a field beam its propagated field and
    interpolation matrices."""
    needed = BYTES_PER_PIXEL * float(n) ** 2
    if isinstance(system.beam, FieldBeam):
        m = float(system.beam.field.n)
        needed += BYTES_PER_FIELD_SAMPLE * m**2 + BYTES_PER_WEIGHT * n * m
    return needed


def beam_image(system, z, x, y, field=None):
    """Beam irradiance (W/m², P = 1 W) at range z on the grid x (columns) by y (rows), m: a Gaussian
    averaged over each pixel (exact, with erf); a field beam's ``field`` (propagated to z)
    interpolated bilinearly."""
    c = system.beam.center(z)
    if not isinstance(system.beam, FieldBeam):
        w, h = float(system.beam.radius(np.array([z]))[0]), x[1] - x[0]
        px, py = (
            (_erf(math.sqrt(2) * (u - cu + h / 2) / w) - _erf(math.sqrt(2) * (u - cu - h / 2) / w))
            / (2 * h)
            for u, cu in ((x, c[0]), (y, c[1]))
        )
        return np.outer(py, px)
    return (
        _bilinear(y - c[1], field.y)
        @ (field.intensity / system.beam.field.power)
        @ _bilinear(x - c[0], field.x).T
    )


def _bilinear(dst, src):
    """Matrix (dst.size, src.size) of linear interpolation from the ascending grid src; zero
    outside."""
    i = np.clip(np.searchsorted(src, dst) - 1, 0, src.size - 2)
    t = (dst - src[i]) / (src[i + 1] - src[i])
    inside = (t >= 0) & (t <= 1)
    m = np.zeros((dst.size, src.size))
    rows = np.arange(dst.size)
    m[rows, i] = (1 - t) * inside
    m[rows, i + 1] = t * inside
    return m


def blurred(image, h, outer, inner):
    """``image`` convolved (FFT, zero-padded) with a uniform annulus inner..outer (m), pixel h
    (m)."""
    n = image.shape[0]
    u = (np.arange(n * 4) - n * 2 - 1.5) * h / 4  # 4 x 4 sub-pixels per pixel, pixel n/2 at 0
    r2 = u[:, None] ** 2 + u[None, :] ** 2  # one (4n)² array: the peak of the call's memory
    r2 = (r2 < outer**2) & (r2 >= inner**2)
    kernel = r2.reshape(n, 4, n, 4).mean(axis=(1, 3))
    if kernel.sum() == 0:  # blur below one pixel: a point
        kernel[n // 2, n // 2] = 1.0
    kernel /= kernel.sum()
    p = 2 * n
    out = np.fft.irfft2(np.fft.rfft2(image, (p, p)) * np.fft.rfft2(kernel, (p, p)), (p, p))
    return np.clip(out[n // 2 : n // 2 + n, n // 2 : n // 2 + n], 0.0, None)


def fov_cone(system, z):
    """Line of sight (nz, 2) and radius (m) of the receiver's full field of view at ranges z: the
    scatterers that send some light to the detector. A ray from P through aperture point A lands at
    A m − P d/z (d = f + defocus, m = 1 + d/z − d/f), so P is seen when |P + o_d z/d| < (R|m| + r_d)
    z/d."""
    tel, det = system.telescope, system.detector
    d, f = system.image_distance, tel.focal_length
    center = -np.outer(z, det.offset) / d  # R|m| z/d written to stay finite at z = 0 (the aperture)
    return center, 0.5 * tel.diameter * np.abs(1.0 + z * (1.0 / d - 1.0 / f)) + det.radius * z / d


def window_about(discs):
    """Centre (2,) and half-width (m) of a square holding every (centre, radius) disc, with 10 %
    margin."""
    lo_ = np.min([np.asarray(c) - r for c, r in discs], axis=0)
    hi_ = np.max([np.asarray(c) + r for c, r in discs], axis=0)
    return 0.5 * (lo_ + hi_), 0.55 * float(np.max(hi_ - lo_))
