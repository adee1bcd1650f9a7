"""Ready-made systems from the paper, for examples, tests and benchmarks."""

from __future__ import annotations

from .system import Detector, GaussianBeam, LidarSystem, Telescope, WidthLaw


def paper_table1(
    wavelength: float = 355e-9,
    waist_radius: float = 1e-3,
    divergence: float | None = None,
    obstruction_radius: float = 0.0,
    obstruction_distance: float = 0.7,
    defocus: float = 0.0,
    width_law: WidthLaw = "gaussian",
) -> LidarSystem:
    """The mono-axial lidar of the paper's Table 1: f = 1 m, D = 150 mm, FFOV 0.9 mrad, w0 = 1 mm.
    Section 4A places the obstruction 0.7 m in front of the aperture stop. SI units."""
    return LidarSystem(
        beam=GaussianBeam(
            wavelength=wavelength,
            waist_radius=waist_radius,
            divergence=divergence,
            width_law=width_law,
        ),
        telescope=Telescope(
            diameter=0.15,
            focal_length=1.0,
            obstruction_radius=obstruction_radius,
            obstruction_distance=obstruction_distance,
        ),
        detector=Detector.from_fov(fov=0.9e-3, focal_length=1.0, defocus=defocus),
    )
