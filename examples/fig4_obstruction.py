"""Effect of the telescope's central obstruction on the overlap function (the paper's Fig. 4).

System: the paper's Table 1 mono-axial lidar (f = 1 m, D = 150 mm, full FOV 0.9 mrad, TEM00 beam at
355 nm with w0 = 1 mm, diffraction-limited divergence), with an opaque disc of radius r_obs = 0, 20
and 40 mm placed z_obs = 0.7 m in front of the aperture stop (Section 4A). Ranges 5-1000 m, log
grid.

Panel (a) sketches the four rays of one emitter (not to scale): two to the aperture edges (signal)
and two grazing the obstruction's edge (its shadow), each pair imaged to a circle on the detector
plane. Panel (b) shows G(z). Printed per case: first-signal range (G >= 1e-3), full-overlap range (G
>= 0.99 max G), max G, the far-range limit 1 - (r_obs/R)^2 and the thin-beam onset range.

Units: SI in the code (m, rad); the plot shows ranges in m and radii in mm.
Writes fig4_obstruction.png to the current directory.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lidar_overlap as lo  # noqa: E402

RANGES = np.geomspace(5.0, 1000.0, 300)  # m
OBSTRUCTION_RADII = (0.0, 20e-3, 40e-3)  # m
OBSTRUCTION_DISTANCE = 0.7  # m, in front of the aperture stop (Section 4A)
# Line styles of the paper's Fig. 4(b): solid, dashed, stars.
STYLES = (
    dict(color="C0", linestyle="-"),
    dict(color="C1", linestyle="--"),
    dict(color="C2", linestyle="none", marker="*", markersize=6, markevery=6),
)


def sketch_four_rays(ax):
    """Four-ray construction for one emitter (Section 4A), drawn in schematic units (not to scale).

    The optical axis runs horizontally: detector plane (DP) at x = -d, thin lens / aperture stop
    (AS) at x = 0, obstruction at x = z_obs, scattering plane at x = z. A ray from emitter P through
    aperture height A reaches the DP at A (1 + d/z - d/f) - P d/z (the ABCD chain B13-B16); it meets
    the obstruction plane at A + (P - A) z_obs / z."""
    f, d, z, z_obs = 1.0, 1.0, 2.6, 0.9  # schematic lengths
    radius, r_obs, p = 0.5, 0.16, 0.25  # aperture and obstruction radii, emitter height

    def at_detector(a):
        return a * (1.0 + d / z - d / f) - p * d / z

    def grazing(edge):  # aperture height of the ray from P through the obstruction's edge
        return (edge * z - p * z_obs) / (z - z_obs)

    ax.plot([z, z], [-0.75, 0.75], color="C3", lw=2)
    ax.text(z, 0.8, "scattering\nplane", ha="center", va="bottom", fontsize=8)
    ax.plot([0, 0], [-radius, radius], color="k", lw=2.5)
    ax.text(0, 0.8, "AS + lens", ha="center", va="bottom", fontsize=8)
    ax.plot([z_obs, z_obs], [-r_obs, r_obs], color="0.3", lw=5, solid_capstyle="butt")
    ax.text(z_obs, 0.8, "obstruction", ha="center", va="bottom", fontsize=8)
    ax.plot([-d, -d], [-0.45, 0.45], color="k", lw=1)
    ax.text(-d, 0.8, "detector\nplane", ha="center", va="bottom", fontsize=8)
    ax.axhline(0.0, color="0.6", lw=0.6, linestyle="-.")
    ax.plot(z, p, "o", color="C3")
    ax.annotate(
        "emitter", (z, p), (z - 0.95, p + 0.3), fontsize=8, arrowprops=dict(arrowstyle="-", lw=0.6)
    )

    signal = [at_detector(a) for a in (radius, -radius)]
    shadow_a = [grazing(e) for e in (r_obs, -r_obs)]
    shadow = [at_detector(a) for a in shadow_a]
    for a, h in zip((radius, -radius), signal):  # signal rays: to the aperture edges
        ax.plot([z, 0, -d], [p, a, h], color="C2", linestyle="--", lw=1.2)
    for a, h in zip(shadow_a, shadow):  # shadow rays: grazing the obstruction
        ax.plot([z, 0, -d], [p, a, h], color="0.45", linestyle="--", lw=1.0)
    ax.fill(
        [z, 0, -d, -d, 0],
        [p, shadow_a[0], shadow[0], shadow[1], shadow_a[1]],
        color="0.5",
        alpha=0.25,
        lw=0,
    )
    ax.plot([-d - 0.06] * 2, signal, color="C2", lw=4, solid_capstyle="butt")
    ax.plot([-d - 0.14] * 2, shadow, color="0.45", lw=4, solid_capstyle="butt")
    ax.text(
        -d - 0.2, signal[0], "circle of\nconfusion", ha="right", va="center", fontsize=8, color="C2"
    )
    ax.text(
        -d - 0.2,
        np.mean(shadow),
        "shadow\ncircle",
        ha="right",
        va="center",
        fontsize=8,
        color="0.35",
    )
    ax.set_xlim(-d - 0.9, z + 0.3)
    ax.set_ylim(-0.8, 1.05)
    ax.set_xlabel("optical axis (schematic, not to scale)")
    ax.set_yticks([])
    ax.set_xticks([])
    ax.set_title("(a) four rays of one emitter", fontsize=10)


def main():
    fig, (ax_a, ax_b) = plt.subplots(
        1, 2, figsize=(12.5, 4.6), gridspec_kw=dict(width_ratios=[1, 1.35]), constrained_layout=True
    )
    sketch_four_rays(ax_a)

    print(
        f"{'r_obs':>6} {'first signal':>13} {'full overlap':>13} {'max G':>8} "
        f"{'1-(r_obs/R)^2':>14} {'thin-beam onset':>16}"
    )
    for r_obs, style in zip(OBSTRUCTION_RADII, STYLES):
        system = lo.paper_table1(
            obstruction_radius=r_obs, obstruction_distance=OBSTRUCTION_DISTANCE
        )
        res = lo.overlap(system, RANGES, method="rt")
        radius = 0.5 * system.telescope.diameter
        alpha = system.detector.radius / system.telescope.focal_length  # half FOV (rad)
        far_limit = 1.0 - (r_obs / radius) ** 2
        # A scatterer on the axis at range z sends rays through |A| <= alpha z to the detector
        # (image radius R|1 + d/z - d/f| with d = f, Eq. B19 geometry) while the obstruction shadows
        # |A| < r_obs z / (z - z_obs); light first passes when alpha (z - z_obs) > r_obs.
        onset = r_obs / alpha + OBSTRUCTION_DISTANCE if r_obs > 0 else float("nan")
        first, full, peak = (
            res.first_signal_range(1e-3),
            res.full_overlap_range(0.99),
            res.overlap.max(),
        )
        print(
            f"{r_obs * 1e3:4.0f}mm {first:11.1f} m {full:11.1f} m {peak:8.4f} {far_limit:14.4f} "
            f"{onset:14.1f} m"
        )

        ax_b.plot(res.ranges, res.overlap, label=f"$r_{{obs}}$ = {r_obs * 1e3:.0f} mm", **style)
        if r_obs > 0:
            ax_b.axhline(far_limit, color=style["color"], lw=0.7, linestyle=":", alpha=0.9)
            ax_b.plot(
                onset,
                0.0,
                marker="^",
                color=style["color"],
                markersize=7,
                linestyle="none",
                clip_on=False,
            )
    ax_b.axhline(1.0, color="C0", lw=0.7, linestyle=":", alpha=0.9)
    ax_b.plot([], [], color="0.3", lw=0.7, linestyle=":", label=r"far limit $1-(r_{obs}/R)^2$")
    ax_b.plot(
        [],
        [],
        color="0.3",
        marker="^",
        linestyle="none",
        label=r"thin-beam onset $r_{obs}/\alpha + z_{obs}$",
    )
    ax_b.set_xscale("log")
    ax_b.set_xlim(RANGES[0], RANGES[-1])
    ax_b.set_ylim(-0.02, 1.05)
    ax_b.set_xlabel("range z (m)")
    ax_b.set_ylabel("overlap G(z)")
    ax_b.set_title(
        f"(b) central obstruction at $z_{{obs}}$ = {OBSTRUCTION_DISTANCE} m (Table 1, 355 nm, "
        "$w_0$ = 1 mm)",
        fontsize=10,
    )
    ax_b.grid(True, which="both", alpha=0.3)
    ax_b.legend(loc="upper left", fontsize=9)
    fig.savefig("fig4_obstruction.png", dpi=150)
    print("wrote fig4_obstruction.png")


if __name__ == "__main__":
    main()
