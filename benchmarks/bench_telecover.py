"""Cost of the telecover test: the four quadrants of lo.telecover against one full-aperture RT curve.

The paper's Table 1 lidar with its beam tilted by 50 µrad in y (the full-aperture coupling keeps a centre of
symmetry, so the full curve is one Rice-weighted radial integral per range; a quadrant breaks the rotation,
so each masked curve integrates over directions too), 100 ranges geomspace(10 m, 3000 m), tolerance 1e-4,
all cores. Times are the best of 3 warm repeats; the quadrant sum is checked against the full curve.
Target: four quadrants within 4x one full curve.

Run:  python benchmarks/bench_telecover.py   (writes benchmarks/results/bench_telecover.json). SI units.
"""

from __future__ import annotations

import dataclasses
import json
import platform
from pathlib import Path

import numpy as np

import lidar_overlap as lo
from _common import best_time, load_average, source_commit

RANGES = np.geomspace(10.0, 3000.0, 100)   # m
TOLERANCE = 1e-4
TARGET = 4.0


def main():
    load_start = load_average()
    system = lo.paper_table1()
    system = dataclasses.replace(system, beam=dataclasses.replace(system.beam, tilt=(0.0, 50e-6)))
    quadrants = lo.ApertureMask.quadrants().split()
    masked = [dataclasses.replace(system, telescope=dataclasses.replace(system.telescope, mask=m)) for m in quadrants]
    t_full, full = best_time(lambda: lo.overlap(system, RANGES, "rt", tolerance=TOLERANCE), 3)
    t_quad, parts = best_time(lambda: [lo.overlap(s, RANGES, "rt", tolerance=TOLERANCE) for s in masked], 3)
    t_tele, tele = best_time(lambda: lo.telecover(system, RANGES, tolerance=TOLERANCE), 1)
    sum_error = float(np.max(np.abs(np.sum([p.overlap for p in parts], axis=0) - full.overlap)))
    out = {
        "ranges": len(RANGES), "tolerance": TOLERANCE,
        "full_s": t_full, "quadrants_s": t_quad, "telecover_s": t_tele,
        "quadrants_over_full": t_quad / t_full, "target": TARGET, "meets_target": t_quad / t_full <= TARGET,
        "quadrant_sum_error": sum_error,
        "max_north_south_deviation": float(np.nanmax(np.abs(tele.deviation[0] - tele.deviation[2]))),
        "meta": {"commit": source_commit(), "python": platform.python_version(), "cores": lo.max_threads(),
                 "load_start": load_start, "load_end": load_average()},
    }
    print(f"full curve {t_full * 1e3:.1f} ms, four quadrants {t_quad * 1e3:.1f} ms "
          f"({t_quad / t_full:.0f}x, target {TARGET:g}x), telecover() {t_tele * 1e3:.1f} ms; "
          f"quadrant sum error {sum_error:.1e}")
    path = Path(__file__).resolve().parent / "results" / "bench_telecover.json"
    path.write_text(json.dumps(out, indent=2) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
