"""Turbulence on both paths (FO): the fast method (reciprocity, random-phase receiver fields through
the beam's screens) against a brute-force oracle (tests/_turbulence_oracle.py: every scatterer's own
wave through the same screens to the aperture and onto the detector, powers summed), and the Python
API of ``paths``.

The oracle case is small: D = 1.5 cm, w0 = 2.5 mm, 1064 nm, a 50 urad field of view (about one
    diffraction
width), 200 m through 3 screens with r0 = 1 cm (plane wave): the image of a scatterer moves and
spreads by about its own size, so the return path changes G by more than the tolerances below.
"""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core
from lidar_overlap.model.turbulence import TWO_WAY_BOUND

sys.path.insert(0, str(Path(__file__).parent))
from _turbulence_oracle import Oracle, replay_screens  # noqa: E402

Z = 200.0
CN2 = 7.3e-13
SEED = 5
GRID = 128
# The oracle's own discretisation (scatterers every 3.3 mm, a 1.1 mm pupil grid, the detector disc
# sampled): measured 2.4e-3 below the exact FO overlap without turbulence; 5e-3 allowed.
ORACLE_ATOL = 5e-3
# Random-phase receiver: the draw's own standard error (spread of its fields over sqrt(M)), 3 of
# them.
RECEIVER_SIGMAS = 3.0
FIELDS = 256


def oracle_system():
    return lo.LidarSystem(
        beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=2.5e-3),
        telescope=lo.Telescope(diameter=0.015, focal_length=0.5),
        detector=lo.Detector(radius=25e-6),
    )


@pytest.fixture(scope="module")
def oracle():
    # reach: the field of view's footprint (1.75 cm) plus the eddies' spread lambda z / r0 (2.1 cm);
    # angle: the scatterers' cone to the aperture plus lambda / r0.
    return Oracle(oracle_system(), Z, n=GRID, spacing=1.1e-3, reach=0.039, angle=0.34e-3, stride=3)


def test_oracle_without_turbulence_is_the_fo_overlap(oracle):
    g = oracle.overlap(oracle.beam(), oracle.scatterers()[0], oracle.vacuum_aperture_power())
    assert abs(g - lo.overlap(oracle_system(), [Z], "fo").overlap[0]) < ORACLE_ATOL


def test_both_paths_agree_with_the_oracle_draw_by_draw(oracle):
    s, air = oracle_system(), lo.Turbulence(CN2)
    opts = _core.TurbulenceOptions(
        realizations=1, screens=3, beam_grid=GRID, seed=SEED, paths="both", receiver_fields=FIELDS
    )
    raw = _core.overlap_fo_turbulent(s._native, [Z], air._native, opts)
    fast, error = float(raw.overlap[0, 0]), float(raw.receiver_error[0, 0])
    screens = replay_screens(raw, GRID, SEED, 0)
    beam, (detector, _) = oracle.beam(screens), oracle.scatterers(screens)
    aperture = oracle.vacuum_aperture_power()
    both = oracle.overlap(beam, detector, aperture)
    transmit = oracle.overlap(beam, oracle.scatterers()[0], aperture)
    print(
        f"G at {Z} m: fast {fast:.4f} +- {error:.4f}, oracle both {both:.4f}, oracle transmit only "
        f"{transmit:.4f}"
    )
    assert abs(fast - both) < RECEIVER_SIGMAS * error + ORACLE_ATOL
    # The transmit-only path replays the same beam: it must agree with the oracle's to its
    # discretisation.
    opts.paths = "transmit"
    plain = _core.overlap_fo_turbulent(s._native, [Z], air._native, opts)
    assert abs(float(plain.overlap[0, 0]) - transmit) < ORACLE_ATOL


def small_lidar():
    return lo.LidarSystem(
        beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=5e-3),
        telescope=lo.Telescope(diameter=0.05, focal_length=0.5),
        detector=lo.Detector(radius=45e-6),
    )


def test_both_is_the_default_and_transmit_is_the_cores_transmit_run():
    s, z, t = small_lidar(), [300.0, 800.0], lo.Turbulence(3e-14)
    assert lo.Turbulent(t).paths == "both"
    explicit = lo.overlap(
        s,
        z,
        lo.Turbulent(t, lo.FO(beam_grid=128), realizations=3, seed=2, screens=3, paths="transmit"),
    )
    # the core's own transmit-only run (its options' default), bit for bit
    opts = _core.TurbulenceOptions(realizations=3, screens=3, beam_grid=128, seed=2)
    assert opts.paths == "transmit"
    raw = _core.overlap_fo_turbulent(s._native, z, t._native, opts)
    assert np.array_equal(explicit.realizations, np.asarray(raw.overlap))
    assert explicit.amplification is None and explicit.paths == "transmit"


def test_both_paths_report_the_amplification_and_may_exceed_one():
    # Strong two-way turbulence through a narrow field of view: the mean G exceeds 1 (bounded by 2).
    s = lo.LidarSystem(
        beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=5e-3),
        telescope=lo.Telescope(diameter=0.05, focal_length=0.5),
        detector=lo.Detector(radius=70e-6),
    )
    r = lo.overlap(
        s,
        [1000.0],
        lo.Turbulent(
            lo.Turbulence(1e-13),
            lo.FO(beam_grid=432),
            realizations=2,
            seed=1,
            screens=5,
            paths="both",
            receiver_fields=2,
        ),
    )
    assert r.paths == "both" and r.uncorrelated.shape == (2, 1) and r.amplification.shape == (1,)
    assert np.all(r.overlap <= TWO_WAY_BOUND)
    assert np.allclose(r.amplification, r.overlap / r.uncorrelated.mean(axis=0))


