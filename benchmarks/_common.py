"""Helpers shared by the benchmark scripts: warm best-of timings and run metadata."""

import os
import subprocess
import time
from pathlib import Path


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


def load_average():
    """1-minute load average (NaN where the platform has none)."""
    return os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
