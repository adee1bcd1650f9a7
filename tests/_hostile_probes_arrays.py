"""Hypothesis strategies probing the entry points that return a plain NumPy array or a tuple: a
phase screen (lo.phase_screen) and the pupil polynomials (lo.zernike, lo.noll_index), each with
hostile values among sane ones. Their arrays must be finite (tests/_probe_worker.py judges them)."""

from __future__ import annotations

from _hostile_values import INF, corrupt, hostile_count, hostile_real, sanes
from _probe_worker import call
from hypothesis import strategies as st

PHASE_SCREEN_HOSTILITY = {
    "n": hostile_count,
    "spacing": hostile_real,
    "r0": hostile_real,
    "outer_scale": hostile_real,
    "inner_scale": hostile_real,
    "seed": hostile_count,
    "index": hostile_count,
}


@st.composite
def phase_screen(draw):
    r = draw(sanes)
    sane = {
        "n": r.choice((8, 16, 32, 64, 128)),
        "spacing": r.log(1e-3, 0.1),
        "r0": r.often(INF, lambda: r.log(0.01, 1.0), p=0.1),
        "outer_scale": r.often(INF, lambda: r.real(1.0, 100.0)),
        "inner_scale": r.often(0.0, lambda: r.real(0.0, 0.01)),
        "seed": r.randint(0, 2**63),
        "index": r.randint(0, 1000),
    }
    return call("phase_screen", **corrupt(draw, sane, PHASE_SCREEN_HOSTILITY))


NOLL_HOSTILITY = {"j": hostile_count | hostile_real}
ZERNIKE_HOSTILITY = {"j": hostile_count | hostile_real, "x": hostile_real, "y": hostile_real}


@st.composite
def noll_index(draw):
    return call("noll_index", **corrupt(draw, {"j": draw(sanes).randint(1, 1000)}, NOLL_HOSTILITY))


@st.composite
def zernike(draw):
    r = draw(sanes)
    sane = {"j": r.randint(1, 231), "x": r.real(-1.0, 1.0), "y": r.real(-1.0, 1.0)}
    return call("zernike", **corrupt(draw, sane, ZERNIKE_HOSTILITY))
