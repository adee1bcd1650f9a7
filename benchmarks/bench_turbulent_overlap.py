"""Turbulent FO overlap: the Table 1 lidar through phase screens, 100 realisations x 50 ranges on
256^2 grids.

`lo.overlap(system, ranges, method="fo", turbulence=lo.Turbulence(1e-14), realizations=100, seed=1)`
with the paper's Table 1 lidar (355 nm, w0 = 1 mm, f = 1 m, D = 150 mm, FFOV 0.9 mrad), 50 ranges
50-2000 m (geometric), constant Cn^2 = 1e-14 m^-2/3 (the moderate case of
examples/turbulence_overlap.py), 10 screens, beam_grid = 256, all cores. One untimed call with 2
realisations first makes the FFTW plans; then the full call (best of REPEATS) and a 1-realisation
call, whose difference gives the cost of one more realisation (the per-range coupling maps are made
once per call). Writes results/bench_turbulent_overlap.json.
Run: python benchmarks/bench_turbulent_overlap.py
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import numpy as np
from _common import best_time, load_average, source_commit

import lidar_overlap as lo

RANGES = np.geomspace(50.0, 2000.0, 50)
CN2 = 1e-14  # m^-2/3
REALIZATIONS = 100
BEAM_GRID = 256
SEED = 1
REPEATS = 2


def run(realizations):
    return lo.overlap(
        lo.paper_table1(),
        RANGES,
        "fo",
        turbulence=lo.Turbulence(CN2),
        realizations=realizations,
        seed=SEED,
        beam_grid=BEAM_GRID,
        paths="transmit",
    )


def main():
    print(
        f"lidar_overlap {lo.__version__} | {os.cpu_count()} cores | load {load_average():.2f} | "
        f"commit {source_commit()}"
    )
    run(2)  # FFTW plans
    t_full, res = best_time(lambda: run(REALIZATIONS), REPEATS)
    t_one, _ = best_time(lambda: run(1), REPEATS)
    per_realization = (t_full - t_one) / (REALIZATIONS - 1)
    print(
        f"{REALIZATIONS} realisations x {RANGES.size} ranges, {BEAM_GRID}^2 grid: {t_full:.2f} s "
        f"({t_full / REALIZATIONS:.3f} s per realisation; one more realisation "
        f"{per_realization:.3f} s, fixed cost {t_one - per_realization:.2f} s)"
    )
    print(
        f"mean G at {RANGES[-1]:g} m: {res.overlap[-1]:.4f} +- {res.error_estimate[-1]:.4f} (5-95 "
        f"%: {res.low[-1]:.4f}-{res.high[-1]:.4f})"
    )
    out = Path(__file__).resolve().parent / "results" / "bench_turbulent_overlap.json"
    out.write_text(
        json.dumps(
            {
                "meta": {
                    "measured": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
                    "commit": source_commit(),
                    "load_average_1min": load_average(),
                    "cores": os.cpu_count(),
                    "cn2": CN2,
                    "ranges_m": [float(RANGES[0]), float(RANGES[-1]), int(RANGES.size)],
                    "beam_grid": BEAM_GRID,
                    "realizations": REALIZATIONS,
                    "seed": SEED,
                    "repeats": REPEATS,
                },
                "result": {
                    "seconds": t_full,
                    "seconds_per_realization": t_full / REALIZATIONS,
                    "seconds_per_additional_realization": per_realization,
                    "seconds_one_realization": t_one,
                    "mean_overlap_last_range": float(res.overlap[-1]),
                    "standard_error_last_range": float(res.error_estimate[-1]),
                },
            },
            indent=2,
        )
    )
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
