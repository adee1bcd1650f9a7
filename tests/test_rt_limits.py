"""Ray-tracing overlap G(z) against closed forms derived from the paraxial geometry.

Geometry (receiver aperture stop at z = 0, thin lens f, aperture radius R, detector plane d = f +
defocus behind the lens, detector radius r_d): a ray from scatterer P at range z through aperture
point A lands on the detector plane at A c - P d/z with c = 1 + d/z - d/f.  The limits checked here
are:

- point aperture (R -> 0): G = 1 - exp(-2 (r_d z/d)^2 / w(z)^2), the Gaussian power inside the field
  of view;
- thin beam (w -> 0): G = coupling of one scatterer = (detector disc ∩ circle of confusion) / circle
  area, computed with the two-circle lens-area formula (paper B19), min(1, (r_d / (R|c|))^2) when
  concentric;
- central obstruction: far-range plateau 1 - (r_obs/R)^2, on-axis signal onset z = r_obs f / r_d +
  z_obs;
- defocus: best-focus range z_opt = f (f + defocus) / defocus (paper Eq. 5), where c = 0;
- numerical properties: obstruction never adds signal, tolerance is honoured, threads do not change
  results.
"""

import dataclasses

import numpy as np
import pytest

import lidar_overlap as lo

# Tolerance passed to lo.overlap in the closed-form checks: far below the assertion tolerances.
ENGINE_TOL = 1e-8
# Point-aperture limit: D = 1e-7 m shifts the accepted scatterer disc by |A| <= 5e-8 m against a
# beam radius >= 1e-3 m; the first-order effect averages out over the aperture, the rest is
# ~(5e-5)^2. What remains is the engine tolerance (1e-8) plus rounding: 1e-6 leaves a wide margin.
POINT_APERTURE_ATOL = 1e-6
# Thin beam (w0 = 1e-9 m, 1e-12 rad): the point image is smeared by <= ~1e-9 m against a detector
# radius of 4.5e-4 m; where the circle of confusion and the detector have equal radii the coupling
# changes at first order, by ~2 * 1e-9 / (pi * 4.5e-4) ~ 1.4e-6. 1e-5 covers that and the engine
# tolerance.
THIN_BEAM_ATOL = 1e-5
# Far-range obstruction: with the paper beam the whole beam images well inside the detector at z >=
# 1e4 m (Gaussian tail beyond 4 m at w = 1.1 m is ~exp(-30)), so the only terms are the exact shadow
# size and the engine tolerance.
FAR_OBSTRUCTION_ATOL = 1e-7
# The plateau value 1 - (r_obs/R)^2 ignores the shadow magnification z/(z - z_obs): at z = 1e4 m the
# difference is (r_obs/R)^2 * 2 * 0.7/1e4 <= 4e-5 for r_obs = 40 mm.
FAR_PLATEAU_ATOL = 5e-5
# "Zero" signal: below the thin-beam onset the accepted and blocked regions are separated by >= 2e-5
# m, i.e. 2e4 residual beam radii: the engine must return 0 up to rounding.
ZERO_SIGNAL = 1e-12
# Exactly focused thin beam: every ray reaches the image point, G = 1 up to rounding and tolerance.
FOCUS_ATOL = 1e-9

F = 1.0  # Table 1 focal length (m)
R = 0.075  # Table 1 aperture radius (m)
R_D = 0.45e-3  # Table 1 detector radius = FOV * f / 2 (m)
Z_OBS = 0.7  # obstruction distance of Section 4A (m)

THIN = dict(
    waist_radius=1e-9, divergence=1e-12, width_law="linear"
)  # a geometric pencil beam (M^2 < 1 needs the linear law)


def beam_radius(z, w0, theta, width_law):
    """1/e^2 radius of the Gaussian beam (DESIGN section 3)."""
    if width_law == "gaussian":
        return np.sqrt(w0**2 + (theta * z) ** 2)
    return w0 + theta * z


