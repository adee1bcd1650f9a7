"""Fourier-optics propagation at the edges of each method's validity (paper Appendix A): inside its
region no SamplingWarning, outside it one naming the reason, and wherever the beam radius D1 is
missed a warning says so; bad arguments raise ValueError naming the parameter."""

import math
import warnings

import numpy as np
import pytest
from _propagation import (
    D1_RTOL,
    DX,
    W0,
    WAVELENGTHS,
    N,
    critical,
    d1,
    d1_errors,
    quiet,
    rayleigh,
    recorded,
)

import lidar_overlap as lo


@pytest.fixture(scope="module", params=WAVELENGTHS, ids=["355nm", "1064nm"])
def beam(request):
    return lo.Field.gaussian(request.param, W0, N, DX)


# --- validity boundaries
# ------------------------------------------------------------------------------

# method: (unit z_c or zR, inside, outside, reason the warning must give, sweep), in that unit
BOUNDARY = {
    "angular_spectrum": (
        "zc",
        0.999,
        100,
        r"(?i)band|edge|wrap|alias|window",
        [2, 5, 10, 20, 50, 200],
    ),
    "fresnel": ("zc", 1.001, 1 / 20, r"(?i)critical|undersampl|alias|chirp", [0.5, 0.2, 0.1, 0.02]),
    "fraunhofer": (
        "zr",
        100,
        1 / math.pi,
        r"(?i)fresnel number|near[ -]?field",
        [1000, 50, 30, 10, 1],
    ),
}


@pytest.mark.parametrize("method", sorted(BOUNDARY))
def test_validity_boundary(beam, method):
    unit, inside, outside, reason, sweep = BOUNDARY[method]
    unit = critical(beam) if unit == "zc" else rayleigh(W0, beam.wavelength)
    assert d1_errors(beam, [inside * unit], method=method)[0] <= D1_RTOL  # and no SamplingWarning
    with warnings.catch_warnings(
        record=True
    ):  # keeps the other reasons pytest.warns passes on quiet
        with pytest.warns(lo.SamplingWarning, match=reason):
            lo.propagate(beam, outside * unit, method=method)
    for z in np.array(sweep) * unit:  # wherever D1 is missed, a warning must say so
        g, messages = recorded(beam, z, method=method)
        error = abs(1.0 - d1(z, W0, beam.wavelength) / g.beam_radius)
        assert error <= D1_RTOL or messages, (
            f"{method} at z = {z:.4g} m: error {error:.3g} and no SamplingWarning"
        )


def test_beam_touching_window_edge_warns():
    assert issubclass(lo.SamplingWarning, RuntimeWarning)
    # Window +-1.5 w0: the irradiance at the edge is exp(-4.5) = 1 % of the peak; its power wraps
    # around.
    wide = lo.Field.gaussian(355e-9, N * DX / 3, N, DX)
    with pytest.warns(lo.SamplingWarning, match=r"(?i)edge|wrap|window"):
        lo.propagate(wide, 0.1 * critical(wide), method="angular_spectrum")
    quiet(
        lo.Field.gaussian(355e-9, W0, N, DX), 0.1 * critical(wide), method="angular_spectrum"
    )  # +-5 w0


# --- bad input
# ----------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "name, field, kwargs",
    [
        ("distance", True, dict(distance=math.nan)),
        ("distance", True, dict(distance=math.inf)),
        ("method", True, dict(method="fresnell")),
        ("method", True, dict(method="")),
        ("output_spacing", True, dict(method="fresnel", output_spacing=0.0)),
        ("output_spacing", True, dict(method="auto", output_spacing=-1e-6)),
        ("output_spacing", True, dict(method="fresnel", output_spacing=math.nan)),
        ("field", None, {}),
        ("field", 1.0, {}),
        ("field", np.ones((64, 64), complex), {}),
    ],
)
def test_bad_arguments(name, field, kwargs):
    if field is True:
        field = lo.Field.gaussian(355e-9, W0, 64, W0 / 8)
    kwargs = dict(dict(distance=1e3), **kwargs)
    with pytest.raises(ValueError, match=name):
        lo.propagate(field, kwargs.pop("distance"), **kwargs)
