"""Ray-tracing overlap G(z) and single-scatterer coupling against an independent Monte-Carlo ray
trace.

The Monte-Carlo here follows the paraxial geometry of the design notes directly: random scatterers P
from the Gaussian beam at range z (each coordinate ~ Normal(centre, w/2), centre = offset + tilt z),
random aperture points A uniform over the aperture disc, one ray per (P, A) pair. A ray counts when
it

- misses the obstruction disc: |A + (P - A) z_obs / z| >= r_obs,
- lands on the detector: |A (1 + d/z - d/f) - P d/z - detector.offset| <= r_d, with d = f + defocus,
- is within the numerical aperture: |(A - P)/z - A/f| <= tan(asin(NA)).

G is the fraction of rays that count (rays through the whole aperture are the denominator). Each
case is checked at a few ranges where G is neither 0 nor 1, within 5 binomial sigma plus a small
floor.
"""

import dataclasses

import numpy as np
import pytest

import lidar_overlap as lo

N_RAYS = 1_000_000  # (scatterer, aperture point) pairs per range
CHUNK = 250_000  # rays traced at once (memory)
N_SIGMA = 5.0  # agreement in binomial standard deviations sqrt(G (1 - G) / N)
ABS_FLOOR = 1e-4  # covers the engine tolerance (1e-6 here) and G values where sigma -> 0
ENGINE_TOL = 1e-6


def beam_radius(beam, z):
    theta = (
        beam.wavelength / (np.pi * beam.waist_radius)
        if beam.divergence is None
        else beam.divergence
    )
    if beam.width_law == "gaussian":
        return np.hypot(beam.waist_radius, theta * z)
    return beam.waist_radius + theta * z


def aperture_points(rng, radius, n):
    r = radius * np.sqrt(rng.random(n))
    phi = 2 * np.pi * rng.random(n)
    return np.column_stack((r * np.cos(phi), r * np.sin(phi)))


def accepted(system, z, p, a):
    """Boolean mask of the rays from scatterers p through aperture points a (both (n, 2)) that
    count."""
    tel, det = system.telescope, system.detector
    f = tel.focal_length
    d = f + det.defocus
    hit = a * (1 + d / z - d / f) - p * d / z - np.asarray(det.offset)
    ok = np.einsum("ij,ij->i", hit, hit) <= det.radius**2
    if tel.obstruction_radius > 0:
        q = a + (p - a) * (tel.obstruction_distance / z)
        ok &= np.einsum("ij,ij->i", q, q) >= tel.obstruction_radius**2
    if det.numerical_aperture is not None:
        slope = (a - p) / z - a / f
        max_slope = np.tan(np.arcsin(det.numerical_aperture))
        ok &= np.einsum("ij,ij->i", slope, slope) <= max_slope**2
    return ok


def mc_overlap(system, z, rng, n=N_RAYS):
    beam = system.beam
    centre = np.asarray(beam.offset) + np.asarray(beam.tilt) * z
    sigma = beam_radius(beam, z) / 2.0  # 1/e^2 radius w  <=>  per-coordinate sigma w/2
    count = 0
    for start in range(0, n, CHUNK):
        m = min(CHUNK, n - start)
        p = centre + sigma * rng.standard_normal((m, 2))
        a = aperture_points(rng, system.telescope.diameter / 2, m)
        count += int(np.count_nonzero(accepted(system, z, p, a)))
    return count / n


def mc_coupling(system, z, position, rng, n=N_RAYS):
    p = np.broadcast_to(np.asarray(position, float), (n, 2))
    a = aperture_points(rng, system.telescope.diameter / 2, n)
    return np.count_nonzero(accepted(system, z, p, a)) / n


def allowed(g, n=N_RAYS):
    return N_SIGMA * np.sqrt(g * (1 - g) / n) + ABS_FLOOR


def _with(system, beam=None, telescope=None, detector=None):
    return dataclasses.replace(
        system,
        beam=dataclasses.replace(system.beam, **(beam or {})),
        telescope=dataclasses.replace(system.telescope, **(telescope or {})),
        detector=dataclasses.replace(system.detector, **(detector or {})),
    )


BASE = lo.paper_table1()