def lens_area(r1, r2, dist):
    """Area of intersection of two discs of radii r1, r2 with centres dist apart (paper B19)."""
    if dist >= r1 + r2:
        return 0.0
    if dist <= abs(r1 - r2):
        return np.pi * min(r1, r2) ** 2
    a1 = np.arccos((dist**2 + r1**2 - r2**2) / (2 * dist * r1))
    a2 = np.arccos((dist**2 + r2**2 - r1**2) / (2 * dist * r2))
    k = np.sqrt((-dist + r1 + r2) * (dist + r1 - r2) * (dist - r1 + r2) * (dist + r1 + r2))
    return r1**2 * a1 + r2**2 * a2 - 0.5 * k


def point_coupling(z, p, defocus=0.0, det_offset=(0.0, 0.0)):
    """Unobstructed coupling of one scatterer at transverse p and range z in the Table 1
    receiver."""
    d = F + defocus
    c = 1 + d / z - d / F
    rho = R * abs(c)
    centre = -np.asarray(p, float) * d / z
    dist = float(np.hypot(*(centre - np.asarray(det_offset, float))))
    if rho == 0.0:
        return 1.0 if dist <= R_D else 0.0
    return lens_area(R_D, rho, dist) / (np.pi * rho**2)


# --- point-aperture limit -------------------------------------------------------------------------


# A 0.1 µm aperture is far outside geometric optics (the library warns so); the test checks the
# ray-tracing model itself in that limit.
@pytest.mark.filterwarnings("ignore:ray tracing outside its validity")
@pytest.mark.parametrize("width_law", ["gaussian", "linear"])
@pytest.mark.parametrize("divergence", [None, 0.5e-3])
def test_point_aperture_limit(width_law, divergence):
    wavelength, w0 = 355e-9, 1e-3
    system = lo.LidarSystem(
        beam=lo.GaussianBeam(
            wavelength=wavelength, waist_radius=w0, divergence=divergence, width_law=width_law
        ),
        telescope=lo.Telescope(diameter=1e-7, focal_length=F),
        detector=lo.Detector(radius=R_D),
    )
    z = np.geomspace(1.0, 2000.0, 80)
    theta = wavelength / (np.pi * w0) if divergence is None else divergence
    w = beam_radius(z, w0, theta, width_law)
    alpha = R_D / F
    expected = 1.0 - np.exp(-2.0 * (alpha * z) ** 2 / w**2)
    res = lo.overlap(system, z, tolerance=ENGINE_TOL)
    np.testing.assert_allclose(res.overlap, expected, rtol=0, atol=POINT_APERTURE_ATOL)
    # the two width laws differ by far more than the tolerance, so the law is really being used
    other = "linear" if width_law == "gaussian" else "gaussian"
    assert (
        np.max(
            np.abs(
                expected
                - (1 - np.exp(-2 * (alpha * z) ** 2 / beam_radius(z, w0, theta, other) ** 2))
            )
        )
        > 0.01
    )


# --- thin-beam limit ------------------------------------------------------------------------------


@pytest.mark.parametrize("defocus", [0.0, 2e-3, 5e-3, -3e-3])
def test_thin_beam_on_axis(defocus):
    system = lo.paper_table1(defocus=defocus, **THIN)
    z = np.geomspace(1.0, 1e5, 150)
    d = F + defocus
    rho = R * np.abs(1 + d / z - d / F)
    with np.errstate(divide="ignore"):
        expected = np.minimum(1.0, (R_D / rho) ** 2)
    res = lo.overlap(system, z, tolerance=ENGINE_TOL)
    np.testing.assert_allclose(res.overlap, expected, rtol=0, atol=THIN_BEAM_ATOL)
    if defocus == 0.0:  # focused on infinity: (r_d z / (f R))^2 below z = f R / r_d = 166.7 m
        near = z < F * R / R_D
        np.testing.assert_allclose(
            res.overlap[near], (R_D * z[near] / (F * R)) ** 2, atol=THIN_BEAM_ATOL
        )


