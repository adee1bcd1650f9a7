"""Turbulence realisations on a Dask LocalCluster against one local call, on the same cores.

The turbulent FO overlap of the Table 1 lidar: constant Cn^2 = 1e-14 m^-2/3, 10 phase screens,
beam_grid = 256, REALIZATIONS realisations at 20 ranges 50-2000 m, seed 1. Timed four ways, best of
REPEATS after one untimed run each, the runs alternated so that all see the same load from other
processes:

- overlap: `lo.overlap(system, ranges, lo.Turbulent(...))`, one core call, its OpenMP threads over
  the realisations (the reference: what a cluster has to beat per core);
- threads: `lo.turbulent_realizations(...)` with no client: dask's threaded scheduler, one task per
  core;
- cluster: the same with `client=` a LocalCluster of 2 worker processes x 1 thread (started before
  timing), the chunk the study chooses (the first realisation here, the others one task per worker);
- cluster_chunk16: the cluster with chunk=16, the same even split without the first realisation
  timed here first (the cost of that timing: one realisation and a set-up before the tasks start);
- cluster_chunk4: the cluster with chunk=4 (8 tasks: the cost of making the FO set-up once per
  task).

The ratio cluster / overlap is the cost of the cluster's processes, pickling, scheduling and the
set-up made once more per worker. All results are checked equal to lo.overlap's bit for bit. Writes
results/bench_turbulent_study.json. Run: python benchmarks/bench_turbulent_study.py (the package
must be importable by the worker processes too).
"""

from __future__ import annotations

import os
import time

import numpy as np
from _common import alternated_best, load_average, run_meta, source_commit, write_result

import lidar_overlap as lo

RANGES = np.geomspace(50.0, 2000.0, 20)
CN2 = 1e-14  # m^-2/3
REALIZATIONS = 32
METHOD = lo.Turbulent(
    lo.Turbulence(CN2),
    lo.FO(beam_grid=256),
    realizations=REALIZATIONS,
    seed=1,
    screens=10,
    paths="transmit",
)
REPEATS = 2
TARGET_RATIO = 1.5


def main():
    from distributed import Client, LocalCluster

    system = lo.paper_table1()
    load = load_average()
    print(
        f"lidar_overlap {lo.__version__} | {os.cpu_count()} cores | load {load:.2f} | commit "
        f"{source_commit()}"
    )
    t0 = time.perf_counter()
    with (
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        Client(cluster) as client,
    ):
        t_start = time.perf_counter() - t0
        runs = {
            "overlap": lambda: lo.overlap(system, RANGES, METHOD),
            "threads": lambda: lo.turbulent_realizations(system, RANGES, METHOD),
            "cluster": lambda: lo.turbulent_realizations(system, RANGES, METHOD, client=client),
            "cluster_chunk16": lambda: lo.turbulent_realizations(
                system, RANGES, METHOD, client=client, chunk=16
            ),
            "cluster_chunk4": lambda: lo.turbulent_realizations(
                system, RANGES, METHOD, client=client, chunk=4
            ),
        }
        best, last = alternated_best(runs, REPEATS)
    ref = last["overlap"]
    same = all(
        np.array_equal(ds.overlap.values, ref.realizations)
        and np.array_equal(ds["mean"].values, ref.overlap)
        and np.array_equal(ds["std"].values, ref.std)
        for name, ds in last.items()
        if name != "overlap"
    )
    tasks = {
        name: int(ds.attrs["realizations_per_task"])
        for name, ds in last.items()
        if name != "overlap"
    }
    ratio = best["cluster"] / best["overlap"]
    for name, t in best.items():
        how = (
            f"{tasks[name]:3d} realisations per task ({last[name].attrs['engine']})"
            if name in tasks
            else "one core call, all cores"
        )
        print(f"{name:15s} {t:6.2f} s  {REALIZATIONS / t:5.1f} realisations/s  {how}")
    print(
        f"cluster start {t_start:.1f} s (not timed above); cluster / overlap = {ratio:.2f} (target "
        f"<= {TARGET_RATIO}); results equal bit for bit: {same}"
    )
    write_result(
        "bench_turbulent_study",
        {
            "meta": {
                **run_meta(load),
                "ranges_m": [float(RANGES[0]), float(RANGES[-1]), int(RANGES.size)],
                "method": repr(METHOD),
                "beam_grid": 256,
                "screens": 10,
                "realizations": REALIZATIONS,
                "repeats": REPEATS,
                "cluster": "LocalCluster(n_workers=2, threads_per_worker=1, processes=True)",
            },
            "result": {
                **{f"{name}_s": t for name, t in best.items()},
                **{f"{name}_realizations_per_task": n for name, n in tasks.items()},
                "cluster_start_s": t_start,
                "cluster_over_overlap": ratio,
                "threads_over_overlap": best["threads"] / best["overlap"],
                **{
                    f"{name}_over_overlap": best[name] / best["overlap"]
                    for name in ("cluster_chunk16", "cluster_chunk4")
                },
                "target_ratio": TARGET_RATIO,
                "target_met": ratio <= TARGET_RATIO,
                "bit_identical": same,
            },
        },
    )


if __name__ == "__main__":  # the cluster's worker processes import this file: start it only once
    main()
