"""Systems carry the bounds their sources allow (``LidarSystem.fit_bounds``, set by the instrument
presets): every fit takes them as default bounds under the caller's ``bounds`` (the caller's win,
path by path), ``fit_bounds=None`` switches them off; the value is validated, pickled, compared
and kept by ``parameters.replace``."""

import dataclasses
import pickle
import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.analysis.fitting.families import LADDER
from lidar_overlap.analysis.fitting.ladder import _family_bounds
from lidar_overlap.analysis.fitting.multi_inputs import checked_bounds, path_bounds
from lidar_overlap.analysis.fitting.problem import fit_problem
from lidar_overlap.model.instruments import (
    CHM15K_OFFSET,
    POLLYXT_DIVERGENCE,
    chm15k,
    chm15k_bounds,
    pollyxt,
    pollyxt_bounds,
)

pytest.importorskip("scipy")

Z = np.linspace(150.0, 1200.0, 12)
FAST = dict(method="rt", tolerance=1e-4, threads=1)
#: The unit's axes 0.09 m apart: closer than the CHM15k's expanded beam allows (0.095 m).
TOO_CLOSE = 0.09


def _close_curve():
    truth = lo.parameters.replace(chm15k(), {"beam.offset[0]": TOO_CLOSE})
    return lo.overlap(truth, Z, "rt", tolerance=1e-6).overlap


