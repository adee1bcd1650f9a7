"""Geometric detector-plane images: power conserved, the beam centre imaged at -c d/z, and the fraction on
the detector equal to the RT overlap (which integrates the same circles of confusion exactly)."""

import dataclasses

import numpy as np
import pytest

import lidar_overlap as lo

# Pixelisation of the circle of confusion and the detector edge on 192^2 samples.
FRACTION_ATOL = 0.01
POWER_RTOL = 1e-6


@pytest.mark.parametrize("z", [30.0, 150.0, 600.0])
@pytest.mark.parametrize("system", [lo.paper_table1(), lo.paper_table1(defocus=2e-3),
                                    dataclasses.replace(lo.paper_table1(),
                                                        beam=lo.GaussianBeam(355e-9, 1e-3, tilt=(0.2e-3, 0.0)))])
def test_fraction_on_detector_is_the_rt_overlap(system, z):
    img = lo.detector_image(system, z)
    h = img.u[1] - img.u[0]
    assert abs(img.image.sum() * h * h - 1.0) < POWER_RTOL
    assert abs(img.fraction - lo.overlap(system, [z], method="rt").overlap[0]) < FRACTION_ATOL


def test_tilted_beam_images_opposite_its_centre():
    system = dataclasses.replace(lo.paper_table1(), beam=lo.GaussianBeam(355e-9, 1e-3, tilt=(0.3e-3, 0.0)))
    z = 400.0
    img = lo.detector_image(system, z)
    col = img.image.sum(axis=0)
    centroid = float((col * img.u).sum() / col.sum())
    assert abs(centroid + 0.3e-3 * z * 1.0 / z) < 0.1 * (img.u[1] - img.u[0])   # -c d/z with d = f = 1 m


def test_plot_detector_image_draws(tmp_path):
    from lidar_overlap.plotting import plot_detector_image
    ax = plot_detector_image(lo.paper_table1(), 200.0)
    ax.figure.savefig(tmp_path / "image.png")
    assert "on the detector" in ax.get_title()


def test_bad_range():
    with pytest.raises(ValueError, match="z = -1"):
        lo.detector_image(lo.paper_table1(), -1.0)
