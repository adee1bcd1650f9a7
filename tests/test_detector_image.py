"""Geometric detector-plane images: power conserved, the beam centre imaged at -c d/z, and the
fraction on the detector equal to the RT overlap (which integrates the same circles of confusion
exactly)."""

import dataclasses
import math

import numpy as np
import pytest

import lidar_overlap as lo

# Pixelisation of the circle of confusion and the detector edge on 192^2 samples.
FRACTION_ATOL = 0.01
POWER_RTOL = 1e-6


@pytest.mark.parametrize("z", [30.0, 150.0, 600.0])
@pytest.mark.parametrize(
    "system",
    [
        lo.paper_table1(),
        lo.paper_table1(defocus=2e-3),
        dataclasses.replace(
            lo.paper_table1(), beam=lo.GaussianBeam(355e-9, 1e-3, tilt=(0.2e-3, 0.0))
        ),
    ],
)
def test_fraction_on_detector_is_the_rt_overlap(system, z):
    img = lo.detector_image(system, z)
    h = img.u[1] - img.u[0]
    assert abs(img.image.sum() * h * h - 1.0) < POWER_RTOL
    assert abs(img.fraction - lo.overlap(system, [z], method="rt").overlap[0]) < FRACTION_ATOL


def test_tilted_beam_images_opposite_its_centre():
    system = dataclasses.replace(
        lo.paper_table1(), beam=lo.GaussianBeam(355e-9, 1e-3, tilt=(0.3e-3, 0.0))
    )
    z = 400.0
    img = lo.detector_image(system, z)
    col = img.image.sum(axis=0)
    centroid = float((col * img.u).sum() / col.sum())
    assert abs(centroid + 0.3e-3 * z * 1.0 / z) < 0.1 * (
        img.u[1] - img.u[0]
    )  # -c d/z with d = f = 1 m


def test_plot_detector_image_draws(tmp_path):
    from lidar_overlap.views.plotting import plot_detector_image

    ax = plot_detector_image(lo.paper_table1(), 200.0)
    ax.figure.savefig(tmp_path / "image.png")
    assert "on the detector" in ax.get_title()


def test_bad_range():
    with pytest.raises(ValueError, match="z = -1"):
        lo.detector_image(lo.paper_table1(), -1.0)


# --------------------------------------------------------------------------------- hostile input
#: Budget (bytes) the memory tests set, whatever the machine's RAM.
TEST_BUDGET = 1 << 30


@pytest.fixture
def small_budget():
    previous = lo.max_memory()
    lo.set_max_memory(TEST_BUDGET)
    yield TEST_BUDGET
    lo.set_max_memory(previous)


@pytest.mark.parametrize("n", [4096, 16384, 65536])
def test_n_beyond_the_memory_budget_is_refused_before_allocation(n, small_budget):
    with pytest.raises(
        ValueError,
        match=rf"^n = {n} needs [0-9.]+ GiB of memory, more than the budget of 1 GiB "
        r"\(max_memory\)",
    ):
        lo.detector_image(lo.paper_table1(), 100.0, n=n)


@pytest.mark.parametrize("n", [2**31 - 1, 2**63, 10**400, 65538, 15, 0, -1, 64.0, True, "64", None])
def test_n_outside_the_grid_sides_is_refused_by_name(n):
    with pytest.raises(ValueError, match="^n = "):
        lo.detector_image(lo.paper_table1(), 100.0, n=n)


@pytest.mark.parametrize("field_beam", [False, True])
def test_memory_estimate_covers_the_arrays_built(field_beam):
    """The budget check's estimate is at least the peak NumPy allocation (tracemalloc) of a real
    call."""
    import tracemalloc

    from lidar_overlap.optics.detector_image import _bytes_needed

    system = lo.paper_table1()
    if field_beam:
        system = dataclasses.replace(
            system, beam=lo.FieldBeam(lo.Field.gaussian(355e-9, 1e-3, 128, 1e-4))
        )
    n = 256
    tracemalloc.start()
    try:
        _ = lo.detector_image(system, 100.0, n=n).fraction
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak <= _bytes_needed(system, n)


@pytest.mark.parametrize(
    "z",
    [math.nan, math.inf, 0.0, -0.0, 5e-324, 1e-300, 1e300, 2e10, 2**63, 10**400, True, "1", None],
)
def test_z_outside_the_ranges_is_refused_by_name(z):
    with pytest.raises(ValueError, match="^z = "):
        lo.detector_image(lo.paper_table1(), z)


def test_z_before_the_obstruction_is_refused_by_name():
    with pytest.raises(
        ValueError, match="^z = 0.5 is invalid: expected a range beyond the obstruction"
    ):
        lo.detector_image(lo.paper_table1(obstruction_radius=0.02, obstruction_distance=0.7), 0.5)


@pytest.mark.parametrize("z", [1e-10, 1e10])
def test_z_at_the_ends_of_the_ranges_gives_a_finite_image(z):
    img = lo.detector_image(lo.paper_table1(), z, n=32)
    assert np.all(np.isfinite(img.image)) and 0.0 <= img.fraction <= 1.0


def test_system_of_the_wrong_kind_is_refused_by_name():
    with pytest.raises(ValueError, match="^system = "):
        lo.detector_image(lo.GaussianBeam(), 100.0)
