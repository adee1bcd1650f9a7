"""Running a long call in a fresh interpreter and interrupting it with SIGINT, timed in CPU seconds.

Shared by the Ctrl-C tests and by scripts/ctrl_c_latency.py. CPU time, not wall-clock time: on a
machine loaded by other jobs the child gets a fraction of the cores, which stretches its wall-clock
latency but not the work it does before stopping. The wall clock only bounds the whole run
(WALL_LIMIT, generous), against a real hang.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from dataclasses import dataclass

#: Ctrl-C: the core asks Python for signals every 0.1 s between ranges, transforms, rows and blocks
#: of a grid; one second covers that, the longest single step between two such points (a few ms)
#: and the interpreter's start of unwinding.
INTERRUPT_LATENCY = 1.0
#: ... measured as the work the child does after SIGINT, in CPU seconds of all its threads: one
#: second on each of 2 cores, so that other jobs loading the machine cannot fail the tests.
INTERRUPT_CPU = 2.0 * INTERRUPT_LATENCY
#: CPU seconds the child spends in the call before SIGINT (well inside it).
WARM_CPU = 0.3
#: Wall-clock seconds the whole run may take; only a hang reaches it.
WALL_LIMIT = 300.0


@dataclass(frozen=True)
class Interrupted:
    """What a run interrupted by SIGINT did after the signal: CPU seconds of all its threads
    (``cpu``), wall-clock seconds (``wall``, load-dependent: for reports, never for asserts), its
    stderr, and whether it printed "finished" (the call ran to its end instead of stopping)."""

    cpu: float
    wall: float
    stderr: str
    finished: bool


def cpu_seconds(pid: int) -> float:
    """CPU seconds (user + system, all threads) process ``pid`` has used so far (Linux /proc)."""
    with open(f"/proc/{pid}/stat", "rb") as f:
        fields = f.read().rsplit(b")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _default_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def interrupted_run(call: str, setup: str = "", warm_cpu: float = WARM_CPU) -> Interrupted:
    """Run ``setup`` then ``call`` in a fresh interpreter (``np`` and ``lo`` imported), SIGINT it
    once it has spent ``warm_cpu`` CPU seconds in ``call``, and return what it did from the signal
    to its end. The setup (building a large input) is not counted in ``warm_cpu``."""
    code = textwrap.dedent(
        """
        import numpy as np, lidar_overlap as lo
        {setup}
        print("started", flush=True)
        {call}
        print("finished", flush=True)
        """
    ).format(setup=setup, call=call)
    proc = subprocess.Popen(
        [sys.executable, "-c", code],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONWARNINGS": "ignore"},
        # A job started in the background of a shell ignores SIGINT, and so would the child, whose
        # interpreter then installs no handler: give it the default disposition.
        preexec_fn=_default_sigint,
    )
    try:
        started = proc.stdout.readline().strip()
        if started != "started":
            proc.wait()
            raise AssertionError(f"the setup failed: {proc.stderr.read()[-2000:]}")
        begin, deadline = cpu_seconds(proc.pid), time.monotonic() + WALL_LIMIT
        while cpu_seconds(proc.pid) - begin < warm_cpu:  # well inside the call
            assert proc.poll() is None, "the call ended before it could be interrupted"
            assert time.monotonic() < deadline, "the call did not start"
            time.sleep(0.02)
        at_signal, wall_at_signal = cpu_seconds(proc.pid), time.monotonic()
        proc.send_signal(signal.SIGINT)
        # wait4 gives the child's total CPU time at its end (/proc is gone by then).
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            assert time.monotonic() < deadline, f"no end within {WALL_LIMIT:g} s after SIGINT"
            time.sleep(0.005)
        wall = time.monotonic() - wall_at_signal
        proc.returncode = os.waitstatus_to_exitcode(status)
        out, err = proc.stdout.read(), proc.stderr.read()
    finally:
        if proc.returncode is None:
            proc.kill()
            proc.wait()
    return Interrupted(usage.ru_utime + usage.ru_stime - at_signal, wall, err, "finished" in out)


#: Long calls, one per class of loop that must stop on Ctrl-C: name -> (setup, call, warm CPU
#: seconds at which SIGINT is sent). Each runs for several CPU seconds (on one core, unloaded) when
#: not interrupted, so that a loop without a cancellation point would spend more than INTERRUPT_CPU
#: after the signal. Several warm points land the signal in different phases of one call.
LONG_CALLS = {
    # ray tracing: tight tolerance on many ranges (one adaptive integral per range)
    "rt_ranges": (
        "",
        "lo.overlap(lo.LidarSystem(beam=lo.GaussianBeam(tilt=(1e-4, 0.0))), "
        "np.geomspace(5, 3000, 300000), 'rt', tolerance=1e-8)",
        (WARM_CPU,),
    ),
    # millions of ranges: the receivers are built in a serial loop before the parallel one
    "rt_millions_of_ranges": (
        "",
        "lo.overlap(lo.paper_table1(), np.geomspace(50, 3000, 3_000_000), 'rt', tolerance=1e-6)",
        (WARM_CPU,),
    ),
    # one range of a 10^6-point map is one long iteration (its grid points are compared)
    "alignment_map": (
        "",
        "lo.alignment_map(lo.paper_table1(), [500.0, 1000.0], tilt_x=np.linspace(-1e-3, 1e-3, "
        "1000), tilt_y=np.linspace(-1e-3, 1e-3, 1000))",
        (WARM_CPU,),
    ),
    "fo_2d_many_ranges": (
        "",
        "lo.overlap(lo.paper_table1(), np.geomspace(50, 3000, 4000), 'fo', fo_path='2d')",
        (WARM_CPU,),
    ),
    # ranges each long: the spectrum's transforms and sums of a 2048^2 grid (the TEM00 beam at each
    # range in closed form)
    "fo_2d_large_grid": (
        "",
        "lo.overlap(lo.paper_table1(), np.geomspace(50, 3000, 200), 'fo', fo_path='2d', "
        "beam_grid=2048)",
        (WARM_CPU, 2.0),
    ),
    # the same with the beam's own transforms: a window that cuts 1e-19 of the waist's power, too
    # much for the closed form, so the sampled field is propagated
    "fo_2d_large_grid_propagated": (
        "",
        "lo.overlap(lo.paper_table1(), np.geomspace(50, 3000, 16), 'fo', fo_path='2d', "
        "beam_grid=2048, beam_window=9.0)",
        (WARM_CPU, 2.0),
    ),
    # a given field: its power and extent (serial sums over the grid), then its propagations
    "fo_field_beam": (
        "s = lo.LidarSystem(beam=lo.FieldBeam(lo.Field.gaussian(355e-9, 1e-3, 2048, 8e-3 / 2048)))",
        "lo.overlap(s, np.geomspace(50, 3000, 16), 'fo')",
        (WARM_CPU, 2.0),
    ),
    "turbulent_many_realizations": (
        "",
        "lo.overlap(lo.paper_table1(), np.geomspace(100, 2000, 20), 'fo', "
        "turbulence=lo.Turbulence(1e-14), realizations=2000, paths='transmit')",
        (WARM_CPU,),
    ),
    # eight realisations of a 1024^2 beam (~6 CPU s): screens, split steps and coupling maps
    "turbulent_large_grid": (
        "",
        "lo.overlap(lo.paper_table1(), np.geomspace(300, 2000, 5), 'fo', "
        "turbulence=lo.Turbulence(1e-14), realizations=8, beam_grid=1024, paths='transmit')",
        (WARM_CPU, 2.0),
    ),
    # both paths: 1000 random-phase receiver fields per draw, made and summed one by one
    "turbulent_both_paths": (
        "s = lo.LidarSystem(beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=2.5e-3), "
        "telescope=lo.Telescope(diameter=0.015, focal_length=0.5), "
        "detector=lo.Detector(radius=25e-6))",
        "lo.overlap(s, [200.0], lo.Turbulent(lo.Turbulence(7.3e-13), lo.FO(beam_grid=256), "
        "realizations=2, screens=3, paths='both', receiver_fields=1000))",
        (WARM_CPU, 3.0),
    ),
    # the spectrum's amplitudes, the deviates and the 8192^2 transform of one screen
    "phase_screen": ("", "lo.phase_screen(8192, 0.01, 0.1)", (WARM_CPU, 1.5, 3.0)),
    # 10240^2 exponentials
    "gaussian_field": ("", "lo.Field.gaussian(355e-9, 2e-3, 10240, 1e-5)", (WARM_CPU, 1.5)),
    # angular spectrum on a zero-padded 8192^2 grid: the transfer function, then the passes
    "propagate_angular_spectrum": (
        "f = lo.Field.gaussian(355e-9, 1e-3, 1024, 1e-5)",
        "lo.propagate(f, 5.0, 'angular_spectrum', grid_size=8192)",
        (WARM_CPU, 3.0),
    ),
    # a given 8192^2 field (1 GiB): the transfer function, then the passes, which read the caller's
    # array and write the result's (no copy in or out outside them)
    "propagate_large_field": (
        "f = lo.Field.gaussian(355e-9, 2e-3, 8192, 2e-6)",
        "lo.propagate(f, 1.0, 'angular_spectrum')",
        (WARM_CPU, 2.0),
    ),
    # the same field by single-FFT Fresnel: per-axis chirps, so nearly all of the call is its passes
    "propagate_large_field_fresnel": (
        "f = lo.Field.gaussian(355e-9, 2e-3, 8192, 2e-6)",
        "lo.propagate(f, 1000.0, 'fresnel')",
        (WARM_CPU, 1.0),
    ),
    # Fresnel onto another spacing: chirps and the chirp-z transforms of a 4096^2 grid
    "propagate_fresnel_scaled": (
        "f = lo.Field.gaussian(355e-9, 2e-3, 4096, 1e-5)",
        "lo.propagate(f, 1000.0, 'fresnel', output_spacing=2e-4)",
        (WARM_CPU, 3.0),
    ),
    # Gerchberg-Saxton iterations on a 2048^2 plate
    "flat_top_beam": (
        "",
        "lo.FlatTopBeam(355e-9, 1e-3, 2e-3, grid=2048, max_iterations=20)",
        (WARM_CPU, 2.0),
    ),
}
