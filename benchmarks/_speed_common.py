"""Pieces shared by the speed-accuracy benchmarks (speed_accuracy.py, failure_map.py,
scaling.py)."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import matplotlib  # noqa: E402

matplotlib.use("Agg")

import lidar_overlap as lo  # noqa: E402
from lidar_overlap import _core  # noqa: E402

RESULTS = HERE / "results"
REPEATS = 3  # best of 3 warm calls (one untimed call first)
THREADS = 0  # all cores
RADIAL_DEFAULT = 8.0  # what lo.overlap(method="fo", fo_path="radial") uses
FO_2D_WINDOW = 10.0
REFERENCE_RADIAL_PERIODS = 1.0


def with_beam(system, **changes):
    return dataclasses.replace(system, beam=dataclasses.replace(system.beam, **changes))


def with_detector_radius(system, radius):
    return dataclasses.replace(system, detector=dataclasses.replace(system.detector, radius=radius))


def airy_radius(system):
    """1.22 lambda f / D, the first dark ring of the in-focus point image."""
    return 1.22 * system.beam.wavelength * system.telescope.focal_length / system.telescope.diameter


TABLE1 = lo.paper_table1()


def radial(system, z, periods, threads=THREADS):
    return _core.overlap_fo_radial(
        system._native, z, _core.RadialFoOptions(periods_per_panel=float(periods), threads=threads)
    ).overlap
