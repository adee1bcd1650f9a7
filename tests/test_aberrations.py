"""Receiver aberrations: Zernike polynomials, Seidel conversion, point image and the aberrated
overlap paths, against closed forms and independent computations."""

import dataclasses
import math

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import with_aberrations

ORTHONORMALITY_TOL = 1e-12  # Gauss quadrature exact for these polynomials
GRADIENT_TOL = 1e-7  # central differences, step 1e-5
STREHL_QUADRATURE_TOL = 2e-4  # sampled pupil (edge pixels) against a polar Gauss rule
MARECHAL_TOL = 0.01  # exp(-sigma_phi^2) against the exact Strehl for sigma <= lambda / 14
Z4_FO_TOL = 2e-6  # FO aberrated path: its sampling accuracy (docs/aberrations.md)
Z4_RT_TOL = 1e-8  # RT pupil form against the exact circle geometry
RT_FO_LARGE_BLUR_TOL = 5e-3  # RT's diffraction floor for Table 1 (docs/auto_method.md: ~3.5e-3)
RAY_FAN_TOL = 3e-4  # ray fan of 48 x 128 rays against the pupil form

F, D = 1.0, 0.15
R = D / 2
BASE = lo.paper_table1()


def polar_rule(n_rho=40, n_theta=96):
    """Gauss-Legendre in rho^2 (area measure) times the trapezoid rule in theta over the unit
    disc."""
    x, w = np.polynomial.legendre.leggauss(n_rho)
    rho = np.sqrt(0.5 * (x + 1))
    theta = 2 * np.pi * np.arange(n_theta) / n_theta
    rr, tt = np.meshgrid(rho, theta, indexing="ij")
    weights = np.repeat(
        0.5 * w[:, None] / n_theta, n_theta, axis=1
    )  # sums to 1 (mean over the disc)
    return rr * np.cos(tt), rr * np.sin(tt), weights


def test_noll_indices_follow_noll():
    expected = {
        1: (0, 0),
        2: (1, 1),
        3: (1, -1),
        4: (2, 0),
        5: (2, -2),
        6: (2, 2),
        7: (3, -1),
        8: (3, 1),
        9: (3, -3),
        10: (3, 3),
        11: (4, 0),
        12: (4, 2),
        13: (4, -2),
        16: (5, 1),
        22: (6, 0),
    }
    for j, nm in expected.items():
        assert lo.noll_index(j) == nm


def test_zernike_closed_forms():
    rng = np.random.default_rng(1)
    x, y = rng.uniform(-0.7, 0.7, (2, 50))
    rho2, theta = x * x + y * y, np.arctan2(y, x)
    rho = np.sqrt(rho2)
    forms = {
        4: math.sqrt(3) * (2 * rho2 - 1),
        6: math.sqrt(6) * rho2 * np.cos(2 * theta),
        8: math.sqrt(8) * (3 * rho**3 - 2 * rho) * np.cos(theta),
        11: math.sqrt(5) * (6 * rho2**2 - 6 * rho2 + 1),
    }
    for j, value in forms.items():
        np.testing.assert_allclose(lo.zernike(j, x, y), value, atol=1e-13)


def test_zernike_orthonormal_on_the_pupil():
    x, y, w = polar_rule()
    z = np.array([lo.zernike(j, x, y) for j in range(1, 29)])
    gram = np.einsum("iab,jab,ab->ij", z, z, w)
    np.testing.assert_allclose(gram, np.eye(28), atol=ORTHONORMALITY_TOL)


def test_wavefront_gradient_matches_finite_differences():
    ab = lo.Aberrations(
        zernike={5: 30e-9, 8: -20e-9, 11: 50e-9, 16: 10e-9},
        w040=40e-9,
        w131=30e-9,
        w222=20e-9,
        w220=-10e-9,
        w311=5e-9,
        field_radius=1e-3,
    )
    rng = np.random.default_rng(2)
    x, y = rng.uniform(-0.6, 0.6, (2, 20))
    field = (0.4e-3, -0.3e-3)
    gx, gy = ab._native.gradient(x, y, field)
    h = 1e-5
    fx = (ab.wavefront(x + h, y, field) - ab.wavefront(x - h, y, field)) / (2 * h)
    fy = (ab.wavefront(x, y + h, field) - ab.wavefront(x, y - h, field)) / (2 * h)
    np.testing.assert_allclose(gx, fx, atol=GRADIENT_TOL * 1e-6)
    np.testing.assert_allclose(gy, fy, atol=GRADIENT_TOL * 1e-6)


