"""Turbulent FO overlap, both paths against transmit only, in the same run (docs/turbulence.md).

Two scenes, each with the transmit-only run on the grid both paths need (so that the ratio is the
return path's cost alone), the library's default receiver_fields, all cores:

- "5 cm": the lidar of docs/turbulence.md (1064 nm, w0 = 5 mm, f = 0.5 m, detector radius 70 um:
  0.28 mrad), Cn^2 = 1e-13 m^-2/3, 20 ranges 100-1000 m, 10 screens, 432^2.
- "Table 1": the paper's Table 1 lidar (355 nm, w0 = 1 mm, D = 0.15 m, f = 1 m, FOV 0.9 mrad), Cn^2
  = 1e-14 m^-2/3, 50 ranges 50-100 m, 10 screens, 800^2. Both paths must sample the receiver's
  field of view on every plane's grid, which holds its footprint: to 100 m that is 780^2, to 2000 m
  7620^2 (a refused size), so the scene stops at 100 m.

One untimed call of each first (FFTW plans); then each call once, CPU time of all threads (the
machine is shared; wall time beside it). Prints the times, their ratio (target <= 2) and G at the
last range with its standard error, the amplification there; writes
results/bench_turbulent_both.json. Run: python benchmarks/bench_turbulent_both.py [realizations of
the 5 cm scene] [of the Table 1 scene]
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np
from _common import FIVE_CM_LIDAR, load_average, run_meta, source_commit, write_result

import lidar_overlap as lo
from lidar_overlap import _core

TARGET_RATIO = 2.0
SEED = 1
SCENES = {
    "5 cm": dict(
        system=FIVE_CM_LIDAR,
        ranges=np.geomspace(100.0, 1000.0, 20),
        cn2=1e-13,
        beam_grid=432,
    ),
    "Table 1": dict(
        system=lo.paper_table1(),
        ranges=np.geomspace(50.0, 100.0, 50),
        cn2=1e-14,
        beam_grid=800,
    ),
}


def run(scene, paths, realizations):
    method = lo.Turbulent(
        lo.Turbulence(scene["cn2"]),
        lo.FO(beam_grid=scene["beam_grid"]),
        realizations=realizations,
        seed=SEED,
        paths=paths,
    )
    t0, c0 = time.perf_counter(), time.process_time()
    res = lo.overlap(scene["system"], scene["ranges"], method)
    return time.perf_counter() - t0, time.process_time() - c0, res


def measure(name, scene, realizations):
    run(scene, "transmit", 2), run(scene, "both", 2)  # FFTW plans
    wall_tx, cpu_tx, tx = run(scene, "transmit", realizations)
    wall_both, cpu_both, both = run(scene, "both", realizations)
    ratio = cpu_both / cpu_tx
    z = scene["ranges"]
    print(
        f"{name}: {realizations} realisations x {z.size} ranges, {scene['beam_grid']}^2: transmit "
        f"{cpu_tx:.2f} CPU s ({wall_tx:.2f} s wall), both {cpu_both:.2f} CPU s ({wall_both:.2f} s "
        f"wall, {_core.TurbulenceOptions().receiver_fields} receiver field(s)): ratio {ratio:.2f} "
        f"(target <= {TARGET_RATIO}: {'met' if ratio <= TARGET_RATIO else 'NOT met'})"
    )
    print(
        f"  G at {z[-1]:g} m: transmit {tx.overlap[-1]:.4f} +- {tx.error_estimate[-1]:.4f}, both "
        f"{both.overlap[-1]:.4f} +- {both.error_estimate[-1]:.4f}, amplification "
        f"{both.amplification[-1]:.3f}"
    )
    return {
        "ranges_m": [float(z[0]), float(z[-1]), int(z.size)],
        "cn2": scene["cn2"],
        "beam_grid": scene["beam_grid"],
        "realizations": realizations,
        "cpu_s_transmit": cpu_tx,
        "cpu_s_both": cpu_both,
        "wall_s_transmit": wall_tx,
        "wall_s_both": wall_both,
        "ratio_cpu": ratio,
        "target_ratio": TARGET_RATIO,
        "target_met": bool(ratio <= TARGET_RATIO),
        "overlap_last_transmit": float(tx.overlap[-1]),
        "standard_error_last_transmit": float(tx.error_estimate[-1]),
        "overlap_last_both": float(both.overlap[-1]),
        "standard_error_last_both": [float(v) for v in both.error_estimate[-3:]],
        "amplification": [float(a) for a in both.amplification],
    }


def main():
    counts = [int(a) for a in sys.argv[1:3]] + [None, None]
    realizations = {"5 cm": counts[0] or 100, "Table 1": counts[1] or 20}
    load_before = load_average()
    print(
        f"lidar_overlap {lo.__version__} | {os.cpu_count()} cores | load {load_before:.2f} | "
        f"commit {source_commit()}"
    )
    results = {name: measure(name, scene, realizations[name]) for name, scene in SCENES.items()}
    write_result(
        "bench_turbulent_both",
        {
            "meta": {
                **run_meta(load_before),
                "receiver_fields": _core.TurbulenceOptions().receiver_fields,
                "seed": SEED,
                "timing": "one call each after an untimed one; CPU of all threads",
            },
            "result": results,
        },
    )


if __name__ == "__main__":
    main()
