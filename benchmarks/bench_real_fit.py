"""Global fit and model ladder on a real curve's scale: six parameters of the PollyXT far-range
preset fitted by lo.fit(search="global") to a 150-point relative curve (synthetic, from a known
system of that preset, sigma = 0.007 like the far-range scatter of the PollyNET default curve in
examples/data/), normalised over 800-1200 m; then free="auto" (the model ladder of
analysis/model_ladder.py) on the same curve.

Counts: candidates of the search (one batched core call per generation), local-fit curves and
Jacobians, and every model evaluation. One timed run each (a global fit is long and seeded: its cost
does not vary between runs); the wall time and the process's CPU time (all threads) of each, the
latter less inflated by other load. Targets on 2 cores: global fit <= 20 s, ladder <= 60 s (wall).
Writes results/bench_real_fit.json.
"""

from __future__ import annotations

import os
import time
import warnings

import numpy as np
from _common import load_average, run_meta, write_result

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.model.instruments import pollyxt

RANGES = np.linspace(150.0, 1200.0, 150)  # m, the PollyNET curves' spacing is 7.5 m
SIGMA = 0.007
NORMALIZE = (800.0, 1200.0)
TRUE = {
    "beam.offset[0]": 0.16,
    "beam.tilt[0]": -8e-5,
    "beam.divergence": 1.0e-4,
    "detector.radius": 4e-4,
    "detector.defocus": 2.5e-3,
    "detector.numerical_aperture": 0.12,
}
BOUNDS = {"detector.numerical_aperture": (0.05, 0.5), "detector.defocus": (-0.01, 0.01)}
TARGETS_S = {"global": 20.0, "ladder": 60.0}


def main():
    load = load_average()
    print(f"lidar_overlap {lo.__version__} | {os.cpu_count()} cores | load average {load:.2f}")
    if load > 0.5:
        print(f"warning: load average {load:.2f} before the run: the times may be inflated")
    start = pollyxt("far", 355e-9, numerical_aperture=0.22)
    truth = parameters.replace(start, TRUE)
    g = lo.overlap(truth, RANGES, "rt", tolerance=1e-6).overlap
    y = 0.97 * (g + np.random.default_rng(0).normal(0.0, SIGMA, RANGES.size))
    common = dict(
        sigma=0.97 * SIGMA,
        bounds=BOUNDS,
        method="rt",
        tolerance=5e-4,
        normalize=NORMALIZE,
        seed=1,
        max_evaluations=300,
        allow_unconverged=True,
    )
    warnings.simplefilter("ignore")
    t0, c0 = time.perf_counter(), time.process_time()
    f = lo.fit(start, RANGES, y, free=list(TRUE), search="global", **common)
    t_global, c_global = time.perf_counter() - t0, time.process_time() - c0
    print(f)
    t0, c0 = time.perf_counter(), time.process_time()
    ladder = lo.fit(start, RANGES, y, free="auto", **common)
    t_ladder, c_ladder = time.perf_counter() - t0, time.process_time() - c0
    print(ladder)
    evaluations = sum(s.fit.evaluations for s in ladder.scores)
    rows = {
        "global": {
            "time_s": t_global,
            "cpu_s": c_global,
            "candidates": f.search.candidates,
            "core_calls": f.search.core_calls,
            "model_evaluations": f.evaluations,
            "jacobian_evaluations": f.jacobian_evaluations,
            "reduced_chi_square": f.reduced_chi_square,
        },
        "ladder": {
            "time_s": t_ladder,
            "cpu_s": c_ladder,
            "model_evaluations": evaluations,
            "chosen": ladder.chosen_family.name,
            "scores": {s.family.name: s.bic for s in ladder.scores},
        },
    }
    for name, row in rows.items():
        met = row["time_s"] <= TARGETS_S[name]
        print(
            f"{name}: {row['time_s']:.1f} s, {row['cpu_s']:.1f} CPU s "
            f"(target {TARGETS_S[name]:g} s: "
            f"{'met' if met else 'NOT met'}), {row['model_evaluations']} model evaluations"
        )
        row["target_met"] = met
    meta = {
        **run_meta(load),
        "ranges_m": {"start": 150.0, "stop": 1200.0, "count": int(RANGES.size)},
        "sigma": SIGMA,
        "true": TRUE,
        "targets_s": TARGETS_S,
    }
    write_result("bench_real_fit", {"meta": meta, "results": rows})


if __name__ == "__main__":
    main()
