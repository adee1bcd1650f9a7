"""Brute-force reference for the overlap through turbulence on both paths (a test helper, NumPy
only).

Every scatterer at range z is its own source: a band-limited point source (flat angular spectrum up
to the angles that reach the aperture through the eddies, a raised-cosine edge beyond) propagated
back to the aperture by the exact angular-spectrum transfer function through the same phase screens
as the beam, in the opposite order; its pupil field is imaged onto the detector plane by a direct
Fourier sum (the lens, and the defocus as the pupil's curvature 1/d - 1/f), and the power inside the
detector disc is summed. The scatterers
are mutually incoherent: G = sum_x E(x) P_det(x) / (sum_x E(x) P_ap), with E the beam's irradiance
    through the
screens and P_ap the power a scatterer sends into the full aperture without turbulence (G's
normalisation). Nothing here uses reciprocity, random phases or the core's split steps: it is the
definition, computed directly.

The screens are passed in (``screens``: range, sampled values, spacing of their grid centred on the
axis) and interpolated bilinearly onto the oracle's uniform grid, so that the oracle can replay a
draw of the core's run (``replay_screens``) and compare realisation by realisation. Errors: the
scatterers sample the plane every ``stride`` grid steps (their products E P_det vary on the speckle
scale, min(r0, lambda z / D)); the aperture and the detector disc are sampled (edges to a sample);
the interpolated screens lack their finest structure.
"""

from __future__ import annotations

import math

import numpy as np

from lidar_overlap import _core


def _transfer(n: int, spacing: float, wavelength: float, dz: float) -> np.ndarray:
    f = np.fft.fftfreq(n, spacing)
    f2 = f[:, None] ** 2 + f[None, :] ** 2
    kz = np.sqrt(np.maximum(1.0 / wavelength**2 - f2, 0.0)) - 1.0 / wavelength
    return np.where(f2 < 1.0 / wavelength**2, np.exp(2j * math.pi * dz * kz), 0.0)


def _interpolate(screen: np.ndarray, spacing: float, x: np.ndarray) -> np.ndarray:
    """The screen (n x n, sample (ix, iy) at ((ix - n/2) spacing, (iy - n/2) spacing)) at the points
    x (1-D axis) of the oracle's grid, bilinear; zero outside its grid (light there never reaches
    the aperture)."""
    n = screen.shape[0]
    u = x / spacing + n / 2
    i0 = np.floor(u).astype(int)
    t = u - i0
    ok = (i0 >= 0) & (i0 < n - 1)
    i0 = np.clip(i0, 0, n - 2)
    a = (
        screen[np.ix_(i0, i0)] * np.outer(1 - t, 1 - t)
        + screen[np.ix_(i0, i0 + 1)] * np.outer(1 - t, t)
        + screen[np.ix_(i0 + 1, i0)] * np.outer(t, 1 - t)
        + screen[np.ix_(i0 + 1, i0 + 1)] * np.outer(t, t)
    )
    return np.where(np.outer(ok, ok), a, 0.0)


def replay_screens(raw, beam_grid: int, seed: int, k: int, outer_scale=math.inf, inner_scale=0.0):
    """Realisation k's screens of a core run (``raw``: its TurbulentOverlap) as (range, values,
    spacing)."""
    out = []
    for j, (zj, dx, r0) in enumerate(zip(raw.screen_range, raw.screen_spacing, raw.screen_r0)):
        stream = (seed ^ ((j + 1) * 0x9E3779B97F4A7C15)) % 2**64
        out.append(
            (
                float(zj),
                np.asarray(
                    _core.phase_screen(
                        beam_grid, float(dx), float(r0), outer_scale, inner_scale, stream, k
                    )
                ),
                float(dx),
            )
        )
    return out


