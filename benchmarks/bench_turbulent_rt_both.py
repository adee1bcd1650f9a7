"""Turbulent RT overlap, both paths against transmit only, in the same run (docs/turbulence.md, "Ray
tracing on both paths").

The 5 cm lidar of docs/turbulence.md (1064 nm, w0 = 5 mm, f = 0.5 m, detector radius 70 um),
Cn^2 = 1e-14 m^-2/3, RANGES ranges 100-1000 m, REALIZATIONS draws, RT tolerance 1e-6, one thread
(the ratio is the work's, not the scheduling's on a shared machine). Both paths trace as many draws
(the beam blurred, the offsets the image's), one more trace per range (the exact mean with
uncorrelated paths) and add the layer model's tilt moments and the regime checks: the target is at
most TARGET_RATIO times transmit only. The two runs
alternate, the first round untimed; the best of REPEATS wall and CPU times. Writes
results/bench_turbulent_rt_both.json. Run: python benchmarks/bench_turbulent_rt_both.py
"""

from __future__ import annotations

import os
import time
import warnings

import numpy as np
from _common import FIVE_CM_LIDAR, load_average, run_meta, source_commit, write_result

import lidar_overlap as lo
from lidar_overlap.forward.backends import turbulent_return

RANGES = np.geomspace(100.0, 1000.0, 20)
CN2 = 1e-14
REALIZATIONS = 500
REPEATS = 5
TARGET_RATIO = 2.0
SYSTEM = FIVE_CM_LIDAR


def run(paths, seed):
    method = lo.Turbulent(
        lo.Turbulence(CN2), lo.RT(1e-6), realizations=REALIZATIONS, seed=seed, paths=paths
    )
    turbulent_return._tilts.cache_clear()  # each run computes its tilt moments
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # RT's diffraction and regime warnings
        return lo.overlap(SYSTEM, RANGES, method, threads=1)


def main():
    load = load_average()
    print(
        f"lidar_overlap {lo.__version__} | {os.cpu_count()} cores | load {load:.2f} | "
        f"commit {source_commit()}"
    )
    wall = {"transmit": [], "both": []}
    cpu = {"transmit": [], "both": []}
    last = {}
    for i in range(REPEATS + 1):
        for paths in ("transmit", "both"):
            # a new seed each round, and no tilt moments cached from the last
            w0, c0 = time.perf_counter(), time.process_time()
            last[paths] = run(paths, seed=i)
            if i:
                wall[paths].append(time.perf_counter() - w0)
                cpu[paths].append(time.process_time() - c0)
    best = {k: min(v) for k, v in wall.items()}
    best_cpu = {k: min(v) for k, v in cpu.items()}
    ratio, ratio_cpu = best["both"] / best["transmit"], best_cpu["both"] / best_cpu["transmit"]
    print(
        f"{REALIZATIONS} draws x {RANGES.size} ranges, one thread: transmit {best['transmit']:.3f} "
        f"s ({best_cpu['transmit']:.3f} s CPU), both {best['both']:.3f} s "
        f"({best_cpu['both']:.3f} s CPU): ratio {ratio:.2f} (CPU {ratio_cpu:.2f}), target "
        f"<= {TARGET_RATIO:g}"
    )
    both = last["both"]
    print(
        f"G at {RANGES[-1]:g} m: transmit {last['transmit'].overlap[-1]:.4f}, both "
        f"{both.overlap[-1]:.4f}, amplification {both.amplification[-1]:.4f}"
    )
    write_result(
        "bench_turbulent_rt_both",
        {
            "meta": {
                **run_meta(load),
                "threads": 1,
                "cn2": CN2,
                "ranges_m": [float(RANGES[0]), float(RANGES[-1]), int(RANGES.size)],
                "realizations": REALIZATIONS,
                "repeats": REPEATS,
                "target_ratio": TARGET_RATIO,
            },
            "result": {
                "seconds_transmit": best["transmit"],
                "seconds_both": best["both"],
                "cpu_seconds_transmit": best_cpu["transmit"],
                "cpu_seconds_both": best_cpu["both"],
                "ratio": ratio,
                "ratio_cpu": ratio_cpu,
                "within_target": bool(ratio_cpu <= TARGET_RATIO),
                "overlap_last_transmit": float(last["transmit"].overlap[-1]),
                "overlap_last_both": float(both.overlap[-1]),
                "amplification": [float(a) for a in both.amplification],
            },
        },
    )


if __name__ == "__main__":
    main()
