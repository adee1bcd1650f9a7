"""Ray tracing with turbulence on both paths (docs/turbulence.md, "Ray tracing on both paths"): the
angle-of-arrival variance against the spherical-wave closed form, the draws' law, the image tilt as
detector offsets averaged by an independent Monte Carlo, the transmit-only path unchanged bit for
bit, calm air, the amplification's limits and the choice auto makes."""

import dataclasses
import math
import warnings

import numpy as np
import pytest
from scipy import integrate, special

import lidar_overlap as lo
from lidar_overlap import _core
from lidar_overlap.forward.backends import turbulent as backend
from lidar_overlap.forward.backends.turbulent_return import missed_enhancement, tilts
from lidar_overlap.model.turbulence import TWO_WAY_BOUND

#: Kolmogorov spectrum constant Γ(8/3) sin(π/3) / (4π²).
KOLMOGOROV = special.gamma(8 / 3) * math.sin(math.pi / 3) / (4 * math.pi**2)
#: Per-axis G-tilt of a plane wave over a disc of diameter D per unit ∫Cn² dr, times D^(1/3):
#: 2π² 0.033 2^(1/3) ∫ x^(-2/3) (2 J1(x) / x)² dx, that integral by Weber–Schafheitlin in Γ
#: functions (Gradshteyn & Ryzhik 6.574.2).
G_TILT = (
    2
    * math.pi**2
    * KOLMOGOROV
    * 2 ** (1 / 3)
    * 4
    * special.gamma(8 / 3)
    * special.gamma(1 / 6)
    / (2 ** (8 / 3) * special.gamma(11 / 6) ** 2 * special.gamma(17 / 6))
)
#: The model's κ and path quadratures against closed forms (measured within 3e-6).
QUADRATURE_RTOL = 1e-4
#: Agreement of two Monte Carlo means, in combined standard errors.
SIGMAS = 4.0


def spherical_weighted(turbulence, z):
    """∫ Cn²(r) (1 − r/z)^(5/3) dr by scipy's adaptive quadrature."""
    value, _ = integrate.quad(
        lambda r: turbulence.cn2_at_range(r) * (1 - r / z) ** (5 / 3),
        0,
        z,
        limit=200,
        points=[z * 1e-3, z * 1e-2, z * 0.1],
    )
    return value


def test_the_g_tilt_constant_is_the_literature_one():
    """0.170 (λ/D)² (D/r0)^(5/3) per axis for a plane wave, r0 = (0.423 k² Cn² L)^(-3/5)."""
    assert abs(G_TILT / (0.170 * 0.423 * 4 * math.pi**2) - 1) < 3e-3


@pytest.mark.parametrize(
    "cn2, elevation, diameter, z",
    [(1e-14, math.pi / 2, 0.05, 1000.0), ("hv57", 0.4, 0.3, 8000.0), (3e-13, 0.1, 0.01, 200.0)],
)
def test_angle_of_arrival_is_the_spherical_wave_closed_form(cn2, elevation, diameter, z):
    t = lo.Turbulence(cn2, elevation=elevation)
    expected = G_TILT * diameter ** (-1 / 3) * spherical_weighted(t, z)
    assert abs(t.angle_of_arrival_variance(diameter, z) / expected - 1) < QUADRATURE_RTOL


def test_angle_of_arrival_with_an_outer_scale_is_the_von_karman_integral():
    """The von Kármán spectrum (κ0 = 2π / L0): the κ integral by scipy's quadrature with scipy's
    J1 at each point of the path, against the model's log grid and closed-form tail."""
    cn2, d, z, outer = 1e-14, 0.1, 2000.0, 2.0
    k0 = 2 * math.pi / outer

    def layer(t):  # the per-axis tilt of the cone's footprint d t, times the lever t²
        a = d * t / 2
        f, _ = integrate.quad(
            lambda q: (
                q**3 * (q * q + k0 * k0) ** (-11 / 6) * (2 * special.j1(q * a) / (q * a)) ** 2
            ),
            0,
            np.inf,
            limit=400,
        )
        return 2 * math.pi**2 * KOLMOGOROV * cn2 * t * t * f

    expected, _ = integrate.quad(layer, 0, 1, limit=200)  # dr = z dt, over z²
    t = lo.Turbulence(cn2, outer_scale=outer)
    got = t.angle_of_arrival_variance(d, z)
    assert abs(got / (z * expected) - 1) < 1e-3
    assert got < lo.Turbulence(cn2).angle_of_arrival_variance(d, z)  # the large eddies are gone


