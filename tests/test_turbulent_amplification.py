"""Backscatter amplification in Fourier optics on both paths: its fall from a receiver about the
size of the coherence radius to one several times larger, and the bound of two.

Published limits (docs/turbulence.md): a point receiver (aperture << r0) in saturated scintillation
gains a factor tending to 2, the mean of the squared exponential intensity the outgoing and
returning waves share (Kravtsov & Saichev, Sov. Phys. Usp. 25, 494 (1982); Banakh & Mironov,
*Lidar in a Turbulent Atmosphere* (1987)); a receiver much larger than r0 averages the shared bright
spots away. The factor 2 itself is out of reach of these grids: the random-phase receiver's speckle
in the sky is λz/D wide, and averaging it under a beam the field of view must also cover needs a
grid of ~320 λz/D² (10⁴ for D = 4 mm at 500 m). What is tested is the fall with the aperture at a
fixed atmosphere, both amplifications above 1, the smaller below the bound, and ray tracing's
large-aperture limit of 1 (tests/test_turbulent_rt_return.py::test_amplification_limits).

The scene is the oracle's (tests/test_turbulent_return.py): 1064 nm, w0 = 2.5 mm, f = 0.5 m, a 25 µm
detector, 200 m through Cn² = 7.3e-13 (spherical r0 = 1.8 cm, spherical-wave Rytov variance 0.48).
"""

import math

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core
from lidar_overlap.model.turbulence import TWO_WAY_BOUND

Z, CN2 = 200.0, 7.3e-13
#: Draws per aperture: the small aperture's G spreads most (its error dominates the difference).
DRAWS = {0.015: 128, 0.05: 64}
FIELDS = 8
#: Standard errors a statistical comparison allows.
SIGMAS = 3.0


def lidar(diameter):
    return lo.LidarSystem(
        beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=2.5e-3),
        telescope=lo.Telescope(diameter=diameter, focal_length=0.5),
        detector=lo.Detector(radius=25e-6),
    )


def amplification(diameter, seed):
    """Mean G over mean uncorrelated G at Z, its standard error (the paired rows, delta method)
    and the mean G."""
    system, air = lidar(diameter), lo.Turbulence(CN2)
    options = _core.TurbulenceOptions(
        paths="both", realizations=DRAWS[diameter], screens=10, receiver_fields=FIELDS, seed=seed
    )
    options.beam_grid = _core.turbulent_grid(
        system._native, [Z], air._native, options
    ).min_beam_grid
    raw = _core.overlap_fo_turbulent(system._native, [Z], air._native, options)
    g, u = raw.overlap[:, 0], raw.uncorrelated[:, 0]
    ratio = g.mean() / u.mean()
    error = np.std(g - ratio * u, ddof=1) / math.sqrt(g.size) / u.mean()
    return float(ratio), float(error), float(g.mean())


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