@pytest.mark.parametrize("z", [30.0, 100.0, 400.0])
@pytest.mark.parametrize("px", [0.0, 0.01, 0.04, 0.08, 0.2])
@pytest.mark.parametrize("det_offset", [(0.0, 0.0), (0.2e-3, -0.1e-3)])
def test_thin_beam_off_axis_lens_area(z, px, det_offset):
    """An offset thin beam images to a circle of confusion centred at -P d/z: coupling = lens area /
    circle."""
    base = lo.paper_table1(**THIN)
    system = dataclasses.replace(
        base,
        beam=dataclasses.replace(base.beam, offset=(px, 0.0)),
        detector=dataclasses.replace(base.detector, offset=det_offset),
    )
    expected = point_coupling(z, (px, 0.0), det_offset=det_offset)
    got = lo.overlap(system, [z], tolerance=ENGINE_TOL).overlap[0]
    assert got == pytest.approx(expected, abs=THIN_BEAM_ATOL)
    # emitter_coupling of the same single point needs no beam at all
    assert lo.emitter_coupling(system, z, position=(px, 0.0)) == pytest.approx(
        expected, abs=THIN_BEAM_ATOL
    )


# --- central obstruction --------------------------------------------------------------------------


@pytest.mark.parametrize("r_obs", [0.02, 0.04])
def test_far_range_obstruction_plateau(r_obs):
    system = lo.paper_table1(obstruction_radius=r_obs, obstruction_distance=Z_OBS)
    z = np.geomspace(1e4, 1e5, 12)
    g = lo.overlap(system, z, tolerance=ENGINE_TOL).overlap
    # the shadow of the disc on the aperture has radius r_obs z / (z - z_obs) and lies inside the
    # aperture
    exact = 1.0 - (r_obs / R) ** 2 * (z / (z - Z_OBS)) ** 2
    np.testing.assert_allclose(g, exact, rtol=0, atol=FAR_OBSTRUCTION_ATOL)
    np.testing.assert_allclose(g, 1.0 - (r_obs / R) ** 2, rtol=0, atol=FAR_PLATEAU_ATOL)


@pytest.mark.parametrize("r_obs, onset_cm", [(0.02, 4514), (0.04, 8959)])
def test_signal_onset_thin_beam(r_obs, onset_cm):
    # on axis the accepted aperture points are |A| <= r_d z / f, the blocked ones |A| < r_obs z / (z
    # - z_obs): signal starts where they meet, z = r_obs f / r_d + z_obs
    onset = r_obs * F / R_D + Z_OBS
    assert round(onset, 2) == pytest.approx(onset_cm / 100.0, abs=1e-9)
    system = lo.paper_table1(obstruction_radius=r_obs, **THIN)
    below, above = lo.overlap(system, [0.999 * onset, 1.001 * onset], tolerance=ENGINE_TOL).overlap
    assert 0.0 <= below <= ZERO_SIGNAL
    assert above > 0.0
    # and the whole curve: annulus between the shadow and the accepted disc (capped by the aperture)
    z = np.linspace(1.0, 400.0, 300)
    outer = np.minimum(R_D * z / F, R)
    inner = r_obs * z / (z - Z_OBS)
    expected = np.clip(outer**2 - inner**2, 0.0, None) / R**2
    g = lo.overlap(system, z, tolerance=ENGINE_TOL).overlap
    np.testing.assert_allclose(g, expected, rtol=0, atol=THIN_BEAM_ATOL)


