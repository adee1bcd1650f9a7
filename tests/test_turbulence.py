"""Turbulence (paper Section 3, step 2): the Python layer over the C++ atmosphere, the turbulent overlap in
both paths, and the split-step FO beam against weak-fluctuation theory.

- no turbulence reproduces the turbulence-free result exactly (both methods) and the split-step beam
  radius equals Eq. (D1);
- path quantities for a constant Cn^2 against their closed forms;
- RT: the mean over wander realisations against the overlap of the long-term beam (G is linear in the
  irradiance, and the long-term beam is the short-term one averaged over the wander);
- FO through phase screens: the split-step beam without screens gives the turbulence-free FO overlap; the
  centroid variance and the long-term second moment of a collimated beam (w0 = 5 cm, z_R = 7.4 km > L = 1 km)
  against the second-order laws of the screen model.
"""

import dataclasses
import math

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core

LAM = 1064e-9
K = 2 * math.pi / LAM
# Closed forms of the C++ path integrals (adaptive quadrature to 1e-12).
CLOSED_FORM_RTOL = 1e-9
# Split-step without screens: scaled angular-spectrum steps of a Gaussian are exact to rounding.
D1_RTOL = 1e-9
# RT mean over K = 400 wander draws against the long-term beam: 4 standard errors.
MEAN_SIGMAS = 4.0
# The turbulent FO grid keeps the aliases' diffraction tails below 1e-4 of G (overlap_turbulent.cpp).
SPLIT_STEP_ATOL = 1e-4
# FO statistics over K realisations on 128^2 grids (w0 = 5 cm, L = 1 km, sigma_R^2 = 0.3). |r_c|^2 of a
# 2-D Gaussian wander is exponential: relative standard error 1 / sqrt(K). The second moment of one
# realisation varies more (random focusing by eddies of the beam's size moves W_ST^2 by up to 30 %): relative
# standard deviation 1.7, measured. 4 standard errors, plus 2 % for the beam's growth along the path,
# which the closed forms leave out.
STATS_REALIZATIONS = 1000
WANDER_RTOL = 4.0 / math.sqrt(STATS_REALIZATIONS) + 0.02
SPREAD_RTOL = 4.0 * 1.7 / math.sqrt(STATS_REALIZATIONS) + 0.02


def test_path_quantities_of_a_constant_cn2():
    cn2, L = 1e-14, 2000.0
    t = lo.Turbulence(cn2)
    assert abs(t.fried_parameter(LAM, L, "plane") / (0.423 * K**2 * cn2 * L) ** -0.6 - 1) < CLOSED_FORM_RTOL
    assert abs(t.fried_parameter(LAM, L) / (0.423 * K**2 * cn2 * L * 3 / 8) ** -0.6 - 1) < CLOSED_FORM_RTOL
    assert abs(t.rytov_variance(LAM, L) / (2.25 * 6 / 11 * cn2 * K ** (7 / 6) * L ** (11 / 6)) - 1) < CLOSED_FORM_RTOL
    assert abs(t.beam_wander_variance(0.05, LAM, L) / (2.42 * cn2 * L**3 * 0.05 ** (-1 / 3)) - 1) < CLOSED_FORM_RTOL
    hv = lo.Turbulence("hv57")
    assert abs(hv.fried_parameter(0.5e-6, 30e3, "plane") / 0.05 - 1) < 0.05     # the model's defining r0


@pytest.mark.parametrize("method", ["rt", "fo"])
def test_no_turbulence_is_the_turbulence_free_result(method):
    s, z = lo.paper_table1(), np.geomspace(50, 1000, 8)
    calm = lo.overlap(s, z, method, turbulence=lo.Turbulence(0.0), realizations=3)
    assert np.array_equal(calm.overlap, lo.overlap(s, z, method).overlap)
    assert np.all(calm.std == 0) and calm.realizations.shape == (3, z.size)


def test_split_step_without_screens_follows_d1():
    s = lo.paper_table1(wavelength=LAM, waist_radius=5e-3)
    raw = _core.overlap_fo_turbulent(s._native, [300.0, 1000.0], lo.Turbulence(0.0)._native, 1, 10, 0, 128, 8.0, 0)
    assert abs(raw["radius_last"][0] / s.beam.radius(1000.0) - 1) < D1_RTOL


def test_rt_mean_is_the_long_term_beam():
    s, z, t = lo.paper_table1(), np.array([150.0, 250.0, 600.0]), lo.Turbulence(3e-14)
    res = lo.overlap(s, z, "rt", turbulence=t, realizations=400, seed=3)
    for i, zi in enumerate(z):
        lt = t.long_term_radius(s.beam.waist_radius, s.beam.wavelength, zi)
        beam = dataclasses.replace(s.beam, divergence=math.sqrt(lt**2 - s.beam.waist_radius**2) / zi)
        expected = lo.overlap(dataclasses.replace(s, beam=beam), [zi], "rt").overlap[0]
        assert abs(res.overlap[i] - expected) < MEAN_SIGMAS * res.error_estimate[i] + 1e-6
    assert np.all(res.std > 0) and np.all(res.low <= res.overlap) and np.all(res.overlap <= res.high)
    again = lo.overlap(s, z, "rt", turbulence=t, realizations=400, seed=3)
    assert np.array_equal(again.realizations, res.realizations)           # reproducible with the seed


