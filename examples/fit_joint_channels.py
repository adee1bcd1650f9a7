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
of these. Each channel is also fitted alone in the family chosen, all its parameters its own,
started from the joint solution (a local fit): a global search from the preset, capped at 300
evaluations as here, ends in a worse valley under these weights (chi-square 4547 and 3740, against
260 and 274). Then, from the chosen fit's solution, the joint fit of the design first proposed
for these channels (offset, tilt and stop radius shared, each channel its own divergence).

Relative data normalised over the far interval, each with its retrieval's extinction bias. Each
channel's noise is range-resolved (lidar_overlap.io.noise_profile): the far-range scatter estimator
(1.4826 MAD of first differences / sqrt 2) in 4 windows over 700-2500 m (the interval the data's
source gives), and a power law sigma(r) = a (r / r_ref)^p fitted to them; the scatter grows with
range (the signal falls as r^-2 and with the extinction), p about 1.45 on both channels. Every fit
is weighted by sigma(r). Below 700 m sigma is held at sigma(700 m) (below="hold"), not extrapolated:
the power law continued gives 0.0002 at 100 m, 25 times less than the scatter the near range shows
(about 0.005 at 100-500 m), whose noise is not the far channel's shot noise alone.

The yardstick both ways: "profile", sqrt(mean((residual / sigma(r))^2)), and "single", the old
RMS / (the one far-range figure over 700-2500 m, far_range_noise), which over-weights the far range.
The "floor" is what no model that reaches full overlap by 700 m can beat, on the same yardstick:
100-700 m fitted exactly and 700-2500 m by its best straight line (the extinction bias is a slow
exponential: a straight line to first order; weighted by 1/sigma(r) for the profile's floor).

Prints each channel's profile, the joint choice, one table row per channel (the yardstick both ways,
joint and single, the floors, the shared parameters with uncertainties joint and single), the
parameter counts, and writes fit_joint_channels.png (both channels' residuals: single, joint, the
first design, in the band ± sigma(r)). SI units.
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
from lidar_overlap.io.noise_profile import noise_profile
from lidar_overlap.io.overlap_curves import read_overlap_curve
from lidar_overlap.model.instruments import pollyxt

DATA = Path(__file__).resolve().parent / "data"
CHANNELS = (("355 nm", "pollyxt_dushanbe_overlap_355.csv", 355e-9),
            ("532 nm", "pollyxt_dushanbe_overlap_532.csv", 532e-9))  # fmt: skip
FITTED, NOISE, INTERVAL = (100.0, 2500.0), (700.0, 2500.0), (1500.0, 2480.0)
WINDOWS = 4  # of about 60 points each over NOISE: each window's estimate scatters by about 17 %
BANDS = ((100.0, 700.0), (700.0, 1500.0), (1500.0, 2500.0))  # m: the yardstick by range
FULL_OVERLAP = 700.0  # m: the floor's model is flat (times the extinction trend) beyond it
PER_CHANNEL = ["beam.divergence", "beam.waist_radius", "beam.tilt[0]",
               "detector.numerical_aperture"]  # fmt: skip
DESIGN_SHARED = ["beam.offset[0]", "beam.tilt[0]", "detector.radius"]
BOUNDS = {"detector.defocus": (-0.01, 0.01)}  # m, as examples/fit_real_overlap.py's ladder
OPTIONS = dict(method="rt", normalize=INTERVAL, extinction_bias=True, seed=1, max_evaluations=300,
               allow_unconverged=True)  # fmt: skip

curves, profiles, noises, starts = [], [], [], []
for _, file, wavelength in CHANNELS:
    curve = read_overlap_curve(DATA / file)
    profiles.append(noise_profile(curve.ranges, curve.overlap, NOISE, windows=WINDOWS))
    curves.append(curve.within(*FITTED))
    noises.append(profiles[-1](curves[-1].ranges, below="hold"))
    starts.append(pollyxt("far", wavelength, numerical_aperture=0.22))
tolerance = 0.05 * min(float(n.min()) for n in noises)
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
    # each channel alone in the family chosen, from the joint solution (the docstring says why)
    singles = [
        lo.fit(fitted.system, c.ranges, c.overlap, sigma=n, free=list(paths),
               tolerance=tolerance, search="local", **OPTIONS)
        for fitted, c, n in zip(joint.curves, curves, noises)
    ]  # fmt: skip
    t_single = time.process_time() - t0
    # the first design, from the chosen fit's solution (a local fit)
    design = lo.fit_joint(
        [f.system for f in joint.curves], ranges, measured, sigma=noises, shared=DESIGN_SHARED,
        per_curve=["beam.divergence"], tolerance=tolerance, search="local", **OPTIONS,
    )  # fmt: skip
print(joint)


