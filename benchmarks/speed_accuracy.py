"""Speed against accuracy of every way to compute an overlap curve, where each model fails, and
scaling.

One process, SI units. Three parts, each with its own chart in benchmarks/results/:

1. ``speed_accuracy.png``: wall time against the maximum |G - G_ref| over the curve, one panel per
   scene, each method a series whose points are its accuracy settings:
   - RT, ``lo.overlap(method="rt", tolerance=tol)`` for tol = 1e-2 ... 1e-9;
   - FO radial, ``_core.overlap_fo_radial(system, z, RadialFoOptions(periods_per_panel=p))`` for
     periods per panel 24, 16, 12, 8 (8 is what ``lo.overlap(method="fo")`` uses) and 4 (every
     Gaussian scene: the beam image's offset enters as J0);
   - FO 2-D, ``lo.overlap(method="fo", fo_path="2d", beam_grid=N)`` for N = 64 ... 512 (window 10
     w0);
   - the NumPy transcription of Appendix B (``bench_rt.baseline_overlap``) on n x n emitters;
   - Appendix C one emitter at a time (``bench_fo_overlap.direct_overlap``, 3 x 3 Gauss-Hermite
     emitters) at two ranges of the first scene, its time extrapolated to the whole curve and its
     error taken over those two ranges;
   - ``lo.overlap(method="auto", tolerance=tol)`` for tol = 1e-2, 1e-3, 1e-4, marked apart and
     compared with the fastest single library method whose measured error meets the same tolerance
     (the requirement: auto no more than 2x slower than it), the two timed again in alternating
     rounds (best of 7 for sub-second calls, 3 for longer ones) so that both see the same machine
     load.
   The reference is FO radial at 1 period per panel (every scene here has a Gaussian beam; on the
   biaxial one FO 2-D at N = 1024 over 12 w0 agrees with it to ~3e-7). Times: best of 3 warm calls,
   threads = 0.
2. ``failure_map.png``: error of RT and of FO 2-D (N = 128, 256) at each (range, detector radius in
   Airy radii 1.22 lambda f / D) on the coaxial Table 1 telescope, with the 1e-3 contour; and the FO
   2-D path's error against its two sampling parameters (grid size N and window W in waist radii).
3. ``scaling.png``: time against the number of ranges (RT, FO radial, FO 2-D), against the FO 2-D
   grid size, and the speed-up of two threads over one.

Part 1 lives in speed_scenes.py, parts 2 and 3 in failure_map.py and scaling.py, the helpers
shared by all three in _speed_common.py; this script runs them all and writes
``results/speed_accuracy.json`` (with a ``meta`` block: date, versions, commit, cores, load).
Run:  python benchmarks/speed_accuracy.py     (about 3.5 minutes on 2 idle cores, 5 under load).
"""

from __future__ import annotations

import os
import platform
import sys
import time
import warnings
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from _common import json_text, load_average, source_commit  # noqa: E402
from _speed_common import (
    FO_2D_WINDOW,
    RADIAL_DEFAULT,
    REPEATS,
    RESULTS,  # noqa: E402
    THREADS,
)

# noqa: E402
from failure_map import CUT_RANGE, FAILURE_TOLERANCE, MAP_WINDOW_GRID, failure_map, plot_failure_map
from scaling import (
    SCALING_COUNTS,
    SCALING_GRID_RANGES,
    SCALING_GRIDS,
    SCALING_SPAN,
    plot_scaling,
    scaling,
)  # noqa: E402
from speed_scenes import (  # noqa: E402
    AUTO_MAX_RATIO,
    AUTO_TOLERANCES,
    PAIRED_ROUNDS,
    RT_TOLERANCES,
    SCENES,
    SINGLE_THREAD_CHECK_BELOW,
    label,
    pareto_front,
    run_scene,
)

import lidar_overlap as lo  # noqa: E402

ERROR_FLOOR = 1e-14  # errors below this are drawn at it

COLOURS = {
    "RT": "C0",
    "FO radial": "C1",
    "FO 2-D": "C2",
    "Appendix B (NumPy)": "C3",
    "Appendix C (direct)": "C4",
    "auto": "k",
}


