"""Cost of the telecover test: the four quadrants of lo.telecover against one full-aperture RT
curve.

The paper's Table 1 lidar with its beam tilted by 50 µrad in y (the full-aperture coupling keeps a
centre of symmetry, so the full curve is one Rice-weighted radial integral per range; a quadrant
breaks the rotation, so each masked curve needs the exact areas of the back-projected detector disc
inside it, integrated against the Marcum-Q kernel), 100 ranges geomspace(10 m, 3000 m), tolerance
1e-4. Timed, best of 5 warm repeats:
- through the public API on all cores: one full curve (lo.overlap), the four quadrants one
  lo.overlap call each, and lo.telecover (the four quadrants in one core call sharing their nodes,
  plus the full curve);
- the core alone on one thread (no Python, no thread start-up): the full curve, and the four
  quadrants in one call.
The quadrant sum is checked against the full curve. Target: the four quadrants within 4x one full
curve.

Run:  python benchmarks/bench_telecover.py   (writes benchmarks/results/bench_telecover.json). SI
units.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from _common import best_time, load_average, run_meta, write_result

import lidar_overlap as lo
from lidar_overlap import _core

RANGES = np.geomspace(10.0, 3000.0, 100)  # m
TOLERANCE = 1e-4
TARGET = 4.0


def main():
    load_start = load_average()
    system = lo.paper_table1()
    system = dataclasses.replace(system, beam=dataclasses.replace(system.beam, tilt=(0.0, 50e-6)))
    quadrants = lo.ApertureMask.quadrants().split()
    masked = [
        dataclasses.replace(system, telescope=dataclasses.replace(system.telescope, mask=m))
        for m in quadrants
    ]
    t_full, full = best_time(lambda: lo.overlap(system, RANGES, "rt", tolerance=TOLERANCE), 5)
    t_quad, parts = best_time(
        lambda: [lo.overlap(s, RANGES, "rt", tolerance=TOLERANCE) for s in masked], 5
    )
    t_tele, tele = best_time(lambda: lo.telecover(system, RANGES, tolerance=TOLERANCE), 5)
    options = _core.RtOptions(tolerance=TOLERANCE, threads=1)
    native, masks = system._native, [m._native for m in quadrants]
    t_core_full, core_full = best_time(lambda: _core.overlap_rt(native, RANGES, options), 5)
    t_core_quad, core_quad = best_time(
        lambda: _core.overlap_rt_masks(native, RANGES, masks, options), 5
    )
    sum_error = float(
        np.max(np.abs(np.sum([p.overlap for p in tele.sectors], axis=0) - full.overlap))
    )
    separate_error = max(
        float(np.max(np.abs(a.overlap - b.overlap))) for a, b in zip(parts, tele.sectors)
    )
    out = {
        "ranges": len(RANGES),
        "tolerance": TOLERANCE,
        "full_s": t_full,
        "quadrants_separate_s": t_quad,
        "telecover_s": t_tele,
        "core_full_one_thread_s": t_core_full,
        "core_quadrants_one_thread_s": t_core_quad,
        "core_evaluations_per_range": {
            "full": core_full.evaluations / len(RANGES),
            "quadrants_together": core_quad[0].evaluations / len(RANGES),
        },
        "quadrants_separate_over_full": t_quad / t_full,
        "telecover_over_full": t_tele / t_full,
        "core_quadrants_over_full": t_core_quad / t_core_full,
        "target": TARGET,
        "meets_target": t_core_quad / t_core_full <= TARGET,
        "quadrant_sum_error": sum_error,
        "together_vs_separate_max_difference": separate_error,
        "max_north_south_deviation": float(
            np.nanmax(np.abs(tele.deviation[0] - tele.deviation[2]))
        ),
        "meta": run_meta(load_start),
    }
    print(
        f"public API: full curve {t_full * 1e3:.1f} ms, four quadrants one call each "
        f"{t_quad * 1e3:.1f} ms ({t_quad / t_full:.1f}x), telecover() {t_tele * 1e3:.1f} ms "
        f"({t_tele / t_full:.1f}x, quadrants together plus the full curve)"
    )
    print(
        f"core, one thread: full {t_core_full * 1e3:.2f} ms, four quadrants together "
        f"{t_core_quad * 1e3:.2f} ms ({t_core_quad / t_core_full:.1f}x, target {TARGET:g}x); nodes "
        f"per range {core_full.evaluations / len(RANGES):.0f} and "
        f"{core_quad[0].evaluations / len(RANGES):.0f}"
    )
    print(f"quadrant sum error {sum_error:.1e}; together vs one at a time {separate_error:.1e}")
    write_result("bench_telecover", out)


if __name__ == "__main__":
    main()
