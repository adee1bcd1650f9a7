"""Shared by the propagation tests: the paper's Appendix D beam on its grid, the closed-form beam
radius D1, and propagation that records (or forbids) SamplingWarnings."""

import math
import warnings

import numpy as np

import lidar_overlap as lo

D1_RTOL = 1e-4  # project target for the beam radius, 0.01 % (the paper's Fig. 8 reaches 0.2 %)
W0 = 5e-3  # paper Appendix D waist
N = 512
DX = 10 * W0 / N  # window +-5 w0, 51 samples per w0; edge irradiance exp(-50) of the peak
WAVELENGTHS = [355e-9, 1064e-9]


def d1(z, w0, wavelength):
    return w0 * math.sqrt(1.0 + (wavelength * z / (math.pi * w0**2)) ** 2)


def rayleigh(w0, wavelength):
    return math.pi * w0**2 / wavelength


def critical(field):
    return field.n * field.spacing**2 / field.wavelength


def recorded(field, distance, **kwargs):
    """Propagate; return the result and the messages of the SamplingWarnings issued."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = lo.propagate(field, distance, **kwargs)
    return out, [str(w.message) for w in caught if issubclass(w.category, lo.SamplingWarning)]


def quiet(field, distance, **kwargs):
    """Propagate inside the method's validity: no SamplingWarning may be issued."""
    out, messages = recorded(field, distance, **kwargs)
    assert not messages, (
        f"SamplingWarning inside the valid region (z = {distance:.4g} m, {kwargs}): {messages}"
    )
    return out


def d1_errors(field, distances, **kwargs):
    """Relative error (paper D2) of the propagated beam radius at each distance."""
    return np.array(
        [
            abs(1.0 - d1(z, W0, field.wavelength) / quiet(field, z, **kwargs).beam_radius)
            for z in distances
        ]
    )
