"""Beams of mutually incoherent Gaussian components (GaussianMixtureBeam) and multimode beams of a
given M² (GaussianBeam.from_m_squared).

Physics: a mixture of identical components is that one beam whatever the weights; ray tracing of a
beam with wings agrees with an independent Monte-Carlo ray trace that draws each scatterer from the
mixture's irradiance; ray tracing and Fourier optics agree where diffraction is small; the
embedded-Gaussian divergence of an M² beam is M² λ / (π w0).
"""

import dataclasses
import math
import pickle

import numpy as np
import pytest
from test_rt_monte_carlo import N_RAYS, accepted, allowed, aperture_points

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.forward.backends import many
from lidar_overlap.model.parameters import unit

BASE = lo.paper_table1()
ENGINE_TOL = 1e-6
#: RT and FO of the Table 1 receiver beyond 300 m: diffraction moves G by less than this.
RT_FO_FAR = 5e-3


def winged(weight=0.1, factor=6.0, base=BASE):
    beam = lo.GaussianMixtureBeam.with_wings(
        base.beam, weight, factor * base.beam.half_angle_divergence
    )
    return dataclasses.replace(base, beam=beam)


def mc_mixture_overlap(system, z, rng, n=N_RAYS):
    """Fraction of (scatterer, aperture point) rays that reach the detector, each scatterer drawn
    from the mixture: a component chosen with its power share, then a Gaussian of its radius."""
    beam = system.beam
    centre = np.asarray(beam.offset) + np.asarray(beam.tilt) * z
    which = rng.choice(len(beam.components), size=n, p=np.asarray(beam.weights))
    radii = np.array(
        [math.hypot(c.waist_radius, d * z) for c, d in zip(beam.components, beam.divergences)]
    )
    p = centre + (radii[which] / 2.0)[:, None] * rng.standard_normal((n, 2))
    a = aperture_points(rng, system.telescope.diameter / 2, n)
    return np.count_nonzero(accepted(system, z, p, a)) / n


def test_identical_components_are_the_single_beam():
    beam = BASE.beam
    same = lo.GaussianMixtureBeam(
        (lo.BeamComponent(0.3, beam.waist_radius), lo.BeamComponent(2.0, beam.waist_radius)),
        beam.wavelength,
    )
    z = np.geomspace(20.0, 2000.0, 7)
    for method in ("rt", "fo"):
        single = lo.overlap(BASE, z, method).overlap
        mixed = lo.overlap(dataclasses.replace(BASE, beam=same), z, method).overlap
        np.testing.assert_allclose(mixed, single, rtol=0, atol=1e-12)


def test_wings_match_monte_carlo():
    system = winged(0.25, 8.0)
    z = [40.0, 120.0, 400.0, 1500.0]
    rng = np.random.default_rng(31)
    got = lo.overlap(system, z, tolerance=ENGINE_TOL).overlap
    mc = np.array([mc_mixture_overlap(system, zi, rng) for zi in z])
    assert np.any((mc > 0.02) & (mc < 0.98)), mc
    for zi, g, ref in zip(z, got, mc):
        assert abs(g - ref) <= allowed(ref), f"z = {zi} m: engine {g:.6f}, Monte-Carlo {ref:.6f}"
    # the wing matters: a beam without it differs by far more than the agreement above
    plain = lo.overlap(BASE, z, tolerance=ENGINE_TOL).overlap
    assert np.max(np.abs(plain - got)) > 20 * allowed(0.5)


def test_rt_and_fo_agree_where_diffraction_is_small():
    system = winged(0.2, 4.0)
    z = np.geomspace(300.0, 5000.0, 6)
    rt = lo.overlap(system, z, "rt")
    fo = lo.overlap(system, z, "fo")
    assert rt.method == "rt" and fo.method == "fo"
    np.testing.assert_allclose(rt.overlap, fo.overlap, atol=RT_FO_FAR)
    # the error stated is the power-weighted sum of the components' (FO: their nominal accuracy)
    assert fo.error_estimate == pytest.approx(np.full(z.size, 1e-8))


