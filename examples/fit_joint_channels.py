"""Fit the 355 nm and 532 nm far-range channels of one PollyXT (Dushanbe, 2015-07-07,
examples/data/) jointly, the family and the per-channel parameters chosen by BIC
(lo.fit_joint(free="auto")), beside each channel fitted alone with the family chosen.

What the channels share. Both go through one telescope and one field stop, and the beam leaves along
one path: the beam's offset from the telescope axis, the field stop's radius and its defocus are one
value for both (the telescope is a mirror, so the stop's focus does not depend on the wavelength;
a radius or defocus per channel would describe two stops). What each channel may have of its own,
PER_CHANNEL, the only paths the choice may split:
- the divergence and the waist: the harmonics leave the laser's crystals with their own beam
  quality and diameter, and an expander's far field scales with the wavelength;
- the tilt: the harmonics are generated in crystals with walk-off and pass separating optics, so
  they may leave along directions tens of µrad apart;
- the acceptance (detector.numerical_aperture): behind the common stop each channel has its own
  dichroic path, lens and detector, so each cuts the steepest rays differently.
The families the joint choice tries (alignment; + beam; + focus) hold the tilt and the divergence
of these. Then, from the chosen fit's solution, the joint fit of the design first proposed for these
channels (offset, tilt and stop radius shared, each channel its own divergence).

Relative data normalised over the far interval, each with its retrieval's extinction bias; each
channel's noise is its far-range scatter (lidar_overlap.io.overlap_curves.far_range_noise, 700-2500
m as the data's source gives). The "floor" column is what no model that reaches full overlap by
700 m can beat: the RMS / noise with 100-700 m fitted exactly and 700-2500 m by its best straight
line (the extinction bias is a slow exponential: a straight line to first order). The far range's
scatter grows with range (the signal falls), above the one noise figure measured over 700-2500 m.

Prints the joint choice, one table row per channel (RMS / noise joint and single, the floor, the
shared parameters with uncertainties joint and single), the parameter counts, and writes
fit_joint_channels.png (both channels' residuals: single, joint, the first design). SI units.
"""

import time
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import numpy as np
from matplotlib.figure import Figure

import lidar_overlap as lo
from lidar_overlap.analysis.fitting.families import LADDER
from lidar_overlap.io.overlap_curves import far_range_noise, read_overlap_curve
from lidar_overlap.model.instruments import pollyxt

DATA = Path(__file__).resolve().parent / "data"
CHANNELS = (("355 nm", "pollyxt_dushanbe_overlap_355.csv", 355e-9),
            ("532 nm", "pollyxt_dushanbe_overlap_532.csv", 532e-9))  # fmt: skip
FITTED, NOISE, INTERVAL = (100.0, 2500.0), (700.0, 2500.0), (1500.0, 2480.0)
FULL_OVERLAP = 700.0  # m: the floor's model is flat (times the extinction trend) beyond it
PER_CHANNEL = ["beam.divergence", "beam.waist_radius", "beam.tilt[0]",
               "detector.numerical_aperture"]  # fmt: skip
DESIGN_SHARED = ["beam.offset[0]", "beam.tilt[0]", "detector.radius"]
BOUNDS = {"detector.defocus": (-0.01, 0.01)}  # m, as examples/fit_real_overlap.py's ladder
OPTIONS = dict(method="rt", normalize=INTERVAL, extinction_bias=True, seed=1, max_evaluations=300,
               allow_unconverged=True)  # fmt: skip

curves, noises, starts = [], [], []
for _, file, wavelength in CHANNELS:
    curve = read_overlap_curve(DATA / file)
    noises.append(far_range_noise(curve.ranges, curve.overlap, NOISE))
    curves.append(curve.within(*FITTED))
    starts.append(pollyxt("far", wavelength, numerical_aperture=0.22))
tolerance = 0.05 * min(noises)
ranges, measured = [c.ranges for c in curves], [c.overlap for c in curves]