class Oracle:
    """The direct sum for ``system`` (coaxial, a GaussianBeam without tilt) at range ``z`` on an n x
    n grid of ``spacing`` (m); scatterers within ``reach`` (m) of the axis every ``stride`` samples;
    point sources flat to ``angle`` (rad) with a raised-cosine edge to ``1.25 angle``."""

    def __init__(
        self, system, z: float, n: int, spacing: float, reach: float, angle: float, stride: int = 4
    ):
        beam, tel, det = system.beam, system.telescope, system.detector
        self.lam, self.z, self.n, self.dx = beam.wavelength, z, n, spacing
        if 1.25 * angle > 0.9 * self.lam / (2 * spacing):
            raise ValueError(
                "the point sources' angles exceed the grid's band: lower spacing or angle"
            )
        self.x = (np.arange(n) - n / 2) * spacing
        X, Y = np.meshgrid(self.x, self.x)
        self.r2 = X**2 + Y**2
        self.w0, self.d, self.f = (
            beam.waist_radius,
            tel.focal_length + det.defocus,
            tel.focal_length,
        )
        pick = np.zeros((n, n), bool)
        pick[::stride, ::stride] = True
        self.points = np.argwhere(pick & (self.r2 <= reach**2))  # (iy, ix)
        self.cell = (stride * spacing) ** 2
        f = np.fft.fftfreq(n, spacing)
        theta = self.lam * np.hypot(f[:, None], f[None, :])
        edge = np.clip((theta - angle) / (0.25 * angle), 0.0, 1.0)
        self.source = np.cos(0.5 * math.pi * edge) ** 2  # flat, then a raised cosine to zero
        self.fx = f
        # The pupil: samples inside the annulus; the detector: samples of lambda d / (4 D) (at most
        # r_d / 10) inside its disc.
        R, r_obs = 0.5 * tel.diameter, tel.obstruction_radius
        self.pupil = (self.r2 <= R**2) & (self.r2 >= r_obs**2)
        self.ap = self.r2 <= R**2
        step = min(self.lam * self.d / (4 * tel.diameter), det.radius / 10)
        m = int(math.ceil(det.radius / step)) + 1
        u = np.arange(-m, m + 1) * step
        DX, DY = np.meshgrid(u + det.offset[0], u + det.offset[1])
        inside = (DX - det.offset[0]) ** 2 + (DY - det.offset[1]) ** 2 <= det.radius**2
        self.det_x, self.det_y, self.det_cell = DX[inside], DY[inside], step**2
        ax, ay = X[self.pupil], Y[self.pupil]
        k = 2 * math.pi / self.lam
        self.curvature = np.exp(0.5j * k * (1 / self.d - 1 / self.f) * self.r2[self.pupil])
        self.kernel = np.exp(
            -2j
            * math.pi
            / (self.lam * self.d)
            * (np.outer(ax, self.det_x) + np.outer(ay, self.det_y))
        )

    def _screens(self, screens):
        return [
            (zj, np.exp(1j * _interpolate(values, dx, self.x)))
            for zj, values, dx in screens
            if zj < self.z
        ]

    def beam(self, screens=()) -> np.ndarray:
        """The beam's irradiance at z through the screens (any unit: G divides it out)."""
        u = np.exp(-self.r2 / self.w0**2).astype(complex)
        at = 0.0
        for zj, phasor in sorted(self._screens(screens), key=lambda s: s[0]):
            u = (
                np.fft.ifft2(np.fft.fft2(u) * _transfer(self.n, self.dx, self.lam, zj - at))
                * phasor
            )
            at = zj
        u = np.fft.ifft2(np.fft.fft2(u) * _transfer(self.n, self.dx, self.lam, self.z - at))
        return np.abs(u) ** 2

    def scatterers(self, screens=(), batch: int = 64):
        """Power of each scatterer (self.points) on the detector and into the full aperture (sources
        of unit spectral density; only ratios are used)."""
        planes = sorted(self._screens(screens), key=lambda s: -s[0])
        det, ap = np.empty(len(self.points)), np.empty(len(self.points))
        for b in range(0, len(self.points), batch):
            pts = self.points[b : b + batch]
            # a source at array index (iy, ix): the FFT's origin is index 0, the grid's coordinates
            # are centred
            ramp_y = np.exp(-2j * math.pi * np.outer(pts[:, 0] * self.dx, self.fx))
            ramp_x = np.exp(-2j * math.pi * np.outer(pts[:, 1] * self.dx, self.fx))
            spectrum = self.source[None] * ramp_y[:, :, None] * ramp_x[:, None, :]
            at = self.z
            for zj, phasor in planes:
                u = np.fft.ifft2(spectrum * _transfer(self.n, self.dx, self.lam, at - zj)) * phasor
                spectrum, at = np.fft.fft2(u), zj
            u = np.fft.ifft2(spectrum * _transfer(self.n, self.dx, self.lam, at))
            ap[b : b + batch] = np.sum(np.abs(u[:, self.ap]) ** 2, axis=1) * self.dx**2
            field = (
                (u[:, self.pupil] * self.curvature) @ self.kernel * self.dx**2 / (self.lam * self.d)
            )
            det[b : b + batch] = np.sum(np.abs(field) ** 2, axis=1) * self.det_cell
        return det, ap

    def overlap(self, beam: np.ndarray, detector_power: np.ndarray, aperture_power: float) -> float:
        """G = sum E P_det / (sum E P_ap): the scatterers' sum over their cells, the beam's over the
        grid."""
        e = beam[self.points[:, 0], self.points[:, 1]]
        return float(
            np.sum(e * detector_power) * self.cell / (np.sum(beam) * self.dx**2 * aperture_power)
        )

    def vacuum_aperture_power(self) -> float:
        """P_ap of the scatterer on the axis without turbulence (the same for every scatterer whose
        cone to the aperture lies inside the flat part of the source's spectrum)."""
        centre = self.points[np.argmin(self.r2[self.points[:, 0], self.points[:, 1]])]
        keep = self.points
        self.points = centre[None]
        try:
            return float(self.scatterers()[1][0])
        finally:
            self.points = keep
