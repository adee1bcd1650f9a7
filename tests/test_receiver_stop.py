"""A second receiver stop behind the lens (Detector.stop_radius at Detector.stop_distance).

Ray tracing against an independent Monte-Carlo ray trace (test_rt_monte_carlo's, with each ray also
required to cross the stop's plane within its radius: |A (1 + s/z - s/f) - P s/z| <= r_s), the far
range's closed form, Fourier optics where diffraction is small, and hostile values refused by name.
"""

import dataclasses
import warnings

import numpy as np
import pytest
from test_rt_monte_carlo import CHUNK, N_RAYS, accepted, allowed, aperture_points, beam_radius

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.io.scenario import scenario_from_dict
from lidar_overlap.io.scenario_writer import scenario_toml

BASE = lo.paper_table1()
ENGINE_TOL = 1e-6
#: RT and FO of the Table 1 receiver beyond 300 m: diffraction moves G by less than this.
RT_FO_FAR = 5e-3


def with_stop(system, radius, distance, **detector):
    det = dataclasses.replace(
        system.detector, stop_radius=radius, stop_distance=distance, **detector
    )
    return dataclasses.replace(system, detector=det)


def through_stop(system, z, p, a):
    """The rays of ``accepted`` that also pass the second stop."""
    f, det = system.telescope.focal_length, system.detector
    s = det.stop_distance
    c = a * (1 + s / z - s / f) - p * s / z
    return accepted(system, z, p, a) & (np.einsum("ij,ij->i", c, c) <= det.stop_radius**2)


def mc_overlap(system, z, rng, n=N_RAYS):
    beam = system.beam
    centre = np.asarray(beam.offset) + np.asarray(beam.tilt) * z
    sigma = beam_radius(beam, z) / 2.0
    count = 0
    for start in range(0, n, CHUNK):
        m = min(CHUNK, n - start)
        p = centre + sigma * rng.standard_normal((m, 2))
        a = aperture_points(rng, system.telescope.diameter / 2, m)
        count += int(np.count_nonzero(through_stop(system, z, p, a)))
    return count / n