def test_seidel_to_zernike_is_exact_and_reversible():
    seidel = lo.Aberrations(
        w040=80e-9, w131=-50e-9, w222=30e-9, w220=20e-9, w311=10e-9, field_radius=2e-3
    )
    field = (1.2e-3, 0.9e-3)
    z = lo.seidel_to_zernike(seidel, field)
    x, y, _ = polar_rule(10, 24)
    diff = seidel.wavefront(x, y, field) - z.wavefront(x, y)
    assert np.ptp(diff) < 1e-20  # equal up to piston
    at_edge = lo.seidel_to_zernike(seidel, (2e-3, 0.0))
    back = lo.zernike_to_seidel(at_edge, field_radius=2e-3)
    for name in ("w040", "w131", "w222", "w220", "w311"):
        assert getattr(back, name) == pytest.approx(getattr(seidel, name), abs=1e-22)
    with pytest.raises(ValueError, match="no Seidel counterpart"):
        lo.zernike_to_seidel(lo.Aberrations(zernike={7: 1e-8}), 1e-3)


def exact_strehl(ab, wavelength):
    x, y, w = polar_rule(64, 128)
    return abs(np.sum(w * np.exp(2j * np.pi * ab.wavefront(x, y) / wavelength))) ** 2


@pytest.mark.parametrize("term", [4, 6, 8, 11])
def test_strehl_ratio_against_quadrature_and_marechal(term):
    lam = BASE.beam.wavelength
    system = lo.paper_table1(defocus=1e-3)
    z = lo.optimal_focus_range(F, 1e-3)  # the detector plane is the image plane
    sigma = lam / 16
    ab = lo.Aberrations(zernike={term: sigma})
    ideal = lo.point_image(system, z, n=512)  # 256 samples across the pupil
    aberrated = lo.point_image(with_aberrations(system, ab), z, n=512)
    c = 256
    strehl = abs(aberrated.values[c, c]) ** 2 / abs(ideal.values[c, c]) ** 2
    assert strehl == pytest.approx(exact_strehl(ab, lam), abs=STREHL_QUADRATURE_TOL)
    assert strehl == pytest.approx(math.exp(-((2 * np.pi * sigma / lam) ** 2)), abs=MARECHAL_TOL)


def test_point_image_keeps_the_power_the_pupil_passes():
    """A phase aberration moves light, never removes it: the aberrated image holds the ideal one's
    power (the transform is unitary), which is the pupil's area up to its edge pixels (about 0.42
    spacing / R short)."""
    system = lo.paper_table1(defocus=1e-3)

    def power(s):
        image = lo.point_image(s, 1000.0, n=512)
        return (np.abs(image.values) ** 2).sum() * image.spacing**2

    ideal = power(system)
    assert power(
        with_aberrations(system, lo.Aberrations(zernike={8: 0.3e-6, 11: 0.2e-6}))
    ) == pytest.approx(ideal, rel=1e-12)
    assert ideal == pytest.approx(1.0, abs=0.42 * 2 / 256 * 1.5)


@pytest.mark.parametrize("defocus", [1e-3, -0.5e-3])
def test_zernike_defocus_reproduces_detector_defocus(defocus):
    """Z4 in the pupil of a receiver focused at infinity is the detector moved by `defocus`, with
    the whole detector-plane picture scaled by f/d: the same overlap once the detector radius is
    scaled too."""
    z = np.array([30.0, 100.0, 300.0, 1000.0, 3000.0])
    moved = lo.paper_table1(defocus=defocus)
    d = F + defocus
    c4 = (1 / d - 1 / F) * R**2 / (4 * math.sqrt(3))
    in_pupil = dataclasses.replace(
        moved, detector=lo.Detector(radius=moved.detector.radius * F / d)
    )
    in_pupil = with_aberrations(in_pupil, lo.Aberrations(zernike={4: c4}))
    fo = lo.overlap(in_pupil, z, "fo").overlap
    np.testing.assert_allclose(fo, lo.overlap(moved, z, "fo").overlap, atol=Z4_FO_TOL)
    rt = lo.overlap(in_pupil, z, "rt", tolerance=1e-9).overlap
    np.testing.assert_allclose(
        rt, lo.overlap(moved, z, "rt", tolerance=1e-9).overlap, atol=Z4_RT_TOL
    )


def test_rt_and_fo_agree_when_the_blur_dwarfs_the_airy_disc():
    # 1 um RMS spherical + 0.5 um astigmatism: a blur ~0.35 mm, 120 Airy radii.
    system = with_aberrations(BASE, lo.Aberrations(zernike={6: 0.5e-6, 11: 1e-6}))
    z = np.array([300.0, 1000.0, 3000.0])
    rt, fo = lo.overlap(system, z, "rt").overlap, lo.overlap(system, z, "fo").overlap
    np.testing.assert_allclose(rt, fo, atol=RT_FO_LARGE_BLUR_TOL)
    ideal = lo.overlap(BASE, z, "fo").overlap
    assert np.all((ideal - fo)[:2] > 2 * RT_FO_LARGE_BLUR_TOL)  # the aberrations do matter here


