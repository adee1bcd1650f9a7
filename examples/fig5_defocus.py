"""Effect of moving the detector (fibre) behind the focal plane on the overlap function (the paper's
Fig. 5).

(a) The paper's Table 1 lidar (f = 1 m, D = 150 mm, full FOV 0.9 mrad, TEM00 beam at 355 nm, w0 = 1
    mm, diffraction-limited divergence) with the detector defocus delta_f = 0, 2, 5 and 8 mm, ranges
    5-1000 m. The vertical lines mark z_opt = f (f + delta_f) / delta_f, the paper's Eq. (5).
(b) HELIX, the helium resonance-fluorescence lidar of Section 4B: full FOV 61 urad, D = 762 mm,
    f = 1875 mm, w0 = 7.2 mm, delta_f = 0.22 mm and 0 mm, ranges 1-1000 km (the instrument studies
    the 300-800 km band, shaded). Wavelength and divergence are not given in the paper; the
    assumptions are stated in HELIX_* below and printed.

Units: SI in the code (m, rad); the plots show ranges in m (a) and km (b).
Writes fig5_defocus.png to the current directory.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lidar_overlap as lo  # noqa: E402

STYLES = ("-", "--", ":", "-.")  # the paper's Fig. 5 line styles, in order

# (a) Table 1 system.
TABLE1_RANGES = np.geomspace(5.0, 1000.0, 300)  # m
TABLE1_DEFOCI = (0.0, 2e-3, 5e-3, 8e-3)  # m

# (b) HELIX (Section 4B).
HELIX_RANGES = np.geomspace(1e3, 1e6, 300)  # m
HELIX_FOV = 61e-6  # rad, full angle
HELIX_DIAMETER = 0.762  # m
HELIX_FOCAL_LENGTH = 1.875  # m
HELIX_WAIST = 7.2e-3  # m
HELIX_DEFOCI = (0.22e-3, 0.0)  # m
HELIX_FIRST_FOCUS = 18.5e3  # m, the layer the telescope is first focused on
# Assumed: the metastable-helium line (2^3S - 2^3P) at 1083 nm. In ray tracing the wavelength only
# enters through a diffraction-limited divergence, which is shown for comparison.
HELIX_WAVELENGTH = 1083e-9  # m
# Assumed divergence. A diffraction-limited 7.2 mm waist at 1083 nm spreads with lambda/(pi w0) = 48
# urad (1/e^2 half-angle), wider than the 30.5 urad half FOV, so the far-range overlap could never
# exceed 1 - exp(-2 (30.5/48)^2) = 0.56: the transmitted beam must be expanded. We take a common
# design choice of a beam half as wide as the field of view (full 1/e^2 beam angle = FFOV/2, theta =
# 15.25 urad); a beam this narrow needs a waist >= lambda/(pi theta) = 23 mm, i.e. the 7.2 mm beam
# expanded about 3x. w0 itself hardly matters here: theta z exceeds it beyond 0.5 km. Beyond a few
# km G depends on theta only.
HELIX_DIVERGENCE = HELIX_FOV / 4.0  # rad, 1/e^2 half-angle


def panel_table1(ax):
    print("(a) Table 1 system, 355 nm, w0 = 1 mm")
    print(
        f"{'defocus':>8} {'z_opt (Eq. 5)':>14} {'full overlap':>13} {'max G at':>10} "
        f"{'G(1000 m)':>10}"
    )
    for defocus, style in zip(TABLE1_DEFOCI, STYLES):
        system = lo.paper_table1(defocus=defocus)
        res = lo.overlap(system, TABLE1_RANGES)
        z_opt = lo.optimal_focus_range(system.telescope.focal_length, defocus)
        (line,) = ax.plot(
            res.ranges, res.overlap, linestyle=style, label=rf"$\delta_f$ = {defocus * 1e3:g} mm"
        )
        if np.isfinite(z_opt):
            ax.axvline(z_opt, color=line.get_color(), lw=0.8, linestyle=(0, (2, 2)), alpha=0.8)
        z_peak = res.ranges[np.argmax(res.overlap)]
        print(
            f"{defocus * 1e3:6.0f}mm {z_opt:12.1f} m {res.full_overlap_range(0.99):11.1f} m "
            f"{z_peak:8.1f} m {res.overlap[-1]:10.4f}"
        )
    ax.plot([], [], color="0.3", lw=0.8, linestyle=(0, (2, 2)), label=r"$z_{opt}$, Eq. (5)")
    ax.set_xscale("log")
    ax.set_xlim(TABLE1_RANGES[0], TABLE1_RANGES[-1])
    ax.set_ylim(-0.02, 1.05)
    ax.set_xlabel("range z (m)")
    ax.set_ylabel("overlap G(z)")
    ax.set_title("(a) Table 1 lidar: detector defocus", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)


def helix_system(defocus, divergence):
    # The expanded beam: a Gaussian beam cannot spread less than lambda / (pi w0) (M^2 >= 1), so a
    # divergence below that of the 7.2 mm waist takes the smallest waist that allows it.
    waist = (
        HELIX_WAIST
        if divergence is None
        else max(HELIX_WAIST, HELIX_WAVELENGTH / (np.pi * divergence))
    )
    return lo.LidarSystem(
        beam=lo.GaussianBeam(
            wavelength=HELIX_WAVELENGTH, waist_radius=waist, divergence=divergence
        ),
        telescope=lo.Telescope(diameter=HELIX_DIAMETER, focal_length=HELIX_FOCAL_LENGTH),
        detector=lo.Detector.from_fov(
            fov=HELIX_FOV, focal_length=HELIX_FOCAL_LENGTH, defocus=defocus
        ),
    )


def panel_helix(ax):
    f, half_fov = HELIX_FOCAL_LENGTH, 0.5 * HELIX_FOV
    theta_dl = HELIX_WAVELENGTH / (np.pi * HELIX_WAIST)
    print("\n(b) HELIX: FFOV 61 urad, D = 762 mm, f = 1875 mm, w0 = 7.2 mm")
    print(f"    assumed wavelength {HELIX_WAVELENGTH * 1e9:.0f} nm (metastable helium line)")
    print(
        f"    diffraction-limited divergence of w0 = 7.2 mm: {theta_dl * 1e6:.1f} urad half-angle "
        f"> half FOV {half_fov * 1e6:.2f} urad -> far-range G <= 1 - exp(-2 (half FOV/theta)^2) = "
        f"{1 - np.exp(-2 * (half_fov / theta_dl) ** 2):.3f}"
    )
    print(
        f"    assumed divergence: full beam angle = FFOV/2, theta = {HELIX_DIVERGENCE * 1e6:.2f} "
        "urad half-angle (needs a waist >= "
        f"{HELIX_WAVELENGTH / (np.pi * HELIX_DIVERGENCE) * 1e3:.1f} mm: the beam is expanded)"
    )
    # Eq. (5) puts the focus of delta_f = 0.22 mm at 16.0 km, not at the 18.5 km layer the paper
    # names for the first focusing step; 18.5 km needs 0.190 mm. Either 0.22 mm is the fibre
    # position after the paper's second step (a fixed offset from that focus) or the two numbers are
    # rounded; we plot 0.22 mm.
    z_opt = lo.optimal_focus_range(f, HELIX_DEFOCI[0])
    defocus_first = f * f / (HELIX_FIRST_FOCUS - f)  # Eq. (5) solved for delta_f
    print(
        f"    Eq. (5): delta_f = {HELIX_DEFOCI[0] * 1e3:.2f} mm focuses at z_opt = "
        f"{z_opt / 1e3:.2f} km; focus at {HELIX_FIRST_FOCUS / 1e3:.1f} km needs delta_f = "
        f"{defocus_first * 1e3:.3f} mm"
    )
    # Far away (z >> z_opt) the defocused detector sees every point as a disc of radius R delta_f /
    # f (B18 with d/z -> 0); only scatterers within (r_d - R delta_f / f) / d of the axis couple
    # fully, and a Gaussian beam keeps 99 % of its power inside that cone if theta <= cone /
    # sqrt(ln(100) / 2).
    blur = 0.5 * HELIX_DIAMETER * HELIX_DEFOCI[0] / f
    cone = (half_fov * f - blur) / (f + HELIX_DEFOCI[0])
    print(
        f"    at z -> inf, delta_f = 0.22 mm blurs a point to a {blur * 1e6:.1f} um radius disc on "
        f"the {half_fov * f * 1e6:.1f} um detector: full coupling only within {cone * 1e6:.2f} "
        "urad of the axis, so G >= 0.99 there needs theta <= "
        f"{cone / np.sqrt(np.log(100) / 2) * 1e6:.1f} urad"
    )
    print(
        f"{'defocus':>9} {'theta':>9} {'full overlap':>13} {'max G':>8} {'G(300 km)':>10} "
        f"{'G(500 km)':>10} {'G(800 km)':>10} {'far limit':>10}"
    )
    curves = [(d, HELIX_DIVERGENCE, style, None) for d, style in zip(HELIX_DEFOCI, STYLES)]
    curves.append((0.0, None, "-", "0.55"))  # diffraction-limited beam, for comparison
    for defocus, divergence, style, color in curves:
        system = helix_system(defocus, divergence)
        theta = system.beam.half_angle_divergence
        res = lo.overlap(system, HELIX_RANGES)
        g = np.interp([300e3, 500e3, 800e3], res.ranges, res.overlap)
        # Far-range closed form, detector in focus: fraction of the Gaussian inside the half FOV.
        far = f"{1 - np.exp(-2 * (half_fov / theta) ** 2):10.4f}" if defocus == 0 else f"{'-':>10}"
        print(
            f"{defocus * 1e3:7.2f}mm {theta * 1e6:5.2f}urad "
            f"{res.full_overlap_range(0.99) / 1e3:10.1f} km {res.overlap.max():8.4f} {g[0]:10.4f} "
            f"{g[1]:10.4f} {g[2]:10.4f} {far}"
        )
        label = rf"$\delta_f$ = {defocus * 1e3:.2f} mm, $\theta$ = {theta * 1e6:.4g} µrad"
        if color is not None:
            label += " (diffr.-limited)"
        ax.plot(
            res.ranges / 1e3,
            res.overlap,
            linestyle=style,
            color=color,
            lw=1.0 if color else 1.6,
            label=label,
        )
    ax.axvspan(300, 800, color="0.85", alpha=0.6, lw=0, label="300-800 km band")
    ax.axvline(
        z_opt / 1e3,
        color="C0",
        lw=0.8,
        linestyle=(0, (2, 2)),
        label=rf"$z_{{opt}}$ = {z_opt / 1e3:.1f} km, Eq. (5)",
    )
    ax.axvline(
        HELIX_FIRST_FOCUS / 1e3,
        color="k",
        lw=0.8,
        linestyle=(0, (1, 2)),
        label=f"{HELIX_FIRST_FOCUS / 1e3:.1f} km (first focus)",
    )
    ax.set_xscale("log")
    ax.set_xlim(HELIX_RANGES[0] / 1e3, HELIX_RANGES[-1] / 1e3)
    ax.set_ylim(-0.02, 1.05)
    ax.set_xlabel("range z (km)")
    ax.set_ylabel("overlap G(z)")
    ax.set_title(
        r"(b) HELIX: detector defocus (assumed $\lambda$ = 1083 nm, $\theta$ = FFOV/4)", fontsize=10
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)


def main():
    fig, (ax_a, ax_b) = plt.subplots(1, 2, figsize=(12.5, 4.6), constrained_layout=True)
    panel_table1(ax_a)
    panel_helix(ax_b)
    fig.savefig("fig5_defocus.png", dpi=150)
    print("wrote fig5_defocus.png")


if __name__ == "__main__":
    main()
