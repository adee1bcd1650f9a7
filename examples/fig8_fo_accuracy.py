"""Accuracy of the Fourier-optics propagation against the Gaussian-beam closed form (the paper's
Fig. 8).

A TEM00 beam with waist w0 = 5 mm (flat phase at z = 0) is propagated at 355 nm and 1064 nm to 200
ranges from 1 mm to 100 km (log grid) with ``lo.propagate(field, z, method="auto")``, always from
the same input grid, and its second-moment radius (D4sigma/2, the 1/e^2 radius of a TEM00 beam) is
compared with Eq. (D1) by the relative error eps_w of Eq. (D2), in percent.

Grid: n = 512 samples of spacing 10 w0 / n = 97.7 um, i.e. a window of +-5 w0 (the input Gaussian is
down to exp(-50) of its peak irradiance at the edge) with 51 samples per w0. ``auto`` uses the
angular spectrum, Eq. (A1), up to the critical distance n dx^2 / lambda (13.8 m at 355 nm, 4.6 m at
1064 nm) and the single-FFT Fresnel integral, Eq. (A5), beyond it; the Fresnel output spacing lambda
z / (n dx) grows with z, so the beam always holds L / (pi w0) = 3.2 output samples per radius in the
far field, enough for its second moment. The method auto used is read from the output spacing (the
angular spectrum keeps the input grid) and checked against the critical distance.

``auto`` never switches to Fraunhofer: beyond the critical distance the single-FFT Fresnel integral
costs the same and does not drop the input chirp. For comparison, ``method="fraunhofer"`` (Eq. (A7))
is run at every range too, as the paper's blue dotted line: it is only right where the phase pi a^2
/ (lambda z) it neglects (Eq. (A6), a = radius holding all but 1e-6 of the power) is small. The
library warns (``lo.SamplingWarning``) where that phase exceeds 0.1 rad; the warnings are caught and
counted, and the bars at the top of the lower panel mark the ranges where they fire.

Printed per wavelength: the worst eps_w of auto in each method's region and at lidar ranges (>= 100
m), the SamplingWarnings of auto (expected: none), the Fraunhofer warnings and the ranges from which
its eps_w stays below the paper's 0.2 % and the project's 0.01 %.

Units: SI in the code (m); the plot shows ranges in m and radii in mm.
Writes fig8_fo_accuracy.png to the current directory.
"""

import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lidar_overlap as lo  # noqa: E402

WAIST = 5e-3  # m, w0
WAVELENGTHS = (355e-9, 1064e-9)  # m
RANGES = np.geomspace(1e-3, 1e5, 200)  # m
N_GRID = 512
SPACING = 10.0 * WAIST / N_GRID  # m: window +-5 w0
TARGET = 0.01  # %, the project's accuracy target for eps_w
PAPER = 0.2  # %, the paper's bound in the Fresnel and Fraunhofer regions
LIDAR_START = 100.0  # m, where lidars usually start to operate (Appendix D)
ERROR_FLOOR = 1e-14  # %, plotted instead of an exact zero on the log axis

METHOD_STYLE = {
    "angular_spectrum": dict(color="tab:purple", label="angular spectrum (A1)"),
    "fresnel": dict(color="tab:green", label="Fresnel (A5)"),
}
WAVELENGTH_STYLE = {
    355e-9: dict(marker="o", linestyle="-", fraunhofer=":"),
    1064e-9: dict(marker="^", linestyle="--", fraunhofer="-."),
}


def d1_radius(z, wavelength, waist=WAIST):
    """Eq. (D1) in vacuum (refractive index 1)."""
    return waist * np.sqrt(1.0 + (wavelength * z / (np.pi * waist**2)) ** 2)


def eps_percent(w_fo, w_d1):
    """Eq. (D2), in percent."""
    return 100.0 * np.abs(1.0 - w_d1 / w_fo)


def run(wavelength):
    """FO radius by method="auto" and by Fraunhofer at every range, the method auto used, and the
    Fraunhofer SamplingWarnings per range."""
    field = lo.Field.gaussian(wavelength, WAIST, N_GRID, SPACING)
    critical = N_GRID * SPACING**2 / wavelength
    w_auto, w_fra = np.empty(RANGES.size), np.empty(RANGES.size)
    used, fra_warnings, auto_warnings = [], np.zeros(RANGES.size, dtype=int), []
    for i, z in enumerate(RANGES):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", lo.SamplingWarning)
            g = lo.propagate(field, z, method="auto")
        auto_warnings += [
            str(w.message) for w in caught if issubclass(w.category, lo.SamplingWarning)
        ]
        w_auto[i] = g.beam_radius
        # The angular spectrum keeps the input grid; Fresnel samples the output at lambda z / (n
        # dx).
        used.append("angular_spectrum" if g.spacing == field.spacing else "fresnel")
        expected = "angular_spectrum" if z <= critical else "fresnel"
        if used[-1] != expected:
            raise RuntimeError(
                f"auto used {used[-1]} at z = {z:g} m, expected {expected} (critical distance "
                f"{critical:g} m)"
            )
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", lo.SamplingWarning)
            w_fra[i] = lo.propagate(field, z, method="fraunhofer").beam_radius
        fra_warnings[i] = sum(issubclass(w.category, lo.SamplingWarning) for w in caught)
    return dict(
        wavelength=wavelength,
        critical=critical,
        w_auto=w_auto,
        w_fra=w_fra,
        used=np.array(used),
        fra_warnings=fra_warnings,
        auto_warnings=auto_warnings,
        w_d1=d1_radius(RANGES, wavelength),
    )