def test_angle_of_arrival_hostile_input_is_refused_by_name():
    t = lo.Turbulence(1e-14)
    for bad in (0.0, -0.1, math.nan, math.inf, 1e300, 2.0**-1100):
        with pytest.raises(ValueError, match="diameter"):
            t.angle_of_arrival_variance(bad, 100.0)
        with pytest.raises(ValueError, match="path_length"):
            t.angle_of_arrival_variance(0.1, bad)
    with pytest.raises(ValueError, match="diameter"):
        t.angle_of_arrival_variance("0.1", 100.0)


def tilted_lidar(tilt=0.0, offset=0.0, diameter=0.02, waist=0.01):
    """1064 nm, f = 0.2 m, a 200 um field stop (1 mrad half field of view, 15 Airy radii); the beam
    tilted towards the stop's edge."""
    return lo.LidarSystem(
        beam=lo.GaussianBeam(1064e-9, waist, offset=(offset, 0.0), tilt=(tilt, 0.0)),
        telescope=lo.Telescope(diameter, 0.2),
        detector=lo.Detector(200e-6),
    )


def run(system, z, paths, k, cn2=1e-13, seed=4, **kw):
    method = lo.Turbulent(lo.Turbulence(cn2), lo.RT(1e-6), realizations=k, seed=seed, paths=paths)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # regime and diffraction, said elsewhere
        return lo.overlap(system, z, method, **kw)


def test_transmit_is_the_old_wander_bit_for_bit():
    """paths='transmit' draws the beam wander alone, as before both paths existed: numpy's
    default_rng(seed) range by range, sd sqrt(W_LT² − W_ST²) / 2 per axis, the short-term beam
    moved by it; each draw ray traced alone."""
    system, z, k, seed = tilted_lidar(0.9e-3, 0.01), np.array([200.0, 500.0]), 3, 9
    res = run(system, z, "transmit", k, seed=seed)
    t, beam = lo.Turbulence(1e-13), system.beam
    draws = np.random.default_rng(seed).standard_normal((z.size, k, 2))
    options = _core.RtOptions()
    options.tolerance = 1e-6
    for i, zi in enumerate(z):
        st = t.short_term_radius(beam.wavelength, beam.waist_radius, zi)
        lt = t.long_term_radius(beam.wavelength, beam.waist_radius, zi)
        sigma = 0.5 * math.sqrt(lt**2 - st**2)
        for j in range(k):
            drawn = backend.beam_for(beam, zi, st, 0.0 + sigma * draws[i, j])
            native = _core.LidarSystem(
                drawn._native, system.telescope._native, system.detector._native
            )
            assert _core.overlap_rt(native, [zi], options).overlap[0] == res.realizations[j, i]
    assert res.paths == "transmit" and res.amplification is None


def test_both_paths_draw_the_stated_law():
    """The return path's tilt z α = u − c: per-axis sd the angle of arrival's, correlated with the
    wander c by −ρ; the radius the blurred one."""
    system, z, k = tilted_lidar(), np.array([300.0, 900.0]), 20000
    t = lo.Turbulence(1e-13)
    method = lo.Turbulent(t, lo.RT(), realizations=k, seed=2, paths="both")
    plan = lo.plan(system, z, method)
    short_term, wander = backend.wander(plan)
    radii, offsets = backend.draws(plan)
    moments = tilts(system, t, z)
    for i, zi in enumerate(z):
        c = wander[:, i, 0]
        own = offsets[:, i, 0] - c  # z α
        sd = zi * math.sqrt(t.angle_of_arrival_variance(system.telescope.diameter, zi))
        se = math.sqrt(2 / k)  # relative standard error of a sample sd
        assert abs(own.std() / sd - 1) < SIGMAS * se
        rho = moments.correlation[i]
        assert 0.5 < rho < 1.0  # coaxial: mostly the same eddies
        assert abs(np.corrcoef(c, own)[0, 1] + rho) < SIGMAS / math.sqrt(k)
        assert radii[i] >= short_term[i]


