"""lo.fit_telecover: a known tilt of the Table 1 lidar recovered from its quadrant deviations
(noise-free to 1e-3, noisy within the stated uncertainty), north = +tilt[1], the constraint's
degrees of freedom, the TelecoverResult input, and bad input refused naming the argument."""

import importlib.util
import math

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters

pytest.importorskip("scipy")
TRUE = {"beam.tilt[0]": 30e-6, "beam.tilt[1]": 50e-6}
Z = np.geomspace(60.0, 400.0, 6)


@pytest.fixture(scope="module")
def measured():
    """The quadrants of the tilted Table 1 lidar, computed more tightly than the fit's model."""
    return lo.telecover(parameters.replace(lo.paper_table1(), TRUE), Z, tolerance=1e-6)


@pytest.fixture(scope="module")
def exact(measured):
    with pytest.warns(
        RuntimeWarning, match="scatter of the residuals"
    ):  # noise-free: no scatter to compare
        return lo.fit_telecover(lo.paper_table1(), Z, measured)


def test_noise_free_recovers_the_tilt_to_1e_3(exact):
    assert exact.converged
    for path, value in TRUE.items():
        assert exact.parameters[path] == pytest.approx(value, rel=1e-3)
    assert isinstance(exact.result, lo.TelecoverResult) and exact.result.names == (
        "north",
        "east",
        "south",
        "west",
    )
    assert exact.degrees_of_freedom == 3 * Z.size - 2  # the deviations of a range sum to zero
    assert exact.measured.shape == exact.residuals.shape == (4 * Z.size,)


def test_noisy_deviations_recover_the_tilt_within_the_stated_uncertainty(measured):
    sigma = 0.01
    noisy = measured.deviation + np.random.default_rng(3).normal(
        0.0, sigma, measured.deviation.shape
    )
    f = lo.fit_telecover(lo.paper_table1(), Z, noisy, sigma=sigma)
    for path, value in TRUE.items():
        u = f.uncertainties[path]
        assert 0 < u < 0.05 * value and abs(f.parameters[path] - value) < 3 * u
    assert 0.3 < f.reduced_chi_square < 2.0 and not f.covariance_scaled
    # unit weights: the noise is estimated from the scatter, to about the true sigma
    g = lo.fit_telecover(f.system, Z, noisy)  # started at the solution: one step
    assert g.covariance_scaled and math.sqrt(g.reduced_chi_square) == pytest.approx(sigma, rel=0.4)
    assert g.parameters == pytest.approx(f.parameters, rel=1e-6)


def test_a_north_tilt_fits_as_positive_tilt_y():
    z = np.geomspace(60.0, 300.0, 5)
    north = lo.telecover(parameters.replace(lo.paper_table1(), {"beam.tilt[1]": 40e-6}), z)
    assert np.all(north.deviation[0] > north.deviation[2])  # north sees more, as telecover says
    f = lo.fit_telecover(lo.paper_table1(), z, north.deviation, sigma=0.01, free=["beam.tilt[1]"])
    assert f.parameters["beam.tilt[1]"] == pytest.approx(40e-6, rel=1e-2)
    assert np.all(f.result.deviation[0] > 0)


def test_a_telecover_result_and_its_array_fit_alike(measured, exact):
    assert exact.measured == pytest.approx(
        (measured.deviation - measured.deviation.mean(axis=0)).ravel()
    )
    assert exact.system.beam.tilt == pytest.approx(
        (TRUE["beam.tilt[0]"], TRUE["beam.tilt[1]"]), rel=1e-3
    )
    if importlib.util.find_spec("matplotlib"):
        assert len(exact.plot().axes) == 2  # deviations and residuals


S = lo.paper_table1()
D = np.zeros((4, 3))
R = [100.0, 200.0, 300.0]


@pytest.mark.parametrize(
    "call, message",
    [
        (
            lambda: lo.fit_telecover(S, R, np.zeros((3, 3))),
            r"measured_deviation has shape \(3, 3\): expected \(4, 3\)",
        ),
        (lambda: lo.fit_telecover(S, R, np.zeros(12)), r"measured_deviation has shape \(12,\)"),
        (
            lambda: lo.fit_telecover(S, R, [[0, 0, 0]] * 3 + [[0, np.nan, 0]]),
            r"measured_deviation\[3, 1\] = nan \(west, 200 m\) is invalid",
        ),
        (
            lambda: lo.fit_telecover(S, R, [[0, 0, 0]] * 3 + [[0, -2, 0]]),
            r"measured_deviation\[3, 1\] = -2.0",
        ),
        (lambda: lo.fit_telecover(S, R, "zeros"), r"measured_deviation = 'zeros' is invalid"),
        (lambda: lo.fit_telecover(S, R, D, sigma=0), r"sigma\[0, 0\] = 0.0 \(north\) is invalid"),
        (lambda: lo.fit_telecover(S, R, D, sigma=[1, 1, -1]), r"sigma\[0, 2\] = -1.0"),
        (lambda: lo.fit_telecover(S, R, D, sigma=[1, 1]), r"sigma = \[1, 1\] is invalid"),
        (lambda: lo.fit_telecover(S, R, D, sigma=np.nan), r"sigma\[0, 0\] = nan"),
        (lambda: lo.fit_telecover(S, R, D, sectors="octants"), r"sectors"),
        (lambda: lo.fit_telecover(S, R, D, sectors=4), r"sectors = 4 is invalid"),
        (
            lambda: lo.fit_telecover(S, R, np.zeros((1, 3)), sectors=lo.ApertureMask.sectors(1)),
            r"sectors has 1 sector: expected at least two",
        ),
        (
            lambda: lo.fit_telecover(S, R, D, free=["beam.tilted"]),
            r"free: parameter 'beam.tilted' is invalid",
        ),
        (lambda: lo.fit_telecover(S, R, D, free=[]), r"free = \[\] is invalid"),
        (
            lambda: lo.fit_telecover(S, R, D, free=["telescope.aberrations.w040"]),
            r"free: .*not available",
        ),
        (
            lambda: lo.fit_telecover(
                S, [100.0], np.zeros((4, 1)), free=["beam.tilt", "beam.offset[0]"]
            ),
            r"measured has 3 independent points for 3 free parameters",
        ),
        (lambda: lo.fit_telecover(S, [300.0, 100.0], D), r"ranges"),
        (
            lambda: lo.fit_telecover(S, R, D, bounds={"beam.tilt[0]": (1e-3, 2e-3)}),
            r"excludes the start",
        ),
        (lambda: lo.fit_telecover(S, R, D, loss="squared"), r"loss"),
        (lambda: lo.fit_telecover(S, R, D, tolerance=-1), r"tolerance"),
        (lambda: lo.fit_telecover("system", R, D), r"system = 'system' is invalid"),
        (lambda: lo.fit_telecover(S, [-1.0, 100.0, 200.0], D), r"ranges"),
        (
            lambda: lo.fit_telecover(S, R, lo.telecover(S, [100.0, 200.0])),
            r"TelecoverResult at other ranges",
        ),
    ],
)
def test_bad_input_is_refused_naming_the_argument(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_ranges_where_no_sector_sees_light_are_refused():
    off = parameters.replace(
        lo.paper_table1(), {"beam.offset[0]": 0.2}
    )  # the beam enters the view far out
    with pytest.raises(
        ValueError, match=r"ranges\[0\] = 5 m is invalid for a telecover fit: no sector"
    ):
        lo.fit_telecover(off, [5.0, 1000.0, 2000.0], D)
