"""Alignment maps: each grid point is lo.overlap of the misaligned system bit for bit; the physics
of tilts and offsets (mirror and swap symmetry, a tilt equal to the offset that puts the beam at the
same place); bad axes refused naming the axis and the value."""

import sys
import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.analysis.design.alignment import misaligned

pytest.importorskip("xarray")

TOL = 1e-5
#: Two G values each within TOL of the truth differ by at most 2 TOL.
PAIR_TOL = 2 * TOL
BIAXIAL = lo.LidarSystem(
    beam=lo.GaussianBeam(wavelength=355e-9, waist_radius=1e-3, offset=(0.05, 0.0)),
    telescope=lo.paper_table1().telescope,
    detector=lo.paper_table1().detector,
)


def test_grid_points_equal_overlap_of_the_misaligned_system_bit_for_bit():
    z = np.array([60.0, 250.0, 900.0])
    tilt, det = np.array([-2e-4, 0.0, 1.5e-4]), np.array([-1e-4, 5e-5])
    ds = lo.alignment_map(BIAXIAL, z, tilt_x=tilt, detector_offset_y=det, tolerance=TOL, threads=2)
    assert ds["overlap"].dims == ("tilt_x", "detector_offset_y", "range")
    assert ds["tilt_x"].attrs["units"] == "rad" and ds["range"].attrs["units"] == "m"
    assert ds.attrs["method"] == "rt" and ds.attrs["tolerance"] == TOL
    for i, t in enumerate(tilt):
        for j, d in enumerate(det):
            one = lo.overlap(
                misaligned(BIAXIAL, tilt_x=t, detector_offset_y=d),
                z,
                "rt",
                tolerance=TOL,
                threads=2,
            )
            assert np.array_equal(ds["overlap"].values[i, j], one.overlap)
            assert np.array_equal(ds["error_estimate"].values[i, j], one.error_estimate)


def test_fourier_optics_maps_are_lo_overlap_per_grid_point_and_agree_with_rt():
    # RT's diffraction error here is bounded by 3.5e-3 (validity.rt_error_bound; the two differ by
    # 2.4e-3): 1e-2 leaves room for the tilts.
    z, tilt = np.array([150.0, 1000.0]), np.array([-3e-4, 0.0, 2e-4])
    fo = lo.alignment_map(BIAXIAL, z, tilt_x=tilt, method="fo")
    assert (
        fo.attrs["method"] == "fo"
        and fo.attrs["fo_path"] == "radial"
        and np.isnan(fo.attrs["tolerance"])
    )
    for i, t in enumerate(tilt):
        one = lo.overlap(misaligned(BIAXIAL, tilt_x=t), z, "fo")
        assert np.array_equal(fo["overlap"].values[i], one.overlap)
    rt = lo.alignment_map(BIAXIAL, z, tilt_x=tilt, tolerance=TOL)
    np.testing.assert_allclose(fo["overlap"].values, rt["overlap"].values, rtol=0, atol=1e-2)


def test_axes_add_to_the_systems_own_value():
    tilted = misaligned(BIAXIAL, tilt_x=1e-4)
    ds = lo.alignment_map(tilted, [300.0], tilt_x=[-1e-4, 0.0], tolerance=TOL)
    assert ds["tilt_x"].attrs["system_value"] == 1e-4
    aligned = lo.overlap(BIAXIAL, [300.0], "rt", tolerance=TOL)
    assert ds["overlap"].values[0, 0] == aligned.overlap[0]


def test_axisymmetric_map_is_mirror_and_swap_symmetric():
    t = np.linspace(-4e-4, 4e-4, 5)
    g = lo.alignment_map(lo.paper_table1(), [80.0, 600.0], tilt_x=t, tilt_y=t, tolerance=TOL)[
        "overlap"
    ].values
    np.testing.assert_allclose(g, g[::-1], rtol=0, atol=PAIR_TOL)  # tilt_x -> -tilt_x
    np.testing.assert_allclose(g, g.transpose(1, 0, 2), rtol=0, atol=PAIR_TOL)  # tilt_x <-> tilt_y
    assert g[2, 2, 1] > g[0, 2, 1] + 0.1  # and tilts do matter


def test_a_tilt_equals_the_offset_that_puts_the_beam_centre_at_the_same_place():
    # Ray tracing weighs each scatterer at range z by the beam irradiance there, which depends on
    # the centre offset + tilt z and the radius only: at z0 the two beams light the same scatterers,
    # so G agrees to the two quadrature errors (PAIR_TOL). Away from z0 the centres differ and so
    # does G.
    z0, z = 800.0, np.array([100.0, 800.0])
    t = np.array([1e-4, 2e-4, 3e-4])
    by_tilt = lo.alignment_map(lo.paper_table1(), z, tilt_x=t, tolerance=TOL)["overlap"].values
    by_offset = lo.alignment_map(lo.paper_table1(), z, beam_offset_x=t * z0, tolerance=TOL)[
        "overlap"
    ].values
    np.testing.assert_allclose(by_tilt[:, 1], by_offset[:, 1], rtol=0, atol=PAIR_TOL)
    assert np.max(np.abs(by_tilt[:, 0] - by_offset[:, 0])) > 0.1