@pytest.mark.parametrize("diameter, tilt", [(0.02, 0.97e-3), (0.1, 0.9e-3)])
def test_the_image_tilt_is_an_offset_of_the_detector(diameter, tilt):
    """A beam whose image straddles the field stop's edge: mean G on both paths against an
    independent Monte Carlo that draws the wander c and the angle of arrival α (closed-form sd,
    correlation −ρ with c) and the blur, and ray traces the short-term beam moved by c onto the
    detector moved by d α (d the image distance): the image's tilt is a shift of the detector. The
    2 cm aperture is smaller than r0 (3.5 cm: no blur), the 10 cm one larger (a blur as large as the
    tilt)."""
    # G 0.86 and 0.97 through the return path unperturbed
    system, z = tilted_lidar(tilt=tilt, diameter=diameter), 500.0
    t = lo.Turbulence(1e-13)
    both = run(system, [z], "both", 4000)
    transmit = run(system, [z], "transmit", 4000)
    beam, f, lam = system.beam, system.telescope.focal_length, system.beam.wavelength
    st = t.short_term_radius(lam, beam.waist_radius, z)
    sigma_c = 0.5 * math.sqrt(t.long_term_radius(lam, beam.waist_radius, z) ** 2 - st**2)
    sigma_a = math.sqrt(t.angle_of_arrival_variance(system.telescope.diameter, z))
    rho = tilts(system, t, [z]).correlation[0]
    k0 = 0.423 * (2 * math.pi / lam) ** 2 * spherical_weighted(t, z)
    theta_lt = 0.98 / math.sqrt(2 * math.log(2)) * lam * k0**0.6  # the seeing FWHM as 1/e² radius
    blur = math.sqrt(max(theta_lt**2 - 4 * sigma_a**2, 0.0))
    assert (blur > 0.5 * sigma_a) == (diameter > 0.05)
    d = 1 / (1 / f - 1 / z)
    rng = np.random.default_rng(123)

    def monte_carlo(correlation):
        g = []
        for _ in range(1000):
            c = rng.normal(0, sigma_c, 2)
            alpha = -correlation * sigma_a * c / sigma_c
            alpha = alpha + math.sqrt(1 - correlation**2) * rng.normal(0, sigma_a, 2)
            alpha = alpha + rng.normal(0, blur / 2, 2)  # the blur: a Gaussian of 1/e² radius θ_ST
            drawn = dataclasses.replace(
                system,
                beam=backend.beam_for(beam, z, st, c),
                detector=dataclasses.replace(system.detector, offset=tuple(d * alpha)),
            )
            g.append(lo.overlap(drawn, [z], "rt", tolerance=1e-6).overlap[0])
        return np.mean(g), np.std(g, ddof=1) / math.sqrt(len(g))

    mc, mc_se = monte_carlo(rho)
    # the mean with uncorrelated paths, which RT computes exactly (a wider beam), drawn here
    independent, independent_se = monte_carlo(0.0)
    exact = both.overlap[0] / both.amplification[0]
    assert abs(exact - independent) < SIGMAS * independent_se
    print(f"D = {diameter} m, G at {z} m: both {both.overlap[0]:.4f}, Monte Carlo {mc:.4f} +- ")
    print(f"{mc_se:.4f}, transmit only {transmit.overlap[0]:.4f}, blur / tilt {blur / sigma_a:.3g}")
    assert abs(both.overlap[0] - mc) < SIGMAS * math.hypot(both.error_estimate[0], mc_se)
    # the return path moves G the way the detector offsets do, by more than the errors
    change = both.overlap[0] - transmit.overlap[0]
    assert abs(change) > SIGMAS * math.hypot(both.error_estimate[0], transmit.error_estimate[0])
    assert np.sign(change) == np.sign(mc - transmit.overlap[0])


def amplification_error(res, i=0):
    """Standard error of mean G / mean uncorrelated G at ranges[i]: RT's denominator is exact; FO's
    from the paired rows (delta method)."""
    if res.uncorrelated is None:
        return res.error_estimate[i] * res.amplification[i] / res.overlap[i]
    g, u = res.realizations[:, i], res.uncorrelated[:, i]
    ratio = g.mean() / u.mean()
    return np.std(g - ratio * u, ddof=1) / math.sqrt(g.size) / u.mean()


