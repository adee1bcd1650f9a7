"""Ray tracing with turbulence on both paths (``paths="both"``): the geometric counterpart of the
return path that Fourier optics carries through the phase screens (docs/turbulence.md).

Each draw is the transmitted draw (the short-term beam displaced by its wander c) seen through a
return path that tilts and blurs the image of the scattering volume:

- tilt: the angle of arrival α over the aperture of a point scatterer's light, the same for every
  scatterer of the spot (isoplanatic). Seen from the receiver the scene moves by z α, so the draw
  is traced with the beam displaced by c + z α (the same as moving the image by f α on the
  detector).
  z α is drawn correlated with c: on the layer model of :mod:`lidar_overlap.model.tilt` its
  covariance with c is minus ``cross``, its per-axis variance ``image`` (the spherical-wave
  angle-of-arrival variance times z²), and the correlation ρ is kept with c's own sd (Andrews &
  Phillips' wander, as the transmit path draws it): z α = −ρ (σ_i / σ_c) c + sqrt(1 − ρ²) σ_i ξ, ξ
  standard normal from the stream ``default_rng((seed, 1))``.
- blur: the short-term image of a point is a Gaussian of 1/e² angular radius θ_ST, θ_ST² = θ_LT² −
  4 σ_α² (the long-term image, 0.98 λ / r0 FWHM for the returning spherical wave's r0, less its
  tilt); 0 where the aperture is smaller than about r0 (the image is then diffraction's, which ray
  tracing leaves out). Blurring every scatterer's image by it is the same as blurring the beam:
  the draw's beam radius is sqrt(W_ST² + (z θ_ST)²).
- uncorrelated paths: z α independent of c. Their mean G is computed exactly, not drawn: c + z α is
  then Gaussian, and the blurred beam averaged over it is the Gaussian beam of radius² W_b² +
  4 (σ_c² + σ_i²) (G is linear in the irradiance), one trace per range. The amplification is mean G
  over it.

What it leaves out: the correlated bright spots of the two paths (the backscatter enhancement of
scintillation, the FO effect that lets mean G exceed 1). :func:`missed_enhancement` estimates it
as the spherical-wave Rytov variance β0² times the aperture averaging factor times ρ; auto runs
Fourier optics where it exceeds the tolerance, and ray tracing warns where it exceeds 1 %.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from ... import _checks
from ...model.tilt import PathTilts, path_tilts, spherical_rytov
from ...model.turbulence import TWO_WAY_BOUND
from ..validity import RT_MODEL_ERROR_LIMIT

#: 1/e² radius of the long-term image of a point in λ / r0: the seeing FWHM 0.98 λ / r0 of a
#: Gaussian (FWHM = sqrt(2 ln 2) x the 1/e² radius).
LONG_TERM_IMAGE = 0.98 / math.sqrt(2.0 * math.log(2.0))
#: Andrews & Phillips' aperture averaging of a spherical wave (weak fluctuations): A = 1 / (1 +
#: APERTURE_AVERAGING (k D² / 4z)^(7/6)).
APERTURE_AVERAGING = 0.33


def tilts(system, turbulence, z) -> PathTilts:
    """The layer model's tilt moments of ``system``'s two paths through ``turbulence`` (a
    :class:`~lidar_overlap.Turbulence`) at ranges ``z`` (m). Remembered for the last 8 calls: a
    run's draws, its regime warning and auto's estimate share one computation."""
    z = np.ascontiguousarray(z, dtype=float)
    try:
        return _tilts(system, turbulence, z.tobytes())
    except TypeError:  # a system or profile that cannot be hashed
        return _compute_tilts(system, turbulence, z)


@functools.lru_cache(maxsize=8)
def _tilts(system, turbulence, z: bytes) -> PathTilts:
    return _compute_tilts(system, turbulence, np.frombuffer(z))


def _compute_tilts(system, turbulence, z: np.ndarray) -> PathTilts:
    beam, native = system.beam, turbulence._native
    return path_tilts(
        native.cn2_at_range,
        z,
        wavelength=beam.wavelength,
        diameter=system.telescope.diameter,
        beam_radius=lambda r: np.array([beam.radius(float(x)) for x in r]),
        separation=math.hypot(*beam.offset),
        outer_scale=native.outer_scale,
        inner_scale=native.inner_scale,
    )


def image_blur(wavelength: float, z: np.ndarray, moments: PathTilts) -> np.ndarray:
    """θ_ST (rad): the 1/e² radius of the short-term image of a point at each range (m), tilt
    removed."""
    long_term = LONG_TERM_IMAGE * wavelength / moments.r0
    return np.sqrt(np.maximum(long_term**2 - 4.0 * moments.image / np.asarray(z) ** 2, 0.0))


def return_draws(plan, short_term: np.ndarray, offsets: np.ndarray, sigma: np.ndarray):
    """The blurred beam radius at each range (m) and the offsets (m, realisations x ranges x 2) of
    every draw through both paths, from the transmit draws (``short_term``, ``offsets`` and the
    wander's per-axis sd ``sigma``)."""
    z, request = plan.ranges, plan.turbulence
    moments = tilts(plan.system, request.turbulence, z)
    image = np.sqrt(moments.image)
    rho = np.clip(moments.correlation, -1.0, 1.0)  # the quadrature's round-off past Cauchy–Schwarz
    blur = image_blur(plan.system.beam.wavelength, z, moments)
    xi = np.random.default_rng((request.seed, 1)).standard_normal((z.size, request.realizations, 2))
    xi = xi.transpose(1, 0, 2) * image[None, :, None]
    gain = np.divide(rho * image, sigma, out=np.zeros_like(image), where=sigma > 0.0)
    lone = np.where(sigma > 0.0, np.sqrt(1.0 - rho**2), 1.0)  # no wander: nothing to correlate
    correlated = offsets * (1.0 - gain)[None, :, None] + lone[None, :, None] * xi
    return np.sqrt(short_term**2 + (z * blur) ** 2), correlated


def uncorrelated_radius(plan, short_term: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """The radius (m) at each range of the beam whose G is the mean G with uncorrelated paths: the
    blurred short-term beam moved by c + z α with c and z α independent, Gaussian, of per-axis
    variances sigma² and ``image``; G is linear in the irradiance, and a Gaussian beam averaged over
    Gaussian offsets is the Gaussian beam of radius² W² + 4 (sigma² + image)."""
    z = plan.ranges
    moments = tilts(plan.system, plan.turbulence.turbulence, z)
    blur = image_blur(plan.system.beam.wavelength, z, moments)
    return np.sqrt(short_term**2 + (z * blur) ** 2 + 4.0 * (sigma**2 + moments.image))


def missed_enhancement(system, turbulence, z) -> np.ndarray:
    """Estimate of what the RT return path misses at each range (a fraction of G): β0² A ρ, the
    spherical-wave Rytov variance (scintillation of the return wave, weak fluctuations) times the
    aperture averaging factor times the paths' tilt correlation (bright spots shared as eddies
    are), at most TWO_WAY_BOUND − 1."""
    z = np.asarray(z, dtype=float)
    lam, d = system.beam.wavelength, system.telescope.diameter
    k = 2.0 * math.pi / lam
    rho = np.clip(tilts(system, turbulence, z).correlation, 0.0, 1.0)
    beta2 = np.array([spherical_rytov(turbulence._native.cn2_at_range, lam, zi) for zi in z])
    averaging = 1.0 / (1.0 + APERTURE_AVERAGING * (k * d**2 / (4.0 * z)) ** (7.0 / 6.0))
    return np.minimum(beta2 * averaging * rho, TWO_WAY_BOUND - 1.0)


def warn_outside_regime(plan, long_term: np.ndarray) -> None:
    """RuntimeWarning naming the first range where the RT return path leaves its regime: strong
    fluctuations (plane-wave Rytov variance >= 1), a spot (the long-term beam radius ``long_term``,
    m, at each range) wider than the isoplanatic angle (its scatterers do not share one tilt), or a
    missed enhancement above 1 % of G."""
    system, z, turbulence = plan.system, plan.ranges, plan.turbulence.turbulence
    lam = system.beam.wavelength
    reasons = []
    if turbulence.rytov_variance(lam, float(z[-1])) >= 1.0:  # it grows with the range
        rytov = np.array([turbulence.rytov_variance(lam, float(zi)) for zi in z])
        i = int(np.argmax(rytov >= 1.0))
        reasons.append(
            f"the fluctuations are strong from ranges[{i}] = {z[i]:.4g} m (Rytov variance "
            f"{rytov[i]:.3g} >= 1), beyond the weak-fluctuation tilt and blur"
        )
    spot = np.array(
        [long_term[i] / zi / turbulence.isoplanatic_angle(lam, float(zi)) for i, zi in enumerate(z)]
    )
    if np.any(spot > 1.0):
        i = int(np.argmax(spot > 1.0))
        reasons.append(
            f"the beam's spot is {spot[i]:.3g} isoplanatic angles wide at ranges[{i}] = "
            f"{z[i]:.4g} m: its scatterers do not share one tilt, so the draws' spread and the "
            "tilt's correlation with the wander are approximate"
        )
    missed = missed_enhancement(system, turbulence, z)
    if np.any(missed > RT_MODEL_ERROR_LIMIT):
        i = int(np.argmax(missed))
        reasons.append(
            f"it leaves out the backscatter enhancement (the two paths' shared bright spots), "
            f"estimated up to {missed[i]:.2g} of G at ranges[{i}] = {z[i]:.4g} m"
        )
    if reasons:
        _checks.warn(
            "ray tracing with turbulence on both paths outside its regime: "
            + "; ".join(reasons)
            + ". Fourier optics (lo.FO) carries both paths through phase screens"
        )
