"""Instrument presets: the published design values (aperture, focal length, field of view,
wavelength, expanded beam) and a biaxial overlap curve that reaches full overlap in the range the
instruments' papers report."""

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
