"""Where ray tracing fails: a detector shrinking towards the Airy radius.

Geometric optics images a point to a point, so RT says a focused scatterer couples fully (G = 1)
into any detector. Fourier optics gives the Airy pattern, whose encircled energy 1 - J0(v)^2 -
J1(v)^2, v = pi D r_d / (lambda f), is what reaches the detector. This example charts, against r_d /
r_Airy (r_Airy = 1.22 lambda f / D):

- one on-axis scatterer at 1e9 m (in focus): RT coupling, FO coupling, and the closed form;
- the relative error of RT for that point, and for the paper's Table 1 lidar (355 nm, f = 1 m, D =
  150 mm, 1 mm Gaussian beam) focused on 1000 m (Eq. 5) with its detector radius varied. The beam
  there is 40 to 100 000 times wider than the field of view: an extended incoherent source, whose
  power on the detector is set by the etendue (FOV x aperture), not by the shape of the point image,
  so RT stays within ~1 % of FO even for a detector smaller than the Airy disc. RT fails for narrow
  images.

Writes rt_vs_fo_diffraction.png. SI units.
"""

import dataclasses
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from scipy.special import j0, j1

import lidar_overlap as lo

base = lo.paper_table1()
lam, f, diameter = base.beam.wavelength, base.telescope.focal_length, base.telescope.diameter
r_airy = 1.22 * lam * f / diameter
ratios = np.geomspace(0.3, 300, 40)


def with_radius(system, r_d):
    return dataclasses.replace(system, detector=dataclasses.replace(system.detector, radius=r_d))


point_fo, point_rt, closed = [], [], []
for r in ratios:
    s = with_radius(base, r * r_airy)
    point_fo.append(lo.emitter_coupling(s, 1e9, (0.0, 0.0), method="fo"))
    point_rt.append(lo.emitter_coupling(s, 1e9, (0.0, 0.0), method="rt"))
    v = np.pi * diameter * r * r_airy / (lam * f)
    closed.append(1 - j0(v) ** 2 - j1(v) ** 2)
point_fo, point_rt, closed = map(np.asarray, (point_fo, point_rt, closed))

z = np.array([1000.0])
focused = dataclasses.replace(
    base, detector=dataclasses.replace(base.detector, defocus=f * f / (z[0] - f))
)
g_fo, g_rt = [], []
with warnings.catch_warnings():
    warnings.simplefilter(
        "ignore", RuntimeWarning
    )  # RT's own validity warning is what is charted here
    for r in ratios:
        s = with_radius(focused, r * r_airy)
        g_fo.append(lo.overlap(s, z, method="fo").overlap[0])
        g_rt.append(lo.overlap(s, z, method="rt").overlap[0])
g_fo, g_rt = np.asarray(g_fo), np.asarray(g_rt)
rt_error = np.abs(1 - g_rt / g_fo)

fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.4), constrained_layout=True)
a1.semilogx(ratios, point_rt, "k--", label="RT (geometric: a point)")
a1.semilogx(ratios, point_fo, "C0-", lw=2, label="FO (emitter_coupling)")
a1.semilogx(ratios, closed, "C1:", lw=2, label=r"$1-J_0^2(v)-J_1^2(v)$")
a1.set(
    xlabel=r"detector radius / Airy radius $r_d/r_{Airy}$",
    ylabel="coupling of an in-focus point",
    title="one scatterer at infinity, on axis",
    ylim=(0, 1.05),
)
a1.legend()
a1.grid(True, which="both", alpha=0.3)

a2.loglog(ratios, np.abs(1 - point_rt / point_fo), "C0-", lw=2, label="in-focus point scatterer")
a2.loglog(ratios, rt_error, "C3-o", ms=3, label="Table 1 beam at 1000 m (extended source)")
a2.loglog(
    ratios,
    2 / (np.pi * np.pi * diameter * ratios * r_airy / (lam * f)),
    "k:",
    label=r"Airy tail $2/(\pi v)$",
)
a2.axhline(lo.forward.validity.RT_MODEL_ERROR_LIMIT, color="grey", lw=1)
a2.text(
    ratios[0], lo.forward.validity.RT_MODEL_ERROR_LIMIT * 1.2, "RT warns above this", color="grey"
)
r_table1 = base.detector.radius / r_airy
a2.axvline(r_table1, color="C2", lw=1)
a2.text(r_table1 * 1.05, 0.3, "Table 1 detector", color="C2", rotation=90, va="top")
a2.set(
    xlabel=r"$r_d/r_{Airy}$",
    ylabel=r"relative error of RT, $|1 - G_{RT}/G_{FO}|$",
    title="RT error: a point fails, an extended beam does not",
)
a2.legend()
a2.grid(True, which="both", alpha=0.3)
fig.savefig("rt_vs_fo_diffraction.png", dpi=130)

print(f"Airy radius {r_airy * 1e6:.2f} um; Table 1 detector = {r_table1:.0f} Airy radii")
print(f"max |FO - closed form| for the point: {np.max(np.abs(point_fo - closed)):.2e}")
for r, p, e in zip(ratios[::6], np.abs(1 - point_rt / point_fo)[::6], rt_error[::6]):
    print(f"r_d = {r:7.2f} Airy radii: RT error {p:8.2%} for a point, {e:.2%} for the Table 1 beam")
print("wrote rt_vs_fo_diffraction.png")