def test_amplification_limits():
    """A receiver whose aperture is much larger than the beam and the coherence radius (r0 = 3.5
    cm here) averages eddies the beam does not see: no amplification. A receiver as small as the
    beam, coaxial, whose image sits inside the field stop near its edge, sees the beam's wander
    back: its image stays put and G is above that of independent paths (which move it out)."""
    z = [500.0]
    wide = run(tilted_lidar(tilt=0.97e-3, diameter=0.5, waist=0.005), z, "both", 3000)
    small = run(tilted_lidar(tilt=0.97e-3, diameter=0.02, waist=0.01), z, "both", 3000)
    print(
        f"amplification: D = 0.5 m {wide.amplification[0]:.4f} +- {amplification_error(wide):.4f}"
    )
    print(f"D = 2 cm {small.amplification[0]:.4f} +- {amplification_error(small):.4f}")
    assert abs(wide.amplification[0] - 1) < SIGMAS * amplification_error(wide) + 1e-3
    assert small.amplification[0] - 1 > SIGMAS * amplification_error(small)
    for res in (wide, small):
        assert res.paths == "both" and np.all(res.overlap <= 1.0)  # RT: at most all the light
        assert np.all(res.amplification <= TWO_WAY_BOUND)


def test_calm_air_is_the_unperturbed_overlap():
    system, z = tilted_lidar(tilt=0.9e-3, offset=0.02), np.array([100.0, 400.0, 1500.0])
    plain = lo.overlap(system, z, "rt", tolerance=1e-8)
    res = run(system, z, "both", 50, cn2=1e-24)  # the machinery runs; its tilts are nanoradians
    assert np.all(np.abs(res.overlap - plain.overlap) < 1e-6)
    assert np.all(np.abs(res.amplification - 1) < 1e-6)
    zero = run(system, z, "both", 5, cn2=0.0)  # no turbulence at all: every draw the plain curve
    assert np.allclose(zero.overlap, lo.overlap(system, z, lo.RT(1e-6)).overlap, atol=0, rtol=0)
    assert zero.paths == "both" and np.all(zero.amplification == 1.0)


def test_auto_takes_ray_tracing_where_the_missed_enhancement_fits():
    """Weak turbulence: RT on both paths; stronger turbulence: Fourier optics (the backscatter
    enhancement ray tracing leaves out, 0.016 of G, with its diffraction error 0.036 exceeds the
    tolerance 0.05) on the grid the scene needs (670). Strong turbulence over a long path through a
    wide field of view: FO would need a grid of ~24000, so ray tracing, with a warning
    (tests/test_turbulent_auto.py)."""
    lidar = lo.LidarSystem(
        beam=lo.GaussianBeam(532e-9, 5e-3),
        telescope=lo.Telescope(0.1, 1.0),
        detector=lo.Detector.from_fov(0.5e-3, 1.0),
    )
    z = np.geomspace(100.0, 500.0, 6)
    weak = lo.plan(lidar, z, lo.Turbulent(lo.Turbulence(1e-17), lo.Auto(5e-2)))
    strong = lo.plan(lidar, z, lo.Turbulent(lo.Turbulence(1e-13), lo.Auto(5e-2)))
    assert weak.backend == "rt_turbulent" and strong.backend == "fo_turbulent"
    assert "backscatter enhancement" in " ".join(strong.reasons + weak.reasons)
    assert strong.options.beam_grid > 256 and not strong.warnings
    wide = lo.LidarSystem(
        beam=lo.GaussianBeam(532e-9, 5e-3),
        telescope=lo.Telescope(0.2, 1.0),
        detector=lo.Detector.from_fov(2e-3, 1.0),
    )
    far = lo.plan(
        wide, np.geomspace(200.0, 2000.0, 6), lo.Turbulent(lo.Turbulence(1e-13), lo.Auto(1e-2))
    )
    assert far.backend == "rt_turbulent" and "cannot run" in far.warnings[0]


