"""Aperture masks and the telecover test: partitions add up to the full aperture, sector couplings
against an independent Monte-Carlo ray trace, symmetry and the sign and size of a tilt's north-south
asymmetry, the planner's choices and bad input."""

import dataclasses
import math
import warnings

import numpy as np
import pytest

import lidar_overlap as lo

TOL = 1e-4


def awkward_system(mask=None):
    """Tilted, offset, obstructed, defocused, with an NA and a detector offset."""
    return lo.LidarSystem(
        beam=lo.GaussianBeam(
            waist_radius=1e-3, divergence=0.2e-3, offset=(0.01, -0.005), tilt=(20e-6, -40e-6)
        ),
        telescope=lo.Telescope(
            diameter=0.15,
            focal_length=1.0,
            obstruction_radius=0.02,
            obstruction_distance=0.4,
            mask=mask,
        ),
        detector=lo.Detector(
            radius=0.45e-3, defocus=2e-3, offset=(4e-5, 0.0), numerical_aperture=0.22
        ),
    )


def tilted_table1(tilt_y=50e-6):
    s = lo.paper_table1()
    return dataclasses.replace(s, beam=dataclasses.replace(s.beam, tilt=(0.0, tilt_y)))


def in_sector(points, sector: lo.Sector, aperture_radius):
    rho = np.hypot(points[:, 0], points[:, 1])
    t = np.mod(np.arctan2(points[:, 1], points[:, 0]) - sector.start_angle, 2 * np.pi)
    outer = aperture_radius if sector.outer_radius is None else sector.outer_radius
    return (t <= sector.span) & (rho >= sector.inner_radius) & (rho <= outer)


def sector_points(rng, sector, aperture_radius, n):
    """Uniform points over the annular sector, and its area."""
    outer = aperture_radius if sector.outer_radius is None else sector.outer_radius
    r2 = sector.inner_radius**2 + (outer**2 - sector.inner_radius**2) * rng.random(n)
    phi = sector.start_angle + sector.span * rng.random(n)
    area = 0.5 * sector.span * (outer**2 - sector.inner_radius**2)
    return np.sqrt(r2)[:, None] * np.column_stack((np.cos(phi), np.sin(phi))), area


def rays_counted(system, z, scatterers, apertures):
    """The paraxial ray P -> A of docs/rt_method.md: past the obstruction, onto the detector, within
    the NA."""
    tel, det = system.telescope, system.detector
    f, d = tel.focal_length, tel.focal_length + det.defocus
    ok = np.ones(len(apertures), bool)
    if tel.obstruction_radius > 0:
        at_obstruction = apertures + (scatterers - apertures) * tel.obstruction_distance / z
        ok &= np.hypot(*at_obstruction.T) >= tel.obstruction_radius
    slope = (apertures - scatterers) / z - apertures / f
    landing = apertures + d * slope - np.asarray(det.offset)
    ok &= np.hypot(*landing.T) <= det.radius
    if det.numerical_aperture is not None:
        ok &= np.hypot(*slope.T) <= math.tan(math.asin(det.numerical_aperture))
    return ok


def test_quadrants_add_up_to_the_full_aperture():
    s = awkward_system()
    z = np.array([30.0, 80.0, 250.0, 900.0])
    r = lo.telecover(s, z, "quadrants", tolerance=TOL)
    assert r.names == ("north", "east", "south", "west")
    assert np.all(r.full.overlap > 0.01)
    np.testing.assert_allclose(r.overlap.sum(axis=0), r.full.overlap, rtol=0, atol=4 * TOL)
    # a rotated set of six sectors too, through the same system carrying the mask itself
    six = lo.ApertureMask.sectors(6, rotation=0.4)
    parts = [lo.overlap(awkward_system(m), z[:2], "rt", tolerance=TOL).overlap for m in six.split()]
    np.testing.assert_allclose(np.sum(parts, axis=0), r.full.overlap[:2], rtol=0, atol=6 * TOL)