@pytest.mark.parametrize("r_obs", [0.02, 0.04])
def test_wide_beam_signal_starts_before_thin_beam_onset(r_obs):
    # A scatterer at transverse P accepts aperture points in a disc centred on P (radius r_d z / f),
    # while the shadow is centred on -P z_obs / (z - z_obs): off-axis scatterers of a real beam move
    # the two apart, so light passes beside the obstruction before the on-axis onset r_obs f / r_d +
    # z_obs.
    onset = r_obs * F / R_D + Z_OBS
    z = np.linspace(5.0, 1.2 * onset, 1200)
    res = lo.overlap(lo.paper_table1(obstruction_radius=r_obs), z, tolerance=1e-6)
    first = res.first_signal_range()
    assert np.isfinite(first)
    assert first < onset
    thin = lo.overlap(lo.paper_table1(obstruction_radius=r_obs, **THIN), z, tolerance=1e-6)
    assert thin.first_signal_range() >= onset


@pytest.mark.parametrize("defocus", [0.0, 2e-3, 5e-3])
def test_obstruction_never_adds_signal(defocus):
    z = np.geomspace(1.0, 1e4, 120)
    for tilt in [(0.0, 0.0), (0.2e-3, 0.1e-3)]:
        clear = lo.paper_table1(defocus=defocus)
        clear = dataclasses.replace(clear, beam=dataclasses.replace(clear.beam, tilt=tilt))
        blocked = dataclasses.replace(clear, telescope=lo.Telescope(0.15, F, 0.02, Z_OBS))
        g_clear = lo.overlap(clear, z, tolerance=ENGINE_TOL).overlap
        g_blocked = lo.overlap(blocked, z, tolerance=ENGINE_TOL).overlap
        assert np.all(g_blocked <= g_clear + 2 * ENGINE_TOL)
        assert np.max(g_clear - g_blocked) > 0.05  # the obstruction matters on this grid


# --- defocus --------------------------------------------------------------------------------------


def test_optimal_focus_range_formula():
    assert lo.optimal_focus_range(1.0, 2e-3) == pytest.approx(1.0 * 1.002 / 0.002, rel=1e-14)
    assert lo.optimal_focus_range(1.0, 2e-3) == pytest.approx(501.0, rel=1e-12)
    assert lo.optimal_focus_range(0.5, 1e-3) == pytest.approx(0.5 * 0.501 / 1e-3, rel=1e-14)
    assert lo.optimal_focus_range(1.0, 0.0) == np.inf
    assert lo.optimal_focus_range(2.0, 0.0) == np.inf
    with pytest.raises(ValueError, match="defocus"):
        lo.optimal_focus_range(1.0, -1e-3)


@pytest.mark.parametrize("defocus", [2e-3, 5e-3, 8e-3])
def test_defocused_thin_beam_is_fully_coupled_at_z_opt(defocus):
    z_opt = lo.optimal_focus_range(F, defocus)
    g = lo.overlap(
        lo.paper_table1(defocus=defocus, **THIN),
        [0.5 * z_opt, z_opt, 2 * z_opt],
        tolerance=ENGINE_TOL,
    ).overlap
    assert g[1] == pytest.approx(1.0, abs=FOCUS_ATOL)


@pytest.mark.parametrize("defocus", [2e-3, 5e-3, 8e-3])
def test_defocused_paper_beam_peaks_at_z_opt(defocus):
    z_opt = lo.optimal_focus_range(F, defocus)
    system = lo.paper_table1(defocus=defocus)
    # At z_opt every ray of a scatterer reaches -P d/z = -P defocus/f: accepted iff |P| <= r_d f /
    # defocus, so G(z_opt) = 1 - exp(-2 (r_d f / (defocus w))^2), which is 1 to ~1e-13 for the paper
    # beam.
    w = beam_radius(z_opt, 1e-3, 355e-9 / (np.pi * 1e-3), "gaussian")
    expected = 1.0 - np.exp(-2.0 * (R_D * F / (defocus * w)) ** 2)
    z = np.sort(np.append(np.geomspace(1.0, 1e5, 400), z_opt))
    res = lo.overlap(system, z, tolerance=ENGINE_TOL)
    g_opt = res.overlap[np.searchsorted(z, z_opt)]
    assert g_opt == pytest.approx(expected, abs=FOCUS_ATOL)
    # z_opt is where G is largest, so it lies on the 0.99 plateau. (How far before z_opt the plateau
    # starts depends on the defocus: ~z_opt/3.4 for 2 mm, ~z_opt/1.6 for 8 mm, so no fixed factor is
    # asserted.)
    assert g_opt >= res.overlap.max() - FOCUS_ATOL
    assert res.full_overlap_range(0.99) < z_opt
    # beyond z_opt the circle of confusion grows again: for 8 mm G falls well below its peak far
    # away
    if defocus == 8e-3:
        assert res.overlap[-1] < 0.9 * g_opt


