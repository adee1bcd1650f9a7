"""lidar_overlap: the overlap function of atmospheric lidars (SI units throughout)."""

from . import parameters
from ._core import __version__, max_memory, max_threads, set_max_memory
from .atmosphere import Atmosphere
from .aperture_mask import ApertureMask, Sector
from .alignment import alignment_map, alignment_maps
from .autoalign import AlignResult, align
from .aberrations import Aberrations, noll_index, seidel_to_zernike, with_aberrations, zernike, zernike_to_seidel
from .beam_fields import annular_field, laguerre_gauss_field, super_gaussian_field
from .detector_image import DetectorImage, detector_image
from .field_beam import FieldBeam
from .fields import Field, SamplingWarning, propagate
from .flat_top import FlatTopBeam
from .fit import fit
from .fit_telecover import fit_telecover
from .fit_result import DegeneracyWarning, FitResult, Prediction
from .compute import overlap, run
from .coupling import emitter_coupling, optimal_focus_range
from .imaging import point_image
from .methods import FO, RT, Auto, Turbulent
from .objectives import MaximumOverlapAt, Objective, SmallestFieldOfView
from .optimize import OptimizeResult, optimize
from .planning import Plan, explain, plan
from .phase_screen import phase_screen
from .presets import paper_table1
from .result import OverlapResult
from .sensitivity import sensitivity
from .scene import save_scene, scene
from .signals import CorrectedSignal, LidarSignal, correct, signal
from .studies import tolerance_study
from .telecover import TelecoverResult, telecover
from .system import Detector, GaussianBeam, LidarSystem, Telescope
from .turbulence import Turbulence, TurbulentOverlapResult
from .turbulent_study import turbulent_realizations
from .views.app import view

__all__ = [
    "__version__",
    "Aberrations",
    "ApertureMask",
    "Atmosphere",
    "CorrectedSignal",
    "LidarSignal",
    "Auto",
    "FO",
    "Plan",
    "RT",
    "Turbulent",
    "alignment_map",
    "alignment_maps",
    "fit",
    "fit_telecover",
    "DegeneracyWarning",
    "FitResult",
    "Prediction",
    "AlignResult",
    "align",
    "MaximumOverlapAt",
    "Objective",
    "OptimizeResult",
    "SmallestFieldOfView",
    "optimize",
    "sensitivity",
    "plan",
    "run",
    "with_aberrations",
    "annular_field",
    "laguerre_gauss_field",
    "noll_index",
    "point_image",
    "seidel_to_zernike",
    "zernike",
    "zernike_to_seidel",
    "super_gaussian_field",
    "Detector",
    "DetectorImage",
    "Field",
    "FieldBeam",
    "FlatTopBeam",
    "GaussianBeam",
    "LidarSystem",
    "OverlapResult",
    "SamplingWarning",
    "Sector",
    "Telescope",
    "TelecoverResult",
    "Turbulence",
    "TurbulentOverlapResult",
    "detector_image",
    "emitter_coupling",
    "explain",
    "optimal_focus_range",
    "overlap",
    "paper_table1",
    "parameters",
    "phase_screen",
    "max_memory",
    "max_threads",
    "set_max_memory",
    "telecover",
    "tolerance_study",
    "turbulent_realizations",
    "view",
    "propagate",
    "save_scene",
    "scene",
    "correct",
    "signal",
]
