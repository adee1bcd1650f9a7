"""Overlap of the paper's Table 1 lidar with spherical aberration and astigmatism in the receiver.

The telescope (f = 1 m, D = 150 mm, full FOV 0.9 mrad at 355 nm) gets 0.5 um RMS of primary
spherical aberration (Zernike Z11), 0.5 um RMS of astigmatism (Z6), or both (about 1.4 waves RMS
each). Their blur on the detector plane (~0.1-0.3 mm) is a large part of the 0.45 mm detector radius
and ~100 Airy radii, so ray tracing (rays displaced by d grad W) and Fourier optics (the aberrated
pupil's OTF) should agree to RT's diffraction floor of a few 1e-3, and both show how much later the
lidar reaches full overlap.

(a) G(z): RT lines over 5-3000 m, FO markers from 150 m (nearer, the defocus blur needs transforms
    beyond the default cap: the geometric regime, where RT is exact).
(b) The point images at 1000 m (log irradiance), with the detector's edge.

Units: SI in the code; plots in m and mm. Writes aberrations_overlap.png to the current directory.
"""

import dataclasses

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lidar_overlap as lo  # noqa: E402

RT_RANGES = np.geomspace(5.0, 3000.0, 200)  # m
FO_RANGES = np.geomspace(150.0, 3000.0, 8)  # m
IMAGE_RANGE = 1000.0  # m
STYLES = {"ideal": "-", "spherical 0.5 um RMS": "--", "astigmatism 0.5 um RMS": ":", "both": "-."}
CASES = {
    "ideal": lo.Aberrations(),
    "spherical 0.5 um RMS": lo.Aberrations(zernike={11: 0.5e-6}),
    "astigmatism 0.5 um RMS": lo.Aberrations(zernike={6: 0.5e-6}),
    "both": lo.Aberrations(zernike={6: 0.5e-6, 11: 0.5e-6}),
}


def system_with(aberrations):
    base = lo.paper_table1()
    return dataclasses.replace(
        base, telescope=dataclasses.replace(base.telescope, aberrations=aberrations)
    )


def main():
    fig, (ax, *image_axes) = plt.subplots(
        1, 3, figsize=(15, 4.6), gridspec_kw={"width_ratios": [1.6, 1, 1]}
    )
    print(f"{'receiver':>24} {'full overlap (RT)':>18} {'G_RT(3 km)':>11} {'max |RT - FO|':>14}")
    for name, aberrations in CASES.items():
        system = system_with(aberrations)
        rt = lo.overlap(system, RT_RANGES, "rt")
        fo = lo.overlap(system, FO_RANGES, "fo")
        (line,) = ax.plot(rt.ranges, rt.overlap, linestyle=STYLES[name], label=f"{name} (RT)")
        ax.plot(fo.ranges, fo.overlap, "o", color=line.get_color(), mfc="none", ms=5)
        difference = np.max(np.abs(np.interp(FO_RANGES, rt.ranges, rt.overlap) - fo.overlap))
        print(
            f"{name:>24} {rt.full_overlap_range():>16.0f} m {rt.overlap[-1]:>11.4f} "
            f"{difference:>14.2e}"
        )
    ax.set_xscale("log")
    ax.set_xlabel("range z (m)")
    ax.set_ylabel("overlap G(z)")
    ax.set_title(
        "(a) Table 1 lidar with receiver aberrations\nlines: ray tracing, circles: Fourier optics"
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)

    r_d = lo.paper_table1().detector.radius
    for axis, name in zip(image_axes, ("spherical 0.5 um RMS", "astigmatism 0.5 um RMS")):
        image = lo.point_image(system_with(CASES[name]), IMAGE_RANGE, n=512, spacing=2e-6)
        extent = np.array([image.x[0], image.x[-1], image.y[0], image.y[-1]]) * 1e3
        irradiance = image.intensity / image.intensity.max()
        axis.imshow(
            np.log10(np.maximum(irradiance, 1e-5)), extent=extent, origin="lower", cmap="magma"
        )
        axis.add_patch(
            plt.Circle((0, 0), r_d * 1e3, fill=False, color="c", lw=1.2, label="detector")
        )
        axis.set_xlabel("x (mm)")
        axis.set_ylabel("y (mm)")
        axis.set_title(
            f"(b) point image at {IMAGE_RANGE:.0f} m, {name}\nlog10 irradiance (peak = 0)",
            fontsize=9,
        )
    fig.tight_layout()
    fig.savefig("aberrations_overlap.png", dpi=130)
    print("wrote aberrations_overlap.png")


if __name__ == "__main__":
    main()
