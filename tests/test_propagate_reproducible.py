"""lo.propagate gives the same bits in every process and for any thread count: its transforms are
made of 1-D plans whose choice depends on the shape alone (cpp/src/fourier/fft.hpp), never on
timings. Each case runs in fresh interpreters with one and with two OpenMP threads, and the SHA-256
of the output values must agree."""

import hashlib
import os
import subprocess
import sys

import lidar_overlap as lo

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
