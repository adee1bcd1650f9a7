"""The joint two-channel ladder against the single ladders, on the measured PollyXT pair at Dushanbe
(examples/data/: 355 nm and 532 nm far range, one telescope and field stop): in one run, the model
ladder of each channel alone (lo.fit(free="auto")) and the joint ladder of both
(lo.fit_joint(free="auto"): the family and the per-channel parameters chosen by BIC; once with any
path allowed per channel, once with only those physics allows, PER_CHANNEL, as
examples/fit_joint_channels.py), with the
settings of examples/fit_real_overlap.py (ray tracing, tolerance 5 % of the noise, normalised over
1500-2480 m, the retrieval's extinction bias, seed 1, at most 300 evaluations per local fit), each
channel weighted by its range-resolved noise sigma(r) as examples/fit_joint_channels.py weights it
(lidar_overlap.io.noise_profile: 4 windows over 700-2500 m, held at sigma(700 m) below) and the
model's tolerance 5 % of the smallest sigma(r).

Figures: CPU time of the process (all threads; steadier than wall time on a shared machine) and wall
time of each ladder, the model evaluations (search candidates and local fits; the single ladder's
summed over its families), each channel's yardstick sqrt(mean((residual / sigma(r))^2)) beside the
old RMS / (the one far-range noise figure), and the family chosen. Target: the joint
ladder's CPU time <= 2x one channel's (the mean of the two single ladders; each ratio is given).
The joint ladder tries three families (alignment; + beam; + focus), the first by the joint global
search, the next from the one before's solution; the single ladder six, each by its own search.
Writes results/bench_joint.json.
"""

from __future__ import annotations

import os
import time
import warnings
from pathlib import Path

import numpy as np
from _common import load_average, run_meta, write_result

import lidar_overlap as lo
from lidar_overlap.io.noise_profile import noise_profile
from lidar_overlap.io.overlap_curves import read_overlap_curve
from lidar_overlap.model.instruments import pollyxt

DATA = Path(__file__).resolve().parent.parent / "examples" / "data"
CHANNELS = (("355 nm", "pollyxt_dushanbe_overlap_355.csv", 355e-9),
            ("532 nm", "pollyxt_dushanbe_overlap_532.csv", 532e-9))  # fmt: skip
FITTED, NOISE, INTERVAL = (100.0, 2500.0), (700.0, 2500.0), (1500.0, 2480.0)  # m
BOUNDS = {"detector.numerical_aperture": (0.05, 0.5), "detector.defocus": (-0.01, 0.01)}
PER_CHANNEL = ["beam.divergence", "beam.waist_radius", "beam.tilt[0]",
               "detector.numerical_aperture"]  # fmt: skip
WINDOWS = 4  # as examples/fit_joint_channels.py
TARGET_RATIO = 2.0


def _yardsticks(fit, sigma, single: float) -> dict:
    """sqrt(mean((residual / sigma(r))^2)) and the old RMS / the one far-range figure."""
    residual = fit.fitted - fit.measured
    return {
        "profile": float(np.sqrt(np.mean((residual / sigma) ** 2))),
        "single": float(np.sqrt(np.mean(residual**2)) / single),
    }


def _timed(fn, *args, **kwargs):
    """(fn's result, wall time, CPU time of the process) in s."""
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn(*args, **kwargs)
    return out, time.perf_counter() - t0, time.process_time() - c0


def main():
    load = load_average()
    print(f"lidar_overlap {lo.__version__} | {os.cpu_count()} cores | load average {load:.2f}")
    curves, profiles, noises, starts = [], [], [], []
    for _, file, wavelength in CHANNELS:
        curve = read_overlap_curve(DATA / file)
        profiles.append(noise_profile(curve.ranges, curve.overlap, NOISE, windows=WINDOWS))
        curves.append(curve.within(*FITTED))
        noises.append(profiles[-1](curves[-1].ranges, below="hold"))
        starts.append(pollyxt("far", wavelength, numerical_aperture=0.22))
    options = dict(
        method="rt", tolerance=0.05 * min(float(n.min()) for n in noises), normalize=INTERVAL,
        extinction_bias=True, seed=1, max_evaluations=300, allow_unconverged=True, bounds=BOUNDS,
    )  # fmt: skip
    warnings.simplefilter("ignore")  # each fit's verdicts are in its figures below
    rows = {}
    for (name, _, _), start, curve, noise, profile in zip(
        CHANNELS, starts, curves, noises, profiles
    ):
        ladder, wall, cpu = _timed(
            lo.fit, start, curve.ranges, curve.overlap, sigma=noise, free="auto", **options
        )
        rows[f"single {name}"] = {
            "wall_s": wall,
            "cpu_s": cpu,
            "model_evaluations": sum(s.fit.evaluations for s in ladder.scores),
            "family": ladder.chosen_family.name,
            "yardsticks": [_yardsticks(ladder.chosen, noise, profile.single)],
        }
        print(f"single ladder {name}: {cpu:.1f} CPU s, {wall:.1f} s, {rows[f'single {name}']}")
    ranges, measured = [c.ranges for c in curves], [c.overlap for c in curves]
    for name, allowed in (("joint", ()), ("joint, physical per-channel", PER_CHANNEL)):
        joint, wall, cpu = _timed(
            lo.fit_joint, starts, ranges, measured, sigma=noises, free="auto",
            per_curve=allowed, **options,
        )  # fmt: skip
        print(joint)
        rows[name] = {
            "wall_s": wall,
            "cpu_s": cpu,
            "model_evaluations": joint.evaluations,
            "family": joint.family,
            "per_curve": list(joint.per_curve),
            "parameters": len(joint.parameters),
            "yardsticks": [
                _yardsticks(f, n, p.single) for f, n, p in zip(joint.curves, noises, profiles)
            ],
        }
    singles = [rows[f"single {name}"]["cpu_s"] for name, _, _ in CHANNELS]
    ratios = {}
    for joint_name in ("joint", "joint, physical per-channel"):
        cpu = rows[joint_name]["cpu_s"]
        key = joint_name.replace(", ", "_").replace(" ", "_").replace("-", "_")
        ratios[f"{key}_over_mean_single_cpu"] = cpu / float(np.mean(singles))
        for (name, _, _), s in zip(CHANNELS, singles):
            ratios[f"{key}_over_single_{name.split()[0]}_cpu"] = cpu / s
    worst = max(v for k, v in ratios.items() if k.endswith("_over_mean_single_cpu"))
    met = worst <= TARGET_RATIO
    for name, row in rows.items():
        print(f"{name}: {row}")
    print(
        f"joint / one channel (CPU, the larger of the two joint ladders): {worst:.2f} "
        f"(target {TARGET_RATIO:g}: {'met' if met else 'NOT met'}); "
        + ", ".join(f"{k} {v:.2f}" for k, v in ratios.items())
    )
    meta = {**run_meta(load), "fitted_m": FITTED, "noise_interval_m": NOISE,
            "normalize_m": INTERVAL, "tolerance": options["tolerance"],
            "noise_profiles": [{"amplitude": p.amplitude, "exponent": p.exponent,
                                "reference_range_m": p.reference_range, "single": p.single,
                                "windows": WINDOWS, "below": "hold"} for p in profiles],
            "target_ratio": TARGET_RATIO}  # fmt: skip
    write_result("bench_joint", {"meta": meta, "results": rows, "ratios": ratios, "met": met})


if __name__ == "__main__":
    main()
