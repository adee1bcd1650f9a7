"""Overlap through a turbulent atmosphere: the Table 1 lidar and a long-range lidar, for weak,
moderate and strong turbulence (constant Cn^2 = 1e-15, 1e-14, 1e-13 m^-2/3 along a horizontal path).

RT on both paths (the default): the short-term beam displaced by the random beam wander and seen
through the return path's image tilt (correlated with the wander) and blur, 200 realisations per
range; FO on the beam's path alone (the beam carried through 10 phase screens, 12 realisations on
128^2 grids) against RT on the beam's path alone, for the moderate case of the Table 1 lidar.
Shaded: the 5-95 % band of the realisations. Where the wander pushes the beam off the field of view
the band widens. The RT wander
and spread are weak-fluctuation results: where the Rytov variance in the legend exceeds ~1 the bands
are indicative only. Writes turbulence_overlap.png. SI units.
"""

import time
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import lidar_overlap as lo

LEVELS = {"weak": 1e-15, "moderate": 1e-14, "strong": 1e-13}
long_range = lo.LidarSystem(
    beam=lo.GaussianBeam(1064e-9, 4e-3),
    telescope=lo.Telescope(0.3, 1.5),
    detector=lo.Detector.from_fov(0.3e-3, 1.5),
)
systems = {
    "Table 1 lidar (355 nm, FFOV 0.9 mrad)": (lo.paper_table1(), np.geomspace(20, 2000, 60)),
    "long-range lidar (1064 nm, D = 0.3 m, FFOV 0.3 mrad)": (
        long_range,
        np.geomspace(100, 10000, 60),
    ),
}

fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), constrained_layout=True)
for ax, (title, (system, z)) in zip(axes, systems.items()):
    calm = lo.overlap(system, z, "rt")
    ax.plot(z, calm.overlap, color="k", lw=1.2, label="no turbulence")
    for (name, cn2), color in zip(LEVELS.items(), ("tab:green", "tab:orange", "tab:red")):
        t = lo.Turbulence(cn2)
        t0 = time.perf_counter()
        with warnings.catch_warnings(record=True) as caught:  # RT's regime, said once below
            warnings.simplefilter("always", RuntimeWarning)
            res = lo.overlap(system, z, "rt", turbulence=t, realizations=200, seed=1)
        dt = time.perf_counter() - t0
        ax.plot(
            z,
            res.overlap,
            color=color,
            label=f"{name}: Cn² = {cn2:g}, σ_R²({z[-1]:g} m) = "
            f"{t.rytov_variance(system.beam.wavelength, z[-1]):.2g}",
        )
        ax.fill_between(z, res.low, res.high, color=color, alpha=0.2)
        w = np.sqrt(t.beam_wander_variance(system.beam.wavelength, system.beam.waist_radius, z[-1]))
        print(
            f"{title}, {name}: full overlap {res.full_overlap_range():.0f} m (calm "
            f"{calm.full_overlap_range():.0f} m), rms wander at {z[-1]:g} m {w * 1e3:.1f} mm, "
            f"widest band {np.max(res.high - res.low):.3f}, RT {dt:.1f} s"
        )
        for w in caught:  # the weak-fluctuation model's limits, in one line each
            reason = str(w.message).split("outside its regime: ", 1)[-1].split(". Fourier")[0]
            print(f"  outside RT's regime: {reason.split(';')[0]}")
    if system is systems["Table 1 lidar (355 nm, FFOV 0.9 mrad)"][0]:
        zf = np.geomspace(50, 2000, 12)
        t0 = time.perf_counter()
        fo = lo.overlap(
            system,
            zf,
            "fo",
            turbulence=lo.Turbulence(LEVELS["moderate"]),
            realizations=12,
            seed=1,
            beam_grid=128,
            paths="transmit",  # the beam's path alone, as the RT curve below
        )
        rt = lo.overlap(
            system,
            zf,
            "rt",
            turbulence=lo.Turbulence(LEVELS["moderate"]),
            realizations=200,
            seed=1,
            paths="transmit",
        )
        print(
            f"{title}, moderate, FO through phase screens: {time.perf_counter() - t0:.1f} s; mean "
            f"G at {zf[-1]:g} m {fo.overlap[-1]:.4f} ± {fo.error_estimate[-1]:.4f} (RT "
            f"{rt.overlap[-1]:.4f})"
        )
        ax.errorbar(
            zf,
            fo.overlap,
            yerr=fo.std,
            fmt="o",
            ms=3,
            color="tab:orange",
            label="moderate, FO (12 draws)",
        )
    ax.set_xscale("log")
    ax.set_xlabel("range z (m)")
    ax.set_ylabel("overlap G(z)")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
fig.savefig("turbulence_overlap.png", dpi=130)
print("wrote turbulence_overlap.png")
