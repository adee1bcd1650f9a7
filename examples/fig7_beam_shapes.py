"""Overlap of the Table 1 lidar for a flat-top beam and for Gaussian beams of growing divergence
(the paper's Fig. 7, Section 4C).

System: f = 1 m, D = 150 mm, full FOV 0.9 mrad (``lo.paper_table1()``), 355 nm, ranges 5-1000 m (200
on a linear grid, as the paper plots). Beams, all from a w0 = 1 mm waist at z = 0:

  - flat top: the Gerchberg-Saxton phase plate of ``examples/fig6_flat_top.py`` (far-field disc of
    full angle Psi = 0.36 mrad at half plateau, soft edge), Fourier optics only (FO);
  - Gaussian 0.23 mrad full angle: the diffraction-limited TEM00 (half angle lambda / (pi w0)), ray
    tracing (RT) and FO;
  - Gaussians 0.45 and 0.60 mrad full angle (``divergence`` is the 1/e^2 half angle: 0.225 and 0.30
    mrad), RT.

Lower panel: eps_G = 100 abs(1 - G_RT / G_FO) (Eq. 6) of the TEM00 beam, in percent, where G > 0.05.

Up to about R / alpha = 167 m (R = D / 2, alpha = half FOV) every curve follows the thin-beam limit
(alpha z / R)^2: the detector sees only the central part of the aperture's defocus blur, whatever
the beam. Full overlap then comes when the beam's outer power fits inside the cone alpha z - R, so
it is set by the beam's tail rather than by its nominal width: the flat top's soft edge puts as much
power beyond 0.3 mrad as the 0.45 mrad Gaussian (3 %), and more beyond the 0.45 mrad half FOV.
Printed per curve: full-overlap range (G >= 0.99 max G, on the 5 m grid), first-signal range (G >=
1e-3), G at 1000 m and compute time.

Units: SI in the code (m, rad); the plot shows ranges in m. Writes fig7_beam_shapes.png to the
current directory.
"""

import dataclasses
import time

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lidar_overlap as lo  # noqa: E402

RANGES = np.linspace(5.0, 1000.0, 200)  # m
WAVELENGTH = 355e-9  # m
WAIST = 1e-3  # m
PSI = 0.36e-3  # rad, flat-top full angular diameter
RT_TOLERANCE = 1e-8  # absolute, so that eps_G shows the models' difference only


def main():
    t0 = time.perf_counter()
    flat = lo.FlatTopBeam(WAVELENGTH, WAIST, PSI)
    design_time = time.perf_counter() - t0
    tem00 = lo.paper_table1()
    # (label, system, method, plot style)
    cases = [
        (
            f"flat top {PSI * 1e3:.2f} mrad, FO",
            dataclasses.replace(tem00, beam=flat),
            "fo",
            dict(color="k", lw=2.2),
        ),
        ("Gaussian 0.23 mrad, RT", tem00, "rt", dict(color="C1", lw=2)),
        (
            "Gaussian 0.23 mrad, FO",
            tem00,
            "fo",
            dict(color="C2", ls="none", marker="*", ms=7, markevery=5),
        ),
        (
            "Gaussian 0.45 mrad, RT",
            lo.paper_table1(divergence=0.225e-3),
            "rt",
            dict(color="C0", ls="--", lw=2),
        ),
        (
            "Gaussian 0.60 mrad, RT",
            lo.paper_table1(divergence=0.30e-3),
            "rt",
            dict(color="C3", ls="-.", lw=2),
        ),
    ]

    fig, (a1, a2) = plt.subplots(
        2, 1, figsize=(8, 7.5), sharex=True, height_ratios=[2.2, 1], constrained_layout=True
    )
    print(f"flat-top plate design: {design_time:.2f} s ({flat.iterations} iterations, {flat.stop})")
    print(f"{'beam':<26} {'full overlap':>12} {'first signal':>12} {'G(1000 m)':>10} {'time':>8}")
    results = {}
    for label, system, method, style in cases:
        t0 = time.perf_counter()
        res = lo.overlap(
            system, RANGES, method=method, **({"tolerance": RT_TOLERANCE} if method == "rt" else {})
        )
        elapsed = time.perf_counter() - t0
        results[label] = res
        # a beam whose G still rises at 1 km (the paper's range) has its full overlap beyond it
        full = res.full_overlap_range() if res.reaches_far_range() else float("nan")
        shown = f"{full:10.0f} m" if np.isfinite(full) else "    > 1 km  "
        print(
            f"{label:<26} {shown} {res.first_signal_range():10.0f} m "
            f"{res.overlap[-1]:10.5f} {elapsed:7.2f} s"
        )
        a1.plot(RANGES, res.overlap, label=label, **style)
        if np.isfinite(full):
            a1.plot(
                full, np.interp(full, RANGES, res.overlap), "|", color=style["color"], ms=14, mew=2
            )

    telescope, detector = tem00.telescope, tem00.detector
    radius, alpha = 0.5 * telescope.diameter, detector.radius / telescope.focal_length
    thin = RANGES <= radius / alpha
    a1.plot(
        RANGES[thin],
        (alpha * RANGES[thin] / radius) ** 2,
        ":",
        color="0.5",
        lw=1.5,
        label=r"thin-beam limit $(\alpha z / R)^2$",
    )
    a1.plot([], [], "|", color="0.3", ms=10, mew=2, label="full overlap (0.99 max G)")
    a1.set(
        ylabel="overlap G(z)",
        ylim=(-0.02, 1.05),
        title="Table 1 lidar (f = 1 m, D = 150 mm, FFOV 0.9 mrad)\nbeams from w0 = 1 mm at 355 nm",
    )
    a1.legend(loc="lower right", fontsize=9)
    a1.grid(True, alpha=0.3)

    rt, fo = results["Gaussian 0.23 mrad, RT"].overlap, results["Gaussian 0.23 mrad, FO"].overlap
    valid = rt > 0.05
    eps = np.where(valid, 100 * np.abs(1.0 - rt / fo), np.nan)
    a2.semilogy(
        RANGES, eps, "k--", label=r"$\varepsilon_G = 100\,|1 - G_{RT}/G_{FO}|$, Gaussian 0.23 mrad"
    )
    a2.axvspan(RANGES[0], RANGES[np.argmax(valid)], color="0.9", label="G < 0.05 (not shown)")
    a2.axhline(0.5, color="C3", lw=1, label="target 0.5 % where G > 0.05")
    a2.set(
        xlabel="range z (m)",
        ylabel=r"$\varepsilon_G$ (%)",
        xlim=(0, RANGES[-1]),
        ylim=(0.01, 1),
        yticks=[0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1],
    )
    a2.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    a2.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    a2.legend(loc="lower right", fontsize=9)
    a2.grid(True, which="both", alpha=0.3)
    fig.savefig("fig7_beam_shapes.png", dpi=130)

    worst = np.nanargmax(eps)
    print(
        f"eps_G where G > 0.05: max {eps[worst]:.3f} % at {RANGES[worst]:.0f} m, "
        f"{np.nanmean(eps):.3f} % on average"
    )
    print(f"thin-beam limit: G = (alpha z / R)^2 up to R / alpha = {radius / alpha:.1f} m")
    print("wrote fig7_beam_shapes.png")


if __name__ == "__main__":
    main()