def test_split_step_without_screens_gives_the_fo_overlap():
    s, z = lo.paper_table1(), np.geomspace(50, 2000, 12)
    raw = _core.overlap_fo_turbulent(s._native, z, lo.Turbulence(0.0)._native, 1, 10, 0, 128, 8.0, 0)
    assert np.max(np.abs(np.asarray(raw["overlap"])[0] - lo.overlap(s, z, "fo").overlap)) < SPLIT_STEP_ATOL


def gradient_law(cn2, L, width2, inner_scale):
    """4 pi^2 int_0^L (L - z)^2 dz int_0^inf kappa^3 Phi_n exp(-kappa^2 (width2 / 4 + 1 / kappa_m^2)) dkappa
    for Phi_n = 0.033 Cn^2 kappa^(-11/3) and kappa_m = 5.92 / l0: the displacement at L of layers' phase
    gradients averaged over a Gaussian of 1/e^2 radius^2 width2 (m^2)."""
    scale2 = width2 / 4 + (inner_scale / 5.92) ** 2
    return 4 * math.pi**2 * 0.033 * math.gamma(1 / 6) / 6 * cn2 * L**3 * scale2 ** (-1 / 6)


def test_fo_screens_wander_and_spread_a_collimated_beam():
    """Second-order laws of thin screens (paraxial, any strength). A screen tilts the centroid by its phase
    gradient averaged over the irradiance: <r_c^2> (2-D) = gradient_law(W0^2), 1.52 Cn^2 L^3 W0^(-1/3) for
    l0 = 0 (Klyatskin & Kon 1972). It adds its whole gradient variance to the mean-square angle: the second
    moment of the long-term irradiance grows by W_LT^2 - W^2 = 2 gradient_law(0) (1/e^2 radii, W^2 =
    2 <rho^2>), per realisation W_ST^2 + 2 |r_c|^2. With l0 = 0 that moment diverges (wings of scattered
    light) and the grid's Nyquist frequency sets it: 1.40 and 1.68 times 1.33 sigma_R^2 Lambda^(5/6) W^2
    on 128^2 and 256^2 grids. Andrews & Phillips' W_LT is the Gaussian core of the mean irradiance (the FO
    core gives their T within 10 %), and their 2.42 Cn^2 L^3 W0^(-1/3) is 2 gradient_law(4 W0^2), the
    large-scale part of that W_LT^2: 2^(2/3) = 1.59 times the centroid variance."""
    w0, L, cn2, l0 = 5e-2, 1000.0, 1e-14, 0.02
    s, t = lo.paper_table1(wavelength=LAM, waist_radius=w0), lo.Turbulence(cn2, inner_scale=l0)
    raw = _core.overlap_fo_turbulent(s._native, [L], t._native, STATS_REALIZATIONS, 10, 1, 128, 8.0, 0)
    wx, wy, r = (np.asarray(raw[k]) for k in ("wander_x", "wander_y", "radius_last"))
    wander = np.mean(wx**2 + wy**2)
    spread = np.mean(r**2 + 2 * (wx**2 + wy**2)) - s.beam.radius(L) ** 2
    assert abs(wander / gradient_law(cn2, L, w0**2, l0) - 1) < WANDER_RTOL
    assert abs(spread / (2 * gradient_law(cn2, L, 0.0, l0)) - 1) < SPREAD_RTOL


def test_fo_turbulent_overlap_is_reproducible_and_spread():
    s, z, t = lo.paper_table1(), np.array([200.0, 500.0]), lo.Turbulence(2e-14)
    a = lo.overlap(s, z, "fo", turbulence=t, realizations=6, seed=7, beam_grid=128)
    b = lo.overlap(s, z, "fo", turbulence=t, realizations=6, seed=7, beam_grid=128, threads=1)
    assert np.array_equal(a.realizations, b.realizations)                  # whatever the thread count
    assert np.all(a.std > 0)


def test_bad_turbulence_input():
    with pytest.raises(ValueError, match="cn2"):
        lo.Turbulence(-1e-14)
    with pytest.raises(ValueError, match="elevation"):
        lo.Turbulence(1e-14, elevation=2.0)
    with pytest.raises(ValueError, match="turbulence = "):
        lo.overlap(lo.paper_table1(), [100.0], "rt", turbulence=1e-14)
    with pytest.raises(ValueError, match="realizations"):
        lo.overlap(lo.paper_table1(), [100.0], "rt", turbulence=lo.Turbulence(1e-14), realizations=0)
