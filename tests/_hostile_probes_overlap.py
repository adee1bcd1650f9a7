"""Hypothesis strategies probing lo.overlap: one per kind of computation (RT, radial and 2-D FO,
auto, field beams, turbulence, aberrations) with the hostile values in the system, the ranges or
the options, and the method objects (RT, FO, Auto) with hostile options.
"""

from __future__ import annotations

from _hostile_probes_fields import field_beam
from _hostile_probes_turbulence import turbulence
from _hostile_values import (
    corrupt,
    corruptions,
    hostile_choice,
    hostile_count,
    hostile_object,
    hostile_real,
    ranges,
    sanes,
    system,
    tolerance,
)
from _probe_worker import call
from hypothesis import strategies as st

_where = st.sampled_from(("system", "ranges", "options"))


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
