"""The model of a lidar: immutable value types checked on construction (system, beams, fields,
masks, aberrations, turbulence, atmosphere), their parameters by path, and the paper's Table 1
preset.

Files: aberrations.py, aperture_mask.py, atmosphere.py, field.py, field_beam.py, flat_top.py,
instruments.py, mixture_beam.py, parameter_paths.py, parameters.py, path_syntax.py, presets.py,
system.py, system_attributes.py, tilt.py, turbulence.py.
"""

__all__ = [
    "aberrations",
    "aperture_mask",
    "atmosphere",
    "field",
    "field_beam",
    "flat_top",
    "instruments",
    "mixture_beam",
    "parameter_paths",
    "parameters",
    "path_syntax",
    "presets",
    "system",
    "system_attributes",
    "tilt",
    "turbulence",
]