@pytest.mark.parametrize(
    "axes, message",
    [
        (dict(tilt_x=[0.0, np.nan]), r"tilt_x\[1\] = nan"),
        (dict(tilt_y=[0.0, np.inf]), r"tilt_y\[1\] = inf"),
        (dict(defocus=[]), "defocus has shape"),
        (dict(tilt_x=[1e-4, 0.0]), r"tilt_x must be strictly increasing"),
        (dict(tilt_x=[[0.0, 1e-4]]), "tilt_x has shape"),
        (dict(tilt_x=["a"]), "tilt_x"),
        (dict(), "one or two axes, 0 given"),
        (dict(tilt_x=[0.0], tilt_y=[0.0], defocus=[0.0]), "one or two axes, 3 given"),
        (
            dict(tilt_x=np.arange(65536) * 1e-12, tilt_y=np.arange(65536) * 1e-12),
            "4294967296 grid points",
        ),
        (dict(tilt_y=[0.0, 1e300]), r"tilt_y\[1\] = 1e\+300 makes an invalid system"),
        (dict(beam_offset_x=[-1e300]), r"beam_offset_x\[0\] = -1e\+300"),
        (dict(defocus=[-2.0]), r"defocus\[0\] = -2 makes an invalid system"),
    ],
)
def test_bad_axes_are_refused_naming_the_axis_and_value(axes, message):
    with pytest.raises(ValueError, match=message):
        lo.alignment_map(lo.paper_table1(), [300.0], **axes)


def test_other_bad_input_is_refused():
    with pytest.raises(ValueError, match="not available for alignment maps"):
        lo.alignment_map(lo.paper_table1(), [300.0], tilt_x=[0.0], method="auto")
    with pytest.raises(ValueError, match="too many for method='fo'"):
        lo.alignment_map(
            lo.paper_table1(),
            [300.0],
            tilt_x=np.arange(60) * 1e-6,
            tilt_y=np.arange(60) * 1e-6,
            method="fo",
        )
    with pytest.raises(ValueError, match="ranges"):
        lo.alignment_map(lo.paper_table1(), [300.0, 100.0], tilt_x=[0.0])
    with pytest.raises(ValueError, match="tolerance"):
        lo.alignment_map(lo.paper_table1(), [300.0], tilt_x=[0.0], tolerance=2.0)
    with pytest.raises(TypeError):
        lo.alignment_map(lo.paper_table1(), [300.0], tilt_z=[0.0])


def test_an_unreached_tolerance_warns_counting_the_map_values_not_its_ranges():
    # one segment per integral: every tilted point's integral stops short. The warning once said
    # "9 of 2 ranges".
    tilted = lo.LidarSystem(beam=lo.GaussianBeam(tilt=(1e-4, 0.0)))
    with pytest.warns(RuntimeWarning, match=r"not reached at \d+ of 10 values \(grid points"):
        lo.alignment_map(
            tilted,
            [500.0, 1000.0],
            tilt_x=np.linspace(-1e-3, 1e-3, 5),
            method=lo.RT(tolerance=1e-9, max_segments=1),
        )


@pytest.mark.parametrize("tolerance", [1e-300, 1e-15, 0.0, -1e-3, 1.0, float("nan")])
def test_a_tolerance_double_precision_cannot_meet_is_refused_by_name(tolerance):
    # 1e-300 once ran every integral of lo.align to its segment limit: 20 CPU s, then a warning
    with pytest.raises(ValueError, match=r"tolerance = .* expected a value in \[1e-14, 1\)"):
        lo.alignment_map(lo.paper_table1(), [300.0], tilt_x=[0.0], tolerance=tolerance)


def test_without_xarray_the_error_says_how_to_install_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(ImportError, match=r"pip install 'lidar-overlap\[io\]'"):
        lo.alignment_map(lo.paper_table1(), [300.0], tilt_x=[0.0])


def test_plot_alignment_map_draws_a_heat_map_per_range():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    from lidar_overlap.views.plotting import plot_alignment_map

    t = np.linspace(-3e-4, 3e-4, 4)
    ds = lo.alignment_map(lo.paper_table1(), [100.0, 500.0], tilt_x=t, tilt_y=t, tolerance=1e-3)
    axes = plot_alignment_map(ds)
    assert (
        len(axes) == 2 and axes[0].get_xlabel() == "tilt_y (mrad)" and "100" in axes[0].get_title()
    )
    one = plot_alignment_map(ds, range=500.0)
    assert (
        one.get_ylabel() == "tilt_x (mrad)" and len(one.figure.axes) == 2
    )  # the map and its colorbar
    line = plot_alignment_map(
        lo.alignment_map(lo.paper_table1(), [100.0], defocus=[0.0, 1e-3]), range=100.0
    )
    assert line.get_xlabel() == "defocus (mm)"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import matplotlib.pyplot as plt

        plt.close("all")
