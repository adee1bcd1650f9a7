"""Hypothesis strategies probing the calls that ask a system or a result one question:
parameters.replace, emitter_coupling, explain, full_overlap_range and first_signal_range, point and
detector images, optimal_focus_range.
"""

from __future__ import annotations

from _hostile_probes_fields import field_beam
from _hostile_values import (
    corrupt,
    corruptions,
    hostile_choice,
    hostile_count,
    hostile_pair,
    hostile_real,
    ranges,
    sanes,
    system,
    tolerance,
)
from _probe_worker import Attr, call
from hypothesis import strategies as st

_booleans = st.booleans()


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