def report(r):
    """Print the worst eps_w per method region, and where Fraunhofer becomes usable."""
    lam_nm = r["wavelength"] * 1e9
    eps_auto = eps_percent(r["w_auto"], r["w_d1"])
    eps_fra = eps_percent(r["w_fra"], r["w_d1"])
    print(
        f"{lam_nm:.0f} nm: critical distance n dx^2/lambda = {r['critical']:.2f} m, Rayleigh range "
        f"= {np.pi * WAIST**2 / r['wavelength']:.1f} m"
    )
    for method in ("angular_spectrum", "fresnel"):
        sel = r["used"] == method
        k = np.argmax(np.where(sel, eps_auto, -1.0))
        print(
            f"  auto, {method:16} {sel.sum():3d} ranges "
            f"{RANGES[sel][0]:9.3g}-{RANGES[sel][-1]:9.3g} m: worst eps_w = {eps_auto[k]:.2e} % at "
            f"z = {RANGES[k]:.3g} m"
        )
    lidar = RANGES >= LIDAR_START
    print(
        f"  auto, z >= {LIDAR_START:g} m: worst eps_w = {eps_auto[lidar].max():.2e} %; "
        f"SamplingWarnings from auto: {len(r['auto_warnings'])}"
    )
    for message in r["auto_warnings"][:3]:
        print(f"    {message}")
    warned = r["fra_warnings"] > 0
    print(
        f"  Fraunhofer: {int(r['fra_warnings'].sum())} SamplingWarnings at {warned.sum()} of "
        f"{RANGES.size} "
        f"ranges" + (f", the last at z = {RANGES[warned][-1]:.3g} m" if warned.any() else "")
    )
    if warned.any():
        print(
            f"    worst eps_w where it warns: {eps_fra[warned].max():.2e} %, at the last warned "
            f"range: {eps_fra[warned][-1]:.2e} %"
        )
    if (~warned).any():
        print(f"    worst eps_w where it does not warn: {eps_fra[~warned].max():.2e} %")
    for bound in (PAPER, TARGET):
        ok = np.nonzero(eps_fra <= bound)[0]
        first = RANGES[ok[0]] if ok.size and np.all(eps_fra[ok[0] :] <= bound) else np.nan
        print(f"    eps_w <= {bound:g} % from z = {first:.3g} m on")
    return eps_auto, eps_fra, warned


