"""Hypothesis strategies for one probe of each public entry point of lidar_overlap, and how many
examples each gets.

Each strategy draws a :class:`Call` tree: a sane call near the paper's Table 1 with (usually) one or
two hostile values in the system, the ranges or the options. Valid work is kept small (at most 6
ranges, 8-128 sample grids, 1-3 turbulence realisations and screens) so that a probe costs
milliseconds; the expensive valid Fourier-optics paths get fewer examples.
"""

from __future__ import annotations

import math

import _hostile_probes_analysis as analysis
from _hostile_values import (
    INF,
    aberrations,
    cached,
    corrupt,
    corruptions,
    detector,
    detector_from_fov,
    gaussian_beam,
    hostile_choice,
    hostile_count,
    hostile_object,
    hostile_pair,
    hostile_real,
    ranges,
    sanes,
    system,
    telescope,
    tolerance,
)
from _probe_worker import Attr, call
from hypothesis import strategies as st

_booleans = st.booleans()
_where = st.sampled_from(("system", "ranges", "options"))

# ------------------------------------------------------------------------------------------
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


# ------------------------------------------------------------------------------------------ fields
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


# ------------------------------------------------------------------------------------------ overlap
OPTION_HOSTILITY = {
    "method": hostile_choice,
    "tolerance": hostile_real,
    "threads": hostile_count,
    "max_segments": hostile_count,
    "fo_path": hostile_choice,
    "beam_grid": hostile_count,
    "beam_window": hostile_real,
    "max_spectrum_grid": hostile_count,
    "turbulence": hostile_object | hostile_real,
    "realizations": hostile_count,
    "seed": hostile_count,
    "screens": hostile_count,
}
_rt_or_fo = st.sampled_from(("rt", "fo"))


@st.composite
def overlap_call(draw, kind: str, max_ranges: int = 6, low: float = 2.0):
    """overlap(system, ranges, method, **options) for one kind of computation, with the hostile
    values in the system, the ranges or the options."""
    count, where = draw(corruptions), draw(_where)
    bad = {w: (count if w == where else 0) for w in ("system", "ranges", "options")}
    beam = field_beam(bad=0) if kind == "field_beam" else None
    sys_ = draw(system(bad=bad["system"], aberrated=kind == "aberrated", beam=beam))
    z = draw(ranges(low=low, bad=bad["ranges"], max_size=max_ranges))
    r = draw(sanes)
    options = {"threads": r.choice((0, 1, 2))}
    if kind == "rt":
        options.update(method="rt", tolerance=tolerance(r), max_segments=r.choice((4000, 200)))
    elif kind == "radial":
        options.update(method="fo", fo_path=r.choice(("radial", "auto")))
    elif kind == "auto":
        options.update(method="auto", tolerance=tolerance(r))
    elif kind == "2d":
        options.update(
            method="fo",
            fo_path="2d",
            beam_grid=r.choice((32, 64, None)),
            beam_window=r.choice((None, 6.0, 10.0)),
            max_spectrum_grid=r.choice((256, 512, 1024)),
        )
    elif kind == "field_beam":
        options.update(method="fo", max_spectrum_grid=r.choice((256, 512, 1024)))
    elif kind == "turbulent":
        method = r.choice(("rt", "fo"))
        options.update(
            method=method,
            turbulence=draw(turbulence(bad=0)),
            realizations=r.randint(1, 3),
            seed=r.randint(0, 2**31 - 1),
        )
        if method == "fo":  # grids this coarse hold the beam's path only
            options.update(screens=r.randint(1, 3), beam_grid=r.choice((32, 64)), paths="transmit")
    elif kind == "aberrated":
        options.update(
            method=r.choice(("rt", "fo", "auto")),
            tolerance=tolerance(r),
            max_spectrum_grid=r.choice((256, 512, 1024)),
        )
    options = corrupt(draw, options, OPTION_HOSTILITY, bad["options"])
    return call("overlap", sys_, z, options.pop("method"), **options)


METHOD_HOSTILITY = {
    "tolerance": hostile_real,
    "max_segments": hostile_count,
    "rings": hostile_count,
    "ring_rays": hostile_count,
    "path": hostile_choice,
    "beam_grid": hostile_count,
    "beam_window": hostile_real,
    "max_spectrum_grid": hostile_count,
}


@st.composite
def overlap_method_object(draw):
    """overlap(system, ranges, <RT | FO | Auto object>), the hostile values in the method object's
    options (aberrated systems have their own probe: their ray fans cost seconds)."""
    count = draw(corruptions)
    sys_ = draw(system(bad=0))
    z = draw(ranges(low=20.0, bad=0, max_size=3))
    r = draw(sanes)
    kind = r.choice(("RT", "FO", "Auto"))
    sane = {
        "RT": {
            "tolerance": tolerance(r),
            "max_segments": r.choice((4000, 200)),
            "rings": r.choice((8, 48)),
            "ring_rays": r.choice((16, 128)),
        },
        "FO": {
            "path": r.choice(("auto", "radial", "2d")),
            "max_spectrum_grid": r.choice((256, 1024)),
        },
        "Auto": {"tolerance": tolerance(r)},
    }[kind]
    if kind == "FO" and sane["path"] == "2d":
        sane.update(beam_grid=r.choice((32, 64)), beam_window=r.choice((6.0, 10.0)))
    return call("overlap", sys_, z, call(kind, **corrupt(draw, sane, METHOD_HOSTILITY, count)))


