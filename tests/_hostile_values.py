"""Hypothesis strategies for hostile-input probes: pools of hostile values, sane values near the
paper's Table 1, and the lidar system's parts built from them as :class:`Call` trees.

A probe is mostly sane with one or two hostile values in it, so that each hostile value reaches the
code behind the checks it passes instead of stopping at the first check of a call full of garbage.

Hypothesis draws the structure of a probe: which parameters turn hostile and their hostile values.
The sane values around them come from a :class:`Sane` generator seeded by one hypothesis draw per
part, since a hypothesis draw costs ~0.1 ms and a system has some twenty sane values: this keeps
generation at about a millisecond a probe, well below what most probes cost to run.
"""

from __future__ import annotations

import functools
import math
import random

from _probe_worker import call
from hypothesis import strategies as st

NAN, INF = math.nan, math.inf
MAX_FLOAT = 1.7976931348623157e308

#: Non-finite, signed-zero, subnormal and astronomically large reals, and a plain negative one.
HOSTILE_REALS = (
    NAN,
    INF,
    -INF,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    1e-300,
    1e300,
    -1e300,
    MAX_FLOAT,
    -MAX_FLOAT,
    -1.0,
)
#: Integers around the limits of C int, unsigned, int64 and double.
HUGE_INTS = (2**31 - 1, 2**31, 2**32, 2**40, 2**63 - 1, 2**64, 10**400, -(10**400))
#: Things that are not numbers, or numbers in disguise.
JUNK = (True, False, "0", "1e-3", "", None, (True, False), ("0", "0"), [1e-3], (1.0, 2.0, 3.0), {})
#: Hostile (x, y) pairs.
HOSTILE_PAIRS = (
    (NAN, 0.0),
    (0.0, INF),
    (-INF, 0.0),
    (1e300, 0.0),
    (1e30, 0.0),
    (5e-324, 5e-324),
    (MAX_FLOAT, -MAX_FLOAT),
    (10**400, 0),
    (2**63 - 1, 0),
    (True, False),
    ("0", "0"),
    (None, None),
    (1.0,),
    (1.0, 2.0, 3.0),
    [[0.0, 0.0]],
    "xy",
    None,
    0.0,
    (),
)
#: Hostile sample counts: C-integer limits, grids too small, odd or too large, and non-integers.
HOSTILE_COUNTS = HUGE_INTS + (
    -1,
    0,
    1,
    2,
    3,
    7,
    15,
    17,
    16383,
    16384,
    1.0,
    64.0,
    2.5,
    NAN,
    INF,
    True,
    False,
    "64",
    None,
    (64,),
)
#: Hostile names for string choices (method, fo_path, width_law, ...).
HOSTILE_CHOICES = ("", "RT", "Fo", "gaussian ", "2D", "auto\x00", None, 0, 1, True, ("rt",), b"rt")

hostile_real = st.sampled_from(HOSTILE_REALS + HUGE_INTS + JUNK)
hostile_pair = st.sampled_from(HOSTILE_PAIRS) | st.tuples(
    st.sampled_from(HOSTILE_REALS + HUGE_INTS), st.just(0.0)
)
hostile_count = st.sampled_from(HOSTILE_COUNTS)
hostile_choice = st.sampled_from(HOSTILE_CHOICES)
#: An object of the wrong kind where a system part, a field or a turbulence is expected.
hostile_object = (
    st.sampled_from((None, 1.0, "paper_table1", (), {}))
    | st.just(call("paper_table1"))
    | st.just(call("Telescope"))
    | st.just(call("Aberrations"))
)

#: How many of a call's own parameters a probe makes hostile (0: the sane call itself).
corruptions = st.sampled_from((0, 1, 1, 1, 2))


class Sane(random.Random):
    """Sane values within given bounds; one in ten is exactly a bound."""

    def real(self, low: float, high: float) -> float:
        u = self.random()
        return low if u < 0.05 else high if u < 0.1 else self.uniform(low, high)

    def log(self, low: float, high: float) -> float:
        """Log-uniform in [low, high] (for bounds decades apart)."""
        u = self.random()
        return (
            low
            if u < 0.05
            else high
            if u < 0.1
            else math.exp(self.uniform(math.log(low), math.log(high)))
        )

    def often(self, value, otherwise, p: float = 0.5):
        """``value`` with probability p, else ``otherwise()``."""
        return value if self.random() < p else otherwise()

    def pair(self, limit: float) -> tuple:
        """(0, 0) half of the time, else a pair within ±limit."""
        return self.often((0.0, 0.0), lambda: (self.real(-limit, limit), self.real(-limit, limit)))

    def wavelength(self) -> float:
        """m: a common laser line, or anything from 250 nm to 2 µm."""
        return self.often(self.choice((355e-9, 532e-9, 1064e-9)), lambda: self.real(250e-9, 2e-6))

    def waist(self) -> float:
        """m: a 1/e² waist radius from 0.2 to 5 mm."""
        return self.log(2e-4, 5e-3)

    def ranges(self, low: float = 2.0, high: float = 2e4, max_size: int = 6) -> list:
        """1 to ``max_size`` distinct increasing ranges (m), log-uniform in [low, high]."""
        return sorted({self.log(low, high) for _ in range(self.randint(1, max_size))})