def test_fo_without_a_grid_on_both_paths_takes_the_least_grid_the_core_accepts():
    # a 70 um detector through Cn2 = 1e-13 over 1 km: the core needs more than the default 256
    # samples per side; lo.FO() with its grid left to the library takes what auto would
    s = lo.LidarSystem(
        beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=5e-3),
        telescope=lo.Telescope(diameter=0.05, focal_length=0.5),
        detector=lo.Detector(radius=70e-6),
    )
    z, t = np.array([1000.0]), lo.Turbulence(1e-13)
    options = _core.TurbulenceOptions(paths="both", realizations=2, receiver_fields=2)
    needed = int(_core.turbulent_grid(s._native, z, t._native, options).min_beam_grid)
    assert needed > _core.TurbulenceOptions().beam_grid  # the case the default grid cannot run
    request = dict(paths="both", realizations=2, receiver_fields=2)
    fo = lo.plan(s, z, lo.Turbulent(t, lo.FO(), **request))
    by_auto = lo.plan(s, z, lo.Turbulent(t, **request))
    assert fo.backend == by_auto.backend == "fo_turbulent"
    assert fo.options.beam_grid == by_auto.options.beam_grid == needed


def test_paths_is_checked_by_name():
    t = lo.Turbulence(1e-14)
    for hostile in ("return", "Both", " both", None, 3, True, b"both"):
        with pytest.raises(ValueError, match=r"paths = .* is invalid: expected one of"):
            lo.Turbulent(t, paths=hostile)
    with pytest.raises(ValueError, match="receiver_fields"):
        lo.Turbulent(t, paths="both", receiver_fields=0)
    # the shortcut names it as the caller did
    with pytest.raises(ValueError, match="paths = 'Both' is invalid"):
        lo.overlap(small_lidar(), [500.0], "rt", turbulence=t, paths="Both")
    # a detector 3.5 Airy radii wide: ray tracing's diffraction error exceeds auto's tolerance, so
    # auto runs Fourier optics on both paths
    plan = lo.plan(
        small_lidar(),
        [500.0],
        lo.Turbulent(t, lo.Auto(fo=lo.FO(beam_grid=128)), paths="both", realizations=2),
    )
    assert plan.backend == "fo_turbulent" and plan.options.paths == "both"


def test_a_mean_above_one_is_refused_without_two_way_turbulence():
    s, z = small_lidar(), np.array([500.0])
    with pytest.raises(ValueError, match=r"within \[0, 1\]"):
        lo.OverlapResult(
            ranges=z,
            overlap=np.array([1.2]),
            method="fo",
            error_estimate=np.array([0.0]),
            system=s,
            tolerance=math.nan,
            error_kind="nominal",
        )
    with pytest.raises(ValueError, match=r"within \[0, 2\]"):
        lo.TurbulentOverlapResult(
            ranges=z,
            overlap=np.array([2.3]),
            method="fo",
            error_estimate=np.array([0.01]),
            system=s,
            tolerance=math.nan,
            error_kind="standard_error",
            paths="both",
        )


def test_one_draw_above_two_is_kept_on_both_paths_but_not_a_mean():
    # A single draw's G is not bounded by the two-way limit (a bright spot, or the speckle of one
    # receiver field): kept as it is; only the mean over draws is held to TWO_WAY_BOUND.
    s, z = small_lidar(), np.array([500.0])
    draws = np.array([[2.6], [0.2]])
    kw = dict(ranges=z, method="fo", system=s, tolerance=math.nan, error_kind="standard_error")
    r = lo.TurbulentOverlapResult(
        overlap=draws.mean(axis=0),
        error_estimate=np.array([1.7]),
        realizations=draws,
        high=np.array([2.48]),
        paths="both",
        **kw,
    )
    assert r.realizations[0, 0] == 2.6 and r.high[0] == 2.48
    with pytest.raises(
        ValueError, match=r"realizations holds 2.6: expected finite values within \[0, 1\]"
    ):
        lo.TurbulentOverlapResult(
            overlap=np.array([0.9]), error_estimate=np.array([0.1]), realizations=draws, **kw
        )


def test_turbulent_realizations_through_both_paths_is_lo_overlap():
    pytest.importorskip("xarray")
    s, z = small_lidar(), [300.0, 600.0]
    method = lo.Turbulent(
        lo.Turbulence(1e-14),
        lo.FO(beam_grid=128),
        realizations=5,
        seed=3,
        screens=3,
        paths="both",
        receiver_fields=2,
    )
    ds = lo.turbulent_realizations(s, z, method, chunk=2, threads=1)
    res = lo.overlap(s, z, method)
    assert ds.attrs["paths"] == "both"
    assert np.array_equal(
        ds["overlap"].values, res.realizations
    )  # the parts are the whole run's rows
    assert np.array_equal(ds["amplification"].values, res.amplification)
