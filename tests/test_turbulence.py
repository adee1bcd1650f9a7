"""Turbulence (paper Section 3, step 2): the Python layer over the C++ atmosphere, the turbulent
overlap in both paths, and the split-step FO beam against weak-fluctuation theory.

- no turbulence reproduces the turbulence-free result exactly (both methods) and the split-step beam
  radius equals Eq. (D1);
- path quantities for a constant Cn^2 against their closed forms;
- RT: the mean over wander realisations against the overlap of the long-term beam (G is linear in
  the irradiance, and the long-term beam is the short-term one averaged over the wander);
- FO through phase screens: the split-step beam without screens gives the turbulence-free FO
  overlap; the centroid variance and the long-term second moment of a collimated beam (w0 = 5 cm,
  z_R = 7.4 km > L = 1 km) against the second-order laws of the screen model.
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
# The turbulent FO grid keeps the aliases' diffraction tails below 1e-4 of G
# (overlap_turbulent.cpp).
SPLIT_STEP_ATOL = 1e-4
# FO statistics over K realisations on 128^2 grids (w0 = 5 cm, L = 1 km, sigma_R^2 = 0.3). |r_c|^2
# of a 2-D Gaussian wander is exponential: relative standard error 1 / sqrt(K). The second moment of
# one realisation varies more (random focusing by eddies of the beam's size moves W_ST^2 by up to 30
# %): relative standard deviation 1.7, measured. 4 standard errors, plus 2 % for the beam's growth
# along the path, which the closed forms leave out.
STATS_REALIZATIONS = 1000
WANDER_RTOL = 4.0 / math.sqrt(STATS_REALIZATIONS) + 0.02
SPREAD_RTOL = 4.0 * 1.7 / math.sqrt(STATS_REALIZATIONS) + 0.02


def test_path_quantities_of_a_constant_cn2():
    cn2, L = 1e-14, 2000.0
    t = lo.Turbulence(cn2)
    assert (
        abs(t.fried_parameter(LAM, L, "plane") / (0.423 * K**2 * cn2 * L) ** -0.6 - 1)
        < CLOSED_FORM_RTOL
    )
    assert (
        abs(t.fried_parameter(LAM, L) / (0.423 * K**2 * cn2 * L * 3 / 8) ** -0.6 - 1)
        < CLOSED_FORM_RTOL
    )
    assert (
        abs(t.rytov_variance(LAM, L) / (2.25 * 6 / 11 * cn2 * K ** (7 / 6) * L ** (11 / 6)) - 1)
        < CLOSED_FORM_RTOL
    )
    assert (
        abs(t.beam_wander_variance(LAM, 0.05, L) / (2.42 * cn2 * L**3 * 0.05 ** (-1 / 3)) - 1)
        < CLOSED_FORM_RTOL
    )
    hv = lo.Turbulence("hv57")
    assert (
        abs(hv.fried_parameter(0.5e-6, 30e3, "plane") / 0.05 - 1) < 0.05
    )  # the model's defining r0


@pytest.mark.parametrize("method", ["rt", "fo"])
def test_no_turbulence_is_the_turbulence_free_result(method):
    s, z = lo.paper_table1(), np.geomspace(50, 1000, 8)
    calm = lo.overlap(s, z, method, turbulence=lo.Turbulence(0.0), realizations=3)
    assert np.array_equal(calm.overlap, lo.overlap(s, z, method).overlap)
    assert np.all(calm.std == 0) and calm.realizations.shape == (3, z.size)


def test_split_step_without_screens_follows_d1():
    s = lo.paper_table1(wavelength=LAM, waist_radius=5e-3)
    raw = _core.overlap_fo_turbulent(
        s._native,
        [300.0, 1000.0],
        lo.Turbulence(0.0)._native,
        _core.TurbulenceOptions(
            realizations=1, screens=10, seed=0, beam_grid=128, beam_window=8.0, threads=0
        ),
    )
    assert abs(raw.radius_last[0] / s.beam.radius(1000.0) - 1) < D1_RTOL


def test_rt_mean_is_the_long_term_beam():
    s, z, t = lo.paper_table1(), np.array([150.0, 250.0, 600.0]), lo.Turbulence(3e-14)
    # the transmitted beam's physics: the return path unperturbed
    res = lo.overlap(s, z, "rt", turbulence=t, realizations=400, seed=3, paths="transmit")
    for i, zi in enumerate(z):
        lt = t.long_term_radius(s.beam.wavelength, s.beam.waist_radius, zi)
        beam = dataclasses.replace(
            s.beam, divergence=math.sqrt(lt**2 - s.beam.waist_radius**2) / zi
        )
        expected = lo.overlap(dataclasses.replace(s, beam=beam), [zi], "rt").overlap[0]
        assert abs(res.overlap[i] - expected) < MEAN_SIGMAS * res.error_estimate[i] + 1e-6
    assert (
        np.all(res.std > 0) and np.all(res.low <= res.overlap) and np.all(res.overlap <= res.high)
    )
    again = lo.overlap(s, z, "rt", turbulence=t, realizations=400, seed=3, paths="transmit")
    assert np.array_equal(again.realizations, res.realizations)  # reproducible with the seed


def test_split_step_without_screens_gives_the_fo_overlap():
    s, z = lo.paper_table1(), np.geomspace(50, 2000, 12)
    raw = _core.overlap_fo_turbulent(
        s._native,
        z,
        lo.Turbulence(0.0)._native,
        _core.TurbulenceOptions(
            realizations=1, screens=10, seed=0, beam_grid=128, beam_window=8.0, threads=0
        ),
    )
    assert np.max(np.abs(raw.overlap[0] - lo.overlap(s, z, "fo").overlap)) < SPLIT_STEP_ATOL


def gradient_law(cn2, L, width2, inner_scale):
    """4 pi^2 int_0^L (L - z)^2 dz int_0^inf kappa^3 Phi_n exp(-kappa^2 (width2 / 4 + 1 /
    kappa_m^2)) dkappa for Phi_n = 0.033 Cn^2 kappa^(-11/3) and kappa_m = 5.92 / l0: the
    displacement at L of layers' phase gradients averaged over a Gaussian of 1/e^2 radius^2 width2
    (m^2)."""
    scale2 = width2 / 4 + (inner_scale / 5.92) ** 2
    return 4 * math.pi**2 * 0.033 * math.gamma(1 / 6) / 6 * cn2 * L**3 * scale2 ** (-1 / 6)


def test_fo_screens_wander_and_spread_a_collimated_beam():
    """Second-order laws of thin screens (paraxial, any strength). A screen tilts the centroid by
    its phase
    gradient averaged over the irradiance: <r_c^2> (2-D) = gradient_law(W0^2), 1.52 Cn^2 L^3
    W0^(-1/3) for l0 = 0 (Klyatskin & Kon 1972). It adds its whole gradient variance to the
    mean-square angle: the second moment of the long-term irradiance grows by W_LT^2 - W^2 = 2
    gradient_law(0) (1/e^2 radii, W^2 = 2 <rho^2>), per realisation W_ST^2 + 2 |r_c|^2. With l0 = 0
    that moment diverges (wings of scattered light) and the grid's Nyquist frequency sets it: 1.40
    and 1.68 times 1.33 sigma_R^2 Lambda^(5/6) W^2 on 128^2 and 256^2 grids. Andrews & Phillips'
    W_LT is the Gaussian core of the mean irradiance (the FO core gives their T within 10 %), and
    their 2.42 Cn^2 L^3 W0^(-1/3) is 2 gradient_law(4 W0^2), the large-scale part of that W_LT^2:
    2^(2/3) = 1.59 times the centroid variance."""
    w0, L, cn2, l0 = 5e-2, 1000.0, 1e-14, 0.02
    s, t = lo.paper_table1(wavelength=LAM, waist_radius=w0), lo.Turbulence(cn2, inner_scale=l0)
    raw = _core.overlap_fo_turbulent(
        s._native,
        [L],
        t._native,
        _core.TurbulenceOptions(
            realizations=STATS_REALIZATIONS,
            screens=10,
            seed=1,
            beam_grid=128,
            beam_window=8.0,
            threads=0,
        ),
    )
    wx, wy, r = raw.wander_x, raw.wander_y, raw.radius_last
    wander = np.mean(wx**2 + wy**2)
    spread = np.mean(r**2 + 2 * (wx**2 + wy**2)) - s.beam.radius(L) ** 2
    assert abs(wander / gradient_law(cn2, L, w0**2, l0) - 1) < WANDER_RTOL
    assert abs(spread / (2 * gradient_law(cn2, L, 0.0, l0)) - 1) < SPREAD_RTOL


def test_fo_turbulent_overlap_is_reproducible_and_spread():
    s, z, t = lo.paper_table1(), np.array([200.0, 500.0]), lo.Turbulence(2e-14)
    common = dict(turbulence=t, realizations=6, seed=7, beam_grid=128, paths="transmit")
    a = lo.overlap(s, z, "fo", **common)
    b = lo.overlap(s, z, "fo", **common, threads=1)
    assert np.array_equal(a.realizations, b.realizations)  # whatever the thread count
    assert np.all(a.std > 0)


def test_bad_turbulence_input():
    with pytest.raises(ValueError, match="cn2"):
        lo.Turbulence(-1e-14)
    with pytest.raises(ValueError, match="elevation"):
        lo.Turbulence(1e-14, elevation=2.0)
    with pytest.raises(ValueError, match="turbulence = "):
        lo.overlap(lo.paper_table1(), [100.0], "rt", turbulence=1e-14)
    with pytest.raises(ValueError, match="realizations"):
        lo.overlap(
            lo.paper_table1(), [100.0], "rt", turbulence=lo.Turbulence(1e-14), realizations=0
        )


@pytest.mark.parametrize(
    "cn2, w0, L", [(1e-14, 0.05, 2000.0), (3e-15, 1e-3, 500.0), (1e-13, 0.2, 10e3)]
)
def test_beam_quantities_take_wavelength_first(cn2, w0, L):
    """(wavelength, waist_radius, path_length): the closed form 2.42 Cn² L³ W0^(-1/3) of the wander,
    and the same numbers as the core's (waist_radius, wavelength, path_length) for the same physical
    inputs."""
    t = lo.Turbulence(cn2)
    assert (
        abs(t.beam_wander_variance(LAM, w0, L) / (2.42 * cn2 * L**3 * w0 ** (-1 / 3)) - 1)
        < CLOSED_FORM_RTOL
    )
    for name in ("beam_wander_variance", "long_term_radius", "short_term_radius"):
        value = getattr(t, name)(LAM, w0, L)
        assert value == getattr(t._native, name)(w0, LAM, L)
        assert value == getattr(t, name)(path_length=L, waist_radius=w0, wavelength=LAM)
    lt, st = t.long_term_radius(LAM, w0, L), t.short_term_radius(LAM, w0, L)
    assert abs(lt**2 - st**2 - t.beam_wander_variance(LAM, w0, L)) <= 1e-12 * lt**2


def test_turbulence_is_an_immutable_value():
    t = lo.Turbulence(1e-14, elevation=0.5, outer_scale=20.0)
    for name in (
        "cn2",
        "elevation",
        "altitude",
        "outer_scale",
        "inner_scale",
        "hv_ground",
        "hv_wind",
        "_native",
    ):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(t, name, 1.0)
    assert (t.elevation, t.altitude, t.outer_scale, t.inner_scale) == (0.5, 0.0, 20.0, 0.0)
    assert t == lo.Turbulence(1e-14, elevation=0.5, outer_scale=20.0)
    steeper = dataclasses.replace(t, elevation=1.0)
    assert (steeper.elevation, t.elevation, steeper.outer_scale) == (1.0, 0.5, 20.0)
    assert steeper.cn2_at_range(100.0) == 1e-14
    with pytest.raises(ValueError, match="^elevation = "):
        dataclasses.replace(t, elevation=2.0)


# --------------------------------------------------------------------------------- hostile input
NON_REALS = [None, "1", "", True, 10**400, -(10**400), (1.0, 2.0, 3.0), [1e-3], {}]
PATH_ARGUMENTS = {
    "fried_parameter": ("wavelength", "path_length"),
    "rytov_variance": ("wavelength", "path_length"),
    "isoplanatic_angle": ("wavelength", "path_length"),
    "beam_wander_variance": ("wavelength", "waist_radius", "path_length"),
    "long_term_radius": ("wavelength", "waist_radius", "path_length"),
    "short_term_radius": ("wavelength", "waist_radius", "path_length"),
}
SANE_PATH = {"waist_radius": 1e-3, "wavelength": 1064e-9, "path_length": 1000.0}


@pytest.mark.parametrize("value", NON_REALS)
@pytest.mark.parametrize(
    "method, argument", [(m, a) for m, args in PATH_ARGUMENTS.items() for a in args]
)
def test_path_methods_refuse_non_numbers_by_name(method, argument, value):
    """No pybind11 signature dump: each argument is converted, and refused by its own name, before
    the core."""
    args = {a: SANE_PATH[a] for a in PATH_ARGUMENTS[method]}
    args[argument] = value
    with pytest.raises(ValueError, match=f"^{argument} = "):
        getattr(lo.Turbulence(1e-14), method)(**args)


@pytest.mark.parametrize("value", [math.nan, math.inf, 0.0, -0.0, 5e-324, 1e-300, 1e300, 2**63])
@pytest.mark.parametrize("method", sorted(PATH_ARGUMENTS))
def test_path_lengths_outside_the_scales_are_refused_by_name(method, value):
    args = {a: SANE_PATH[a] for a in PATH_ARGUMENTS[method]}
    args["path_length"] = value
    with pytest.raises(ValueError, match="^path_length = "):
        getattr(lo.Turbulence("hv57"), method)(**args)


@pytest.mark.parametrize("value", NON_REALS + [math.nan, math.inf, -1.0, -5e-324, 1e300, 2**63])
def test_cn2_at_range_refuses_z_by_name(value):
    with pytest.raises(ValueError, match="^z = "):
        lo.Turbulence(1e-14).cn2_at_range(value)


@pytest.mark.parametrize("z", [0.0, -0.0, 5e-324, 1e10])
def test_cn2_at_range_takes_every_range_of_the_scales(z):
    assert lo.Turbulence(3e-15).cn2_at_range(z) == 3e-15  # a constant profile


@pytest.mark.parametrize("value", NON_REALS + [math.nan, 0.0, -1.0, 5e-324])
def test_outer_scale_refused_by_name(value):
    with pytest.raises(ValueError, match="^outer_scale = "):
        lo.Turbulence(1e-14, outer_scale=value)


@pytest.mark.parametrize("answer", [math.nan, math.inf, -1e-15, 1.0, "1e-14", None, True, 10**400])
def test_a_custom_profile_answer_is_refused_naming_cn2(answer):
    with pytest.raises(
        ValueError, match=r"^cn2\([^)]* m\) = "
    ):  # the height the quadrature asked for
        lo.Turbulence(lambda h: answer).rytov_variance(LAM, 1000.0)


def test_a_custom_constant_profile_is_the_constant():
    custom, constant = lo.Turbulence(lambda h: 1e-14), lo.Turbulence(1e-14)
    assert (
        abs(custom.rytov_variance(LAM, 2000.0) / constant.rytov_variance(LAM, 2000.0) - 1)
        < CLOSED_FORM_RTOL
    )


@pytest.mark.parametrize("law", ["gaussian", "linear"])
def test_rt_realisation_beam_has_the_short_term_radius_on_either_width_law(law):
    """The beam each RT realisation traces has radius W_ST at its range, whatever the beam's width
    law."""
    from lidar_overlap.forward.backends.turbulent import beam_for

    beam, z, radius = lo.GaussianBeam(width_law=law), 150.0, 0.06
    drawn = beam_for(beam, z, radius, (0.01, -0.02))
    assert abs(drawn.radius(z) / radius - 1) < 1e-12
    assert drawn.center(z) == pytest.approx((0.01, -0.02), abs=1e-15)


@pytest.mark.parametrize("cn2, z", [(1e-9, 1e9), (1e-9, 1e10)])
def test_rt_turbulence_beyond_the_paraxial_model_names_ranges_and_turbulence(cn2, z):
    """Strong turbulence over a long path spreads the short-term beam beyond 1 rad: refused naming
    the range and the turbulence, not the internal beam.divergence."""
    with pytest.raises(
        ValueError, match=r"^ranges\[0\] = .* with turbulence = Turbulence\(cn2="
    ) as info:
        lo.overlap(lo.paper_table1(), [z], "rt", turbulence=lo.Turbulence(cn2), realizations=2)
    assert "beam.divergence" not in str(info.value)


def test_rt_turbulence_with_a_beam_axis_beyond_the_lengths_names_ranges():
    s = lo.paper_table1()
    tilted = dataclasses.replace(
        s, beam=dataclasses.replace(s.beam, tilt=(1.0, 0.0), offset=(0.01, 0.0))
    )
    with pytest.raises(
        ValueError, match=r"^ranges\[0\] = 10000000000\.0 m with turbulence = .*smaller tilt"
    ):
        lo.overlap(tilted, [1e10], "rt", turbulence=lo.Turbulence(1e-14), realizations=2)


@pytest.mark.parametrize("cn2", [1e-9, 1e-12, "hv57"])
@pytest.mark.parametrize("z", [1e5, 1e6])
@pytest.mark.parametrize("waist", [1e-3, 1e-6])
def test_rt_turbulence_strong_long_and_tiny_gives_overlaps_in_the_unit_interval(cn2, z, waist):
    s = lo.paper_table1(waist_radius=waist)
    res = lo.overlap(s, [z], "rt", turbulence=lo.Turbulence(cn2), realizations=3)
    for values in (res.overlap, res.low, res.high, res.realizations):
        assert np.all(np.isfinite(values)) and np.all((values >= 0) & (values <= 1))


@pytest.mark.parametrize(
    "ranges, name",
    [([0.0], r"ranges\[0\]"), ([100.0, 2e10], r"ranges\[1\]"), ([1e-300], r"ranges\[0\]")],
)
def test_rt_turbulence_refuses_ranges_by_index(ranges, name):
    with pytest.raises(ValueError, match=f"^{name} = "):
        lo.overlap(
            lo.paper_table1(), ranges, lo.Turbulent(lo.Turbulence(1e-14), "rt", realizations=2)
        )


def test_rt_turbulence_refuses_realisations_beyond_the_cap_and_the_budget():
    s, t = lo.paper_table1(), lo.Turbulence(1e-14)
    with pytest.raises(ValueError, match="^realizations = 2147483648 is invalid"):
        lo.overlap(s, [100.0], "rt", turbulence=t, realizations=2**31)
    with pytest.raises(ValueError, match=r"^realizations = 1000000 needs .* \(max_memory\)"):
        lo.overlap(s, np.arange(1.0, 100001.0), "rt", turbulence=t, realizations=10**6)


@pytest.mark.parametrize(
    "value", [np.array(["plane", "spherical"]), np.array(["plane"]), ["plane"], None, b"plane"]
)
def test_fried_parameter_refuses_a_wave_that_is_not_a_string_by_name(value):
    with pytest.raises(ValueError, match="^wave = "):
        lo.Turbulence(1e-14).fried_parameter(LAM, 1000.0, value)