@pytest.mark.parametrize(
    "sector",
    [lo.Sector(0.3, 1.9), lo.Sector(-2.0, 0.5, 0.03, 0.07), lo.Sector(2.5, 2.5 + 2 * np.pi, 0.05)],
)
def test_sector_coupling_against_monte_carlo(sector):
    s = awkward_system()
    R = 0.5 * s.telescope.diameter
    mask = lo.ApertureMask((sector,))
    masked = awkward_system(mask)
    rng = np.random.default_rng(7)
    n = 200_000
    # scatterers near the field of view's edge, where the sector is partly seen (couplings 0.01-0.4)
    for z, p in (
        (40.0, (0.015, 0.01)),
        (100.0, (0.04, -0.02)),
        (300.0, (0.13, 0.03)),
        (1000.0, (-0.44, 0.1)),
    ):
        a, area = sector_points(rng, sector, R, n)
        hits = rays_counted(s, z, np.broadcast_to(p, a.shape), a)
        frac = hits.mean()
        mc = frac * area / (np.pi * R**2)
        se = math.sqrt(max(frac * (1 - frac), 1.0 / n) / n) * area / (np.pi * R**2)
        exact = lo.emitter_coupling(masked, z, p)
        assert abs(exact - mc) <= 4 * se, (z, p, exact, mc, se)


def test_symmetric_system_gives_equal_sectors():
    s = lo.paper_table1(obstruction_radius=0.02, defocus=2e-3)
    z = np.geomspace(10, 2000, 8)
    r = lo.telecover(s, z, tolerance=TOL)
    assert np.all(np.abs(r.overlap - r.full.overlap / 4) <= 2 * TOL)
    assert np.all(np.abs(np.nan_to_num(r.deviation) * r.full.overlap / 4) <= 2 * TOL)


def test_tilt_north_south_asymmetry_sign_and_size():
    s = tilted_table1(50e-6)
    z = np.array([60.0, 120.0])
    r = lo.telecover(s, z, tolerance=TOL)
    north, east, south, west = r.overlap
    assert np.all(north > south + 10 * TOL)  # tilted towards +y: north sees more
    np.testing.assert_allclose(east, west, atol=2 * TOL)  # mirror symmetry about the y axis
    # size: an independent Monte-Carlo of the beam-averaged north and south G at 60 m
    rng = np.random.default_rng(11)
    z0, n = 60.0, 400_000
    w = s.beam.radius(z0)
    R = 0.5 * s.telescope.diameter
    for k, name in ((0, "north"), (2, "south")):
        sector = lo.ApertureMask.quadrants().sectors[k]
        p = np.array(s.beam.center(z0)) + 0.5 * w * rng.standard_normal((n, 2))
        a, area = sector_points(rng, sector, R, n)
        frac = rays_counted(s, z0, p, a).mean()
        mc, se = (
            frac * area / (np.pi * R**2),
            math.sqrt(frac * (1 - frac) / n) * area / (np.pi * R**2),
        )
        assert abs(r.overlap[k, 0] - mc) <= 4 * se + TOL, (name, r.overlap[k, 0], mc, se)
    # and the deviation has the tilt's sign, opposite for north and south
    assert r.deviation[0, 0] > 0.05 and r.deviation[2, 0] < -0.05


