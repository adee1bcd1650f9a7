"""Hypothesis strategies for the probes of the analysis layer on top of the forward model (alignment
maps, the telecover test, sensitivities, overlap correction); see _hostile_probes.py, which lists
them in PROBES."""

from __future__ import annotations

from _hostile_values import (
    corrupt,
    corruptions,
    hostile_choice,
    hostile_count,
    hostile_real,
    ranges,
    sanes,
    system,
    tolerance,
)
from _probe_worker import Attr, call
from hypothesis import strategies as st

_explain_where = st.sampled_from(("system", "ranges", "tolerance"))


# ------------------------------------------------------------------------------------------
# alignment, telecover
ALIGNMENT_AXES = (
    "tilt_x",
    "tilt_y",
    "beam_offset_x",
    "beam_offset_y",
    "detector_offset_x",
    "detector_offset_y",
    "defocus",
)
_alignment_where = st.sampled_from(("system", "ranges", "axis", "tolerance"))


@st.composite
def alignment_map(draw):
    """lo.alignment_map over one or two sane or hostile axes (values, order, sizes), of a hostile
    system or ranges, or at a hostile tolerance."""
    count, where, r = draw(corruptions), draw(_alignment_where), draw(sanes)
    axes = r.sample(ALIGNMENT_AXES, r.randint(1, 2))
    kwargs = {}
    for axis in axes:
        scale = 2e-3 if axis == "defocus" else (1e-3 if axis.startswith("tilt") else 1e-2)
        low = 0.0 if axis == "defocus" else -scale
        kwargs[axis] = sorted({r.real(low, scale) for _ in range(r.randint(1, 4))})
    if count and where == "axis":
        bad_axis = axes[0]
        kwargs[bad_axis] = r.choice(
            (
                lambda: kwargs[bad_axis] + [draw(hostile_real)],
                lambda: kwargs[bad_axis][::-1] + kwargs[bad_axis],
                lambda: [],
                lambda: draw(hostile_real),
            )
        )()
    tol = draw(hostile_real) if count and where == "tolerance" else tolerance(r)
    return call(
        "alignment_map",
        draw(system(bad=count if where == "system" else 0)),
        draw(ranges(bad=count if where == "ranges" else 0, max_size=3)),
        tolerance=tol,
        **kwargs,
    )


TELECOVER_HOSTILITY = {
    "sectors": hostile_choice,
    "tolerance": hostile_real,
    "threads": hostile_count,
}
_telecover_where = st.sampled_from(("system", "ranges", "options", "mask"))


@st.composite
def telecover(draw):
    """lo.telecover of a hostile system or ranges, with hostile options, or through a mask with a
    hostile sector (angles, radii)."""
    count, where, r = draw(corruptions), draw(_telecover_where), draw(sanes)
    sane = {"sectors": "quadrants", "tolerance": tolerance(r), "threads": r.choice((0, 1, 2))}
    kwargs = corrupt(draw, sane, TELECOVER_HOSTILITY, count if where == "options" else 0)
    if where == "mask":
        start = r.real(-3.0, 3.0)
        sector = {
            "start_angle": start,
            "stop_angle": start + r.real(0.1, 3.0),
            "inner_radius": r.real(0.0, 0.03),
        }
        if count:
            sector[r.choice(sorted(sector))] = draw(hostile_real)
        kwargs["sectors"] = call("ApertureMask", (call("Sector", **sector),))
    return call(
        "telecover",
        draw(system(bad=count if where == "system" else 0)),
        draw(ranges(bad=count if where == "ranges" else 0, max_size=4)),
        **kwargs,
    )


SENSITIVITY_PATHS = (
    "beam.tilt[0]",
    "beam.offset[1]",
    "detector.defocus",
    "detector.radius",
    "beam.divergence",
)


@st.composite
def sensitivity(draw):
    """lo.sensitivity of sane or hostile parameter paths, of a hostile system or ranges."""
    count, where, r = draw(corruptions), draw(_explain_where), draw(sanes)
    paths = r.sample(SENSITIVITY_PATHS, r.randint(1, 2))
    if count and where == "tolerance":
        paths = [draw(hostile_choice)] + paths[1:]
    return call(
        "sensitivity",
        draw(system(bad=count if where == "system" else 0)),
        draw(ranges(bad=count if where == "ranges" else 0, max_size=3)),
        paths,
    )


CORRECT_HOSTILITY = {"min_overlap": hostile_real}


@st.composite
def correct(draw):
    """lo.correct of a signal by a sane overlap curve, with hostile signal values or threshold."""
    count, r = draw(corruptions), draw(sanes)
    z = r.ranges(max_size=5)
    overlap = call("overlap", draw(system(bad=0)), z, "rt")
    signal = [r.log(1e-3, 1e3) for _ in z]
    if count and r.random() < 0.5:
        signal[r.randrange(len(signal))] = draw(hostile_real)
    kwargs = corrupt(draw, {"min_overlap": r.real(0.01, 0.9)}, CORRECT_HOSTILITY, count)
    return call("correct", z, signal, overlap, **kwargs)


# ------------------------------------------------------------------------------------------
# the empirical drift model of a series of curves
@st.composite
def empirical_drift(draw):
    """lo.empirical_drift of 3-5 sane positive curves, with a hostile value in one curve, the
    covariate or the reference, then its predict at a sane or hostile covariate."""
    count, r = draw(corruptions), draw(sanes)
    z = r.ranges(max_size=5)
    n = r.randrange(3, 6)
    curves = [[r.real(0.01, 1.0) for _ in z] for _ in range(n)]
    covariate = [r.real(250.0, 320.0) for _ in range(n)]
    reference = [r.real(0.01, 1.0) for _ in z]
    for _ in range(count):
        target = r.choice((curves[r.randrange(n)], covariate, reference))
        target[r.randrange(len(target))] = draw(hostile_real)
    model = call("empirical_drift", z, curves, covariate, reference)
    x = draw(hostile_real) if count and r.random() < 0.3 else r.real(250.0, 320.0)
    return call(Attr(model, "predict"), z, [x])
