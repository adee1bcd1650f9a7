"""How many random-phase receiver fields M a both-paths turbulent FO draw should carry: the standard
error of the mean G at the last ranges against CPU time, for M = 1, 2, 4, 8 at (about) equal CPU.

Each draw of the atmosphere costs one beam and M receiver propagations, so at a fixed budget M = 1
affords about (1 + 8) / (1 + 1) = 4.5 times the draws of M = 8. The receiver's sensitivity is
unbiased for every M; its random-phase noise is independent between draws and averages over them
like the atmosphere's own spread: Var(G of a draw) = s_atm^2 + s_rx^2 / M, so the standard error at
a budget B is sqrt((s_atm^2 + s_rx^2 / M) c(M) / B), c(M) the CPU time of a draw. The runs below
measure it directly: the figure of merit is SE x sqrt(CPU s), the standard error one CPU second
would give (lower is better; each SE is itself uncertain by ~1 / sqrt(2 draws)).

The 5 cm lidar of docs/turbulence.md and bench_turbulent_both.py (1064 nm, w0 = 5 mm, f = 0.5 m,
detector radius 70 um), Cn^2 = 1e-13 m^-2/3, 20 ranges 100-1000 m, 10 screens, 432^2, all cores.
Writes results/study_receiver_fields.json. Run: python benchmarks/study_receiver_fields.py [scale]
(scale multiplies the draws: 1 gives 16 draws at M = 8).
"""

from __future__ import annotations

import sys
import time

import numpy as np
from _common import FIVE_CM_LIDAR, load_average, run_meta, source_commit, write_result

import lidar_overlap as lo

RANGES = np.geomspace(100.0, 1000.0, 20)
CN2 = 1e-13
BEAM_GRID = 432
SEED = 11
LAST = 3  # the last LAST ranges are reported
FIELDS = (1, 2, 4, 8)
SYSTEM = FIVE_CM_LIDAR


def run(fields, realizations):
    method = lo.Turbulent(
        lo.Turbulence(CN2),
        lo.FO(beam_grid=BEAM_GRID),
        realizations=realizations,
        seed=SEED,
        paths="both",
        receiver_fields=fields,
    )
    c0 = time.process_time()
    res = lo.overlap(SYSTEM, RANGES, method)
    return time.process_time() - c0, res


def main():
    scale = float(sys.argv[1]) if len(sys.argv) > 1 else 1.0
    load_before = load_average()
    print(f"lidar_overlap {lo.__version__} | load {load_before:.2f} | commit {source_commit()}")
    run(1, 2)  # FFTW plans
    rows = {}
    for m in FIELDS:
        draws = max(4, int(round(scale * 16 * (1 + 8) / (1 + m))))
        cpu, res = run(m, draws)
        se = res.error_estimate[-LAST:]
        merit = se * np.sqrt(cpu)
        rows[m] = {
            "realizations": draws,
            "cpu_s": cpu,
            "cpu_s_per_draw": cpu / draws,
            "mean_overlap_last": [float(v) for v in res.overlap[-LAST:]],
            "standard_error_last": [float(v) for v in se],
            "se_times_sqrt_cpu_last": [float(v) for v in merit],
        }
        print(
            f"M = {m}: {draws} draws, {cpu:.1f} CPU s ({cpu / draws:.2f} s a draw); G at "
            f"{RANGES[-1]:g} m {res.overlap[-1]:.4f} +- {se[-1]:.4f}; SE x sqrt(CPU s) at the last "
            f"{LAST} ranges {np.array2string(merit, precision=4)}"
        )
    cost = {k: rows[k]["cpu_s_per_draw"] for k in FIELDS}
    print("cost per draw (CPU s):", {k: round(v, 3) for k, v in cost.items()})
    best = min(FIELDS, key=lambda k: float(np.mean(rows[k]["se_times_sqrt_cpu_last"])))
    print(f"lowest SE at equal CPU (mean over the last {LAST} ranges): M = {best}")
    write_result(
        "study_receiver_fields",
        {
            "meta": {
                **run_meta(load_before),
                "cn2": CN2,
                "ranges_m": [float(RANGES[0]), float(RANGES[-1]), int(RANGES.size)],
                "beam_grid": BEAM_GRID,
                "seed": SEED,
                "timing": "CPU time of each call (all threads), one call per M",
                "figure_of_merit": "standard error of mean G x sqrt(CPU s): the SE at 1 CPU s",
            },
            "result": {str(k): v for k, v in rows.items()},
            "lowest_se_at_equal_cpu": best,
        },
    )


if __name__ == "__main__":
    main()
