"""Sensitivities dG/dp: against a finer finite difference at a much tighter tolerance, against
closed forms (a point aperture; G depending on the beam centre offset + tilt z only), and bad
parameters refused by name."""

import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters

pytest.importorskip("xarray")

TOL = 1e-4
#: The reference: steps 4x smaller (truncation 16x smaller) at a quadrature tolerance 1e5 x tighter.
REF_TOL, REF_SHRINK = 1e-9, 4.0
CROSSING = lo.LidarSystem(
    beam=lo.GaussianBeam(
        wavelength=355e-9, waist_radius=1e-3, offset=(0.05, 0.0), tilt=(-1e-4, 0.0)
    ),  # back on the axis at 500 m
    telescope=lo.paper_table1().telescope,
    detector=lo.paper_table1().detector,
)


def _reference(system, z, path, h):
    """dG/dp by a central difference of step h at REF_TOL."""
    v = parameters.get(system, path)
    up, down = (
        lo.overlap(
            parameters.replace(system, {path: v + s * h}), z, "rt", tolerance=REF_TOL
        ).overlap
        for s in (1, -1)
    )
    return (up - down) / (2 * h)


def test_against_a_finer_difference_at_a_much_tighter_tolerance():
    z = np.array([150.0, 400.0, 800.0])
    paths = ["beam.tilt[0]", "detector.defocus", "detector.offset[1]", "beam.waist_radius"]
    ds = lo.sensitivity(CROSSING, z, paths, tolerance=TOL)
    assert ds["derivative"].dims == ("parameter", "range") and list(ds["parameter"].values) == paths
    assert list(ds["unit"].values) == ["rad", "m", "m", "m"]
    for k, path in enumerate(paths):
        ref = _reference(CROSSING, z, path, float(ds["step"][k]) / REF_SHRINK)
        # The stated error must cover the actual one (the reference's own error is ~1/16 of the
        # truncation).
        assert np.all(np.abs(ds["derivative"].values[k] - ref) <= ds["error_estimate"].values[k]), (
            path
        )
    assert np.any(
        np.abs(ds["derivative"].values) > 10 * ds["error_estimate"].values
    )  # and tells something


def test_the_step_follows_the_tolerance_and_the_parameter_scale():
    ds = lo.sensitivity(
        lo.paper_table1(), [300.0], ["beam.tilt[0]", "detector.radius"], tolerance=1e-4
    )
    half_fov = 0.45e-3
    assert float(ds["step"][0]) == pytest.approx(half_fov * (3e-4) ** (1 / 3), rel=1e-12)
    assert float(ds["step"][1]) == pytest.approx(0.45e-3 * (3e-4) ** (1 / 3), rel=1e-12)


def test_detector_radius_against_the_point_aperture_closed_form():
    # A point aperture sees the detector as a cone of half-angle r_d/f: G = 1 - exp(-u), u = 2 (r_d
    # z / f)² / w², so dG/dr_d = exp(-u) 4 r_d z² / (f² w²).
    system = parameters.replace(lo.paper_table1(), {"telescope.diameter": 1e-7})
    z = np.array([0.8, 1.5, 3.0])  # where u ~ 1: the beam still near its 1 mm waist
    with warnings.catch_warnings():
        warnings.simplefilter(
            "ignore", RuntimeWarning
        )  # RT outside its diffraction validity: geometry only
        ds = lo.sensitivity(system, z, ["detector.radius"], tolerance=1e-7)
    r_d, f, w = system.detector.radius, 1.0, system.beam.radius(z)
    u = 2 * (r_d * z / f) ** 2 / w**2
    exact = np.exp(-u) * 4 * r_d * z**2 / (f**2 * w**2)
    err = ds["error_estimate"].values[0]
    assert np.all(np.abs(ds["derivative"].values[0] - exact) <= err)
    assert np.all(err < 0.01 * exact)


def test_tilt_is_range_times_offset_and_vanishes_at_the_crossing():
    # RT's G depends on the beam through its centre offset + tilt z (and its radius): dG/dtilt = z
    # dG/doffset. At 500 m the beam is centred on the axisymmetric receiver, where G is even in the
    # centre: both vanish; before, the centre is at positive x, so tilting towards +x takes it
    # farther off the axis and lowers G.
    z = np.array([100.0, 150.0, 500.0])
    ds = lo.sensitivity(CROSSING, z, ["beam.tilt[0]", "beam.offset[0]"], tolerance=TOL)
    d, e = ds["derivative"].values, ds["error_estimate"].values
    assert np.all(np.abs(d[0] - z * d[1]) <= e[0] + z * e[1])
    assert abs(d[0, 2]) <= e[0, 2] and abs(d[1, 2]) <= e[1, 2]
    assert np.all(d[0, :2] < -10 * e[0, :2])


def test_axisymmetric_tilt_derivative_is_zero():
    ds = lo.sensitivity(lo.paper_table1(), [100.0, 500.0], "beam.tilt")
    assert np.all(np.abs(ds["derivative"].values) <= ds["error_estimate"].values)


@pytest.mark.parametrize(
    "paths, message",
    [
        (["beam.tilt[2]"], r"parameter 'beam.tilt\[2\]' is invalid"),
        (["detector.size"], "parameter 'detector.size' is invalid"),
        ([], r"parameters = \[\] is invalid"),
        (["beam.tilt", "beam.tilt[0]"], "named twice"),
        (["telescope.obstruction_radius"], "telescope.obstruction_radius = 0 is at the edge"),
        (
            ["detector.defocus", "telescope.aberrations.zernike[11]"],
            r"zernike\[11\] is not available",
        ),
    ],
)
def test_bad_parameters_are_refused_by_name(paths, message):
    with pytest.raises(ValueError, match=message):
        lo.sensitivity(lo.paper_table1(), [300.0], paths)


def test_other_bad_input_is_refused():
    near_limit = parameters.replace(lo.paper_table1(), {"detector.defocus": -0.99999})
    with pytest.raises(
        ValueError,
        match=r"detector.defocus = -0.99999 - 1 x step 0.000402, a point of the central "
        r"difference, leaves",
    ):
        lo.sensitivity(near_limit, [300.0], ["detector.defocus"])
    with pytest.raises(ValueError, match="not available"):
        lo.sensitivity(lo.paper_table1(), [300.0], ["detector.radius"], method="fo")
    with pytest.raises(ValueError, match="ranges"):
        lo.sensitivity(lo.paper_table1(), [np.nan], ["detector.radius"])
