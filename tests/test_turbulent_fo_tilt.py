"""Image motion in Fourier optics on both paths against the Kolmogorov closed forms.

A receiver focused at range Z (detector defocus to the conjugate of Z) sends its light back through
the aperture as the cone that converges on the point at Z: by reciprocity the motion of its
sensitivity's centroid at Z (``receiver_x``, ``receiver_y`` of the core's result) is Z times the
angle of arrival of that point's spherical wave over the aperture, the G-tilt (the centroid of a
paraxial field moves by the irradiance-weighted mean phase gradient of each screen times its lever;
the cone's footprint at range r is D (Z − r)/Z). Its per-axis variance is
``Turbulence.angle_of_arrival_variance(D, Z)`` times Z², the same closed form ray tracing draws its
tilts from (C D^(-1/3) ∫ Cn² (1 − r/Z)^(5/3) dr, C = 2.84). The beam's own centroid (``wander_x``)
follows the same integral with the beam's Gaussian footprint (``tilt.path_tilts``'s ``beam``) and
its correlation with the receiver's is ``path_tilts``'s ``correlation``.

The scene: D = 5 cm, 1064 nm, Cn² = 1e-13 over 500 m (spherical r0 = 3.4 cm, D/r0 = 1.5), a
collimated 1 cm waist, a detector 0.2 µm in radius (its random-phase fields' own image jitter,
about (r_det Z / d)² / 4, is 1 % of the signal: measured in calm air below). 200 draws, x and y
each: 400 samples of a variance, whose relative standard error is √(2/400) = 7 %.
"""

import math

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core
from lidar_overlap.model import tilt

Z, F, D, WAVELENGTH, WAIST = 500.0, 0.5, 0.05, 1064e-9, 1e-2
CN2 = 1e-13
DRAWS = 200
SEED = 3
GRID = 128  # the least the core accepts here is 60
#: Standard errors allowed on a statistical comparison.
SIGMAS = 3.0
#: What the closed forms leave out: the detector's own image jitter (1 %), the focused spot's
#: diffraction near Z, ten screens for a continuous path, the screens' sampling.
MODEL_TOLERANCE = 0.05
#: On the correlation: its standard error (1 − ρ²)/√n is ~0.005; the beam's footprint in the closed
#: form is its vacuum radius (turbulence widens the draws' beam a little).
CORRELATION_TOLERANCE = 0.02


def focused_receiver(detector_radius=2e-7):
    d = F * Z / (Z - F)  # the detector at the conjugate of Z
    return lo.LidarSystem(
        beam=lo.GaussianBeam(WAVELENGTH, WAIST),
        telescope=lo.Telescope(D, F),
        detector=lo.Detector(radius=detector_radius, defocus=d - F),
    )


def run(cn2, draws=DRAWS):
    options = _core.TurbulenceOptions(
        paths="both",
        realizations=draws,
        screens=10,
        receiver_fields=1,
        seed=SEED,
        beam_grid=GRID,
    )
    air = lo.Turbulence(cn2)
    return _core.overlap_fo_turbulent(focused_receiver()._native, [Z], air._native, options)


@pytest.fixture(scope="module")
def draws():
    return run(CN2)


def vacuum_radius(r):
    rayleigh = math.pi * WAIST**2 / WAVELENGTH
    return WAIST * np.sqrt(1.0 + (np.asarray(r) / rayleigh) ** 2)


def closed_forms():
    moments = tilt.path_tilts(
        lambda r: CN2, np.array([Z]), wavelength=WAVELENGTH, diameter=D, beam_radius=vacuum_radius
    )
    return moments, Z**2 * lo.Turbulence(CN2).angle_of_arrival_variance(D, Z)


def test_receiver_image_motion_is_the_spherical_wave_angle_of_arrival(draws):
    image = np.concatenate([draws.receiver_x, draws.receiver_y])
    measured = float(np.mean(image**2))
    _, expected = closed_forms()
    error = math.sqrt(2.0 / image.size)
    print(
        f"receiver centroid variance at {Z} m: {measured:.4g} m², closed form Z² σ_α² "
        f"{expected:.4g} m² (ratio {measured / expected:.3f} ± {error:.3f})"
    )
    assert abs(measured / expected - 1.0) < SIGMAS * error + MODEL_TOLERANCE
    assert abs(float(np.mean(image))) < SIGMAS * math.sqrt(expected / image.size)


def test_beam_wander_and_its_correlation_with_the_image_motion(draws):
    moments, _ = closed_forms()
    beam = np.concatenate([draws.wander_x, draws.wander_y])
    image = np.concatenate([draws.receiver_x, draws.receiver_y])
    measured = float(np.mean(beam**2))
    error = math.sqrt(2.0 / beam.size)
    rho = float(np.mean(beam * image) / math.sqrt(np.mean(beam**2) * np.mean(image**2)))
    expected_rho = float(moments.correlation[0])
    print(
        f"beam centroid variance {measured:.4g} m², closed form {moments.beam[0]:.4g} m² (ratio "
        f"{measured / moments.beam[0]:.3f} ± {error:.3f}); correlation {rho:.3f}, closed form "
        f"{expected_rho:.3f}"
    )
    assert abs(measured / moments.beam[0] - 1.0) < SIGMAS * error + MODEL_TOLERANCE
    # the paths share their eddies: the sensitivity's centroid follows the beam's
    rho_error = (1.0 - expected_rho**2) / math.sqrt(beam.size)
    assert abs(rho - expected_rho) < SIGMAS * rho_error + CORRELATION_TOLERANCE


def test_in_calm_air_the_image_stays_within_the_detectors_own_jitter():
    calm = run(0.0, draws=8)
    image = np.concatenate([calm.receiver_x, calm.receiver_y])
    _, expected = closed_forms()
    assert float(np.mean(image**2)) < 0.02 * expected
    # transmit only: no receiver, no centroid
    options = _core.TurbulenceOptions(realizations=1, screens=2, beam_grid=64)
    plain = _core.overlap_fo_turbulent(
        focused_receiver()._native, [Z], lo.Turbulence(CN2)._native, options
    )
    assert plain.receiver_x.size == 0 and plain.receiver_y.size == 0