with warnings.catch_warnings():
    # the degeneracies (tilt against offset and radius) are in the printed uncertainties
    warnings.simplefilter("ignore", lo.DegeneracyWarning)
    warnings.simplefilter("ignore", lo.FitQualityWarning)  # RMS / noise is in the table
    t0 = time.process_time()
    joint = lo.fit_joint(
        starts, ranges, measured, sigma=noises, free="auto", per_curve=PER_CHANNEL,
        bounds=BOUNDS, tolerance=tolerance, **OPTIONS,
    )  # fmt: skip
    t_joint = time.process_time() - t0
    paths = next(f.paths for f in LADDER if f.name == joint.family)
    bounds = {p: v for p, v in BOUNDS.items() if p in paths} or None
    t0 = time.process_time()
    singles = [
        lo.fit(
            s,
            c.ranges,
            c.overlap,
            sigma=n,
            free=list(paths),
            tolerance=tolerance,
            search="global",
            **OPTIONS,
        )  # fmt: skip
        for s, c, n in zip(starts, curves, noises)
    ]
    t_single = time.process_time() - t0
    # the first design, from the chosen fit's solution (a local fit)
    design = lo.fit_joint(
        [f.system for f in joint.curves], ranges, measured, sigma=noises, shared=DESIGN_SHARED,
        per_curve=["beam.divergence"], tolerance=tolerance, search="local", **OPTIONS,
    )  # fmt: skip
print(joint)


def rms(fit) -> float:
    return float(np.sqrt(np.mean((fit.fitted - fit.measured) ** 2)))


def floor(z, g, noise) -> float:
    """RMS / noise with the near range fitted exactly and the far range by its best line."""
    far = z >= FULL_OVERLAP
    line = np.polyval(np.polyfit(z[far], g[far], 1), z[far])
    return float(np.sqrt(np.sum((line - g[far]) ** 2) / z.size) / noise)


def shown(value, sd, path) -> str:
    factor, unit = (1e3, "mrad") if "tilt" in path or "divergence" in path else (1e3, "mm")
    return f"{factor * value:.4g} ± {factor * sd:.2g} {unit}"


k_single = sum(len(s.parameters) for s in singles)
print(
    f"\nchosen: family '{joint.family}', per channel {', '.join(joint.per_curve) or 'nothing'}; "
    f"fitted parameters: joint {len(joint.parameters)}, two single fits {k_single} (each "
    f"channel's extinction bias besides, in both); first design {len(design.parameters)}; "
    f"CPU time: joint choice {t_joint:.0f} s, two single global fits {t_single:.0f} s"
)
header = " | ".join(f"{p} joint | {p} single" for p in joint.shared)
print(f"\n| channel | RMS/noise joint | RMS/noise single | floor | {header} |")
print("|---" * (4 + 2 * len(joint.shared)) + "|")
for (name, _, _), fit, single, noise, c in zip(CHANNELS, joint.curves, singles, noises, curves):
    cells = " | ".join(
        f"{shown(joint.parameters[p], joint.uncertainties[p], p)} | "
        f"{shown(single.parameters[p], single.uncertainties[p], p)}"
        for p in joint.shared
    )
    print(
        f"| {name} | {rms(fit) / noise:.3f} | {rms(single) / noise:.3f} | "
        f"{floor(c.ranges, c.overlap, noise):.3f} | {cells} |"
    )
ratios = [f"{name} {rms(f) / n:.3f}" for (name, _, _), f, n in zip(CHANNELS, design.curves, noises)]
geometry = [f"{p} {shown(design.parameters[p], design.uncertainties[p], p)}" for p in design.shared]
print(
    f"\nfirst design (per-channel divergence): RMS/noise {', '.join(ratios)}; {', '.join(geometry)}"
)

fig = Figure(figsize=(7.5, 5.5), constrained_layout=True)
axes = fig.subplots(2, 1, sharex=True)
for ax, (name, _, _), fit, first, single, noise in zip(
    axes, CHANNELS, joint.curves, design.curves, singles, noises
):
    z = fit.ranges
    ax.axhspan(-noise, noise, color="0.9", label="± noise")
    ax.plot(z, single.fitted - single.measured, ".", ms=3, color="C1", label="single fit")
    ax.plot(z, fit.fitted - fit.measured, ".", ms=3, color="C0", label="joint (BIC's choice)")
    ax.plot(z, first.fitted - first.measured, ".", ms=2, color="C2", label="joint, first design")
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.set_ylabel(f"{name}: model - data")
    ax.set_xscale("log")
axes[0].legend(fontsize=8, ncol=4)
axes[1].set_xlabel("range (m)")
fig.suptitle(
    f"PollyXT Dushanbe, two channels fitted jointly: '{joint.family}', per channel "
    f"{', '.join(joint.per_curve) or 'nothing'}",
    fontsize=9,
)
fig.savefig("fit_joint_channels.png", dpi=120)
