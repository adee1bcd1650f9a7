"""lo.propagate gives the same bits in every process and for any thread count: its transforms are
made of 1-D plans whose choice depends on the shape alone (cpp/src/fourier/fft.hpp), never on
timings. Each case runs in fresh interpreters with one and with two OpenMP threads, and the SHA-256
of the output values must agree."""

import hashlib
import os
import subprocess
import sys
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core

# (n, method, distance m, output spacing m or None): the angular spectrum and the single-FFT Fresnel
# and Fraunhofer paths at the sizes whose measured plans used to differ between processes, and the
# chirp-z path.
CASES = [
    (512, "angular_spectrum", 2.0, None),
    (1024, "angular_spectrum", 2.0, None),
    (512, "fresnel", 100.0, None),
    (1024, "fresnel", 100.0, None),
    (512, "fraunhofer", 5000.0, None),
    (256, "fresnel", 100.0, 2e-4),
]

SCRIPT = """
import hashlib, sys
import lidar_overlap as lo
for n, method, z, out in {cases!r}:
    field = lo.Field.gaussian(355e-9, 5e-3, n, 10 * 5e-3 / n)
    values = lo.propagate(field, z, method=method, output_spacing=out).values
    print(hashlib.sha256(values.tobytes()).hexdigest())
"""


def digests(threads):
    env = {**os.environ, "OMP_NUM_THREADS": str(threads)}
    run = subprocess.run(
        [sys.executable, "-c", SCRIPT.format(cases=CASES)],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert run.returncode == 0, run.stderr
    return run.stdout.split()


def test_same_bits_in_every_process_and_for_any_thread_count():
    runs = [digests(1), digests(2), digests(2), digests(1)]
    assert all(len(r) == len(CASES) for r in runs)
    for i, case in enumerate(CASES):
        assert len({r[i] for r in runs}) == 1, f"{case}: {[r[i][:12] for r in runs]}"


def test_same_bits_in_this_process():
    """And the same as this process's own result (any earlier planning in it changes nothing)."""
    n, method, z, out = CASES[1]
    field = lo.Field.gaussian(355e-9, 5e-3, n, 10 * 5e-3 / n)
    here = hashlib.sha256(
        lo.propagate(field, z, method=method, output_spacing=out).values.tobytes()
    ).hexdigest()
    assert here == digests(2)[1]


def _misaligned(values):
    """A copy of ``values`` 8 bytes off the 16-byte alignment of complex128 (and of FFTW's SIMD
    plans), so that the core cannot hand it to its transforms as it is."""
    raw = np.zeros(values.nbytes + 8, dtype=np.uint8)
    copy = np.frombuffer(raw.data, dtype=np.complex128, count=values.size, offset=8)
    copy = copy.reshape(values.shape)
    copy[...] = values
    return copy


@pytest.mark.parametrize("method, z", [("angular_spectrum", 2.0), ("fresnel", 100.0)])
def test_same_bits_from_any_input_array(method, z):
    """The first pass reads the caller's array where it lies (transformed straight from its rows
    when it has FFTW's alignment, copied row by row when not) and never writes it: every route
    gives the same bits, the zero-padding one (grid_size = n, a copy made by the core) too."""
    n = 256
    field = lo.Field.gaussian(355e-9, 5e-3, n, 10 * 5e-3 / n)
    expected = lo.propagate(field, z, method=method).values
    unaligned = _misaligned(field.values)
    assert unaligned.ctypes.data % 16 == 8
    writable = field.values.copy()
    for values, grid in ((unaligned, 0), (writable, 0), (writable, n)):
        out, _, report = _core.propagate(values, field.spacing, 355e-9, z, method, 0.0, grid)
        assert report.method == method
        assert out.tobytes() == expected.tobytes(), (values.ctypes.data % 16, grid)
    assert writable.tobytes() == field.values.tobytes()  # only read


def test_released_results_are_reused_and_live_ones_kept():
    """From 4 MiB on, a result is written into the memory of a released earlier result of its size
    (no fresh pages to fault in and zero): a result still held is never written, and one written
    into reused memory has the same bits as one written into fresh memory."""
    n = 512  # 512^2 complex values: 4 MiB, the smallest size reused
    field = lo.Field.gaussian(355e-9, 5e-3, n, 10 * 5e-3 / n)
    held = lo.propagate(field, 100.0, method="fresnel")
    held_bits = held.values.tobytes()
    released = lo.propagate(field, 2.0, method="angular_spectrum")
    address, bits = released.values.ctypes.data, released.values.tobytes()
    assert address != held.values.ctypes.data
    del released
    again = lo.propagate(field, 2.0, method="angular_spectrum")
    assert again.values.ctypes.data == address
    assert again.values.tobytes() == bits
    assert held.values.tobytes() == held_bits
    view = again.values[::2]  # a view keeps the memory of its result alive
    del again
    other = lo.propagate(field, 100.0, method="fresnel")
    assert other.values.ctypes.data != address
    assert view.tobytes() == np.frombuffer(bits, dtype=np.complex128).reshape(n, n)[::2].tobytes()


def test_transform_timer_refuses_what_it_cannot_time():
    """The benchmarks' timer of bare transforms names the parameter it refuses."""
    assert _core._fft_pair_seconds(64, 2, True, 1) > 0.0
    assert _core._fft_pair_seconds(64, 2, False, 2, 2) > 0.0
    with pytest.raises(ValueError, match="transforms = 3 is invalid"):
        _core._fft_pair_seconds(64, 1, True, 3)
    with pytest.raises(ValueError, match="threads = 0 is invalid"):
        _core._fft_pair_seconds(64, 1, False, 1, 0)


def test_same_bits_from_threads_propagating_at_once():
    """Two threads propagating at once (an acquisition and a display thread): the transform passes'
    team (cpp/src/core/team.hpp) serves one caller at a time and the other runs its passes alone,
    so each result, and each report's extents (summed per team member), are those computed alone."""
    n = 512
    cases = [("fresnel", 100.0), ("angular_spectrum", 2.0), ("fresnel", 50.0), ("fraunhofer", 5e3)]
    field = lo.Field.gaussian(355e-9, 5e-3, n, 10 * 5e-3 / n)

    def run(method, z):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", lo.SamplingWarning)  # Fraunhofer's near-field warning
            out, _, report = _core.propagate(field.values, field.spacing, 355e-9, z, method, 0.0, 0)
        return (
            out.tobytes(),
            report.output_edge_power,
            report.fresnel_phase_error,
            report.fraunhofer_phase,
        )

    alone = [run(m, z) for m, z in cases]
    rounds = 6
    with ThreadPoolExecutor(max_workers=2) as pool:
        together = list(pool.map(lambda k: run(*cases[k % len(cases)]), range(rounds * len(cases))))
    for k, result in enumerate(together):
        assert result == alone[k % len(cases)], cases[k % len(cases)]