PARAMETER_PATHS = (
    "beam.tilt[0]",
    "beam.offset[1]",
    "beam.divergence",
    "beam.waist_radius",
    "detector.defocus",
    "detector.radius",
    "detector.offset[0]",
    "telescope.diameter",
    "telescope.obstruction_radius",
    "telescope.aberrations.zernike[11]",
    "telescope.aberrations.w131",
)


@st.composite
def parameter_replace(draw):
    """parameters.replace(system, {path: value}) with a hostile path or value."""
    count, r = draw(corruptions), draw(sanes)
    path = draw(hostile_choice) if count and draw(_booleans) else r.choice(PARAMETER_PATHS)
    value = draw(hostile_real) if count else r.real(-1e-4, 1e-4)
    return call("parameters.replace", draw(system(bad=0)), {path: value})


COUPLING_HOSTILITY = {"z": hostile_real, "position": hostile_pair, "method": hostile_choice}


@st.composite
def emitter_coupling(draw, method: str):
    count, in_system = draw(corruptions), draw(_booleans)
    sys_ = draw(system(bad=count if in_system else 0))
    r = draw(sanes)
    sane = {"z": r.log(2.0, 2e4), "position": r.pair(0.2), "method": method}
    return call(
        "emitter_coupling",
        sys_,
        **corrupt(draw, sane, COUPLING_HOSTILITY, 0 if in_system else count),
    )


_explain_where = st.sampled_from(("system", "ranges", "tolerance"))


@st.composite
def explain(draw):
    count, where = draw(corruptions), draw(_explain_where)
    return call(
        "explain",
        draw(system(bad=count if where == "system" else 0)),
        draw(ranges(bad=count if where == "ranges" else 0)),
        draw(hostile_real) if count and where == "tolerance" else tolerance(draw(sanes)),
    )


_result_methods = st.sampled_from(("full_overlap_range", "first_signal_range"))


@st.composite
def result_method(draw):
    """full_overlap_range / first_signal_range of a sane RT result, with a hostile threshold or a
    curve too short to reach full overlap."""
    obj = call("overlap", draw(system(bad=0)), draw(ranges(bad=0)), "rt")
    threshold = draw(hostile_real) if draw(corruptions) else draw(sanes).real(1e-3, 0.999)
    return call(Attr(obj, draw(_result_methods)), threshold)


# ------------------------------------------------------------------------------------------ flat
# top, images
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


POINT_IMAGE_HOSTILITY = {"z": hostile_real, "n": hostile_count, "spacing": hostile_real}


@st.composite
def point_image(draw):
    count, in_system = draw(corruptions), draw(_booleans)
    sys_ = draw(system(bad=count if in_system else 0, aberrated=draw(_booleans)))
    r = draw(sanes)
    sane = {
        "z": r.log(20.0, 2e4),
        "n": r.choice((16, 32, 64, 128)),
        "spacing": r.often(None, lambda: r.log(1e-7, 1e-5)),
    }
    return call(
        "point_image", sys_, **corrupt(draw, sane, POINT_IMAGE_HOSTILITY, 0 if in_system else count)
    )


_one_in_five = st.integers(0, 4)
DETECTOR_IMAGE_HOSTILITY = {"z": hostile_real, "n": hostile_count}


@st.composite
def detector_image(draw):
    count, in_system = draw(corruptions), draw(_booleans)
    beam = field_beam(bad=0) if draw(_one_in_five) == 0 else None
    sys_ = draw(system(bad=count if in_system else 0, beam=beam))
    r = draw(sanes)
    sane = {"z": r.log(2.0, 2e4), "n": r.choice((16, 32, 64))}
    return call(
        "detector_image",
        sys_,
        **corrupt(draw, sane, DETECTOR_IMAGE_HOSTILITY, 0 if in_system else count),
    )


FOCUS_HOSTILITY = {"focal_length": hostile_real, "defocus": hostile_real}


@st.composite
def optimal_focus(draw):
    r = draw(sanes)
    sane = {"focal_length": r.real(0.1, 5.0), "defocus": r.often(0.0, lambda: r.log(1e-5, 0.05))}
    return call("optimal_focus_range", **corrupt(draw, sane, FOCUS_HOSTILITY))


#: Every entry point's probe strategy, and its examples in a run of the test suite (2,560 in all; a
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
    "alignment_map": (analysis.alignment_map(), 60),
    "telecover": (analysis.telecover(), 60),
    "sensitivity": (analysis.sensitivity(), 40),
    "correct": (analysis.correct(), 40),
}