def yardstick(fit, sigma, keep=slice(None)) -> float:
    """sqrt(mean((residual / sigma)^2)) over the points ``keep``."""
    return float(np.sqrt(np.mean(((fit.fitted - fit.measured) / sigma)[keep] ** 2)))


def single_figure(fit, profile) -> float:
    """The old yardstick: RMS / the one far-range noise figure."""
    return float(np.sqrt(np.mean((fit.fitted - fit.measured) ** 2))) / profile.single


def floor(z, g, sigma) -> float:
    """The yardstick with the near range fitted exactly and the far range by its best line
    (weighted by 1 / sigma)."""
    far = z >= FULL_OVERLAP
    coefficients = np.polyfit(z[far], g[far], 1, w=1.0 / sigma[far])
    residual = (np.polyval(coefficients, z[far]) - g[far]) / sigma[far]
    return float(np.sqrt(np.sum(residual**2) / z.size))


def shown(value, sd, path) -> str:
    factor, unit = (1e3, "mrad") if "tilt" in path or "divergence" in path else (1e3, "mm")
    return f"{factor * value:.4g} ± {factor * sd:.2g} {unit}"


for (name, _, _), p in zip(CHANNELS, profiles):
    windows = ", ".join(
        f"{1e3 * s:.2f} at {r:.0f} m" for r, s in zip(p.window_ranges, p.window_sigmas)
    )
    print(
        f"\n{name} noise: sigma(r) = {1e3 * p.amplitude:.2f}e-3 (r / {p.reference_range:.0f} m)^"
        f"{p.exponent:.2f} from windows {windows} (1e-3); one far-range figure "
        f"{1e3 * p.single:.2f}e-3"
    )
k_single = sum(len(s.parameters) for s in singles)
print(
    f"\nchosen: family '{joint.family}', per channel {', '.join(joint.per_curve) or 'nothing'}; "
    f"fitted parameters: joint {len(joint.parameters)}, two single fits {k_single} (each "
    f"channel's extinction bias besides, in both); first design {len(design.parameters)}; "
    f"CPU time: joint choice {t_joint:.0f} s, two single fits {t_single:.0f} s"
)
header = " | ".join(f"{p} joint | {p} single" for p in joint.shared)
print(
    "\nyardstick: profile = sqrt(mean((residual / sigma(r))^2)); single = RMS / the one far-range "
    "figure (each fit weighted by sigma(r))"
)
print(
    "\n| channel | profile joint | profile single | profile floor | single-figure joint | "
    f"single-figure single | single-figure floor | {header} |"
)
print("|---" * (7 + 2 * len(joint.shared)) + "|")
rows = zip(CHANNELS, joint.curves, singles, noises, curves, profiles)
for (name, _, _), fit, single, noise, c, profile in rows:
    cells = " | ".join(
        f"{shown(joint.parameters[p], joint.uncertainties[p], p)} | "
        f"{shown(single.parameters[p], single.uncertainties[p], p)}"
        for p in joint.shared
    )
    flat = np.full(c.ranges.size, profile.single)
    print(
        f"| {name} | {yardstick(fit, noise):.3f} | {yardstick(single, noise):.3f} | "
        f"{floor(c.ranges, c.overlap, noise):.3f} | {single_figure(fit, profile):.3f} | "
        f"{single_figure(single, profile):.3f} | {floor(c.ranges, c.overlap, flat):.3f} | {cells} |"
    )
for (name, _, _), fit, noise, profile in zip(CHANNELS, joint.curves, noises, profiles):
    z = fit.ranges
    by_band = ", ".join(
        f"{low:.0f}-{high:.0f} m {yardstick(fit, noise, (z >= low) & (z < high)):.2f}"
        for low, high in BANDS
    )
    extrapolated = yardstick(fit, profile(z))
    print(
        f"{name} joint, profile yardstick by range: {by_band}; with sigma extrapolated below "
        f"700 m instead of held: {extrapolated:.2f}"
    )
ratios = [
    f"{name} {yardstick(f, n):.3f} (single figure {single_figure(f, p):.3f})"
    for (name, _, _), f, n, p in zip(CHANNELS, design.curves, noises, profiles)
]
geometry = [f"{p} {shown(design.parameters[p], design.uncertainties[p], p)}" for p in design.shared]
print(
    f"\nfirst design (per-channel divergence): yardstick {', '.join(ratios)}; {', '.join(geometry)}"
)

fig = Figure(figsize=(7.5, 5.5), constrained_layout=True)
axes = fig.subplots(2, 1, sharex=True)
for ax, (name, _, _), fit, first, single, noise in zip(
    axes, CHANNELS, joint.curves, design.curves, singles, noises
):
    z = fit.ranges
    ax.fill_between(z, -noise, noise, color="0.9", label="± sigma(r)")
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