@pytest.mark.parametrize("z", [15.0, 150.0, 1500.0])
def test_tilted_quadrant_g_against_a_monte_carlo_of_rays(z):
    # The 1-D path (one moving disc: Table 1, no NA, no obstruction) end to end: scatterers drawn
    # from the Gaussian beam (sigma = w/2 per axis), aperture points uniform over the north
    # quadrant, each ray counted.
    s = tilted_table1(80e-6)
    north = lo.ApertureMask.quadrants().split()[0]
    g = lo.overlap(
        dataclasses.replace(s, telescope=dataclasses.replace(s.telescope, mask=north)),
        [z],
        "rt",
        tolerance=1e-6,
    ).overlap[0]
    rng = np.random.default_rng(11)
    n = 400_000
    beam_sigma = 0.5 * s.beam.radius(z)
    scatterers = np.asarray(s.beam.center(z)) + beam_sigma * rng.standard_normal((n, 2))
    apertures, area = sector_points(rng, north.sectors[0], 0.5 * s.telescope.diameter, n)
    share = area / (math.pi * (0.5 * s.telescope.diameter) ** 2)
    hits = rays_counted(s, z, scatterers, apertures)
    estimate, sd = share * hits.mean(), share * hits.std() / math.sqrt(n)
    assert abs(g - estimate) <= 4.5 * sd + 1e-6, (g, estimate, sd)


def test_stated_errors_bound_the_actual_ones_through_masks():
    # The 1-D path's error estimate (Gauss-Kronrod past the kinks it knows, tails bounded) against
    # the same path at 1e-10: random tilts, offsets, defocus, detector offsets and NAs (none, wide:
    # left out, narrow: the scatterer-plane path); rotated quadrants, six sectors and an annular
    # sector; tolerances 1e-3 and 1e-4. (Leaving the corners out of the breakpoints failed this.)
    rng = np.random.default_rng(5)
    z = np.geomspace(5.0, 5000.0, 40)
    for i in range(12):
        s = lo.paper_table1()
        beam = dataclasses.replace(
            s.beam, tilt=tuple(rng.normal(0, 150e-6, 2)), offset=tuple(rng.normal(0, 0.02, 2))
        )
        det = dataclasses.replace(
            s.detector,
            defocus=float(abs(rng.normal(0, 2e-3))),
            offset=tuple(rng.normal(0, 5e-5, 2)),
            numerical_aperture=(None, 0.4, 0.05)[i % 3],
        )
        masks = (
            lo.ApertureMask.quadrants(rotation=float(rng.uniform(0, 1))),
            lo.ApertureMask.sectors(6, rotation=float(rng.uniform(0, 1))),
            lo.ApertureMask([lo.Sector(0.3, 2.5, 0.02, 0.06)]),
        )
        narrow = det.numerical_aperture == 0.05  # the slow path: its quadrants at fewer ranges
        zz = z[::5] if narrow else z
        for part in (p for mask in (masks[:1] if narrow else masks) for p in mask.split()):
            m = dataclasses.replace(
                s, beam=beam, detector=det, telescope=dataclasses.replace(s.telescope, mask=part)
            )
            ref = lo.overlap(m, zz, "rt", tolerance=1e-10).overlap
            for tol in (1e-3, 1e-4):
                g = lo.overlap(m, zz, "rt", tolerance=tol)
                assert np.all(np.abs(g.overlap - ref) <= g.error_estimate + 1e-12)


@pytest.mark.parametrize(
    "tilt, offset, waist",
    [(0.0, 0.0, 1e-6), (5e-3, 0.07, 1e-3), (1e-6, 0.5, 0.05), (5e-3, 0.5, 1e-6)],
)
def test_extreme_beams_through_the_sectors_give_finite_g_in_0_1(tilt, offset, waist):
    # Beams far off the aperture, tilted out of the field of view, point-like or wide, from 0.5 m to
    # 1000 km: the 1-D path and the sectors-together call stay finite and within [0, 1] (or refuse
    # by name).
    s = lo.paper_table1()
    s = dataclasses.replace(
        s,
        beam=dataclasses.replace(
            s.beam, tilt=(tilt, 0.0), offset=(0.0, offset), waist_radius=waist
        ),
    )
    z = np.array([0.5, 1.0, 10.0, 1e3, 1e6])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # RT outside its validity near the lidar: said, not tested
        tele = lo.telecover(s, z)
    g = np.array([p.overlap for p in tele.sectors])
    assert np.all(np.isfinite(g)) and np.all((g >= -TOL) & (g <= 1 + TOL))
    with pytest.raises(ValueError, match=r"ranges\[0\]"):
        lo._core.overlap_rt_masks(s._native, [float("nan")], [lo.ApertureMask.quadrants()._native])
    with pytest.raises(ValueError, match="masks = 0"):
        lo._core.overlap_rt_masks(s._native, [100.0], [])


