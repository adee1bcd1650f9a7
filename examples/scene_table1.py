"""3-D views of two lidars: the paper's Table 1 mono-axial system and a biaxial variant.

System: the paper's Table 1 lidar (f = 1 m, D = 150 mm, full FOV 0.9 mrad, TEM00 beam at 355 nm with
w0 = 1 mm, diffraction-limited divergence). The biaxial variant moves the beam 0.2 m off the
telescope axis (along x) and tilts it by -0.4 mrad, so that its axis crosses the receiver's line of
sight at 500 m: the beam enters the field of view at about 150 m.

Each picture shows, with the transverse axes exaggerated x100 and the range to scale: the beam's
1/e^2 envelope coloured by the overlap G(z), the receiver's full field of view (translucent), the
aperture and detector, the full-overlap range (red ring) and, at two ranges, the beam irradiance in
the scattering plane with the field of view (cyan) and its image on the detector plane with the
detector (cyan). Printed: G at the two ranges and the full-overlap range (G >= 0.99 max G).

Units: SI (m, rad). Needs PyVista (pip install 'lidar-overlap[viz]'); renders off-screen.
Writes scene_table1.png and scene_biaxial.png to the current directory.
"""

import dataclasses

import numpy as np

import lidar_overlap as lo
from lidar_overlap.views.scene import save_scene

RANGES = np.geomspace(1.0, 1000.0, 200)  # m
BEAM_OFFSET = (0.2, 0.0)  # m, biaxial beam position at z = 0
CROSSING = 500.0  # m, where the tilted beam axis crosses the telescope axis


def main():
    table1 = lo.paper_table1()
    biaxial = dataclasses.replace(
        table1,
        beam=dataclasses.replace(
            table1.beam, offset=BEAM_OFFSET, tilt=(-BEAM_OFFSET[0] / CROSSING, 0.0)
        ),
    )
    cases = (
        ("scene_table1.png", table1, (100.0, 300.0)),
        ("scene_biaxial.png", biaxial, (250.0, 500.0)),
    )
    for filename, system, planes in cases:
        result = lo.overlap(system, RANGES, method="rt")
        g = np.interp(planes, result.ranges, result.overlap)
        # The scene ends at twice the full-overlap range (as with the default ranges).
        shown = result.ranges[result.ranges <= 2.0 * result.full_overlap_range()]
        path = save_scene(
            system, filename, ranges=shown, result=result, planes=planes, color_by="overlap"
        )
        print(
            f"{filename}: G({planes[0]:g} m) = {g[0]:.3f}, G({planes[1]:g} m) = {g[1]:.3f}, full "
            f"overlap at {result.full_overlap_range():.1f} m"
        )
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