BIAXIAL = dataclasses.replace(
    BASE, beam=dataclasses.replace(BASE.beam, offset=(0.1, 0.0), tilt=(-0.4e-3, 0.0))
)
CASES = {
    # halfway to the focus: vignettes the outer pupil, (0.03 / 0.0375)^2 = 0.64 of it far away
    "vignetting": (with_stop(BASE, 0.03, 0.5), [15.0, 60.0, 300.0, 3000.0]),
    # a relay aperture just before the focus: a second, larger field stop for near scatterers
    "relay": (with_stop(BASE, 6e-3, 0.9), [10.0, 25.0, 80.0, 1000.0]),
    "biaxial": (with_stop(BIAXIAL, 0.02, 0.7), [130.0, 250.0, 1000.0]),
    # behind the focal plane of a defocused detector: the stop is in focus (a gate) at 501 m
    "gate": (with_stop(BASE, 0.5e-3, 1.002, defocus=5e-3), [120.0, 501.0, 3000.0]),
    "with_na_and_obstruction": (
        with_stop(lo.paper_table1(obstruction_radius=0.02), 0.018, 0.6, numerical_aperture=0.06),
        [40.0, 150.0, 1000.0],
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_stop_matches_monte_carlo(case):
    system, z = CASES[case]
    rng = np.random.default_rng(4040 + len(case))
    got = lo.overlap(system, z, tolerance=ENGINE_TOL).overlap
    mc = np.array([mc_overlap(system, zi, rng) for zi in z])
    assert np.any((mc > 0.02) & (mc < 0.98)), mc
    for zi, g, ref in zip(z, got, mc):
        assert abs(g - ref) <= allowed(ref), f"{case}: z = {zi} m: engine {g:.6f}, MC {ref:.6f}"
    # the stop cuts: without it G is larger somewhere by far more than the agreement
    free = dataclasses.replace(
        system, detector=dataclasses.replace(system.detector, stop_radius=None, stop_distance=0.0)
    )
    assert np.max(lo.overlap(free, z, tolerance=ENGINE_TOL).overlap - got) > 0.05


def test_far_range_closed_form():
    # far away every ray of an on-axis point crosses the stop's plane at A (1 - s/f)
    system, _ = CASES["vignetting"]
    far = lo.overlap(system, [1e6], tolerance=ENGINE_TOL).overlap[0]
    assert far == pytest.approx((0.03 / (0.075 * 0.5)) ** 2, abs=1e-3)


def test_rt_and_fo_agree_where_diffraction_is_small():
    for case in ("vignetting", "relay"):
        system, _ = CASES[case]
        z = np.geomspace(300.0, 5000.0, 5)
        rt = lo.overlap(system, z, "rt").overlap
        fo = lo.overlap(system, z, "fo").overlap
        np.testing.assert_allclose(fo, rt, atol=RT_FO_FAR, err_msg=case)
        assert np.min(rt) < 0.9  # the stop cuts on these ranges


def test_fo_says_where_it_neglects_the_stop_motion():
    relay, _ = CASES["relay"]
    offset = dataclasses.replace(relay, beam=dataclasses.replace(relay.beam, offset=(0.1, 0.0)))
    with pytest.warns(RuntimeWarning, match="second stop's pupil disc moves by 0.33 of its radius"):
        lo.overlap(offset, [50.0, 1000.0], "fo")
    # (|c| + 2 w) s / (z r_s) = (0.1 + 0.0115) 0.9 / (50 x 0.006) = 0.33 there; coaxial and far
    # it is 2 w s / (z r_s) = 0.034, below the limit
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        lo.overlap(relay, [1000.0], "fo")


def test_parameters_and_files(tmp_path):
    system, _ = CASES["relay"]
    assert parameters.get(system, "detector.stop_radius") == 6e-3
    moved = parameters.replace(system, {"detector.stop_distance": 0.8})
    assert moved.detector.stop_distance == 0.8
    with pytest.raises(ValueError, match=r"detector.stop_distance = 1.5 makes an invalid system"):
        parameters.replace(system, {"detector.stop_distance": 1.5})
    r = lo.overlap(system, [100.0, 1000.0])
    r.to_csv(tmp_path / "g.csv")
    assert lo.OverlapResult.from_csv(tmp_path / "g.csv").system == system


@pytest.mark.parametrize(
    "radius, distance, message",
    [
        (0.0, 0.5, r"detector.stop_radius = 0 is invalid"),
        (float("inf"), 0.5, r"detector.stop_radius = inf is invalid"),
        (float("nan"), 0.5, r"detector.stop_radius = nan is invalid"),
        (-1e-3, 0.5, r"detector.stop_radius = -0.001 is invalid"),
        (1e300, 0.5, r"detector.stop_radius = 1\.0*\d*e\+300 is invalid"),
        (1e-3, 0.0, r"detector.stop_distance = 0 is invalid"),
        (1e-3, -0.1, r"detector.stop_distance = -0\.10*\d* is invalid"),
        (1e-3, float("nan"), r"detector.stop_distance = nan is invalid"),
        (1e-3, float("inf"), r"detector.stop_distance = inf is invalid"),
        (1e-3, 1.0, r"detector.stop_distance = 1 is invalid: .* focal_length \+ defocus = 1 m"),
        (1e-3, 2.0, r"detector.stop_distance = 2 is invalid: .* detector plane"),
        (None, 0.5, r"detector.stop_distance = 0.5 is invalid: expected 0 without a stop_radius"),
    ],
)
def test_hostile_stops_are_refused_by_name(radius, distance, message):
    with pytest.raises(ValueError, match=message):
        with_stop(BASE, radius, distance)


def test_unmodelled_combinations_are_refused():
    system, z = CASES["relay"]
    aberrated = dataclasses.replace(
        system,
        telescope=dataclasses.replace(system.telescope, aberrations=lo.Aberrations(w040=1e-7)),
    )
    with pytest.raises(ValueError, match="detector.stop_radius with receiver aberrations"):
        lo.plan(aberrated, z, "rt")
    masked = dataclasses.replace(
        system,
        telescope=dataclasses.replace(
            system.telescope, mask=lo.ApertureMask.quadrants().split()[0]
        ),
    )
    with pytest.raises(ValueError, match="detector.stop_radius with telescope.mask"):
        lo.plan(masked, z, "fo")


def test_scenario_tables_carry_the_stop():
    scenario = scenario_from_dict(
        {
            "name": "stop",
            "beam": {"wavelength": 355e-9, "waist_radius": 1e-3},
            "telescope": {"diameter": 0.15, "focal_length": 1.0},
            "detector": {"fov": 0.9e-3, "stop_radius": 0.03, "stop_distance": 0.5},
            "ranges": {"start": 100.0, "stop": 1000.0, "count": 3},
        }
    )
    assert scenario.system.detector == CASES["vignetting"][0].detector


def test_the_view_saves_the_stop():
    system, z = CASES["relay"]
    text = scenario_toml(system, np.asarray(z), "relay", 1e-4)
    assert "stop_radius = 0.006" in text and "stop_distance = 0.9" in text
    plain = scenario_toml(BASE, np.asarray(z), "plain", 1e-4)
    assert "stop_" not in plain