def test_auto_runs_one_model_for_every_component():
    system = winged(0.1, 3.0)
    z = np.geomspace(30.0, 3000.0, 9)
    p = lo.plan(system, z, "auto", tolerance=1e-3)
    assert {part.method for part in p.parts} == {p.method}
    r = lo.run(p)
    ref = lo.overlap(system, z, "fo").overlap
    np.testing.assert_allclose(r.overlap, ref, atol=1e-3 + 1e-6)


def test_plan_retargets_every_component():
    system = winged(0.1, 5.0)
    z = np.geomspace(50.0, 2000.0, 6)
    p = lo.plan(system, z, "rt")
    other = parameters.replace(system, {"beam.components[1].weight": 0.4, "beam.tilt[0]": 1e-5})
    got = lo.run(p.with_system(other)).overlap
    np.testing.assert_allclose(got, lo.overlap(other, z, "rt").overlap, atol=0)
    np.testing.assert_allclose(lo.run(p.at(z[2:])).overlap, lo.run(p).overlap[2:], atol=0)
    # a plan re-ranged or re-targeted by hand (dataclasses.replace) is refused when it runs
    for edited in (dataclasses.replace(p, ranges=z[1:]), dataclasses.replace(p, system=other)):
        with pytest.raises(ValueError, match="built or edited by hand"):
            lo.run(edited)
    np.testing.assert_allclose(lo.run(p.subset(slice(0, 3))).overlap, lo.run(p).overlap[:3], atol=0)
    three = dataclasses.replace(
        system.beam, components=system.beam.components + (lo.BeamComponent(0.1, 2e-3),)
    )
    with pytest.raises(ValueError, match="3 components, the plan's 2"):
        p.with_system(dataclasses.replace(system, beam=three))
    with pytest.raises(ValueError, match="turbulence with a GaussianMixtureBeam"):
        lo.plan(system, z, lo.Turbulent(lo.Turbulence(1e-14)))


def test_parameters_by_path():
    system = winged(0.1, 5.0)
    theta = BASE.beam.half_angle_divergence
    assert parameters.get(system, "beam.components[1].weight") == 0.1
    assert parameters.get(system, "beam.components[1].divergence") == pytest.approx(5 * theta)
    # a diffraction-limited component reads as its actual divergence
    assert parameters.get(system, "beam.components[0].divergence") == pytest.approx(theta)
    moved = parameters.replace(
        system, {"beam.components[1].divergence": 1e-3, "beam.components[0].waist_radius": 2e-3}
    )
    assert moved.beam.components[1].divergence == 1e-3
    assert moved.beam.components[0].waist_radius == 2e-3
    assert parameters.canonical("beam.components[01].weight") == "beam.components[1].weight"
    assert [unit(f"beam.components[1].{n}") for n in ("weight", "waist_radius", "divergence")] == [
        "1",
        "m",
        "rad",
    ]
    with pytest.raises(ValueError, match=r"beam.components\[2\].weight is invalid: the beam has 2"):
        parameters.get(system, "beam.components[2].weight")
    with pytest.raises(ValueError, match="only a GaussianMixtureBeam has components"):
        parameters.get(BASE, "beam.components[0].weight")
    # the beam's own waist and divergence are its main component's
    assert parameters.get(system, "beam.divergence") == pytest.approx(theta)
    main = parameters.replace(system, {"beam.divergence": 2 * theta})
    assert main.beam.components[0].divergence == 2 * theta
    assert main.beam.components[1] == system.beam.components[1]
    with pytest.raises(ValueError, match=r"beam.components\[1\].weight = -0.5 makes an invalid"):
        parameters.replace(system, {"beam.components[1].weight": -0.5})