def test_strongly_defocused_far_range_limit():
    # Far away c -> -defocus/f: a thin beam sees a circle of confusion R defocus/f = 0.6 mm > r_d
    # for 8 mm, so G -> (r_d f / (R defocus))^2 = 0.5625 (the paper beam's larger image would lower
    # it further).
    defocus = 8e-3
    g = lo.overlap(lo.paper_table1(defocus=defocus, **THIN), [1e7], tolerance=ENGINE_TOL).overlap[0]
    d = F + defocus
    c = 1 + d / 1e7 - d / F
    assert g == pytest.approx((R_D / (R * abs(c))) ** 2, abs=THIN_BEAM_ATOL)
    assert g == pytest.approx(0.5625, abs=1e-3)


# --- numerics: tolerance, threads, convergence warning -------------------------------------------


def _cases():
    base = lo.paper_table1()
    return {
        "coaxial": base,
        "obstructed": lo.paper_table1(obstruction_radius=0.02),
        "tilted": dataclasses.replace(
            base, beam=dataclasses.replace(base.beam, tilt=(0.3e-3, 0.0))
        ),
        "detector_offset": dataclasses.replace(
            base, detector=dataclasses.replace(base.detector, offset=(0.2e-3, 0.0))
        ),
    }


@pytest.mark.parametrize("case", ["coaxial", "obstructed", "tilted", "detector_offset"])
def test_tolerance_is_honoured(case):
    system = _cases()[case]
    z = np.geomspace(1.0, 1e4, 200)
    reference = lo.overlap(system, z, tolerance=1e-9)
    assert np.all(reference.error_estimate <= 1e-9)
    for tol in (1e-3, 1e-5):
        res = lo.overlap(system, z, tolerance=tol)
        assert res.tolerance == tol
        assert np.all(res.error_estimate <= tol)
        # the reference is itself within 1e-9 of the truth
        assert np.max(np.abs(res.overlap - reference.overlap)) <= tol + 1e-9
    assert np.ptp(reference.overlap) > 0.5  # a curve that actually rises across the grid


@pytest.mark.parametrize("case", ["coaxial", "tilted", "detector_offset"])
def test_threads_do_not_change_results(case):
    system = _cases()[case]
    z = np.geomspace(1.0, 1e4, 64)
    one = lo.overlap(system, z, tolerance=1e-6, threads=1)
    two = lo.overlap(system, z, tolerance=1e-6, threads=2)
    every = lo.overlap(system, z, tolerance=1e-6, threads=0)
    assert np.array_equal(one.overlap, two.overlap)
    assert np.array_equal(one.overlap, every.overlap)
    assert np.array_equal(one.error_estimate, two.error_estimate)


def test_unconverged_integral_warns():
    base = lo.paper_table1()
    system = dataclasses.replace(base, beam=dataclasses.replace(base.beam, tilt=(0.3e-3, 0.0)))
    with pytest.warns(RuntimeWarning, match="max_segments"):
        lo.overlap(system, np.geomspace(50.0, 500.0, 5), tolerance=1e-9, max_segments=1)
