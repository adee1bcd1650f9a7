"""Every public entry point's hypothesis strategy for the hostile-input probes, and how many
examples each gets (PROBES). The strategies live by concept: tests/_hostile_probes_turbulence.py,
_hostile_probes_fields.py, _hostile_probes_overlap.py, _hostile_probes_queries.py,
_hostile_probes_arrays.py and _hostile_probes_analysis.py.

Each strategy draws a :class:`Call` tree: a sane call near the paper's Table 1 with (usually) one or
two hostile values in the system, the ranges or the options. Valid work is kept small (at most 6
ranges, 8-128 sample grids, 1-3 turbulence realisations and screens) so that a probe costs
milliseconds; the expensive valid Fourier-optics paths get fewer examples.
"""

from __future__ import annotations

import _hostile_probes_analysis as analysis
from _hostile_probes_arrays import noll_index, phase_screen, zernike
from _hostile_probes_fields import (
    field_beam,
    field_from_values,
    flat_top,
    gaussian_field,
    propagation,
)
from _hostile_probes_overlap import overlap_call, overlap_method_object
from _hostile_probes_queries import (
    detector_image,
    emitter_coupling,
    explain,
    optimal_focus,
    parameter_replace,
    point_image,
    result_method,
)
from _hostile_probes_turbulence import turbulence, turbulence_method
from _hostile_values import (
    aberrations,
    detector,
    detector_from_fov,
    gaussian_beam,
    system,
    telescope,
)

#: Every entry point's probe strategy, and its examples in a run of the test suite (2,700 in all; a
#: campaign shares its probes in the same proportions). Paths that draw valid Fourier-optics work
#: get fewer.
PROBES = {
    "GaussianBeam": (gaussian_beam(), 100),
    "Telescope": (telescope(), 60),
    "Telescope_aberrated": (telescope(aberrated=True), 40),
    "Detector": (detector(), 80),
    "Detector.from_fov": (detector_from_fov(), 80),
    "LidarSystem": (system(), 100),
    "Aberrations": (aberrations(), 80),
    "Turbulence": (turbulence(), 80),
    "Field.gaussian": (gaussian_field(), 80),
    "Field": (field_from_values(), 80),
    "propagate": (propagation(), 120),
    "FieldBeam": (field_beam(), 60),
    "overlap_rt": (overlap_call("rt"), 250),
    "overlap_fo_radial": (overlap_call("radial"), 120),
    "overlap_auto": (overlap_call("auto"), 120),
    "overlap_fo_2d": (overlap_call("2d", max_ranges=3, low=20.0), 60),
    "overlap_field_beam": (overlap_call("field_beam", max_ranges=3, low=20.0), 50),
    "overlap_turbulent": (overlap_call("turbulent", max_ranges=3), 60),
    "overlap_aberrated": (overlap_call("aberrated", max_ranges=2, low=20.0), 40),
    "overlap_method_object": (overlap_method_object(), 80),
    "parameters.replace": (parameter_replace(), 60),
    "emitter_coupling_rt": (emitter_coupling("rt"), 80),
    "emitter_coupling_fo": (emitter_coupling("fo"), 40),
    "explain": (explain(), 80),
    "result_ranges": (result_method(), 60),
    "FlatTopBeam": (flat_top(), 40),
    "point_image": (point_image(), 60),
    "detector_image": (detector_image(), 60),
    "Turbulence_methods": (turbulence_method(), 80),
    "optimal_focus_range": (optimal_focus(), 60),
    "phase_screen": (phase_screen(), 40),
    "zernike": (zernike(), 40),
    "noll_index": (noll_index(), 20),
    "alignment_map": (analysis.alignment_map(), 60),
    "telecover": (analysis.telecover(), 60),
    "sensitivity": (analysis.sensitivity(), 40),
    "correct": (analysis.correct(), 40),
    "empirical_drift": (analysis.empirical_drift(), 40),
}