def plot_speed_accuracy(scenes, path):
    fig, axes = plt.subplots(2, 2, figsize=(13, 10.5))
    for ax, (_name, s) in zip(axes.flat, scenes.items()):
        front = pareto_front(s["points"])
        fe = [max(p["max_error"], ERROR_FLOOR) for p in front]
        ft = [p["time_s"] for p in front]
        ax.step(
            fe + [1.0],
            ft + [ft[-1]],
            where="post",
            color="0.55",
            lw=3,
            alpha=0.5,
            zorder=1,
            label="Pareto front (fastest time for an error budget)",
        )
        for method in ("RT", "FO radial", "FO 2-D", "Appendix B (NumPy)", "Appendix C (direct)"):
            pts = [p for p in s["points"] if p["method"] == method]
            if not pts:
                continue
            e = [max(p["max_error"], ERROR_FLOOR) for p in pts]
            t = [p["time_s"] for p in pts]
            direct = method == "Appendix C (direct)"
            ax.plot(
                e,
                t,
                "D" if direct else "o",
                ls="none" if method == "RT" else "-",
                color=COLOURS[method],
                mfc="none" if direct else COLOURS[method],
                ms=7 if direct else 6,
                mew=1.5,
                lw=1,
                zorder=3,
                label=method + (" (2 ranges, time extrapolated)" if direct else ""),
            )
            if method == "RT":
                ax.annotate(
                    f"tol {RT_TOLERANCES[0]:.0e}…{RT_TOLERANCES[-1]:.0e}",
                    (min(e), min(t)),
                    textcoords="offset points",
                    xytext=(6, -11),
                    fontsize=7,
                    color=COLOURS[method],
                )
            elif method == "FO 2-D":  # same error, close times: one label for the column
                ax.annotate(
                    "\n".join(f"N={p['value']}: {p['time_s']:.2f} s" for p in pts),
                    (max(e), max(t)),
                    textcoords="offset points",
                    xytext=(-8, 0),
                    fontsize=7,
                    va="top",
                    ha="right",
                    color=COLOURS[method],
                )
            else:
                for p, ei, ti in zip(pts, e, t):
                    ax.annotate(
                        label(p).split(" ")[-1],
                        (ei, ti),
                        textcoords="offset points",
                        xytext=(4, 3),
                        fontsize=7,
                        color=COLOURS[method],
                    )
        groups = {}
        for a in s["auto"]:  # auto points that coincide are labelled once
            key = (a["chosen"], round(np.log10(max(a["max_error"], ERROR_FLOOR)), 1))
            groups.setdefault(key, []).append(a)
        for (chosen, _), members in groups.items():
            e = max(members[0]["max_error"], ERROR_FLOOR)
            t = min(m["time_s"] for m in members)
            for m in members:
                ax.plot(
                    max(m["max_error"], ERROR_FLOOR),
                    m["time_s"],
                    "*",
                    color="k",
                    ms=14,
                    mfc="gold",
                    zorder=4,
                )
            tols = ", ".join(f"{m['value']:.0e}" for m in members)
            ax.annotate(
                f"auto tol {tols}\n→ {chosen}",
                (e, t),
                textcoords="offset points",
                xytext=(9, -16),
                fontsize=7,
                zorder=5,
            )
        for tol in AUTO_TOLERANCES:
            ax.axvline(tol, color="k", ls=":", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(ERROR_FLOOR / 3, 0.3)
        ax.set_xlabel(f"max |G − G_ref| over the curve (drawn at {ERROR_FLOOR:g} when below)")
        ax.set_ylabel(f"wall time (s), best of {REPEATS}, all cores")
        r = s["ranges_m"]
        ax.set_title(
            f"{s['label']}\n{r['count']} ranges {r['start']:g}–{r['stop']:g} m; ref: "
            f"{s['reference']['kind']}",
            fontsize=9,
        )
        ax.grid(True, which="major", alpha=0.3)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    handles.append(plt.Line2D([], [], ls="none", marker="*", color="k", mfc="gold", ms=13))
    labels.append("auto (tolerance → choice); dotted lines: tolerances 1e-2, 1e-3, 1e-4")
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def timed_part(sections, name, run, plot):
    """run(), its wall time into sections[name + "_s"], its chart drawn to RESULTS / name.png."""
    t0 = time.perf_counter()
    out = run()
    sections[f"{name}_s"] = time.perf_counter() - t0
    plot(out, RESULTS / f"{name}.png")
    return out


def main():
    start = time.perf_counter()
    load_start = load_average()
    print(
        f"lidar_overlap {lo.__version__} | numpy {np.__version__} | {os.cpu_count()} cores | load "
        f"average {load_start:.2f} | commit {source_commit()}"
    )
    if load_start > 0.5:
        print(
            f"warning: 1-min load average {load_start:.2f}: other processes share the cores; times "
            "are upper bounds"
        )
    warnings.simplefilter(
        "ignore", RuntimeWarning
    )  # RT validity warnings: the errors are measured here
    warnings.simplefilter("ignore", lo.SamplingWarning)
    RESULTS.mkdir(exist_ok=True)

    scenes, sections = {}, {}
    for k, (name, spec) in enumerate(SCENES.items()):
        t0 = time.perf_counter()
        scenes[name] = run_scene(name, spec, with_direct=k == 0)
        print(
            f"\n{spec['label']} ({time.perf_counter() - t0:.0f} s; reference "
            f"{scenes[name]['reference']['kind']}"
            + (
                ", |N=1024 - N=512| = "
                f"{scenes[name]['reference']['max_difference_from_grid_512']:.1e}"
                if "max_difference_from_grid_512" in scenes[name]["reference"]
                else ""
            )
            + ")"
        )
        print(f"  {'method / setting':34} {'time':>10} {'max error':>10}")
        front = set(scenes[name]["pareto_front"])
        for p in scenes[name]["points"] + scenes[name]["auto"]:
            mark = " *Pareto" if label(p) in front else ""
            extra = f"  -> {p['chosen']}" if p["method"] == "auto" else ""
            print(f"  {label(p):34} {p['time_s'] * 1e3:8.2f}ms {p['max_error']:10.1e}{mark}{extra}")
    sections["speed_accuracy_s"] = time.perf_counter() - start
    plot_speed_accuracy(scenes, RESULTS / "speed_accuracy.png")

    rows = [row for s in scenes.values() for row in s["auto_vs_fastest"]]
    print(
        "\nauto against the fastest single method meeting the tolerance (requirement: <= "
        f"{AUTO_MAX_RATIO:g}x); '1 thread': the same ratio with threads=1 "
        f"(sub-{SINGLE_THREAD_CHECK_BELOW:g} s rows); 'x public': against the fastest setting "
        f"lo.overlap exposes (FO radial only at {RADIAL_DEFAULT:g} periods per panel)"
    )
    header = (
        f"{'scene':21} {'tol':>6} {'auto ->':16} {'auto':>9} {'auto err':>8} "
        f"{'fastest meeting tol':24} {'time':>9} {'ratio':>7} {'met':>4} {'1 thread':>8} "
        f"{'x public':>8}"
    )
    print(header)
    print("-" * len(header))
    for r in rows:
        print(
            f"{r['scene']:21} {r['tolerance']:6.0e} {r['auto_chosen']:16} "
            f"{r['auto_s'] * 1e3:7.2f}ms {r['auto_max_error']:8.1e} {str(r['fastest']):24} "
            f"{(r['fastest_s'] or float('nan')) * 1e3:7.2f}ms {r['ratio']:6.1f}x "
            f"{'yes' if r['requirement_met'] else 'NO':>4} {r['ratio_threads1']:7.1f}x "
            f"{r['ratio_to_fastest_public']:7.1f}x"
        )

    fm = timed_part(sections, "failure_map", failure_map, plot_failure_map)
    print(
        f"\nfailure map ({sections['failure_map_s']:.0f} s): RT error > {FAILURE_TOLERANCE:g} at "
        f"{CUT_RANGE:g} m for detector radii {fm['rt_cut']['failing_airy_radii']} Airy radii "
        f"(Table 1 detector: {fm['table1_detector_in_airy_radii']:.0f})"
    )
    for z in ("5", "29", "100", "300", "1000", "3000"):
        key = min(
            fm["rt"]["failing_airy_radii_at_range"], key=lambda k: abs(np.log(float(k) / float(z)))
        )
        print(
            f"  RT at {key:>5} m fails for detector radii "
            f"{fm['rt']['failing_airy_radii_at_range'][key]} Airy radii"
        )
    print(
        "  FO 2-D max error over the map: "
        + ", ".join(f"N={n}: {e:.1e}" for n, e in fm["fo_2d"]["max_error"].items())
    )
    print(
        f"  FO 2-D max error per grid at window {FO_2D_WINDOW:g}: "
        + ", ".join(
            f"N={n}: {e:.1e}" for n, e in fm["fo_2d_grid_sweep"]["max_error_per_grid"].items()
        )
    )
    print(
        f"  FO 2-D (N = {MAP_WINDOW_GRID}) ranges failing per window: "
        f"{fm['fo_2d_window_sweep']['failing_ranges_per_window']}"
    )

    sc = timed_part(sections, "scaling", scaling, plot_scaling)
    print(
        f"\nscaling ({sections['scaling_s']:.0f} s), Table 1, ranges "
        f"{SCALING_SPAN[0]:g}-{SCALING_SPAN[1]:g} m:"
    )
    print(f"  {'method':10} {'threads':>7} " + " ".join(f"{n:>9}" for n in SCALING_COUNTS))
    for method, d in sc["time_by_count_s"].items():
        for th, times in d.items():
            print(f"  {method:10} {th:>7} " + " ".join(f"{t * 1e3:7.1f}ms" for t in times))
    print(
        f"  FO 2-D by grid ({SCALING_GRID_RANGES.size} ranges): "
        + "; ".join(
            f"N={n}: {a * 1e3:.0f} / {b * 1e3:.0f} ms"
            for n, a, b in zip(SCALING_GRIDS, sc["time_by_grid_s"]["1"], sc["time_by_grid_s"]["2"])
        )
        + " (1 / 2 threads)"
    )

    total = time.perf_counter() - start
    load_end = load_average()
    meta = {
        "measured": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "versions": {
            "lidar_overlap": lo.__version__,
            "numpy": np.__version__,
            "matplotlib": matplotlib.__version__,
            "python": sys.version.split()[0],
        },
        "source_commit": source_commit(),
        "machine": platform.machine(),
        "cores": os.cpu_count(),
        "load_average_1min": load_start,
        "load_average_1min_end": load_end,
        "timing": f"best of {REPEATS} calls after one untimed call (_common.best_time); threads = "
        f"{THREADS} (all cores) unless stated; auto_vs_fastest: the two in alternating rounds "
        f"(best of {PAIRED_ROUNDS[0]} below {SINGLE_THREAD_CHECK_BELOW:g} s, else "
        f"{PAIRED_ROUNDS[1]})",
        "accuracy": "max over the ranges of |G - G_ref|; reference: FO radial at 1 period per "
        "panel (checked against FO 2-D at beam_grid 1024 over 12 w0 where not axisymmetric)",
        "run_time_s": total,
        "section_times_s": sections,
    }
    for s in scenes.values():
        for p in s["points"] + s["auto"]:
            p.pop("call", None)
    out = RESULTS / "speed_accuracy.json"
    out.write_text(
        json_text(
            {
                "meta": meta,
                "scenes": scenes,
                "auto_vs_fastest": rows,
                "failure_map": fm,
                "scaling": sc,
            },
            indent=1,
        )
    )
    print(
        f"\nwrote {out} and "
        f"{', '.join(p + '.png' for p in ('speed_accuracy', 'failure_map', 'scaling'))} in "
        f"{RESULTS} ({total:.0f} s; load average {load_start:.2f} at the start, {load_end:.2f} at "
        "the end)"
    )


if __name__ == "__main__":
    main()
