"""Scaling: time against the number of ranges (RT, FO radial, FO 2-D), against the 2-D grid size,
and two threads against one. Part of speed_accuracy.py, which runs it and writes scaling.png."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from _common import best_time  # noqa: E402
from _speed_common import RADIAL_DEFAULT, REPEATS, TABLE1, radial  # noqa: E402

import lidar_overlap as lo  # noqa: E402

SCALING_COUNTS = (10, 30, 100, 300, 1000)
SCALING_SPAN = (30.0, 1000.0)  # m, same ranges for every method
SCALING_GRIDS = (64, 128, 256, 512, 1024)
SCALING_GRID_RANGES = np.geomspace(30.0, 1000.0, 20)


def scaling():
    system = TABLE1
    calls = {
        "RT": lambda z, th: lo.overlap(system, z, method="rt", tolerance=1e-4, threads=th),
        "FO radial": lambda z, th: radial(system, z, RADIAL_DEFAULT, th),
        "FO 2-D": lambda z, th: lo.overlap(system, z, method="fo", fo_path="2d", threads=th),
    }
    by_count = {}
    for method, fn in calls.items():
        by_count[method] = {}
        for th in (1, 2):
            times = []
            for n in SCALING_COUNTS:
                z = np.geomspace(*SCALING_SPAN, n)
                repeats = REPEATS if (method != "FO 2-D" or n <= 100) else 1
                times.append(best_time(lambda fn=fn, z=z, th=th: fn(z, th), repeats)[0])
            by_count[method][str(th)] = times
    by_grid = {}
    for th in (1, 2):
        by_grid[str(th)] = [
            best_time(
                lambda n=n, th=th: lo.overlap(
                    system, SCALING_GRID_RANGES, method="fo", fo_path="2d", beam_grid=n, threads=th
                ),
                REPEATS,
            )[0]
            for n in SCALING_GRIDS
        ]
    return {
        "system": "Table 1, coaxial",
        "ranges_m": {"start": SCALING_SPAN[0], "stop": SCALING_SPAN[1], "spacing": "geometric"},
        "counts": list(SCALING_COUNTS),
        "time_by_count_s": by_count,
        "repeats": f"best of {REPEATS}; FO 2-D at more than 100 ranges: 1 timed call after one "
        "untimed",
        "grid_sizes": list(SCALING_GRIDS),
        "grid_ranges": SCALING_GRID_RANGES.size,
        "time_by_grid_s": by_grid,
    }


def plot_scaling(sc, path):
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    counts = np.array(sc["counts"])
    for method, colour in (("RT", "C0"), ("FO radial", "C1"), ("FO 2-D", "C2")):
        for th, ls in (("1", "-"), ("2", "--")):
            axes[0].loglog(
                counts,
                sc["time_by_count_s"][method][th],
                "o" + ls,
                color=colour,
                label=f"{method}, {th} thread{'s' if th == '2' else ''}",
            )
        axes[2].semilogx(
            counts,
            np.array(sc["time_by_count_s"][method]["1"])
            / np.array(sc["time_by_count_s"][method]["2"]),
            "o-",
            color=colour,
            label=method,
        )
    axes[0].loglog(
        counts,
        sc["time_by_count_s"]["FO radial"]["1"][2] * counts / counts[2],
        ":",
        color="0.5",
        label="∝ number of ranges",
    )
    axes[0].set_xlabel("number of ranges (30–1000 m, geometric)")
    axes[0].set_ylabel("wall time (s)")
    axes[0].set_title("Table 1 coaxial: time against the number of ranges", fontsize=9)
    axes[0].legend(fontsize=7)
    grids = np.array(sc["grid_sizes"])
    for th, ls in (("1", "-"), ("2", "--")):
        axes[1].loglog(
            grids, sc["time_by_grid_s"][th], "o" + ls, color="C2", label=f"FO 2-D, {th} thread(s)"
        )
    t1 = np.array(sc["time_by_grid_s"]["1"])
    axes[1].loglog(
        grids,
        t1[-1] * (grids / grids[-1]) ** 2 * np.log(grids) / np.log(grids[-1]),
        ":",
        color="0.5",
        label="∝ N² log N",
    )
    axes[1].set_xlabel("beam_grid N")
    axes[1].set_ylabel("wall time (s)")
    axes[1].set_title(
        f"FO 2-D: time against the grid size ({sc['grid_ranges']} ranges)", fontsize=9
    )
    axes[1].legend(fontsize=7)
    axes[2].semilogx(
        grids,
        t1 / np.array(sc["time_by_grid_s"]["2"]),
        "s--",
        color="C2",
        label="FO 2-D (by grid size)",
    )
    axes[2].axhline(2.0, color="0.5", ls=":")
    axes[2].axhline(1.0, color="0.5", ls=":")
    axes[2].set_xlabel("number of ranges (or N for the squares)")
    axes[2].set_ylabel("time with 1 thread / time with 2")
    axes[2].set_title("speed-up of 2 threads over 1", fontsize=9)
    axes[2].legend(fontsize=7)
    for ax in axes:
        ax.grid(True, which="major", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------