sanes = st.integers(0, 2**32 - 1).map(Sane)


def tolerance(r) -> float:
    """A sane RT tolerance: 1e-4, 1e-3 or 1e-2, or log-uniform in [1e-6, 0.5]."""
    return r.often(r.choice((1e-4, 1e-3, 1e-2)), lambda: r.log(1e-6, 0.5))


def cached(factory):
    """One strategy object per set of arguments: hypothesis validates each new object on its first
    draw."""
    return functools.lru_cache(maxsize=None)(factory)


@cached
def _names(names: tuple):
    return st.sampled_from(names)


def corrupt(draw, sane: dict, hostile: dict, bad=None) -> dict:
    """``sane`` kwargs with ``bad`` (default: drawn from ``corruptions``) of the parameters named
    in ``hostile`` replaced by a draw of their hostile strategy (``draw`` is a composite
    strategy's)."""
    kwargs = dict(sane)
    count = draw(corruptions) if bad is None else bad
    names = _names(tuple(sorted(hostile)))
    for _ in range(count):
        name = draw(names)
        kwargs[name] = draw(hostile[name])
    return kwargs


#: A divergence below the diffraction limit λ/(π w0) (M² < 1), as the factor on that limit.
BELOW_DIFFRACTION = "below diffraction"
GAUSSIAN_BEAM_HOSTILITY = {
    "wavelength": hostile_real,
    "waist_radius": hostile_real,
    "offset": hostile_pair,
    "tilt": hostile_pair,
    "width_law": hostile_choice,
    "divergence": hostile_real
    | st.sampled_from((0.5, 0.999)).map(lambda m2: (BELOW_DIFFRACTION, m2)),
}


@cached
@st.composite
def gaussian_beam(draw, bad=None):
    r = draw(sanes)
    wl, w0 = r.wavelength(), r.waist()
    diffraction = wl / (math.pi * w0)
    sane = {
        "wavelength": wl,
        "waist_radius": w0,
        "divergence": r.often(None, lambda: r.real(1.0, 4.0) * diffraction),
        "offset": r.pair(0.2),
        "tilt": r.pair(1e-3),
        "width_law": r.often("gaussian", lambda: "linear", 0.75),
    }
    kwargs = corrupt(draw, sane, GAUSSIAN_BEAM_HOSTILITY, bad)
    if isinstance(kwargs["divergence"], tuple) and kwargs["divergence"][:1] == (BELOW_DIFFRACTION,):
        kwargs["divergence"] = kwargs["divergence"][1] * diffraction
    return call("GaussianBeam", **kwargs)


ABERRATION_HOSTILITY = {
    "zernike": st.dictionaries(
        st.sampled_from((0, -1, 1001, 2**31, 10**400, True, "11", 1.5, None)),
        st.just(5e-8),
        min_size=1,
        max_size=1,
    )
    | st.dictionaries(st.integers(1, 40), hostile_real, min_size=1, max_size=1)
    | st.sampled_from(([11, 5e-8], None, "11", 5e-8, ((11, 5e-8),))),
    "w040": hostile_real,
    "w131": hostile_real,
    "w222": hostile_real,
    "field_radius": hostile_real,
}


@cached
@st.composite
def aberrations(draw, bad=None):
    r = draw(sanes)
    field_radius = r.often(0.0, lambda: 1e-3)
    sane = {
        "zernike": {r.randint(2, 37): r.real(-80e-9, 80e-9) for _ in range(r.randint(0, 3))},
        "w040": r.often(0.0, lambda: r.real(-5e-7, 5e-7)),
        "w222": r.real(-1e-6, 1e-6) if field_radius else 0.0,
        "field_radius": field_radius,
    }
    return call("Aberrations", **corrupt(draw, sane, ABERRATION_HOSTILITY, bad))


