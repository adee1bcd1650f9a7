"""threads=0 against threads=1 on a busy machine: the thread policy of docs/reliability.md.

In one process, each case is called with threads=0 and threads=1 in alternating rounds, so that both
see the same load; the best and the median time of each are recorded, and their ratios (target:
threads=0 within 1.2x of threads=1 at any load; below 1 on an idle machine with more than one core).
- ``rt``: the paper's Table 1 lidar, 200 ranges 5-1000 m, ray tracing at its default tolerance 1e-4
  (~2 ms on one core: the case where a late team used to cost many times the work);
- ``fo_radial``: the same ranges on the radial FO path;
- ``fo_2d``: Table 1 with its beam tilted by 50 urad, 50 ranges 30-1000 m on the 2-D FO path.
The cases run once per entry of ``--load`` (default 0 and 6): that many busy processes (pure-Python
loops, started here and ended by their process ids when the run is done) on top of the machine's own
load, 6 giving load ~8 on 2 cores. The 1-minute load average is recorded before and after each run.

Run:  python benchmarks/bench_threads.py [--load N [N ...]]
(writes benchmarks/results/bench_threads.json)
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import statistics
import time

import numpy as np
from _common import busy_processes, load_average, run_meta, source_commit, write_result

import lidar_overlap as lo

TARGET_RATIO = 1.2
#: Rounds per case: at load 8 a call waits whole scheduler slices (4-8 ms), so the RT case (1.4 ms a
#: call) needs hundreds of rounds, the FO cases tens, for a median that does not swing by +-0.5
#: between runs.
ROUNDS = {"rt": 400, "fo_radial": 60, "fo_2d": 30}
#: Busy processes added, one run each: none (the machine as it is) and six (load ~8 on 2 cores).
LOADS = (0, 6)


def cases():
    table1 = lo.paper_table1()
    tilted = dataclasses.replace(table1, beam=dataclasses.replace(table1.beam, tilt=(50e-6, 0.0)))
    z200, z50 = np.geomspace(5.0, 1000.0, 200), np.geomspace(30.0, 1000.0, 50)
    return {
        "rt": (lambda t: lo.overlap(table1, z200, method="rt", threads=t), 1e-4),
        "fo_radial": (
            lambda t: lo.overlap(table1, z200, method="fo", fo_path="radial", threads=t),
            1e-8,
        ),
        "fo_2d": (lambda t: lo.overlap(tilted, z50, method="fo", fo_path="2d", threads=t), 1e-8),
    }


def alternate(fn, rounds):
    times = {0: [], 1: []}
    fn(0), fn(1)
    for _ in range(rounds):
        for threads in (0, 1):
            t0 = time.perf_counter()
            fn(threads)
            times[threads].append(time.perf_counter() - t0)
    return times


def measure(added: int) -> dict:
    """Every case in alternating rounds with ``added`` busy processes running (pure-Python loops,
    started here, ended at the end or with this process)."""
    with busy_processes(added) as busy:
        time.sleep(2.0 if busy else 0.0)
        load_start = load_average()
        print(f"-- {added} busy processes added | load {load_start:.2f}")
        rows = {}
        for name, (fn, tolerance) in cases().items():
            times = alternate(fn, ROUNDS[name])
            best = {t: min(v) for t, v in times.items()}
            median = {t: statistics.median(v) for t, v in times.items()}
            rows[name] = {
                "tolerance": tolerance,
                "rounds": ROUNDS[name],
                "threads0_best_s": best[0],
                "threads1_best_s": best[1],
                "threads0_median_s": median[0],
                "threads1_median_s": median[1],
                "ratio_best": best[0] / best[1],
                "ratio_median": median[0] / median[1],
                "target_ratio": TARGET_RATIO,
                "target_met": bool(median[0] / median[1] <= TARGET_RATIO),
                "load_average_1min": load_average(),
            }
            print(
                f"{name:10} threads=0 {best[0] * 1e3:8.2f} ms (median {median[0] * 1e3:8.2f}), "
                f"threads=1 {best[1] * 1e3:8.2f} ms (median {median[1] * 1e3:8.2f}): ratio "
                f"{best[0] / best[1]:.2f} best, {median[0] / median[1]:.2f} median (target <= "
                f"{TARGET_RATIO}) | load {load_average():.2f}"
            )
    return {
        "added_busy_processes": added,
        "load_average_1min": load_start,
        "load_average_1min_end": load_average(),
        "cases": rows,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--load",
        type=int,
        nargs="+",
        default=list(LOADS),
        help="busy processes to add, one run per value (default: %(default)s)",
    )
    args = parser.parse_args()
    print(f"lidar_overlap {lo.__version__} | {os.cpu_count()} cores | commit {source_commit()}")
    runs = [measure(added) for added in args.load]
    meta = run_meta(
        runs[0]["load_average_1min"],
        timing="threads=0 and threads=1 in alternating rounds after one untimed call each; best "
        "and median",
    )
    write_result("bench_threads", {"meta": meta, "runs": runs})


if __name__ == "__main__":
    main()
