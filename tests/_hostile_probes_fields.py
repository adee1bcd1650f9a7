"""Hypothesis strategies probing sampled fields: Field.gaussian, Field from raw values, propagate,
FieldBeam and FlatTopBeam, each with hostile values among sane ones.
"""

from __future__ import annotations

import math

from _hostile_values import (
    INF,
    cached,
    corrupt,
    corruptions,
    hostile_choice,
    hostile_count,
    hostile_object,
    hostile_pair,
    hostile_real,
    sanes,
)
from _probe_worker import call
from hypothesis import strategies as st

_booleans = st.booleans()


FIELD_HOSTILITY = {
    "wavelength": hostile_real,
    "waist_radius": hostile_real,
    "n": hostile_count,
    "spacing": hostile_real,
    "center": hostile_pair,
    "power": hostile_real,
}


@cached
@st.composite
def gaussian_field(draw, bad=None, n=(8, 16, 32, 64, 128)):
    r = draw(sanes)
    w0 = r.waist()
    sane = {
        "wavelength": r.wavelength(),
        "waist_radius": w0,
        "n": r.choice(n),
        "spacing": r.real(0.05, 0.5) * w0,
        "center": r.pair(1e-4),
        "power": r.log(1e-3, 10.0),
    }
    return call("Field.gaussian", **corrupt(draw, sane, FIELD_HOSTILITY, bad))


_hostile_shapes = st.sampled_from(((7, 7), (8,), (8, 10), (0, 0), (2, 2), (8, 8, 2), ()))
VALUES_HOSTILITY = {
    "values": _hostile_shapes.map(lambda s: call("np.ones", s, complex))
    | st.sampled_from(
        (
            call("np.full", (8, 8), complex(math.nan, 0.0)),
            call("np.full", (8, 8), complex(0.0, INF)),
            call("np.full", (8, 8), 1e300),
            call("np.full", (8, 8), "a"),
            None,
            "values",
            1.0,
            [[1.0] * 8] * 7,
        )
    ),
    "spacing": hostile_real,
    "wavelength": hostile_real,
}


@st.composite
def field_from_values(draw):
    r = draw(sanes)
    n = r.choice((8, 16, 32))
    sane = {
        "values": call("np.full", (n, n), complex(r.real(0.0, 10.0), r.real(-1.0, 1.0))),
        "spacing": r.log(1e-6, 1e-3),
        "wavelength": r.wavelength(),
    }
    kwargs = corrupt(draw, sane, VALUES_HOSTILITY)
    return call("Field", kwargs["values"], kwargs["spacing"], kwargs["wavelength"])


PROPAGATION_HOSTILITY = {
    "distance": hostile_real,
    "method": hostile_choice,
    "output_spacing": hostile_real,
    "grid_size": hostile_count | st.sampled_from(("AUTO", "auto ", 129, 257)),
}


@st.composite
def propagation(draw):
    count = draw(corruptions)
    in_field = draw(_booleans)
    source = draw(gaussian_field(bad=count if in_field else 0, n=(16, 32, 64, 128)))
    r = draw(sanes)
    sane = {
        "distance": r.log(0.01, 1e4) * r.choice((1, 1, 1, -1)),
        "method": r.choice(("auto", "angular_spectrum", "fresnel", "fraunhofer")),
        "output_spacing": r.often(None, lambda: r.log(1e-6, 1e-2)),
        "grid_size": r.choice((None, None, "auto", 128, 256)),
    }
    return call(
        "propagate", source, **corrupt(draw, sane, PROPAGATION_HOSTILITY, 0 if in_field else count)
    )


FIELD_BEAM_HOSTILITY = {"field": hostile_object, "offset": hostile_pair, "tilt": hostile_pair}


@cached
@st.composite
def field_beam(draw, bad=None):
    count = draw(corruptions) if bad is None else bad
    on_field = draw(_booleans)
    source = draw(gaussian_field(bad=count if on_field else 0, n=(32, 64)))
    r = draw(sanes)
    sane = {"offset": r.pair(0.1), "tilt": r.pair(5e-4)}
    kwargs = corrupt(draw, sane, FIELD_BEAM_HOSTILITY, 0 if on_field else count)
    return call("FieldBeam", kwargs.pop("field", source), **kwargs)


FLAT_TOP_HOSTILITY = {
    name: hostile_real
    for name in (
        "wavelength",
        "waist_radius",
        "angular_diameter",
        "samples_per_waist",
        "tolerance",
        "max_error",
        "power",
        "edge_width",
    )
}
FLAT_TOP_HOSTILITY.update(
    grid=hostile_count, max_iterations=hostile_count, offset=hostile_pair, tilt=hostile_pair
)


@st.composite
def flat_top(draw):
    r = draw(sanes)
    w0, wl = r.waist(), r.wavelength()
    sane = {
        "wavelength": wl,
        "waist_radius": w0,
        "angular_diameter": r.real(3.0, 8.0) * wl / (math.pi * w0),
        "grid": r.choice((64, 128)),
        "samples_per_waist": r.choice((4.0, 8.0)),
        "max_iterations": r.randint(1, 30),
        "tolerance": 1e-4,
        "max_error": 0.05,
        "power": r.log(0.1, 10.0),
        "offset": r.pair(0.1),
        "tilt": r.pair(5e-4),
    }
    kwargs = corrupt(draw, sane, FLAT_TOP_HOSTILITY)
    return call(
        "FlatTopBeam",
        kwargs.pop("wavelength"),
        kwargs.pop("waist_radius"),
        kwargs.pop("angular_diameter"),
        **kwargs,
    )
