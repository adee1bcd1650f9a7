"""Tolerance study, locally against a Dask LocalCluster on the same cores.

The study of examples/tolerance_study.py: 1,000 members of the Table 1 lidar with normal offsets of
the beam tilt (sd 20 µrad, x and y), the detector defocus (sd 0.2 mm) and the detector offset (sd 10
µm, x and y); RT to 1e-3 at 60 ranges 10 m-3 km. Timed three ways, best of REPEATS after one untimed
run each (local and cluster runs alternate, so that both see the same load from other processes):

- local: `lo.tolerance_study(...)` with no client: dask's threaded scheduler, one member per core at
  a time;
- cluster: the same with `client=` a LocalCluster of 2 worker processes x 1 thread (started before
  timing);
- loop: the plain loop used without dask (one member after the other), for reference.

The ratio cluster / local is the cost of the cluster's processes, pickling and scheduling (target:
within 1.5x). All three results are checked equal bit for bit. Writes results/bench_studies.json.
Run: python benchmarks/bench_studies.py (the package must be importable by the worker processes
too).
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np
from _common import alternated_best, best_time, load_average, run_meta, source_commit, write_result

import lidar_overlap as lo

MEMBERS = 1000
RANGES = np.geomspace(10.0, 3000.0, 60)
METHOD = lo.RT(tolerance=1e-3)
TOLERANCES = {
    "beam.tilt": ("normal", 0.0, 20e-6),
    "detector.defocus": ("normal", 0.0, 0.2e-3),
    "detector.offset": ("normal", 0.0, 10e-6),
}
REPEATS = 5
TARGET_RATIO = 1.5


def study(**kw):
    return lo.tolerance_study(
        lo.paper_table1(), TOLERANCES, MEMBERS, RANGES, method=METHOD, seed=1, **kw
    )


def main():
    import dask.base  # noqa: F401  (loaded before the loop below hides dask)
    from distributed import Client, LocalCluster

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
        runs = {"local": study, "cluster": lambda: study(client=client)}
        best, last = alternated_best(runs, REPEATS)
    (t_local, local), (t_cluster, remote) = ((best[k], last[k]) for k in runs)
    dask = sys.modules.pop("dask")
    sys.modules["dask"] = None  # import dask now fails: the plain loop
    try:
        t_loop, loop = best_time(study, REPEATS)
    finally:
        sys.modules["dask"] = dask
    same = all(np.array_equal(local.overlap.values, r.overlap.values) for r in (remote, loop))
    ratio = t_cluster / t_local
    rows = {"local": (t_local, local), "cluster": (t_cluster, remote), "loop": (t_loop, loop)}
    for name, (t, r) in rows.items():
        print(
            f"{name:8s} {t:6.2f} s  {MEMBERS / t:6.0f} members/s  {r.attrs['members_per_task']:4d} "
            f"members per task ({r.attrs['engine']})"
        )
    print(
        f"cluster start {t_start:.1f} s (not timed above); cluster / local = {ratio:.2f} (target "
        f"<= {TARGET_RATIO}); results equal bit for bit: {same}"
    )
    write_result(
        "bench_studies",
        {
            "meta": {
                **run_meta(load),
                "members": MEMBERS,
                "ranges_m": [float(RANGES[0]), float(RANGES[-1]), int(RANGES.size)],
                "method": repr(METHOD),
                "repeats": REPEATS,
                "cluster": "LocalCluster(n_workers=2, threads_per_worker=1, processes=True)",
            },
            "result": {
                **{f"{name}_s": t for name, (t, _) in rows.items()},
                **{f"{name}_members_per_s": MEMBERS / t for name, (t, _) in rows.items()},
                **{
                    f"{name}_members_per_task": int(r.attrs["members_per_task"])
                    for name, (_, r) in rows.items()
                },
                "cluster_start_s": t_start,
                "cluster_over_local": ratio,
                "target_ratio": TARGET_RATIO,
                "target_met": ratio <= TARGET_RATIO,
                "bit_identical": same,
            },
        },
    )


if __name__ == "__main__":  # the cluster's worker processes import this file: start it only once
    main()
