"""Limits every entry point enforces, reproducibility and the public phase screens.

Physical scales, thread counts and the memory budget are refused before any work with a ValueError
naming the parameter (Ctrl-C: tests/test_ctrl_c.py); the 2-D FO path gives the same bits for any
thread count and in another process; lo.phase_screen has the Kolmogorov structure function.
"""

import math
import os
import subprocess
import sys

import numpy as np
import pytest

import lidar_overlap as lo

# Kolmogorov screens: mean structure function over SCREENS screens of 128^2 (along x and y) against
# 6.88 (r/r0)^(5/3). The core is within STRUCTURE_BIAS of it (tests/cpp/test_phase_screen.cpp, 2000
# screens); the sampling scatter is measured (one screen's structure function at n/4 scatters by
# ~85 % of its mean, so 256 screens leave ~4 %) and allowed STRUCTURE_SIGMAS standard errors.
SCREENS = 256
STRUCTURE_BIAS = 0.02
STRUCTURE_SIGMAS = 4.0


@pytest.mark.parametrize(
    "make, name",
    [
        (lambda: lo.GaussianBeam(wavelength=1e300), "beam.wavelength"),
        (lambda: lo.GaussianBeam(waist_radius=1e-300), "beam.waist_radius"),
        (lambda: lo.GaussianBeam(waist_radius=1e-7), "beam.waist_radius"),  # lambda/(pi w0) > 1 rad
        (lambda: lo.GaussianBeam(divergence=1e300), "beam.divergence"),
        (lambda: lo.GaussianBeam(tilt=(2.0, 0.0)), "beam.tilt"),
        (lambda: lo.GaussianBeam(offset=(1e30, 0.0)), "beam.offset"),
        (lambda: lo.Telescope(diameter=5e-324), "telescope.diameter"),
        (lambda: lo.Telescope(focal_length=1e11), "telescope.focal_length"),
        (lambda: lo.Detector(radius=1e300), "detector.radius"),
        (lambda: lo.Aberrations(w040=1e300), "aberrations.w040"),
        (lambda: lo.Aberrations(zernike={232: 1e-9}), "aberrations.zernike"),
        (lambda: lo.Turbulence(1e300), "cn2"),
    ],
)
def test_meaningless_scales_are_refused_by_name(make, name):
    with pytest.raises(ValueError, match=name.replace(".", r"\.")):
        make()


@pytest.mark.parametrize("method", ["rt", "fo", "auto"])
def test_m2_below_one_is_refused_on_construction_for_every_method(method):
    theta_d = 355e-9 / (math.pi * 1e-3)
    with pytest.raises(ValueError, match="beam.divergence.*M\\^2 >= 1"):
        lo.overlap(lo.paper_table1(divergence=0.9 * theta_d), [100.0], method)
    # the paper's geometric marginal-ray law takes any divergence, in ray tracing
    thin = lo.paper_table1(divergence=0.9 * theta_d, width_law="linear")
    assert 0.0 <= lo.overlap(thin, [100.0], "rt").overlap[0] <= 1.0


@pytest.mark.parametrize("threads", [-1, 2**31 - 1, 40000, 2**40, True, 1.5])
def test_threads_beyond_the_cap_are_refused(threads):
    with pytest.raises(ValueError, match="threads"):
        lo.overlap(lo.paper_table1(), [100.0], threads=threads)
    assert lo.max_threads() >= 256


def test_memory_budget_is_checked_before_allocating():
    default = lo.max_memory()
    try:
        lo.set_max_memory(2**20)  # 1 MiB
        with pytest.raises(ValueError, match=r"n = 512 needs .*\(max_memory\)"):
            lo.Field.gaussian(355e-9, 1e-3, 512, 1e-5)
        with pytest.raises(ValueError, match="beam_grid"):
            lo.overlap(lo.paper_table1(), [100.0], "fo", fo_path="2d", beam_grid=512)
        assert lo.Field.gaussian(355e-9, 1e-3, 64, 1e-4).n == 64  # 64 KiB fits
    finally:
        lo.set_max_memory(0)
    assert lo.max_memory() == default > 0


# A process limited to LIMITED_BYTES of address space, its budget lifted to the most there is, asks
# for a 2-D FO grid of 2^15 per side (~16 GiB of complex samples): the core cannot allocate it.
LIMITED_BYTES = 3 * 2**30
_OUT_OF_MEMORY = """
import resource, sys
import lidar_overlap as lo
resource.setrlimit(resource.RLIMIT_AS, ({limit}, {limit}))
lo.set_max_memory(2**63 - 1)
try:
    lo.overlap(lo.paper_table1(), [100.0], "fo", fo_path="2d", beam_grid=2**15)
except MemoryError as exc:
    print(exc)
    sys.exit(3)
"""


