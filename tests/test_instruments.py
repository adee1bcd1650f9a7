"""Instrument presets: the published design values (aperture, focal length, field of view,
wavelength, expanded beam) and a biaxial overlap curve that reaches full overlap in the range the
instruments' papers report."""

import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.model.instruments import chm15k, pollyxt


def test_pollyxt_far_and_near_range_design_values():
    far, near = pollyxt("far"), pollyxt("near", 532e-9)
    assert far.telescope.diameter == 0.3 and far.telescope.focal_length == 0.9
    assert far.detector.fov(0.9) == pytest.approx(1.0e-3, rel=1e-12)
    assert near.telescope.diameter == 0.05
    assert near.detector.fov(near.telescope.focal_length) == pytest.approx(2.2e-3, rel=1e-12)
    assert near.beam.wavelength == 532e-9 and far.beam.offset == (0.2, 0.0)


def test_chm15k_design_values():
    s = chm15k()
    assert s.beam.wavelength == 1064e-9 and s.beam.waist_radius == 0.045
    assert s.detector.fov(s.telescope.focal_length) == pytest.approx(0.45e-3, rel=1e-12)


@pytest.mark.parametrize(
    "system, window",
    [
        (pollyxt("far"), (300.0, 2000.0)),
        (pollyxt("near"), (30.0, 500.0)),
        (chm15k(), (200.0, 3000.0)),
    ],
)
def test_full_overlap_where_the_papers_place_it(system, window):
    z = np.geomspace(10.0, 20000.0, 120)
    r = lo.overlap(system, z, "rt", tolerance=1e-4, threads=1)
    assert window[0] <= r.full_overlap_range() <= window[1]


def test_bad_channel_is_a_clear_error():
    with pytest.raises(ValueError, match="channel = 'mid' is invalid: expected 'far' or 'near'"):
        pollyxt("mid")


def test_preset_bounds_hold_the_presets_and_the_sources_ranges():
    from lidar_overlap.model.instruments import chm15k_bounds, pollyxt_bounds

    low, high = pollyxt_bounds()["beam.divergence"]
    assert low < pollyxt().beam.divergence < high
    c = chm15k()
    bounds = chm15k_bounds()
    low, high = bounds["beam.divergence"]
    # from just above the 90 mm beam's diffraction limit, 1064 nm / (pi 45 mm) = 7.53 µrad, to the
    # manual's 0.3 mrad full angle
    assert low == pytest.approx(1.05 * 7.526e-6, rel=1e-3) and high == 0.15e-3
    assert low < c.beam.divergence <= high
    low, high = bounds["beam.offset[0]"]
    assert low == pytest.approx(c.beam.waist_radius + c.telescope.diameter / 2)
    assert low <= c.beam.offset[0] <= high


def test_a_fit_names_the_parameter_that_ends_on_a_preset_bound():
    from lidar_overlap.model.instruments import chm15k_bounds

    z = np.linspace(150.0, 1200.0, 12)
    truth = lo.parameters.replace(chm15k(), {"beam.offset[0]": 0.09})  # closer than allowed
    g = lo.overlap(truth, z, "rt", tolerance=1e-6).overlap
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit = lo.fit(chm15k(), z, g, 1e-3, free=["beam.offset[0]"], method="rt",
                     bounds={"beam.offset[0]": chm15k_bounds()["beam.offset[0]"]})  # fmt: skip
    assert fit.at_bounds == ("beam.offset[0]",)
    assert fit.parameters["beam.offset[0]"] == pytest.approx(0.095)
    assert "on a bound" in fit.summary()
