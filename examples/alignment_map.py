"""Alignment maps of the paper's Table 1 lidar and of a biaxial one: G over beam tilt_x x tilt_y.

Table 1 (f = 1 m, D = 150 mm, full FOV 0.9 mrad, w0 = 1 mm at 355 nm) is coaxial: its maps are
round, and the tilt it tolerates shrinks with range towards the half FOV (0.45 mrad) minus the beam
divergence. The biaxial lidar is the same with the beam 0.1 m beside the telescope axis, parallel to
it: the map's centre moves, to negative tilt_x at near range (where tilting the beam towards the
axis brings it into the field of view earlier) and back towards zero far away. Tilts are added to
the system's own (zero) tilt.

Units: SI in the code; plots in mrad. Writes alignment_map.png to the current directory.
"""

import dataclasses

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lidar_overlap as lo  # noqa: E402
from lidar_overlap.views.plotting import plot_alignment_map  # noqa: E402

TILTS = np.linspace(-1.2e-3, 1.2e-3, 41)  # rad
RANGES = [150.0, 2000.0]  # m: near (G still rising) and far
TOLERANCE = 1e-3

table1 = lo.paper_table1()
biaxial = dataclasses.replace(table1, beam=dataclasses.replace(table1.beam, offset=(0.1, 0.0)))
fig, axes = plt.subplots(2, 2, figsize=(9.0, 7.4), constrained_layout=True)
for row, (name, system) in enumerate(
    (("Table 1", table1), ("biaxial, beam 0.1 m off axis", biaxial))
):
    ds = lo.alignment_map(system, RANGES, tilt_x=TILTS, tilt_y=TILTS, tolerance=TOLERANCE)
    for col, z in enumerate(RANGES):
        ax = plot_alignment_map(ds, range=z, ax=axes[row, col])
        ax.set_title(f"{name}, z = {z:g} m")
        g = ds["overlap"].sel(range=z)
        best = g.where(g == g.max(), drop=True)
        print(
            f"{name:30s} z = {z:6g} m: max G {float(g.max()):.3f} at tilt_x = "
            f"{float(best['tilt_x'][0]) * 1e3:+.2f} mrad; G >= 0.9 over "
            f"{float((g >= 0.9).mean()):.0%} of the map"
        )
fig.savefig("alignment_map.png", dpi=120)
print("wrote alignment_map.png")