@pytest.mark.skipif(sys.platform != "linux", reason="RLIMIT_AS as Linux counts it")
@pytest.mark.skipif(
    "asan" in os.environ.get("LD_PRELOAD", ""),
    reason="AddressSanitizer reserves its shadow as address space: nothing starts under RLIMIT_AS",
)
def test_a_budget_above_the_machines_memory_fails_naming_the_grid_and_the_budget():
    code = _OUT_OF_MEMORY.format(limit=LIMITED_BYTES)
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, env=os.environ
    )
    assert done.returncode == 3, done.stderr
    said = done.stdout
    assert "beam grid of 32768² samples" in said and "set_max_memory" in said, said
    assert "set_max_memory(0)" in said and "GiB" in said


@pytest.mark.parametrize("grid", [2**32, 2**40, 16384 * 16])
def test_huge_grids_are_refused_without_allocating(grid):
    with pytest.raises(ValueError, match="beam_grid"):
        lo.overlap(lo.paper_table1(), [100.0], "fo", fo_path="2d", beam_grid=grid)


def test_fo_2d_is_bit_reproducible_across_threads_and_processes():
    system = lo.LidarSystem(beam=lo.GaussianBeam(offset=(0.1, 0.0), tilt=(-0.3e-3, 0.0)))
    z = np.geomspace(50.0, 2000.0, 6)
    one = lo.overlap(system, z, "fo", fo_path="2d", threads=1).overlap
    every = lo.overlap(system, z, "fo", fo_path="2d", threads=0).overlap
    assert one.tobytes() == every.tobytes()
    code = (
        "import numpy as np, lidar_overlap as lo; s = "
        "lo.LidarSystem(beam=lo.GaussianBeam(offset=(0.1, 0.0), tilt=(-0.3e-3, 0.0))); "
        "print(lo.overlap(s, np.geomspace(50.0, 2000.0, 6), 'fo', fo_path='2d', "
        "threads=3).overlap.tobytes().hex())"
    )
    other = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, "PYTHONWARNINGS": "ignore"},
    ).stdout.strip()
    assert other == one.tobytes().hex()


def test_phase_screen_structure_function_is_kolmogorov():
    n, dx, r0 = 128, 0.01, 0.1
    lags = np.array([4, 8, 16, 32])
    kolmogorov = 6.88 * (lags * dx / r0) ** (5 / 3)
    ratio = np.empty((SCREENS, lags.size))
    for index in range(SCREENS):
        s = lo.phase_screen(n, dx, r0, seed=7, index=index)
        d = [np.mean((s[:, m:] - s[:, :-m]) ** 2) + np.mean((s[m:] - s[:-m]) ** 2) for m in lags]
        ratio[index] = 0.5 * np.array(d) / kolmogorov
    mean, error = ratio.mean(0), ratio.std(0, ddof=1) / math.sqrt(SCREENS)
    assert np.all(np.abs(mean - 1) <= STRUCTURE_BIAS + STRUCTURE_SIGMAS * error), (mean, error)
    assert np.all(error[:2] < 0.03)  # the short lags' bounds (<= 0.14) resolve a 15 % error in D


def test_phase_screen_is_reproducible_and_checked():
    a = lo.phase_screen(64, 0.01, 0.05, seed=1, index=3)
    assert a.shape == (64, 64) and np.all(np.isfinite(a))
    assert np.array_equal(a, lo.phase_screen(64, 0.01, 0.05, seed=1, index=3))
    assert not np.array_equal(a, lo.phase_screen(64, 0.01, 0.05, seed=2, index=3))
    assert np.all(lo.phase_screen(64, 0.01, math.inf) == 0.0)  # no turbulence
    for kwargs, name in (
        (dict(n=2**32), "n"),
        (dict(n=63), "n"),
        (dict(r0=0.0), "r0"),
        (dict(spacing=math.nan), "spacing"),
        (dict(seed=-1), "seed"),
        (dict(outer_scale=0.0), "outer_scale"),
        (dict(inner_scale=-1.0), "inner_scale"),
    ):
        args = dict(n=64, spacing=0.01, r0=0.05) | kwargs
        with pytest.raises(ValueError, match=name):
            lo.phase_screen(**args)
