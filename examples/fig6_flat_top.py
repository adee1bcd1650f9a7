"""A flat-top beam from a Gerchberg-Saxton phase plate and its irradiance along the path (the
paper's Section 4C and Fig. 6).

A TEM00 laser at 355 nm with waist w0 = 1 mm passes a phase plate designed so that its far-field
irradiance is a uniform disc of full angular diameter Psi = 0.36 mrad (``lo.FlatTopBeam``). The
plate's field is propagated with ``lo.propagate(..., method="auto")`` (angular spectrum up to the
critical distance n dx^2 / lambda = 22.5 m, Fresnel beyond it) to three ranges. Near the plate the
beam is still the Gaussian, now carrying the plate's phase; beyond the Rayleigh range pi w0^2 /
lambda = 8.9 m its centre dips (by about 11 % at 15 m, a shallow ring); far away it is the disc of
diameter Psi z. The disc's edge cannot be sharper than the laser's own diffraction angle lambda /
(pi w0) = 0.11 mrad, comparable with Psi / 2, so the design's target is a disc with a soft
(Fermi-Dirac) edge: only about 68 % of the power lies inside Psi, and the plateau is narrow.

Panels: (a) the plate's phase, (b)-(e) irradiance at 0, 5, 15 and 1000 m (axes in mm, each
normalised
to its peak, dashed circle: diameter Psi z), (f) far-field radiant intensity through the centre
against the design target (angle in mrad), with the 1000 m cut rescaled to the same units (I z^2
against x / z).
Printed: the design summary and, at each range, the beam's diameters (half maximum, D4sigma) against
Psi z.

Units: SI in the code (m, rad, W); the plots show mm and mrad. Writes fig6_flat_top.png to the
current directory.
"""

import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lidar_overlap as lo  # noqa: E402

WAVELENGTH = 355e-9  # m
WAIST = 1e-3  # m, 1/e^2 radius at the plate
PSI = 0.36e-3  # rad, full angular diameter of the far-field disc
RANGES = (0.0, 5.0, 15.0, 1000.0)  # m: plate, spreading Gaussian, deepest central dip, far field
HALF_WIDTHS = (3e-3, 4e-3, 8e-3, 400e-3)  # m, half width of each displayed window


def radial_profile(field):
    """Azimuthal average of the irradiance about the grid centre: radii (m) and irradiance
    (W/m^2)."""
    x = field.x
    r = np.hypot(*np.meshgrid(x, x))
    bins = np.rint(r / field.spacing).astype(int).ravel()
    mean = np.bincount(bins, field.intensity.ravel()) / np.maximum(np.bincount(bins), 1)
    return np.arange(mean.size) * field.spacing, mean


def half_maximum_diameter(field):
    """Diameter (m) outside which the azimuthally averaged irradiance stays below half its
    maximum."""
    r, mean = radial_profile(field)
    k = np.flatnonzero(mean >= 0.5 * mean.max())[-1]
    return 2 * np.interp(0.5 * mean.max(), [mean[k + 1], mean[k]], [r[k + 1], r[k]])