def test_telecover_traces_the_sectors_together_as_one_at_a_time():
    # One core call for all quadrants (shared nodes) against a call per quadrant: each within the
    # tolerance.
    s = tilted_table1()
    z = np.geomspace(10.0, 3000.0, 12)
    tele = lo.telecover(s, z, tolerance=TOL)
    for part, m in zip(tele.sectors, lo.ApertureMask.quadrants().split()):
        alone = lo.overlap(
            dataclasses.replace(s, telescope=dataclasses.replace(s.telescope, mask=m)),
            z,
            "rt",
            tolerance=TOL,
        )
        np.testing.assert_allclose(part.overlap, alone.overlap, rtol=0, atol=2 * TOL)
        assert np.all(part.error_estimate <= TOL * 1.0001)
    np.testing.assert_allclose(
        np.sum([p.overlap for p in tele.sectors], axis=0), tele.full.overlap, atol=4 * TOL
    )


def test_rings_partition_and_keep_radial_speed():
    s = awkward_system()
    z = np.array([50.0, 400.0])
    rings = lo.ApertureMask.rings([0.0, 0.04, None])
    full = lo.overlap(s, z, "rt", tolerance=TOL).overlap
    parts = [lo.overlap(awkward_system(m), z, "rt", tolerance=TOL).overlap for m in rings.split()]
    np.testing.assert_allclose(np.sum(parts, axis=0), full, atol=4 * TOL)