def test_outside_its_regime_ray_tracing_says_so():
    system = tilted_lidar()
    method = lo.Turbulent(lo.Turbulence(1e-12), lo.RT(), realizations=4, paths="both")
    with pytest.warns(RuntimeWarning, match="outside its regime.*backscatter enhancement"):
        lo.overlap(system, [2000.0], method)


def test_ray_tracing_and_fourier_optics_agree_on_both_paths_where_both_hold():
    """Weak fluctuations (Rytov variance 0.2 at 600 m), a missed enhancement below 3 % of G, a field
    of view 13 diffraction widths across with the beam's image at its edge: the two models' mean G
    on both paths, each over its own calm-air G (which takes out RT's diffraction error), agree
    within FO's standard error (its draws and random-phase receiver fields, 4 of them) plus the
    missed enhancement; so do their amplifications."""
    system = lo.LidarSystem(
        beam=lo.GaussianBeam(1064e-9, 5e-3, tilt=(1.2e-4, 0.0)),
        telescope=lo.Telescope(0.05, 0.5),
        detector=lo.Detector(70e-6),
    )
    z, t = np.array([300.0, 600.0]), lo.Turbulence(2e-14)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # RT's diffraction error, taken out below
        rt = lo.overlap(system, z, lo.Turbulent(t, lo.RT(1e-6), realizations=4000, seed=1))
        rt_calm = lo.overlap(system, z, "rt", tolerance=1e-6).overlap
    fo = lo.overlap(
        system,
        z,
        lo.Turbulent(t, lo.FO(beam_grid=432), realizations=8, seed=1, screens=5, receiver_fields=8),
    )
    fo_calm = lo.overlap(system, z, "fo").overlap
    missed = missed_enhancement(system, t, z)
    assert np.all(missed < 0.03) and t.rytov_variance(1064e-9, 600.0) < 0.3
    print(f"RT both / calm {rt.overlap / rt_calm}, FO both / calm {fo.overlap / fo_calm}")
    print(f"amplification RT {rt.amplification}, FO {fo.amplification}")
    allowed = SIGMAS * np.hypot(fo.error_estimate / fo_calm, rt.error_estimate / rt_calm) + missed
    assert np.all(np.abs(rt.overlap / rt_calm - fo.overlap / fo_calm) < allowed)
    for i in range(z.size):
        error = np.hypot(amplification_error(fo, i), amplification_error(rt, i))
        assert abs(rt.amplification[i] - fo.amplification[i]) < SIGMAS * error + missed[i]


def test_the_paths_decorrelate_as_their_axes_separate():
    """The tilt correlation of the two paths falls as the beam's axis moves away from the
    telescope's; with an outer scale it vanishes once the separation exceeds it (eddies larger than
    L0 / 2π carry no tilt), and the amplification is then 1: the image's tilt is independent of the
    wander. The beam is pointed so that its image sits at the same place at 500 m for every
    separation."""
    z, outer = 500.0, 0.5
    rho = {}
    for a in (0.0, 0.02, 0.05, 0.2, 1.0):
        system = tilted_lidar(tilt=0.97e-3 - a / z, offset=a)
        rho[a] = tilts(system, lo.Turbulence(1e-13), [z]).correlation[0]
    values = list(rho.values())
    assert all(x > y for x, y in zip(values, values[1:])) and values[0] > 0.8
    coaxial = tilted_lidar(tilt=0.97e-3)
    apart = tilted_lidar(tilt=0.97e-3 - 1.0 / z, offset=1.0)
    t = lo.Turbulence(1e-13, outer_scale=outer)
    assert abs(tilts(apart, t, [z]).correlation[0]) < 1e-2
    results = {}
    for name, system in (("coaxial", coaxial), ("1 m apart", apart)):
        method = lo.Turbulent(t, lo.RT(1e-6), realizations=3000, seed=4)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            results[name] = lo.overlap(system, [z], method)
    print({k: (r.amplification[0], amplification_error(r)) for k, r in results.items()})
    assert results["coaxial"].amplification[0] - 1 > SIGMAS * amplification_error(
        results["coaxial"]
    )
    assert abs(results["1 m apart"].amplification[0] - 1) < SIGMAS * amplification_error(
        results["1 m apart"]
    )