def test_ray_fan_agrees_with_the_pupil_form():
    """Seidel W040 traced ray by ray (an NA of 0.99 filters nothing but forces the ray fan) against
    its Zernike form in the pupil integral."""
    w040 = 2e-6
    z = np.array([100.0, 400.0, 2000.0])
    fan = dataclasses.replace(
        BASE, detector=dataclasses.replace(BASE.detector, numerical_aperture=0.99)
    )
    fan = with_aberrations(fan, lo.Aberrations(w040=w040))
    pupil = with_aberrations(
        BASE, lo.Aberrations(zernike={4: w040 / (2 * math.sqrt(3)), 11: w040 / (6 * math.sqrt(5))})
    )
    np.testing.assert_allclose(
        lo.overlap(fan, z, "rt", tolerance=1e-6).overlap,
        lo.overlap(pupil, z, "rt", tolerance=1e-6).overlap,
        atol=RAY_FAN_TOL,
    )


def test_distortion_moves_each_image_by_d_grad_w():
    """W311 is a tilt growing as H^3: a scatterer at field angle phi lands d W311 H^2 h / R further
    along h."""
    w311, field_radius, z = 20e-6, 1e-3, 500.0
    position = (0.2, 0.1)  # m at z: field angle (4e-4, 2e-4) rad
    h = np.array(position) / z / field_radius
    shift = F * w311 * (h @ h) * h / R  # m on the detector plane
    distorted = with_aberrations(BASE, lo.Aberrations(w311=w311, field_radius=field_radius))
    moved = dataclasses.replace(
        BASE, detector=dataclasses.replace(BASE.detector, offset=tuple(-shift))
    )
    assert lo.emitter_coupling(distorted, z, position) == pytest.approx(
        lo.emitter_coupling(moved, z, position), abs=RAY_FAN_TOL
    )
    assert (
        abs(lo.emitter_coupling(distorted, z, position) - lo.emitter_coupling(BASE, z, position))
        > 100 * RAY_FAN_TOL
    )


def test_bad_input_names_the_parameter():
    with pytest.raises(ValueError, match="field_radius"):
        lo.Aberrations(w222=1e-7)
    with pytest.raises(ValueError, match="Noll index"):
        lo.Aberrations(zernike={0: 1e-7})
    with pytest.raises(ValueError, match="aberrations.zernike\\[4\\]"):
        lo.Aberrations(zernike={4: float("nan")})
    with pytest.raises(ValueError, match="telescope.aberrations"):
        lo.Telescope(aberrations={11: 1e-7})
    seidel = with_aberrations(BASE, lo.Aberrations(w131=1e-7, field_radius=1e-3))
    with pytest.raises(ValueError, match="method 'rt'"):
        lo.overlap(seidel, [1000.0], "fo")
    spherical = with_aberrations(BASE, lo.Aberrations(zernike={11: 1e-7}))
    with pytest.raises(ValueError, match="turbulence"):
        lo.overlap(spherical, [1000.0], "fo", turbulence=lo.Turbulence(1e-14))
    with pytest.raises(ValueError, match="max_grid.*'rt'"):
        lo.overlap(spherical, [5.0], "fo")


@pytest.mark.parametrize("tolerance, chosen", [(2e-2, "rt"), (1e-3, "fo")])
def test_auto_with_aberrations_meets_its_tolerance(tolerance, chosen):
    system = with_aberrations(BASE, lo.Aberrations(zernike={6: 0.3e-6, 11: 0.5e-6}))
    z = np.geomspace(150.0, 3000.0, 12)
    res = lo.overlap(system, z, "auto", tolerance=tolerance)
    assert res.method == chosen
    reference = lo.overlap(system, z, "fo").overlap
    assert np.max(np.abs(res.overlap - reference)) <= tolerance
    assert np.all(
        np.abs(res.overlap - reference) <= res.error_estimate + 1e-6
    )  # the estimate covers it


def test_aberrated_ray_tracing_warns_outside_its_validity():
    """A 5 um fibre (1.7 Airy radii) is as far outside geometric optics with aberrations as
    without."""
    fibre = dataclasses.replace(BASE, detector=lo.Detector(radius=5e-6))
    with pytest.warns(RuntimeWarning, match="outside its validity"):
        lo.overlap(with_aberrations(fibre, lo.Aberrations(zernike={11: 0.1e-6})), [1000.0], "rt")