TELESCOPE_HOSTILITY = {
    "diameter": hostile_real,
    "focal_length": hostile_real,
    "obstruction_radius": hostile_real,
    "obstruction_distance": hostile_real,
    "aberrations": hostile_object | aberrations(bad=1),
}


@cached
@st.composite
def telescope(draw, bad=None, aberrated=False):
    r = draw(sanes)
    diameter, obstructed = r.real(0.05, 0.5), r.random() < 0.5
    sane = {
        "diameter": diameter,
        "focal_length": r.real(0.3, 3.0),
        "obstruction_radius": r.real(0.0, 0.3) * diameter if obstructed else 0.0,
        "obstruction_distance": r.real(0.0, 1.0) if obstructed else 0.0,
    }
    if aberrated:
        sane["aberrations"] = draw(aberrations(bad=0))
    return call("Telescope", **corrupt(draw, sane, TELESCOPE_HOSTILITY, bad))


DETECTOR_HOSTILITY = {
    "radius": hostile_real,
    "defocus": hostile_real,
    "offset": hostile_pair,
    "numerical_aperture": hostile_real,
}


@cached
@st.composite
def detector(draw, bad=None):
    r = draw(sanes)
    sane = {
        "radius": r.log(2e-5, 2e-3),
        "defocus": r.often(0.0, lambda: r.real(-2e-3, 1e-2)),
        "offset": r.pair(1e-3),
        "numerical_aperture": r.often(None, lambda: r.real(0.05, 0.6)),
    }
    return call("Detector", **corrupt(draw, sane, DETECTOR_HOSTILITY, bad))


FROM_FOV_HOSTILITY = {
    "fov": hostile_real,
    "focal_length": hostile_real,
    "defocus": hostile_real,
    "offset": hostile_pair,
    "numerical_aperture": hostile_real,
}


@cached
@st.composite
def detector_from_fov(draw, bad=None):
    r = draw(sanes)
    sane = {
        "fov": r.log(1e-4, 5e-3),
        "focal_length": r.real(0.3, 3.0),
        "defocus": r.often(0.0, lambda: r.real(0.0, 1e-2)),
        "offset": r.pair(1e-3),
        "numerical_aperture": r.often(None, lambda: r.real(0.05, 0.6)),
    }
    return call("Detector.from_fov", **corrupt(draw, sane, FROM_FOV_HOSTILITY, bad))


_parts = st.sampled_from(("beam", "telescope", "detector", "object"))
_part_names = st.sampled_from(("beam", "telescope", "detector"))


@cached
@st.composite
def system(draw, bad=None, aberrated=False, beam=None):
    """A LidarSystem with ``bad`` (default: drawn) hostile values in one of its parts, or a hostile
    part; ``beam``: a strategy for its beam (default: a Gaussian beam)."""
    count = draw(corruptions) if bad is None else bad
    part = draw(_parts) if count else None
    parts = {
        "beam": draw(beam)
        if beam is not None
        else draw(gaussian_beam(bad=count if part == "beam" else 0)),
        "telescope": draw(telescope(bad=count if part == "telescope" else 0, aberrated=aberrated)),
        "detector": draw(detector(bad=count if part == "detector" else 0)),
    }
    if part == "object":
        parts[draw(_part_names)] = draw(hostile_object)
    return call("LidarSystem", **parts)


HOSTILE_RANGES = st.sampled_from(
    (
        [],
        [[100.0]],
        "100",
        None,
        100.0,
        [100.0, 100.0],
        [200.0, 100.0],
        [5e-324],
        [1e300],
        [MAX_FLOAT],
        [-1.0],
        [0.0],
        [-0.0],
        [0.5],
        [10**400],
        [True],
        ["100"],
        [100.0, NAN],
        [1e-300, 1.0],
        (1e-3, 1e300),
    )
)
_whole_or_one, _index = st.booleans(), st.integers(0, 5)


@cached
@st.composite
def ranges(draw, low: float = 2.0, high: float = 2e4, bad=None, max_size: int = 6):
    """1 to ``max_size`` increasing ranges (m) in [low, high]; hostile: one replaced, or a hostile
    container."""
    values = draw(sanes).ranges(low, high, max_size)
    if not (draw(corruptions) if bad is None else bad):
        return values
    if draw(_whole_or_one):
        return draw(HOSTILE_RANGES)
    i = draw(_index) % len(values)
    return values[:i] + [draw(hostile_real)] + values[i + 1 :]