def test_planner_and_result():
    s = awkward_system(lo.ApertureMask.quadrants().split()[0])
    p = lo.plan(s, [100.0], "rt")
    assert p.backend == "rt_masked" and "north" in str(p)
    assert lo.plan(s, [100.0], "fo").backend == "fo_masked"
    assert lo.plan(s, [100.0], "auto", tolerance=0.5).backend == "rt_masked"
    assert lo.plan(s, [100.0], "auto", tolerance=1e-4).backend == "fo_masked"
    with pytest.raises(ValueError, match="do not apply with telescope.mask"):
        lo.plan(s, [100.0], "fo", fo_path="2d")
    with pytest.raises(ValueError, match="turbulence"):
        lo.plan(s, [100.0], lo.Turbulent(lo.Turbulence(cn2=1e-15), "rt"))
    r = lo.telecover(tilted_table1(), [100.0, 300.0], tolerance=1e-3)
    ds = r.to_xarray()
    assert ds.overlap.dims == ("sector", "range") and list(ds.sector.values) == list(r.names)
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    top, bottom = r.plot(band=0.1)
    assert len(top.lines) == 5 and len(bottom.lines) == 4 + 3
    matplotlib.pyplot.close("all")


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: lo.Sector(float("nan"), 1.0), "sector.start_angle"),
        (lambda: lo.Sector(0.0, float("inf")), "sector.stop_angle"),
        (lambda: lo.Sector(1.0, 1.0), "sector.stop_angle"),
        (lambda: lo.Sector(0.0, 7.0), "by at most 2 pi"),
        (lambda: lo.Sector(0.0, 1.0, -0.01), "sector.inner_radius"),
        (lambda: lo.Sector(0.0, 1.0, 0.05, 0.04), "sector.outer_radius"),
        (lambda: lo.ApertureMask(()), "at least one Sector"),
        (
            lambda: lo.ApertureMask((lo.Sector(0.0, 2.0), lo.Sector(1.5, 3.0))),
            r"mask.sectors\[1\].*mask.sectors\[0\]",
        ),
        (lambda: lo.ApertureMask((lo.Sector(-0.5, 0.5), lo.Sector(6.0, 6.2))), "does not overlap"),
        (lambda: lo.ApertureMask(lo.Sector(0.0, 1.0)), "tuple of Sector"),
        (lambda: lo.ApertureMask.rings([0.04]), "at least two radii"),
        (lambda: lo.ApertureMask.sectors(0), "n = 0"),
        (lambda: lo.ApertureMask.sectors(65), "n = 65"),
        (lambda: lo.ApertureMask.quadrants(float("nan")), "rotation"),
        (lambda: lo.ApertureMask((lo.Sector(1e4, 1e4 + 1),)), "within"),
        (
            lambda: lo.Telescope(mask=lo.ApertureMask((lo.Sector(0.0, 1.0, 0.0, 0.2),))),
            "outer_radius",
        ),
        (
            lambda: lo.Telescope(
                obstruction_radius=0.02, mask=lo.ApertureMask((lo.Sector(0.0, 1.0, 0.0, 0.015),))
            ),
            "obstruction",
        ),
        (lambda: lo.Telescope(mask="north"), "telescope.mask"),
        (lambda: lo.telecover(lo.paper_table1(), [100.0], sectors="octants"), "sectors"),
        (lambda: lo.telecover(lo.paper_table1(), [100.0], sectors=4), "sectors"),
        (lambda: lo.telecover(lo.paper_table1(), [100.0], method="turbulent"), "method"),
        (
            lambda: lo.telecover(awkward_system(lo.ApertureMask.quadrants()), [100.0]),
            "system.telescope.mask",
        ),
        (
            lambda: lo.telecover(
                lo.paper_table1(), [100.0], sectors=lo.ApertureMask((lo.Sector(0, 1, 0, 0.1),))
            ),
            "outer_radius",
        ),
    ],
)
def test_bad_input(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_fourier_optics_quadrants_against_the_full_curve_and_rt():
    s = lo.paper_table1(defocus=2e-3)
    s = dataclasses.replace(s, beam=dataclasses.replace(s.beam, tilt=(0.0, 50e-6)))
    z = np.array([200.0, 1000.0])
    fo = lo.telecover(s, z, method="fo")
    rt = lo.telecover(s, z, method="rt", tolerance=TOL)
    diffraction = lo.plan(
        s, z, "auto", tolerance=0.5
    ).rt_model_error  # RT's estimated diffraction error
    assert 5e-4 < diffraction < 5e-3
    # the sectors' edges diffract light off the detector: the quadrants fall short of the full FO
    # curve by about RT's diffraction error, never by more
    shortfall = fo.full.overlap - fo.overlap.sum(axis=0)
    assert np.all(shortfall > 0) and np.all(shortfall <= diffraction)
    np.testing.assert_allclose(fo.overlap, rt.overlap, atol=diffraction / 2)
    assert fo.overlap[0, 0] > fo.overlap[2, 0]  # north sees more, as in RT


def test_result_files_keep_the_mask(tmp_path):
    pytest.importorskip("xarray")
    mask = lo.ApertureMask((lo.Sector(0.1, 1.2, 0.01, 0.05), lo.Sector(2.0, 3.0)), ("a", "b"))
    r = lo.overlap(
        lo.LidarSystem(telescope=lo.Telescope(mask=mask)), [100.0, 300.0], "rt", tolerance=1e-3
    )
    r.to_csv(tmp_path / "r.csv")
    assert lo.OverlapResult.from_csv(tmp_path / "r.csv") == r
    back = lo.OverlapResult.from_netcdf(_netcdf(r, tmp_path / "r.nc"))
    assert back == r and back.system.telescope.mask == mask


def _netcdf(result, path):
    try:
        result.to_netcdf(path)
    except ImportError as exc:  # no netCDF engine
        pytest.skip(str(exc))
    return path