CASES = {
    "coaxial": (BASE, [15.0, 60.0, 120.0, 250.0]),
    "linear_width_law": (lo.paper_table1(width_law="linear"), [15.0, 60.0, 150.0]),
    "obstructed": (lo.paper_table1(obstruction_radius=0.02), [40.0, 80.0, 150.0, 1000.0]),
    "defocused": (lo.paper_table1(defocus=5e-3), [20.0, 60.0, 201.0, 3000.0]),
    # beam starts 0.1 m beside the axis and is tilted back across the field of view (crosses it at
    # 250 m)
    "biaxial_tilted": (
        _with(BASE, beam=dict(offset=(0.1, 0.0), tilt=(-0.4e-3, 0.0))),
        [130.0, 180.0, 250.0, 1000.0, 5000.0],
    ),
    "tilted_2d": (
        _with(BASE, beam=dict(offset=(0.03, -0.02), tilt=(-0.2e-3, 0.25e-3), divergence=0.2e-3)),
        [50.0, 150.0, 600.0],
    ),
    # NA 0.05 accepts slopes up to 0.05006 while the marginal ray of the f/6.7 lens has slope 0.075
    "na_limited": (_with(BASE, detector=dict(numerical_aperture=0.05)), [30.0, 100.0, 1000.0]),
    "detector_offset": (
        _with(BASE, detector=dict(offset=(0.25e-3, 0.1e-3))),
        [30.0, 120.0, 1000.0],
    ),
    "everything": (
        _with(
            lo.paper_table1(obstruction_radius=0.025, defocus=3e-3, width_law="linear"),
            beam=dict(offset=(0.05, 0.0), tilt=(-0.15e-3, 0.05e-3)),
            detector=dict(offset=(-0.1e-3, 0.05e-3), numerical_aperture=0.06),
        ),
        [80.0, 200.0, 400.0, 2000.0],
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_overlap_matches_monte_carlo(case):
    system, z = CASES[case]
    rng = np.random.default_rng(20240611 + len(case))
    res = lo.overlap(system, z, tolerance=ENGINE_TOL)
    mc = np.array([mc_overlap(system, zi, rng) for zi in z])
    # the case is informative: G takes intermediate values somewhere on these ranges
    assert np.any((mc > 0.02) & (mc < 0.98)), mc
    for zi, got, ref in zip(z, res.overlap, mc):
        assert abs(got - ref) <= allowed(ref), (
            f"{case}: z = {zi} m: engine G = {got:.6f}, Monte-Carlo {ref:.6f}"
        )


def test_na_case_really_cuts():
    # the numerical-aperture case would be vacuous if NA 0.05 rejected nothing on these ranges
    system, z = CASES["na_limited"]
    free = _with(system, detector=dict(numerical_aperture=None))
    g_na = lo.overlap(system, z, tolerance=ENGINE_TOL).overlap
    g_free = lo.overlap(free, z, tolerance=ENGINE_TOL).overlap
    assert np.max(g_free - g_na) > 0.2
    # far away every ray of an on-axis point leaves the lens at slope |A|/f: only |A| <= f tan(asin
    # NA) pass
    far = lo.overlap(system, [1e6], tolerance=ENGINE_TOL).overlap[0]
    assert far == pytest.approx((np.tan(np.arcsin(0.05)) / 0.075) ** 2, abs=1e-4)


def test_biaxial_case_crosses_the_field_of_view():
    system, _ = CASES["biaxial_tilted"]
    z = np.geomspace(10.0, 1e4, 200)
    g = lo.overlap(system, z, tolerance=ENGINE_TOL).overlap
    assert g[0] < 1e-3  # beam outside the field of view close to the lidar
    assert g.max() > 0.99  # fully seen where it crosses the axis
    assert g[-1] < 0.9 * g.max()  # and leaving the field of view again far away


POINTS = [
    (BASE, 100.0, (0.0, 0.0)),
    (BASE, 100.0, (0.03, 0.01)),
    (BASE, 40.0, (-0.012, 0.0)),
    (lo.paper_table1(obstruction_radius=0.02), 60.0, (0.005, 0.0)),
    (lo.paper_table1(obstruction_radius=0.04), 150.0, (-0.01, 0.02)),
    (lo.paper_table1(defocus=5e-3), 80.0, (0.02, -0.01)),
    (_with(BASE, detector=dict(numerical_aperture=0.05)), 500.0, (0.05, 0.0)),
    (_with(BASE, detector=dict(offset=(0.25e-3, 0.1e-3))), 120.0, (-0.02, -0.01)),
    (
        _with(
            lo.paper_table1(obstruction_radius=0.025, defocus=3e-3),
            detector=dict(offset=(-0.1e-3, 0.05e-3), numerical_aperture=0.06),
        ),
        300.0,
        (0.04, -0.03),
    ),
]


@pytest.mark.parametrize("index", range(len(POINTS)))
def test_emitter_coupling_matches_monte_carlo(index):
    system, z, position = POINTS[index]
    rng = np.random.default_rng(7 + index)
    ref = mc_coupling(system, z, position, rng)
    got = lo.emitter_coupling(system, z, position=position)
    assert abs(got - ref) <= allowed(ref), (
        f"z = {z} m, P = {position}: engine {got:.6f}, Monte-Carlo {ref:.6f}"
    )


def test_some_emitter_points_are_partially_coupled():
    # guard against a point list where every coupling is trivially 0 or 1
    values = [lo.emitter_coupling(s, z, position=p) for s, z, p in POINTS]
    assert sum(0.02 < v < 0.98 for v in values) >= 5, values