def plot(results):
    fig, (ax_w, ax_e) = plt.subplots(
        2, 1, figsize=(11.5, 8.6), sharex=True, constrained_layout=True
    )
    bars = ((0.955, 1.0), (0.91, 0.955))  # axes fractions of the "Fraunhofer warns" bars
    for r, bar in zip(results, bars):
        lam = r["wavelength"]
        style = WAVELENGTH_STYLE[lam]
        lam_label = f"{lam * 1e9:.0f} nm"
        eps_auto, eps_fra, warned = r["eps_auto"], r["eps_fra"], r["warned"]

        # Top: radius by auto (markers coloured by method) and by D1 (line).
        ax_w.plot(
            RANGES,
            r["w_d1"] * 1e3,
            color="k",
            lw=1.0,
            linestyle=style["linestyle"],
            label=f"Eq. (D1), {lam_label}",
            zorder=3,
        )
        for method, mstyle in METHOD_STYLE.items():
            sel = r["used"] == method
            ax_w.plot(
                RANGES[sel][::2],
                r["w_auto"][sel][::2] * 1e3,
                linestyle="none",
                marker=style["marker"],
                ms=4.5,
                mfc=mstyle["color"],
                mec="none",
                alpha=0.75,
                zorder=2,
            )
        ax_w.axvline(r["critical"], color="0.4", lw=0.8, linestyle=(0, (2, 2)))
        right = lam < 5e-7  # 355 nm label right of its line, 1064 nm label left of it
        ax_w.text(
            r["critical"] * (1.15 if right else 1 / 1.15),
            2.5e3,
            f"$n\\,dx^2/\\lambda$ = {r['critical']:.3g} m\n({lam_label})",
            fontsize=8,
            color="0.3",
            va="top",
            ha="left" if right else "right",
        )

        # Bottom: eps_w of auto (markers by method) and of Fraunhofer; a bar (top of the panel) and
        # a vertical line mark the ranges where Fraunhofer warns.
        if warned.any():
            last = RANGES[warned][-1]
            ax_e.axvspan(
                RANGES[0],
                last,
                ymin=bar[0],
                ymax=bar[1],
                color="tab:blue",
                alpha=0.45 if lam < 5e-7 else 0.25,
                lw=0,
                label=f"Fraunhofer warns, {lam_label}: z <= {last / 1e3:.3g} km",
            )
            ax_e.axvline(last, color="tab:blue", lw=0.8, linestyle=style["fraunhofer"], alpha=0.8)
            ax_e.text(
                1.5e-3,
                0.5 * (bar[0] + bar[1]),
                f"Fraunhofer warns ({lam_label})",
                fontsize=7.5,
                va="center",
                color="0.15",
                transform=ax_e.get_xaxis_transform(),
            )
        ax_e.plot(
            RANGES,
            np.maximum(eps_auto, ERROR_FLOOR),
            color="k",
            lw=0.6,
            linestyle=style["linestyle"],
            alpha=0.6,
            zorder=2,
        )
        for method, mstyle in METHOD_STYLE.items():
            sel = r["used"] == method
            ax_e.plot(
                RANGES[sel],
                np.maximum(eps_auto[sel], ERROR_FLOOR),
                linestyle="none",
                marker=style["marker"],
                ms=3.5,
                mfc=mstyle["color"],
                mec="none",
                zorder=3,
            )
        ax_e.plot(
            RANGES,
            eps_fra,
            color="tab:blue",
            lw=1.6,
            linestyle=style["fraunhofer"],
            zorder=2,
            label=f"Fraunhofer (A7) at every z, {lam_label}",
        )

    # Legend entries for the marker meaning (method colour, wavelength shape).
    for _method, mstyle in METHOD_STYLE.items():
        ax_w.plot(
            [],
            [],
            linestyle="none",
            marker="s",
            ms=6,
            mfc=mstyle["color"],
            mec="none",
            label=f"FO auto: {mstyle['label']}",
        )
    for lam, style in WAVELENGTH_STYLE.items():
        ax_w.plot(
            [],
            [],
            linestyle="none",
            marker=style["marker"],
            ms=5,
            mfc="0.5",
            mec="none",
            label=f"FO auto, {lam * 1e9:.0f} nm",
        )
    ax_w.set_xscale("log")
    ax_w.set_yscale("log")
    ax_w.set_ylim(3.0, 2e4)
    ax_w.set_ylabel("beam radius w(z) (mm)")
    ax_w.set_title(
        f'TEM$_{{00}}$, w$_0$ = {WAIST * 1e3:g} mm: FO propagation (method="auto", '
        f"{N_GRID}$^2$ grid, dx = {SPACING * 1e3:.3g} mm) against Eq. (D1)",
        fontsize=10,
    )
    ax_w.grid(True, which="major", alpha=0.3)
    ax_w.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)

    ax_e.axvspan(
        LIDAR_START,
        RANGES[-1],
        color="tab:green",
        alpha=0.07,
        lw=0,
        zorder=0,
        label=f"usual lidar ranges (z >= {LIDAR_START:g} m)",
    )
    ax_e.axhline(PAPER, color="tab:red", lw=1.2, label=f"paper's bound {PAPER:g} %")
    ax_e.axhline(
        TARGET, color="tab:orange", lw=1.2, linestyle="--", label=f"project target {TARGET:g} %"
    )
    ax_e.axhline(
        100 * np.finfo(float).eps,
        color="0.5",
        lw=0.8,
        linestyle=":",
        label="double-precision epsilon",
    )
    for lam, style in WAVELENGTH_STYLE.items():
        ax_e.plot(
            [],
            [],
            color="k",
            lw=0.6,
            linestyle=style["linestyle"],
            marker=style["marker"],
            ms=3.5,
            mfc="0.5",
            mec="none",
            label=f"FO auto, {lam * 1e9:.0f} nm\n(colour = method, as above)",
        )
    ax_e.set_yscale("log")
    ax_e.set_ylim(ERROR_FLOOR / 3, 1e11)  # room above the curves for the "Fraunhofer warns" bars
    ax_e.set_yticks(10.0 ** np.arange(-14, 9, 2))
    ax_e.set_xlim(RANGES[0], RANGES[-1])
    ax_e.set_xlabel("range z (m)")
    ax_e.set_ylabel(r"$\varepsilon_w$, Eq. (D2) (%)")
    ax_e.grid(True, which="major", alpha=0.3)
    ax_e.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    fig.savefig("fig8_fo_accuracy.png", dpi=150)


def main():
    print(
        f"TEM00 w0 = {WAIST * 1e3:g} mm, grid {N_GRID} x {N_GRID}, spacing {SPACING * 1e3:.4g} mm "
        f"(window +-{N_GRID * SPACING / 2 / WAIST:g} w0, {WAIST / SPACING:.1f} samples per w0), "
        f"{RANGES.size} ranges {RANGES[0]:g}-{RANGES[-1]:g} m"
    )
    results = []
    for wavelength in WAVELENGTHS:
        r = run(wavelength)
        r["eps_auto"], r["eps_fra"], r["warned"] = report(r)
        results.append(r)
    plot(results)
    print("wrote fig8_fo_accuracy.png")


if __name__ == "__main__":
    main()
