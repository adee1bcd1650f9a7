"""Fit the 355 nm and 532 nm far-range channels of one PollyXT (Dushanbe, 2015-07-07,
examples/data/) jointly: both go through one telescope and one field stop and the beam leaves along
one path, so the beam's offset and tilt and the field stop's radius are shared, and only the
divergence (it depends on the wavelength) is each channel's own. Beside it, each channel fitted
alone with the same family (alignment + beam: offset, tilt, divergence, detector radius), as
examples/fit_real_overlap.py's ladder chooses for both. Relative data normalised over the far
interval, each with its retrieval's extinction bias; each channel's noise is its far-range scatter
(lidar_overlap.io.overlap_curves.far_range_noise, 700-2500 m as the data's source gives).

Prints one row per channel (RMS / noise, the shared parameters with their uncertainties, joint and
single), then a joint fit in which each channel also has its own tilt (the harmonics may leave the
laser along slightly different directions), and writes fit_joint_channels.png (both channels'
residuals: single, joint, joint with own tilts). SI units.
"""

import time
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import numpy as np
from matplotlib.figure import Figure

import lidar_overlap as lo
from lidar_overlap.io.overlap_curves import far_range_noise, read_overlap_curve
from lidar_overlap.model.instruments import pollyxt

DATA = Path(__file__).resolve().parent / "data"
CHANNELS = (("355 nm", "pollyxt_dushanbe_overlap_355.csv", 355e-9),
            ("532 nm", "pollyxt_dushanbe_overlap_532.csv", 532e-9))  # fmt: skip
FITTED, NOISE, INTERVAL = (100.0, 2500.0), (700.0, 2500.0), (1500.0, 2480.0)
SHARED = ["beam.offset[0]", "beam.tilt[0]", "detector.radius"]
OWN = ["beam.divergence"]
OPTIONS = dict(method="rt", normalize=INTERVAL, extinction_bias=True, search="global", seed=1,
               max_evaluations=300, allow_unconverged=True)  # fmt: skip

curves, noises, starts = [], [], []
for _, file, wavelength in CHANNELS:
    curve = read_overlap_curve(DATA / file)
    noises.append(far_range_noise(curve.ranges, curve.overlap, NOISE))
    curves.append(curve.within(*FITTED))
    starts.append(pollyxt("far", wavelength, numerical_aperture=0.22))
tolerance = 0.05 * min(noises)

with warnings.catch_warnings():
    # the degeneracies (tilt against offset and radius) are in the printed uncertainties
    warnings.simplefilter("ignore", lo.DegeneracyWarning)
    t0 = time.perf_counter()
    singles = [
        lo.fit(s, c.ranges, c.overlap, sigma=n, free=SHARED + OWN, tolerance=tolerance, **OPTIONS)
        for s, c, n in zip(starts, curves, noises)
    ]
    t_single = time.perf_counter() - t0
    t0 = time.perf_counter()
    joint = lo.fit_joint(
        starts, [c.ranges for c in curves], [c.overlap for c in curves], sigma=noises,
        shared=SHARED, per_curve=OWN, tolerance=tolerance, **OPTIONS,
    )  # fmt: skip
    t_joint = time.perf_counter() - t0
    # the harmonics may leave the laser along slightly different directions: each channel's own
    # tilt as well (a local fit from the joint solution)
    pointing = lo.fit_joint(
        [f.system for f in joint.curves], [c.ranges for c in curves], [c.overlap for c in curves],
        sigma=noises, shared=[p for p in SHARED if p != "beam.tilt[0]"],
        per_curve=["beam.tilt[0]"] + OWN, tolerance=tolerance, **{**OPTIONS, "search": "local"},
    )  # fmt: skip
print(joint)
print(pointing)


def rms(fit) -> float:
    return float(np.sqrt(np.mean((fit.fitted - fit.measured) ** 2)))


def shown(value, sd, path) -> str:
    factor, unit = (1e3, "mrad") if "tilt" in path else (1e3, "mm")
    return f"{factor * value:.4g} ± {factor * sd:.2g} {unit}"


print(f"\nfitted parameters: joint {len(joint.parameters)} (with per-channel tilts "
      f"{len(pointing.parameters)}), two single fits "
      f"{sum(len(s.parameters) for s in singles)} (each with its extinction bias besides); "
      f"time joint {t_joint:.0f} s, singles {t_single:.0f} s")  # fmt: skip
header = " | ".join(f"{p} joint | {p} single" for p in SHARED)
print(f"\n| channel | RMS/noise joint | RMS/noise single | {header} |")
print("|---" * (3 + 2 * len(SHARED)) + "|")
for (name, _, _), fit, single, noise in zip(CHANNELS, joint.curves, singles, noises):
    cells = " | ".join(
        f"{shown(joint.parameters[p], joint.uncertainties[p], p)} | "
        f"{shown(single.parameters[p], single.uncertainties[p], p)}"
        for p in SHARED
    )
    print(f"| {name} | {rms(fit) / noise:.3f} | {rms(single) / noise:.3f} | {cells} |")
ratios = [
    f"{name} {rms(f) / n:.3f}" for (name, _, _), f, n in zip(CHANNELS, pointing.curves, noises)
]
geometry = [
    f"{p} {shown(v, pointing.uncertainties[p], p)}"
    for p, v in pointing.parameters.items()
    if "divergence" not in p
]
print(f"\nwith per-channel tilts: RMS/noise {', '.join(ratios)}; {', '.join(geometry)}")

fig = Figure(figsize=(7.5, 5.5), constrained_layout=True)
axes = fig.subplots(2, 1, sharex=True)
for ax, (name, _, _), fit, own, single, noise in zip(
    axes, CHANNELS, joint.curves, pointing.curves, singles, noises
):
    z = fit.ranges
    ax.axhspan(-noise, noise, color="0.9", label="± noise")
    ax.plot(z, single.fitted - single.measured, ".", ms=3, color="C1", label="single fit")
    ax.plot(z, fit.fitted - fit.measured, ".", ms=3, color="C0", label="joint fit")
    ax.plot(z, own.fitted - own.measured, ".", ms=2, color="C2", label="joint, own tilts")
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.set_ylabel(f"{name}: model - data")
    ax.set_xscale("log")
axes[0].legend(fontsize=8, ncol=4)
axes[1].set_xlabel("range (m)")
fig.suptitle("PollyXT Dushanbe: two channels, shared geometry, per-channel divergence", fontsize=9)
fig.savefig("fit_joint_channels.png", dpi=120)
