"""Hypothesis strategies probing turbulence: lo.Turbulence with hostile profile parameters, and
its path methods (Fried parameter, Rytov variance, beam wander, ...) with hostile path arguments.
"""

from __future__ import annotations

import math

from _hostile_values import (
    INF,
    cached,
    corrupt,
    corruptions,
    hostile_choice,
    hostile_real,
    sanes,
)
from _probe_worker import Attr, call
from hypothesis import strategies as st

_booleans = st.booleans()


# turbulence
TURBULENCE_HOSTILITY = {
    "cn2": hostile_real | hostile_choice,
    "elevation": hostile_real,
    "altitude": hostile_real,
    "outer_scale": hostile_real,
    "inner_scale": hostile_real,
    "hv_ground": hostile_real,
    "hv_wind": hostile_real,
}
TURBULENCE_METHODS = {
    "fried_parameter": ("wavelength", "path_length", "wave"),
    "cn2_at_range": ("z",),
    "rytov_variance": ("wavelength", "path_length"),
    "isoplanatic_angle": ("wavelength", "path_length"),
    "beam_wander_variance": ("wavelength", "waist_radius", "path_length"),
    "long_term_radius": ("wavelength", "waist_radius", "path_length"),
    "short_term_radius": ("wavelength", "waist_radius", "path_length"),
}
_turbulence_methods = st.sampled_from(sorted(TURBULENCE_METHODS))
PATH_HOSTILITY = {
    "waist_radius": hostile_real,
    "wavelength": hostile_real,
    "path_length": hostile_real,
    "wave": hostile_choice,
    "z": hostile_real,
}


@cached
@st.composite
def turbulence(draw, bad=None):
    r = draw(sanes)
    sane = {
        "cn2": r.often("hv57", lambda: r.log(1e-17, 1e-13)),
        "elevation": r.often(math.pi / 2, lambda: r.real(0.1, math.pi / 2)),
        "altitude": r.often(0.0, lambda: r.real(0.0, 3000.0)),
        "outer_scale": r.often(INF, lambda: r.real(1.0, 100.0)),
        "inner_scale": r.often(0.0, lambda: r.real(0.0, 0.01)),
    }
    kwargs = corrupt(draw, sane, TURBULENCE_HOSTILITY, bad)
    return call("Turbulence", kwargs.pop("cn2"), **kwargs)


@st.composite
def turbulence_method(draw):
    count = draw(corruptions)
    on_object = draw(_booleans)
    obj = draw(turbulence(bad=count if on_object else 0))
    name = draw(_turbulence_methods)
    r = draw(sanes)
    sane = {
        "waist_radius": r.waist(),
        "wavelength": r.wavelength(),
        "path_length": r.log(1.0, 2e4),
        "wave": r.choice(("spherical", "plane")),
        "z": r.real(0.0, 2e4),
    }
    kwargs = corrupt(
        draw,
        sane,
        {a: PATH_HOSTILITY[a] for a in TURBULENCE_METHODS[name]},
        0 if on_object else count,
    )
    return call(Attr(obj, name), *(kwargs[a] for a in TURBULENCE_METHODS[name]))
