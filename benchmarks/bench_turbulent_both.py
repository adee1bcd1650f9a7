"""Turbulent FO overlap, both paths against transmit only, in the same run (docs/turbulence.md).

The 5 cm lidar of docs/turbulence.md (1064 nm, w0 = 5 mm, f = 0.5 m, detector radius 70 um: 0.28
mrad), Cn^2 = 1e-13 m^-2/3, RANGES ranges 100-1000 m, 10 screens, on the 432^2 grid both paths need
(the transmit-only run on the same grid, so that the ratio is the return path's cost alone),
RECEIVER_FIELDS random-phase receiver fields, all cores. One untimed call of each first (FFTW
plans); then the best of REPEATS. Prints the times, their ratio and G at the last range with its
standard error, the amplification there; writes results/bench_turbulent_both.json. Run: python
benchmarks/bench_turbulent_both.py [realizations]
"""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

import numpy as np
from _common import best_time, load_average, source_commit

import lidar_overlap as lo

RANGES = np.geomspace(100.0, 1000.0, 20)
CN2 = 1e-13
BEAM_GRID = 432
RECEIVER_FIELDS = 8
SEED = 1
REPEATS = 1
SYSTEM = lo.LidarSystem(
    beam=lo.GaussianBeam(wavelength=1064e-9, waist_radius=5e-3),
    telescope=lo.Telescope(diameter=0.05, focal_length=0.5),
    detector=lo.Detector(radius=70e-6),
)


def run(paths, realizations):
    method = lo.Turbulent(
        lo.Turbulence(CN2),
        lo.FO(beam_grid=BEAM_GRID),
        realizations=realizations,
        seed=SEED,
        paths=paths,
        receiver_fields=RECEIVER_FIELDS,
    )
    return lo.overlap(SYSTEM, RANGES, method)


def main():
    realizations = int(sys.argv[1]) if len(sys.argv) > 1 else 10
    print(
        f"lidar_overlap {lo.__version__} | {os.cpu_count()} cores | load {load_average():.2f} | "
        f"commit {source_commit()}"
    )
    run("transmit", 2), run("both", 2)  # FFTW plans
    t_tx, tx = best_time(lambda: run("transmit", realizations), REPEATS)
    t_both, both = best_time(lambda: run("both", realizations), REPEATS)
    print(
        f"{realizations} realisations x {RANGES.size} ranges, {BEAM_GRID}^2: transmit {t_tx:.2f} "
        f"s, both {t_both:.2f} s ({RECEIVER_FIELDS} receiver fields): ratio {t_both / t_tx:.2f}"
    )
    print(
        f"G at {RANGES[-1]:g} m: transmit {tx.overlap[-1]:.4f} +- {tx.error_estimate[-1]:.4f}, "
        f"both {both.overlap[-1]:.4f} +- {both.error_estimate[-1]:.4f}, amplification "
        f"{both.amplification[-1]:.3f}"
    )
    out = Path(__file__).resolve().parent / "results" / "bench_turbulent_both.json"
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
                    "receiver_fields": RECEIVER_FIELDS,
                    "realizations": realizations,
                    "seed": SEED,
                },
                "result": {
                    "seconds_transmit": t_tx,
                    "seconds_both": t_both,
                    "ratio": t_both / t_tx,
                    "overlap_last_transmit": float(tx.overlap[-1]),
                    "overlap_last_both": float(both.overlap[-1]),
                    "standard_error_last_both": float(both.error_estimate[-1]),
                    "amplification": [float(a) for a in both.amplification],
                },
            },
            indent=2,
        )
    )
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
