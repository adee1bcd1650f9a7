"""The interactive view's slow parts: the telecover panel of an obstructed system and the first
curve of a flat-top beam.

- Telecover panel: the paper's Table 1 lidar with a 20 mm central obstruction, the twin's 200
  ranges geomspace(1.05 m, 1 km), tolerance 1e-4, one thread (as the twin computes it). The exact
  sectors (lo.telecover: masked ray tracing through the moving shadow) against the twin's
  centred-shadow estimate (views/twin_telecover.py), alternated, best of 3 each, and one whole
  slider update of the twin (curve, detector image, telecover) with the estimate. Peer: one
  full-aperture RT curve in the same run. Target: an update under 1 s.
- Time to first curve: `lidar-overlap view examples/scenarios/biaxial_flat_top.toml` from reading
  the scenario (the phase plate's design) to the curve of its 40 ranges (auto: Fourier optics, all
  cores), one run.

Run:  python benchmarks/bench_view.py   (writes benchmarks/results/bench_view.json). SI units.
"""

from __future__ import annotations

import pathlib
import time

import numpy as np
from _common import alternated_best, best_time, load_average, run_meta, write_result

import lidar_overlap as lo
from lidar_overlap.io.scenario import load_scenario
from lidar_overlap.views.twin import N_RANGES_AUTO, Twin
from lidar_overlap.views.twin_telecover import centred_shadow_telecover

RANGES = np.geomspace(1.05, 1000.0, 200)  # m: the twin's default for a 0.7 m obstruction distance
TOLERANCE = 1e-4
TARGET = 1.0  # s, a slider update with the telecover panel
FLAT_TOP = (
    pathlib.Path(__file__).resolve().parent.parent / "examples/scenarios/biaxial_flat_top.toml"
)


def main():
    load_start = load_average()
    system = lo.paper_table1(obstruction_radius=0.02)
    times, last = alternated_best(
        {
            "exact": lambda: lo.telecover(system, RANGES, tolerance=TOLERANCE, threads=1),
            "estimate": lambda: centred_shadow_telecover(system, RANGES, tolerance=TOLERANCE),
        },
        3,
    )
    t_full, _ = best_time(
        lambda: lo.overlap(system, RANGES, "rt", tolerance=TOLERANCE, threads=1), 5
    )
    twin = Twin(system, RANGES, telecover="quadrants", tolerance=TOLERANCE)
    positions = iter(range(100, 200))
    t_update, _ = best_time(lambda: twin.update({"tilt_x": next(positions)}), 3)
    seen = last["exact"].full.overlap > 1e-3
    t0 = time.perf_counter()
    scenario = load_scenario(FLAT_TOP)
    z = scenario.ranges
    flat = Twin(scenario.system, np.geomspace(z[0], z[-1], N_RANGES_AUTO), compute=False)
    t_design = time.perf_counter() - t0
    flat.accept(flat.compute())
    t_first = time.perf_counter() - t0
    out = {
        "ranges": len(RANGES),
        "tolerance": TOLERANCE,
        "telecover_exact_s": times["exact"],
        "telecover_estimate_s": times["estimate"],
        "exact_over_estimate": times["exact"] / times["estimate"],
        "full_curve_s": t_full,
        "estimate_over_full_curve": times["estimate"] / t_full,
        "twin_update_with_estimate_s": t_update,
        "target_s": TARGET,
        "meets_target": t_update <= TARGET,
        "estimate_max_abs_g_error": float(
            np.max(np.abs(last["estimate"].overlap - last["exact"].overlap))
        ),
        "estimate_max_abs_deviation_error": float(
            np.max(np.abs(last["estimate"].deviation - last["exact"].deviation)[:, seen])
        ),
        "flat_top_scenario_read_s": t_design,
        "flat_top_first_curve_s": t_first,
        "flat_top_ranges": N_RANGES_AUTO,
        "flat_top_model": flat.result.method,
        "meta": run_meta(load_start),
    }
    print(
        f"telecover, 20 mm obstruction, 200 ranges, one thread: exact {times['exact']:.2f} s, "
        f"estimate {times['estimate'] * 1e3:.0f} ms ({times['exact'] / times['estimate']:.0f}x "
        f"faster; {times['estimate'] / t_full:.0f}x one full curve of {t_full * 1e3:.1f} ms); "
        f"twin update {t_update * 1e3:.0f} ms (target {TARGET:g} s); estimate's error: G "
        f"{out['estimate_max_abs_g_error']:.1e}, "
        f"deviations {out['estimate_max_abs_deviation_error']:.1e}"
    )
    print(
        f"flat-top scenario: read (plate designed) {t_design:.1f} s, first curve of "
        f"{N_RANGES_AUTO} ranges ({flat.result.method}) {t_first:.1f} s after the start"
    )
    write_result("bench_view", out)


if __name__ == "__main__":
    main()