def test_value_semantics(tmp_path):
    system = winged(0.1, 5.0)
    assert pickle.loads(pickle.dumps(system)) == system
    lo.overlap(system, [100.0, 1000.0]).to_csv(tmp_path / "g.csv")
    assert lo.OverlapResult.from_csv(tmp_path / "g.csv").system == system
    beam = system.beam
    assert sum(beam.weights) == pytest.approx(1.0)
    assert beam.dominant == 0
    # the second-moment radius of the irradiance
    z = 800.0
    w = [math.hypot(c.waist_radius, d * z) for c, d in zip(beam.components, beam.divergences)]
    assert beam.radius(z) == pytest.approx(math.sqrt(np.dot(beam.weights, np.square(w))))
    assert beam.rms_divergence == pytest.approx(
        math.sqrt(np.dot(beam.weights, np.square(beam.divergences)))
    )
    # the beam's own waist and divergence are its main component's, as their paths read them
    assert beam.waist_radius == beam.components[0].waist_radius
    assert beam.divergence is None and beam.half_angle_divergence == beam.divergences[0]


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: lo.BeamComponent(-0.1), r"component.weight = -0.1 is invalid"),
        (lambda: lo.BeamComponent(float("nan")), r"component.weight = nan is invalid"),
        (lambda: lo.BeamComponent(0.0), r"component.weight = 0.0 is invalid"),
        (lambda: lo.BeamComponent(float("inf")), r"component.weight = inf is invalid"),
        (lambda: lo.BeamComponent(True), r"component.weight = True is invalid"),
        (lambda: lo.GaussianMixtureBeam(()), r"beam.components has 0 components: expected 1 to"),
        (
            lambda: lo.GaussianMixtureBeam((lo.BeamComponent(),) * 65),
            r"beam.components has 65 components: expected 1 to 64",
        ),
        (lambda: lo.GaussianMixtureBeam(None), r"beam.components = None is invalid"),
        (lambda: lo.GaussianMixtureBeam((1.0,)), r"beam.components\[0\] = 1.0 is invalid"),
        (
            lambda: lo.GaussianMixtureBeam((lo.BeamComponent(1e308), lo.BeamComponent(1e308))),
            r"the weights sum to inf",
        ),
        (
            lambda: lo.GaussianMixtureBeam(
                (lo.BeamComponent(), lo.BeamComponent(divergence=1e300))
            ),
            r"beam.components\[1\].divergence = 1\.0+\d*e\+300 is invalid",
        ),
        (
            lambda: lo.GaussianMixtureBeam((lo.BeamComponent(waist_radius=float("nan")),)),
            r"^component.waist_radius = nan is invalid",  # refused by the component itself
        ),
        (
            lambda: lo.GaussianMixtureBeam((lo.BeamComponent(divergence=1e-9),)),
            r"beam.components\[0\].divergence = .* \(M\^2 >= 1\)",
        ),
        (
            lambda: lo.GaussianMixtureBeam((lo.BeamComponent(),), wavelength=-1.0),
            r"beam.wavelength = -1 is invalid",
        ),
        (lambda: lo.GaussianBeam.from_m_squared(532e-9, 1e-3, 0.5), r"m_squared = 0.5 is invalid"),
        (lambda: lo.GaussianBeam.from_m_squared(532e-9, 1e-3, math.nan), "m_squared = nan"),
        (lambda: lo.GaussianBeam.from_m_squared(532e-9, 1e-3, math.inf), "m_squared = inf"),
        (
            lambda: lo.GaussianBeam.from_m_squared(532e-9, 0.0, 2.0),
            "beam.waist_radius = 0 is invalid",
        ),
        (lambda: lo.GaussianBeam.from_m_squared(532e-9, 1e-3, 1e300), "beam.divergence"),
    ],
)
def test_hostile_input_is_refused_by_name(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_m_squared_beam():
    lam, w0, m2 = 532e-9, 1.5e-3, 3.5
    beam = lo.GaussianBeam.from_m_squared(lam, w0, m2)
    assert beam.divergence == pytest.approx(m2 * lam / (math.pi * w0), rel=1e-15)
    assert beam.m_squared == pytest.approx(m2, rel=1e-14)
    assert lo.GaussianBeam(lam, w0).m_squared == pytest.approx(1.0, rel=1e-14)
    # Fourier optics (a Gaussian Schell-model beam) and ray tracing of its Gaussian irradiance agree
    # where the receiver's diffraction is small
    system = dataclasses.replace(BASE, beam=beam)
    z = np.geomspace(300.0, 5000.0, 5)
    rt, fo = lo.overlap(system, z, "rt").overlap, lo.overlap(system, z, "fo").overlap
    np.testing.assert_allclose(rt, fo, atol=RT_FO_FAR)
    assert np.min(rt) < 0.99  # the beam is not inside the field of view everywhere: informative


def test_many_variants_in_one_call_are_single_runs():
    system = winged(0.1, 5.0)
    z = np.geomspace(50.0, 2000.0, 5)
    p = lo.plan(system, z, "rt")
    variants = [
        parameters.replace(system, {"beam.components[1].weight": w, "beam.tilt[0]": t})
        for w, t in ((0.05, 0.0), (0.3, 2e-5), (1.0, -1e-5))
    ]
    curves = many.systems(p, variants)
    for s, g in zip(variants, curves.overlap):
        np.testing.assert_array_equal(g, lo.run(p.with_system(s)).overlap)


def test_relative_global_fit_recovers_the_wing():
    # relative data (normalised far away), the global search: the paths a real curve's fit takes
    pytest.importorskip("scipy")
    truth = winged(0.2, 5.0)
    z = np.geomspace(30.0, 3000.0, 14)
    g = lo.overlap(truth, z, "rt", tolerance=1e-8).overlap
    y = g / np.mean(g[-4:])
    f = lo.fit(
        winged(0.05, 5.0), z, y, sigma=1e-3, free=["beam.components[1].weight"], method="rt",
        tolerance=1e-7, normalize=(float(z[-4]), float(z[-1])), search="global", seed=1,
    )  # fmt: skip
    assert f.parameters["beam.components[1].weight"] == pytest.approx(0.2, rel=1e-3)


@pytest.mark.parametrize("receiver", ["aberrated", "masked"])
def test_receivers_with_aberrations_or_a_mask_sum_their_components(receiver):
    system = winged(0.1, 4.0)
    tel = system.telescope
    if receiver == "aberrated":  # auto decides for each component when the plan runs
        tel = dataclasses.replace(tel, aberrations=lo.Aberrations(w040=2e-7))
    else:
        tel = dataclasses.replace(tel, mask=lo.ApertureMask.quadrants().split()[0])
    system = dataclasses.replace(system, telescope=tel)
    z = np.geomspace(50.0, 2000.0, 4)
    for method in ("rt", "auto"):
        r = lo.overlap(system, z, method, tolerance=1e-3)
        parts = [
            lo.overlap(s, z, r.method, tolerance=1e-3).overlap for _, s in system.incoherent_parts
        ]
        w = system.beam.weights
        np.testing.assert_allclose(r.overlap, w[0] * parts[0] + w[1] * parts[1], rtol=0, atol=1e-15)


@pytest.mark.parametrize(
    "index, change, message",
    [
        (7, {"weight": 0.5}, r"^index = 7 is invalid: expected an integer from -2 to 1"),
        (1.0, {"weight": 0.5}, r"^index = 1.0 is invalid"),
        (0, {"colour": 1.0}, r"'colour' is invalid: expected weight, waist_radius or divergence"),
    ],
)
def test_with_component_names_a_bad_index_or_field(index, change, message):
    beam = lo.GaussianMixtureBeam.with_wings(lo.paper_table1().beam, 0.1, 2e-3)
    with pytest.raises(ValueError, match=message):
        beam.with_component(index, **change)
    assert beam.with_component(-1, weight=0.2).components[1].weight == 0.2
