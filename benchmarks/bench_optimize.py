"""Design optimisation: evaluations, core calls and wall time of the example problems of
examples/optimize_design.py, and the shots each automatic alignment search needs.

Problems (the paper's Table 1 lidar, tolerance 1e-4):
- smallest FOV for full overlap by 150 m (G >= 0.99 from 150 m to 10 km, far loss <= 1 %), radius
  free;
- the same with radius and defocus free;
- maximum G at 150 m over beam tilt x, y, the beam misaligned by (0.3, -0.2) mrad;
- automatic alignment of the defocused design, so misaligned, on its noisy 1 km signal (20 µJ, 30 %,
  7.5 m bins, 100 shots per measurement): raster and gradient, seeds 0-4.
Times: best of 3 warm runs. Writes results/bench_optimize.json.
"""

from __future__ import annotations

import os
import time

import numpy as np
from _common import best_time, load_average, run_meta, write_result

import lidar_overlap as lo

TABLE1 = lo.paper_table1()
FOV = lo.SmallestFieldOfView(full_overlap_range=150.0)
MISALIGNMENT = {"beam.tilt[0]": 3e-4, "beam.tilt[1]": -2e-4}
SIGNAL = dict(pulse_energy=20e-6, receiver_efficiency=0.3, range_resolution=7.5)
SEEDS = range(5)
PROBLEMS = {
    "smallest_fov_radius": (TABLE1, FOV, ["detector.radius"], [(1e-4, 3e-3)]),
    "smallest_fov_radius_defocus": (
        TABLE1,
        FOV,
        ["detector.radius", "detector.defocus"],
        [(1e-4, 3e-3), (0.0, 1e-2)],
    ),
    "maximum_overlap_150m_tilt": (
        lo.parameters.replace(TABLE1, MISALIGNMENT),
        lo.MaximumOverlapAt(150.0),
        ["beam.tilt"],
        [(-0.9e-3, 1.1e-3)] * 2,
    ),
}


def main():
    load = load_average()
    print(f"lidar_overlap {lo.__version__} | {os.cpu_count()} cores | load average {load:.2f}")
    rows = {}
    for name, (system, objective, free, bounds) in PROBLEMS.items():
        t, res = best_time(
            lambda s=system, o=objective, f=free, b=bounds: lo.optimize(s, o, f, b), 3
        )
        rows[name] = {
            "seconds": t,
            "evaluations": res.evaluations,
            "core_calls": res.core_calls,
            "values": res.values,
            "objective": res.objective,
            "unit": res.unit,
            "constraints": res.constraints,
            "converged": res.converged,
        }
        print(
            f"{name:28s} {t:6.3f} s  {res.evaluations:4d} evaluations in {res.core_calls:3d} core "
            f"calls  objective {res.objective:.6g} {res.unit}  {res.values}"
        )
    design = lo.optimize(*PROBLEMS["smallest_fov_radius_defocus"]).system
    misaligned = lo.parameters.replace(design, MISALIGNMENT)
    for search in ("raster", "gradient"):
        runs = []
        for seed in SEEDS:
            t0 = time.perf_counter()
            a = lo.align(
                misaligned, 1000.0, search=search, shots_per_step=100, signal=SIGNAL, seed=seed
            )
            runs.append(
                {
                    "seconds": time.perf_counter() - t0,
                    "shots_to_within_1_percent": a.shots_to_within,
                    "shots_total": int(a.shots[-1]),
                    "final_overlap": float(a.overlap[-1]),
                }
            )
        reached = [r["shots_to_within_1_percent"] for r in runs]
        rows[f"align_{search}"] = {
            "runs": runs,
            "best_overlap": a.best_overlap,
            "median_shots_to_within_1_percent": (
                float(np.median(reached)) if None not in reached else None
            ),
        }
        print(
            f"align {search:8s}: shots to within 1 % of the best G, seeds 0-4: {reached}; total "
            f"{[r['shots_total'] for r in runs]}; {np.mean([r['seconds'] for r in runs]):.2f} s "
            "each"
        )

    meta = {
        **run_meta(load),
        "tolerance": 1e-4,
    }
    write_result("bench_optimize", {"meta": meta, "results": rows})


if __name__ == "__main__":
    main()
