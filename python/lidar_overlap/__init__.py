"""lidar_overlap: the overlap function of atmospheric lidars (SI units throughout)."""

from ._core import __version__
from .fields import Field, SamplingWarning, propagate
from .overlap import emitter_coupling, optimal_focus_range, overlap
from .presets import paper_table1
from .result import OverlapResult
from .system import Detector, GaussianBeam, LidarSystem, Telescope

__all__ = [
    "__version__",
    "Detector",
    "Field",
    "GaussianBeam",
    "LidarSystem",
    "OverlapResult",
    "SamplingWarning",
    "Telescope",
    "emitter_coupling",
    "optimal_focus_range",
    "overlap",
    "paper_table1",
    "propagate",
]
