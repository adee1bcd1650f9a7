"""LidarSystem's receiver geometry against its closed forms: the image distance d = f + defocus, the
diffraction blur λd/D and Airy radius 1.22 λd/D, the circle of confusion R|1 + d/z − d/f| and the
on-axis obstruction shadow |1 + d/z − d/f| r_obs z/(z − z_obs); and the property/method rule."""

import dataclasses
import math

import numpy as np
import pytest

import lidar_overlap as lo

# Each closed form is one to four floating-point operations away from the library's.
RTOL = 1e-15


@pytest.mark.parametrize("f, defocus", [(1.0, 0.0), (1.0, 5e-3), (0.3, -2e-3), (2.5, 0.1)])
def test_image_distance_is_focal_length_plus_defocus(f, defocus):
    s = lo.paper_table1(defocus=max(defocus, 0.0))
    s = dataclasses.replace(
        s,
        telescope=dataclasses.replace(s.telescope, focal_length=f),
        detector=dataclasses.replace(s.detector, defocus=defocus),
    )
    d = f + defocus
    assert s.image_distance == d
    assert s.diffraction_blur == pytest.approx(
        s.beam.wavelength * d / s.telescope.diameter, rel=RTOL
    )
    assert s.airy_radius == pytest.approx(
        1.22 * s.beam.wavelength * d / s.telescope.diameter, rel=RTOL
    )


def test_circle_of_confusion_and_shadow_against_closed_forms():
    s = lo.paper_table1(defocus=5e-3, obstruction_radius=0.02)
    R, f, d = 0.5 * s.telescope.diameter, s.telescope.focal_length, 1.0 + 5e-3
    z_obs, r_obs = s.telescope.obstruction_distance, s.telescope.obstruction_radius
    z = np.array([0.5 * z_obs, z_obs, 2.0, 201.0, 1e4])
    m = np.abs(1.0 + d / z - d / f)
    assert s.confusion_radius(z) == pytest.approx(R * m, rel=RTOL)
    shadow = np.where(z > z_obs, m * r_obs * z / np.maximum(z - z_obs, 1e-300), 0.0)
    assert s.shadow_radius(z) == pytest.approx(shadow, rel=RTOL)
    assert isinstance(s.confusion_radius(201.0), float) and isinstance(
        s.shadow_radius(201.0), float
    )
    assert s.confusion_radius(f * d / (d - f)) == pytest.approx(
        0.0, abs=1e-15
    )  # the range in focus
    assert lo.paper_table1().shadow_radius(100.0) == 0.0  # no obstruction


def test_derived_quantities_without_arguments_are_properties():
    s = lo.paper_table1()
    field = lo.Field.gaussian(355e-9, 1e-3, 64, 1.25e-4)
    for obj, name in (
        (s, "fov"),
        (s, "image_distance"),
        (s, "diffraction_blur"),
        (s, "airy_radius"),
        (s, "is_axisymmetric"),
        (s, "aberrated"),
        (s.beam, "half_angle_divergence"),
        (field, "power"),
        (field, "centroid"),
        (field, "beam_radius"),
        (lo.Aberrations(zernike={11: 5e-8}), "rms"),
    ):
        assert isinstance(getattr(type(obj), name), property), name
    assert field.beam_radius == pytest.approx(1e-3, rel=1e-9) and field.centroid == pytest.approx(
        (0, 0), abs=1e-15
    )
    assert lo.Aberrations(zernike={4: 3e-8, 11: 4e-8}).rms == pytest.approx(5e-8, rel=RTOL)
    assert s.fov == s.detector.fov(s.telescope.focal_length) == pytest.approx(0.9e-3, rel=1e-12)
    assert math.isfinite(s.beam.radius(100.0))
