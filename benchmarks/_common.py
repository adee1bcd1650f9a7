"""Helpers shared by the benchmark scripts: warm best-of timings, run metadata and result files."""

import contextlib
import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import lidar_overlap as lo

#: Where every benchmark writes its ``<name>.json``.
RESULTS = Path(__file__).resolve().parent / "results"

#: The 5 cm coaxial lidar of docs/turbulence.md (1064 nm, w0 = 5 mm, f = 0.5 m, detector radius
#: 70 um: 0.28 mrad), the scene of the turbulence benchmarks on both paths.
FIVE_CM_LIDAR = lo.LidarSystem(
    beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=5e-3),
    telescope=lo.Telescope(diameter=0.05, focal_length=0.5),
    detector=lo.Detector(radius=70e-6),
)


def best_time(fn, repeats, setup=None):
    """Best wall time (s) of `repeats` calls after one untimed call; `setup()` (untimed) makes the
    argument of each call. Returns (time, last result)."""
    result = fn(setup()) if setup else fn()
    best = float("inf")
    for _ in range(repeats):
        arg = setup() if setup else None
        t0 = time.perf_counter()
        result = fn(arg) if setup else fn()
        best = min(best, time.perf_counter() - t0)
    return best, result


def best_times(fn, repeats):
    """Least wall time and least CPU time (s, all the process's threads) of `repeats` calls after
    one untimed call: on a machine shared with other work the CPU time is the steadier figure.
    Returns (wall, cpu, last result)."""
    result = fn()
    wall = cpu = float("inf")
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        result = fn()
        cpu = min(cpu, time.process_time() - c0)
        wall = min(wall, time.perf_counter() - t0)
    return wall, cpu, result


def alternated_best(runs, repeats):
    """Each callable of ``runs`` (name -> function) run ``repeats`` + 1 times in turn, so that all
    see the same load, the first round untimed. Returns ({name: best time in s}, {name: last
    result})."""
    times, last = {name: [] for name in runs}, {}
    for i in range(repeats + 1):
        for name, fn in runs.items():
            t1 = time.perf_counter()
            last[name] = fn()
            if i:
                times[name].append(time.perf_counter() - t1)
    return {name: min(t) for name, t in times.items()}, last


def source_commit():
    """Commit of the source tree beside this script (the installed build may be older), or None."""
    try:
        out = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"],
            cwd=Path(__file__).resolve().parent,
            capture_output=True,
            text=True,
            timeout=10,
        )
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip() or None


# A busy process's loop: pure Python, ending within ~0.1 s of its parent's death (a benchmark
# killed by a signal runs no cleanup, and its busy processes would load every later run).
_BUSY_LOOP = """
import os
parent = os.getppid()
while os.getppid() == parent:
    for _ in range(1000000):
        pass
"""


@contextlib.contextmanager
def busy_processes(count):
    """``count`` busy processes (pure-Python loops) for the duration of the block, killed at its end
    and ending by themselves if this process dies first."""
    busy = [subprocess.Popen([sys.executable, "-c", _BUSY_LOOP]) for _ in range(count)]
    try:
        yield busy
    finally:
        for p in busy:
            p.kill()
            p.wait()


def load_average():
    """1-minute load average (NaN where the platform has none)."""
    return os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")


def run_meta(load_start, **fields):
    """The record each result file starts with: when it was measured, from which commit and
    versions, on what machine, under what load (the 1-minute load average when the run started,
    ``load_start``, and now, at its end); then the benchmark's own ``fields``."""
    return {
        "measured": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "commit": source_commit(),
        "versions": {
            "lidar_overlap": lo.__version__,
            "numpy": np.__version__,
            "python": sys.version.split()[0],
        },
        "machine": platform.machine(),
        "cores": os.cpu_count(),
        "load_average_1min": load_start,
        "load_average_1min_end": load_average(),
        **fields,
    }


def json_text(record, indent=2, named_non_finite=False):
    """``record`` as strict JSON (RFC 8259), indented. A value that is not finite is written as
    null (a failed or undefined case, which the record explains beside it), or with
    ``named_non_finite`` as the string "NaN", "Infinity" or "-Infinity" (snapshots, whose
    comparisons must tell them apart); never as the bare NaN or Infinity that Python writes by
    default and strict parsers reject."""
    return json.dumps(_finite(record, named_non_finite), indent=indent, allow_nan=False) + "\n"


def _finite(value, named):
    if isinstance(value, float):  # numpy's float64 too
        if math.isfinite(value):
            return value
        if not named:
            return None
        return "NaN" if math.isnan(value) else ("Infinity" if value > 0 else "-Infinity")
    if isinstance(value, dict):
        return {key: _finite(v, named) for key, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v, named) for v in value]
    return value


def write_result(name, record):
    """``record`` as indented strict JSON (json_text) in results/<name>.json; returns the path."""
    RESULTS.mkdir(parents=True, exist_ok=True)
    out = RESULTS / f"{name}.json"
    out.write_text(json_text(record))
    print(f"wrote {out}")
    return out