def _fit(system, g, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return lo.fit(system, Z, g, 1e-3, free=["beam.offset[0]"], **FAST, **options)


def test_presets_carry_their_bounds_and_plain_systems_none():
    assert chm15k().fit_bounds == chm15k_bounds()
    assert pollyxt("near", 532e-9).fit_bounds == pollyxt_bounds()
    assert lo.paper_table1().fit_bounds is None


def test_a_fit_of_a_preset_stops_on_its_bound_unless_the_caller_widens_or_drops_it():
    g = _close_curve()
    fit = _fit(chm15k(), g)  # no bounds given: the preset's
    assert fit.at_bounds == ("beam.offset[0]",)
    assert fit.parameters["beam.offset[0]"] == pytest.approx(CHM15K_OFFSET[0], abs=1e-9)
    # the caller's bounds win (a bare pair names both scalars), and so does switching them off
    for system, bounds in (
        (chm15k(), {"beam.offset[0]": (0.05, 0.5)}),
        (dataclasses.replace(chm15k(), fit_bounds=None), None),
    ):
        free = _fit(system, g, bounds=bounds)
        assert free.at_bounds == ()
        assert free.parameters["beam.offset[0]"] == pytest.approx(TOO_CLOSE, abs=1e-6)


def test_the_problem_takes_the_free_paths_bounds_the_ladder_all_and_the_caller_wins():
    g = _close_curve()
    problem = fit_problem(chm15k(), Z, g, 1e-3, free=["beam.tilt[0]"])
    assert problem.bounds is None  # the preset bounds no free path
    problem = fit_problem(chm15k(), Z, g, 1e-3, free=["beam.tilt[0]", "beam.divergence"])
    assert dict(problem.bounds) == {"beam.divergence": chm15k_bounds()["beam.divergence"]}
    problem = fit_problem(chm15k(), Z, g, 1e-3, free="auto")
    assert dict(problem.bounds) == chm15k_bounds()  # the ladder picks its families' paths
    mine = {"beam.offset": (0.0, 0.4)}  # a bare pair: both scalars, each over the preset's
    problem = fit_problem(chm15k(), Z, g, 1e-3, free="auto", bounds=mine)
    assert dict(problem.bounds) == {
        "beam.divergence": chm15k_bounds()["beam.divergence"],
        "beam.offset[0]": (0.0, 0.4),
        "beam.offset[1]": (0.0, 0.4),
    }


def test_a_bare_pair_bounds_the_scalars_the_fit_frees_in_every_fit():
    """Bounds are matched by scalar path, as free paths are: a bare pair's bound for those of its
    scalars the fit frees (both when it frees both or the ladder chooses), any spelling of an
    index, a scalar bounded twice refused naming both keys."""
    g = _close_curve()
    pair, one = {"beam.offset": (0.05, 0.5)}, ["beam.offset[0]"]
    for bounds in (pair, {"beam.offset[00]": (0.05, 0.5)}):
        assert dict(fit_problem(chm15k(), Z, g, 1e-3, free=one, bounds=bounds).bounds) == {
            "beam.offset[0]": (0.05, 0.5)
        }
        assert checked_bounds(bounds, tuple(one)) == {"beam.offset[0]": (0.05, 0.5)}  # joint
    both = fit_problem(chm15k(), Z, g, 1e-3, free=["beam.offset"], bounds=pair).bounds
    assert dict(both) == {"beam.offset[0]": (0.05, 0.5), "beam.offset[1]": (0.05, 0.5)}
    # the ladder takes its family's scalar from the pair, no longer dropping the bare key
    ladder = fit_problem(chm15k(), Z, g, 1e-3, free="auto", bounds=pair).bounds
    assert _family_bounds(LADDER[0], chm15k(), list(LADDER[0].paths), ladder) == {
        "beam.offset[0]": (0.05, 0.5)
    }
    twice = {"beam.offset": (0.05, 0.5), "beam.offset[0]": (0.1, 0.4)}
    with pytest.raises(ValueError, match=r"bounds: beam.offset\[0\] is bounded twice"):
        fit_problem(chm15k(), Z, g, 1e-3, free=one, bounds=twice)
    with pytest.raises(ValueError, match=r"fit_bounds: beam.tilt\[1\] is bounded twice"):
        dataclasses.replace(chm15k(), fit_bounds={"beam.tilt": (-1, 1), "beam.tilt[01]": (0, 1)})
    # a pair of which nothing is free is still refused, naming its scalar
    with pytest.raises(ValueError, match=r"bounds: 'detector.offset\[0\]' is not a free"):
        _fit(chm15k(), g, bounds={"detector.offset": (0.0, 0.1), "beam.offset": (0.0, 0.5)})


def test_a_start_outside_the_presets_bound_is_named():
    with pytest.raises(ValueError, match=r"beam.offset\[0\].*excludes the start 0.05.*fit_bounds"):
        _fit(chm15k(beam_offset=0.05), _close_curve())


def test_a_telecover_fit_takes_the_presets_bounds_under_the_callers():
    """The telecover fit of a CHM15k whose axes are 0.09 m apart stops on the preset's 0.095 m
    bound; the caller's bound (a bare pair) wins; a start outside is refused naming fit_bounds."""
    z = np.geomspace(300.0, 1500.0, 5)
    truth = lo.parameters.replace(chm15k(), {"beam.offset[0]": TOO_CLOSE})
    measured = lo.telecover(truth, z, tolerance=1e-6)
    options = dict(free=["beam.offset[0]"], tolerance=1e-4, threads=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # noise-free: the scatter warning
        held = lo.fit_telecover(chm15k(), z, measured, **options)
        free = lo.fit_telecover(
            chm15k(), z, measured, bounds={"beam.offset": (0.05, 0.5)}, **options
        )
    assert held.at_bounds == ("beam.offset[0]",)
    assert held.parameters["beam.offset[0]"] == pytest.approx(CHM15K_OFFSET[0], abs=1e-9)
    assert free.at_bounds == ()
    assert free.parameters["beam.offset[0]"] == pytest.approx(TOO_CLOSE, abs=1e-6)
    with pytest.raises(ValueError, match=r"beam.offset\[0\].*excludes the start 0.05.*fit_bounds"):
        lo.fit_telecover(chm15k(beam_offset=0.05), z, measured, **options)


def test_fits_of_several_curves_intersect_each_systems_bounds():
    systems = [chm15k(), pollyxt()]
    low, high = path_bounds(systems, "beam.divergence", None)
    assert (low, high) == (POLLYXT_DIVERGENCE[0], chm15k_bounds()["beam.divergence"][1])
    # the caller's bounds replace every system's
    assert path_bounds(systems, "beam.divergence", {"beam.divergence": (1e-5, 2e-4)}) == (
        1e-5,
        2e-4,
    )


def test_joint_and_drift_fits_stop_on_the_presets_bound():
    g = _close_curve()
    rng = np.random.default_rng(3)
    curves = [g + rng.normal(0.0, 1e-3, Z.size) for _ in range(3)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        joint = lo.fit_joint(
            [chm15k()] * 2, [Z] * 2, curves[:2], sigma=[1e-3] * 2, shared=["beam.offset[0]"],
            **FAST,
        )  # fmt: skip
        drift = lo.fit_drift(
            chm15k(), Z, np.array(curves), [280.0, 290.0, 300.0], sigma=1e-3,
            free=["beam.offset[0]"], drifting=[], **FAST,
        )  # fmt: skip
    assert joint.at_bounds == ("beam.offset[0]",) and drift.at_bounds == ("beam.offset[0]",)


def test_fit_bounds_is_a_checked_read_only_value():
    s = chm15k()
    again = pickle.loads(pickle.dumps(s))
    assert again == s and hash(again) == hash(s) and again.fit_bounds == s.fit_bounds
    assert dataclasses.replace(s, fit_bounds=None) != s
    assert "fit_bounds" in repr(s)
    moved = lo.parameters.replace(s, {"beam.tilt[0]": 1e-5})
    assert moved.fit_bounds == s.fit_bounds  # a fitted system keeps them
    both = dataclasses.replace(s, fit_bounds={"beam.tilt": (-1e-3, 1e-3)})
    assert dict(both.fit_bounds) == {"beam.tilt[0]": (-1e-3, 1e-3), "beam.tilt[1]": (-1e-3, 1e-3)}
    assert dataclasses.replace(s, fit_bounds={}).fit_bounds is None
    with pytest.raises(TypeError):
        s.fit_bounds["beam.divergence"] = (0.0, 1.0)  # type: ignore[index]


@pytest.mark.parametrize(
    "bounds, match",
    [
        ("beam.divergence", "fit_bounds = 'beam.divergence' is invalid"),
        ({"beam.nothing": (0.0, 1.0)}, "fit_bounds: parameter 'beam.nothing'"),
        ({"beam.divergence": (2e-4, 1e-4)}, r"fit_bounds\['beam.divergence'\].*low < high"),
        ({"beam.divergence": (0.0, np.nan)}, r"fit_bounds\['beam.divergence'\]"),
        ({"beam.divergence": (0.0, np.inf)}, r"fit_bounds\['beam.divergence'\]"),
        ({"beam.divergence": (0.0, 1e-3, 2e-3)}, r"fit_bounds\['beam.divergence'\]"),
        ({"beam.divergence": "x"}, r"fit_bounds\['beam.divergence'\]"),
        ({3: (0.0, 1.0)}, "fit_bounds"),
    ],
)
def test_bad_fit_bounds_are_refused_naming_them(bounds, match):
    with pytest.raises(ValueError, match=match):
        dataclasses.replace(chm15k(), fit_bounds=bounds)


def test_a_search_keeps_a_start_on_the_presets_bound_within_it():
    """chm15k()'s divergence starts on its upper bound, 0.15 mrad; the global search takes it in
    its logarithm, and exp(log(0.15e-3)) is one rounding above it: the cube's values stay within
    the bounds (a search's polish from a value beyond them was refused)."""
    from lidar_overlap.analysis.fitting.global_search import UnitCube

    high = chm15k_bounds()["beam.divergence"][1]
    assert np.exp(np.log(high)) > high  # the rounding this guards against
    cube = UnitCube(np.array([1e-5]), np.array([high]), np.array([True]))
    assert cube.values(np.ones((1, 1)))[0, 0] == high
    assert cube.values(np.zeros((1, 1)))[0, 0] >= 1e-5
