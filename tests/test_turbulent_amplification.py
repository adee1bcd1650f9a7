"""Backscatter amplification in Fourier optics on both paths: its fall from a receiver about the
size of the coherence radius to one several times larger, and the bound of two.

Published limits (docs/turbulence.md): a point receiver (aperture << r0) in saturated scintillation
gains a factor tending to 2, the mean of the squared exponential intensity the outgoing and
returning waves share (Kravtsov & Saichev, Sov. Phys. Usp. 25, 494 (1982); Banakh & Mironov,
*Lidar in a Turbulent Atmosphere* (1987)); a receiver much larger than r0 averages the shared bright
spots away. The point-like lidar's 1 + σ_I² is tested in tests/test_turbulent_point_receiver.py;
the saturated factor 2 is out of reach of these grids. What is tested here is the fall with the
aperture at a fixed atmosphere, both amplifications above 1, the smaller below the bound, and the
large-aperture limit: a 20 cm receiver (3.9 r0, aperture averaging 0.011) gains nothing beyond
what ray tracing, which leaves the enhancement out, gives for the same scene (as ray tracing's own
limit, tests/test_turbulent_rt_return.py::test_amplification_limits).

The scene is the oracle's (tests/test_turbulent_return.py): 1064 nm, w0 = 2.5 mm, f = 0.5 m, a 25 µm
detector, 200 m through Cn² = 7.3e-13 (spherical r0 = 1.8 cm, spherical-wave Rytov variance 0.48).
"""

import math

import numpy as np
import pytest
from _amplification import fo_amplification

import lidar_overlap as lo
from lidar_overlap.forward.backends.turbulent_return import missed_enhancement
from lidar_overlap.model.turbulence import TWO_WAY_BOUND

Z, CN2 = 200.0, 7.3e-13
#: Draws per aperture: the small aperture's G spreads most (its error dominates the difference).
DRAWS = {0.015: 128, 0.05: 64, 0.2: 64}
FIELDS = 8
#: Standard errors a statistical comparison allows.
SIGMAS = 3.0
#: A wide receiver's amplification from the tilt its image shares with the beam near the field
#: stop's edge (ray tracing: 1.006 for the wide receiver below).
WIDE_TOLERANCE = 0.01


def lidar(diameter, detector_radius=25e-6, waist=2.5e-3):
    return lo.LidarSystem(
        beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=waist),
        telescope=lo.Telescope(diameter=diameter, focal_length=0.5),
        detector=lo.Detector(radius=detector_radius),
    )


def amplification(diameter, seed, system=None, z=Z, cn2=CN2, fields=FIELDS):
    """Mean G over mean uncorrelated G at z, its standard error (the paired rows, delta method)
    and the mean G."""
    return fo_amplification(system or lidar(diameter), z, cn2, DRAWS[diameter], fields, seed)


@pytest.fixture(scope="module")
def apertures():
    return {d: amplification(d, seed) for d, seed in ((0.015, 1), (0.05, 2))}


def test_amplification_falls_as_the_aperture_grows_past_r0(apertures):
    (small, e_small, _), (large, e_large, _) = apertures[0.015], apertures[0.05]
    r0 = lo.Turbulence(CN2)._native.fried_parameter_spherical(1064e-9, Z)
    print(
        f"amplification at {Z} m (r0 = {r0 * 100:.2g} cm): D = 1.5 cm {small:.3f} ± {e_small:.3f}, "
        f"D = 5 cm {large:.3f} ± {e_large:.3f}"
    )
    assert small - 1.0 > SIGMAS * e_small and large - 1.0 > SIGMAS * e_large
    assert small - large > SIGMAS * math.hypot(e_small, e_large)


def test_the_amplification_stays_below_two(apertures):
    for ratio, error, mean in apertures.values():
        assert ratio < TWO_WAY_BOUND + SIGMAS * error
        assert mean <= TWO_WAY_BOUND


def test_a_receiver_much_wider_than_r0_gains_no_enhancement():
    """D = 20 cm, 100 µm detector, w0 = 5 mm, 500 m through Cn² = 5e-14 (spherical r0 = 5.2 cm):
    FO's amplification is 1 within its error and what ray tracing gives (2000 draws), whose
    return path has no shared bright spots, within their errors and the estimate of those spots."""
    z, cn2 = 500.0, 5e-14
    system = lidar(0.2, detector_radius=100e-6, waist=5e-3)
    fo, error, _ = amplification(0.2, 3, system=system, z=z, cn2=cn2, fields=4)
    request = lo.Turbulent(lo.Turbulence(cn2), lo.RT(1e-4), realizations=2000, seed=1)
    with pytest.warns(RuntimeWarning, match="isoplanatic"):  # a spot 2.2 isoplanatic angles wide
        rt = lo.overlap(system, [z], request)
    rt_error = rt.error_estimate[0] * rt.amplification[0] / rt.overlap[0]
    missed = float(missed_enhancement(system, lo.Turbulence(cn2), np.array([z]))[0])
    print(
        f"D = 20 cm at {z} m: FO {fo:.4f} ± {error:.4f}, RT {rt.amplification[0]:.4f} ± "
        f"{rt_error:.4f}, missed enhancement estimate {missed:.4f}"
    )
    assert abs(fo - 1.0) < SIGMAS * error + WIDE_TOLERANCE
    assert abs(fo - rt.amplification[0]) < SIGMAS * math.hypot(error, rt_error) + missed