def main():
    t0 = time.perf_counter()
    beam = lo.FlatTopBeam(WAVELENGTH, WAIST, PSI)
    design_time = time.perf_counter() - t0
    fields = [beam.field if z == 0 else lo.propagate(beam.field, z) for z in RANGES]

    fig, axes = plt.subplots(2, 3, figsize=(13.5, 8.4), layout="compressed")
    ax = axes[0, 0]
    x, inside = beam.field.x, np.abs(beam.field.x) <= HALF_WIDTHS[0]
    crop = np.ix_(inside, inside)
    lit = beam.field.intensity[crop] > 1e-3 * beam.field.intensity.max()
    ext = np.array([x[inside][0], x[inside][-1]] * 2) * 1e3
    im = ax.imshow(
        np.where(lit, beam.phase[crop], np.nan),
        extent=ext,
        origin="lower",
        cmap="twilight",
        vmin=-np.pi,
        vmax=np.pi,
    )
    fig.colorbar(im, ax=ax, label="phase (rad, wrapped; blank: I < 1e-3 peak)", shrink=0.85)
    ax.set(title="(a) plate phase at z = 0", xlabel="x (mm)", ylabel="y (mm)")

    for k, (ax, z, f, half) in enumerate(zip(axes.flat[1:5], RANGES, fields, HALF_WIDTHS)):
        inside = np.abs(f.x) <= half
        ext = np.array([f.x[inside][0], f.x[inside][-1]] * 2) * 1e3
        image = f.intensity[np.ix_(inside, inside)]
        im = ax.imshow(
            image / image.max(), extent=ext, origin="lower", cmap="viridis", vmin=0, vmax=1
        )
        if z > 0:
            ax.add_patch(
                plt.Circle((0, 0), 0.5 * PSI * z * 1e3, fill=False, color="w", ls="--", lw=1)
            )
            ax.text(
                0.03,
                0.03,
                r"dashed: diameter $\Psi z$",
                transform=ax.transAxes,
                color="w",
                fontsize=8,
            )
        ax.set(
            title=f"({'bcde'[k]}) z = {z:g} m, peak {f.intensity.max():.3g} W/m$^2$",
            xlabel="x (mm)",
            ylabel="y (mm)",
        )
    fig.colorbar(im, ax=axes[1, :2], label="irradiance / peak", shrink=0.85)

    ax = axes[1, 2]
    c = beam.far_field.shape[0] // 2
    theta = beam.angles * 1e3
    ax.plot(theta, 1e-6 * beam.target[c], "k--", lw=1.5, label="target (Fermi-Dirac edge)")
    ax.plot(theta, 1e-6 * beam.far_field[c], "C3-", lw=1.5, label="designed far field")
    far = fields[-1]
    ax.plot(
        far.x / RANGES[-1] * 1e3,
        1e-6 * far.intensity[far.n // 2] * RANGES[-1] ** 2,
        "C0:",
        lw=2,
        label=f"propagated to {RANGES[-1]:g} m, $I z^2$",
    )
    ax.axvline(-0.5 * PSI * 1e3, color="0.5", lw=0.7)
    ax.axvline(0.5 * PSI * 1e3, color="0.5", lw=0.7)
    ax.text(
        0.02,
        0.97,
        f"efficiency (power in $\\Psi$) {beam.efficiency:.3f}\nplateau uniformity: rms "
        f"{100 * beam.uniformity_rms:.1f} %, P-V {100 * beam.uniformity_pv:.1f} %\nedge 10-90 %: "
        f"{beam.edge_width * 1e3:.3f} mrad (target {beam.edge_width_target * 1e3:.3f})",
        transform=ax.transAxes,
        va="top",
        fontsize=8,
        bbox=dict(fc="w", ec="0.7"),
    )
    ax.set(
        xlim=(-0.5, 0.5),
        ylim=(0, 1.75e-6 * beam.far_field.max()),
        xlabel="angle (mrad)",
        ylabel="radiant intensity (MW/sr)",
        title=f"(f) far field, $\\Psi$ = {PSI * 1e3:.2f} mrad",
    )
    ax.legend(loc="upper left", bbox_to_anchor=(0.0, 0.8), fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.suptitle(
        f"Flat-top beam: TEM00 w0 = {WAIST * 1e3:g} mm at {WAVELENGTH * 1e9:g} nm through a "
        "Gerchberg-Saxton plate (power 1 W)"
    )
    fig.savefig("fig6_flat_top.png", dpi=130)

    print(repr(beam))
    print(
        f"design: {beam.iterations} iterations, stop '{beam.stop}', {design_time:.2f} s "
        f"({1e3 * design_time / beam.iterations:.1f} ms per iteration on a {beam.field.n}^2 grid), "
        f"final amplitude error {beam.history[-1]:.4f}"
    )
    print(
        f"efficiency {beam.efficiency:.3f}, plateau rms {100 * beam.uniformity_rms:.2f} %, P-V "
        f"{100 * beam.uniformity_pv:.2f} %, edge {beam.edge_width * 1e3:.3f} mrad (target "
        f"{beam.edge_width_target * 1e3:.3f} mrad, diffraction angle "
        f"{WAVELENGTH / (np.pi * WAIST) * 1e3:.3f} mrad)"
    )
    for z, f in zip(RANGES, fields):
        print(
            f"z = {z:6g} m: grid spacing {f.spacing * 1e3:.4f} mm, half-maximum diameter "
            f"{half_maximum_diameter(f) * 1e3:7.2f} mm, D4sigma {2 * f.beam_radius * 1e3:7.2f} mm, "
            f"Psi z = {PSI * z * 1e3:6.1f} mm"
        )
    print("wrote fig6_flat_top.png")


if __name__ == "__main__":
    main()
