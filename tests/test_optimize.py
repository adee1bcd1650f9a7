"""Design optimisation: the smallest field of view is feasible and tight, a known misalignment is
recovered within the flatness of G at its maximum, the generic objective agrees, unreachable targets
and bad input are refused."""

import sys

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters

pytest.importorskip("scipy")

TOL = 1e-4
#: The independent check: lo.overlap at a tolerance 100x tighter than the search's.
CHECK_TOL = 1e-6
TABLE1 = lo.paper_table1()
MISALIGNMENT = {"beam.tilt[0]": 3e-4, "beam.tilt[1]": -2e-4}  # rad, cancelled by a total tilt of 0
TILTED = parameters.replace(TABLE1, MISALIGNMENT)
#: Asymmetric, so the search's grid does not contain the answer (0, 0) itself.
TILT_BOUNDS = [(-0.9e-3, 1.1e-3)] * 2
Z_ALIGN = 150.0  # m: G = 0.79 at best there, and curved about its maximum (at 2 km it is flat, = 1)


def _g(system, z, tolerance=CHECK_TOL):
    return lo.overlap(system, np.atleast_1d(z), "rt", tolerance=tolerance).overlap


def test_smallest_fov_meets_the_constraint_and_is_tight():
    objective = lo.SmallestFieldOfView(full_overlap_range=150.0, fraction=0.99, max_far_loss=0.01)
    res = lo.optimize(TABLE1, objective, ["detector.radius"], [(1e-4, 3e-3)], tolerance=TOL)
    assert res.converged and res.unit == "m" and res.objective == res.values["detector.radius"]
    assert res.system.detector.radius == res.objective and all(
        v >= 0 for v in res.constraints.values()
    )
    radius, g_limit = res.objective, 1.0  # unobstructed: G_limit = 1 - (r_obs / R)² = 1
    # Feasible for the exact G: the search's constraints use G - error bound, so the check's G
    # (itself within CHECK_TOL) must reach 0.99 G_limit less CHECK_TOL at every range the objective
    # checks.
    assert np.all(_g(res.system, objective.ranges) >= 0.99 * g_limit - CHECK_TOL)
    # Tight: 1 % smaller misses the target by far more than both tolerances.
    smaller = parameters.replace(TABLE1, {"detector.radius": 0.99 * radius})
    assert _g(smaller, 150.0)[0] < 0.99 * g_limit - 10 * TOL
    assert (
        0.5e-3 < radius < 0.65e-3
    )  # FOV ~1.15 mrad: above Table 1's 0.9 mrad, which gives G(150) = 0.79


def test_defocus_buys_a_smaller_fov_within_the_far_loss():
    objective = lo.SmallestFieldOfView(full_overlap_range=150.0)
    plain = lo.optimize(TABLE1, objective, ["detector.radius"], [(1e-4, 3e-3)])
    both = lo.optimize(
        TABLE1, objective, ["detector.radius", "detector.defocus"], [(1e-4, 3e-3), (0.0, 1e-2)]
    )
    assert both.objective < 0.8 * plain.objective
    far = _g(both.system, objective.far_range)[0]
    assert far >= 1 - objective.max_far_loss - CHECK_TOL


def _curvature(system, z, h=1e-5):
    """c in G(t) = G(0) - c t² about the maximum, from a second difference along tilt x at
    CHECK_TOL."""
    g = [_g(parameters.replace(system, {"beam.tilt[0]": s * h}), z)[0] for s in (-1, 0, 1)]
    return (2 * g[1] - g[0] - g[2]) / (2 * h * h)


def _tilt_tolerance(c):
    """How far from the maximum a search that resolves G to TOL can stop: G there may lie TOL
    (quadrature) plus TOL (Nelder-Mead's fatol) plus TOL (the comparison of candidates) below the
    maximum, so |t| <= sqrt(3 TOL / c)."""
    return np.sqrt(3 * TOL / c)


def test_maximum_overlap_recovers_a_known_misalignment():
    aligned = parameters.replace(TABLE1, {"beam.tilt[0]": 0.0, "beam.tilt[1]": 0.0})
    c = _curvature(aligned, Z_ALIGN)
    assert c > 1e6  # 4.5e6 / rad²: the maximum is sharp enough to locate
    res = lo.optimize(
        TILTED, lo.MaximumOverlapAt(range=Z_ALIGN), ["beam.tilt"], TILT_BOUNDS, tolerance=TOL
    )
    tilt = np.array([res.values["beam.tilt[0]"], res.values["beam.tilt[1]"]])
    assert np.hypot(*tilt) <= _tilt_tolerance(c)  # about 8 µrad
    assert _g(res.system, Z_ALIGN)[0] >= _g(aligned, Z_ALIGN)[0] - 3 * TOL
    assert res.objective == pytest.approx(res.result.overlap[0]) and res.unit == "1"


def test_generic_objective_reproduces_maximum_overlap():
    free = ["beam.tilt[0]", "beam.tilt[1]"]
    named = lo.optimize(TILTED, lo.MaximumOverlapAt(range=Z_ALIGN), free, TILT_BOUNDS)
    generic = lo.optimize(
        TILTED, lo.Objective(lambda r: -r.overlap[0]), free, TILT_BOUNDS, ranges=[Z_ALIGN]
    )
    assert generic.objective == pytest.approx(-named.objective, abs=TOL)
    tol = _tilt_tolerance(_curvature(TABLE1, Z_ALIGN))
    assert np.allclose(list(generic.values.values()), list(named.values.values()), atol=2 * tol)


def test_generic_objective_with_a_constraint():
    # The largest tilt x (minimise -t) that keeps G(150 m) >= 0.7: on the constraint's boundary.
    objective = lo.Objective(
        lambda r: -r.system.beam.tilt[0],
        ranges=[Z_ALIGN],
        constraints={"g": lambda r: r.overlap[0] - r.error_estimate[0] - 0.7},
    )
    res = lo.optimize(TABLE1, objective, ["beam.tilt[0]"], [(-1e-3, 1e-3)])
    assert res.constraints["g"] >= 0
    assert _g(res.system, Z_ALIGN)[0] == pytest.approx(0.7, abs=0.01)


def test_unreachable_target_is_an_error_with_the_best_value():
    objective = lo.SmallestFieldOfView(full_overlap_range=20.0)
    with pytest.raises(ValueError, match=r"unreachable.*detector.radius = 0.0006.*full_overlap"):
        lo.optimize(TABLE1, objective, ["detector.radius"], [(1e-4, 6e-4)])


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(free=["beam.tilted"]), "parameter 'beam.tilted' is invalid"),
        (dict(free=["detector.defocus"]), "detector.radius, which must be one of the free"),
        (dict(bounds=[(5e-4, 1e-4)]), r"bounds\['detector.radius'\].*low < high"),
        (dict(bounds=[(float("nan"), 1e-3)]), r"bounds\['detector.radius'\].*finite"),
        (dict(bounds=[(1e-3, 2e-3)]), "excludes the start detector.radius = 0.00045"),
        (dict(bounds={"detector.defocus": (0, 1)}), "no free parameter detector.defocus"),
        (dict(bounds=[(1e-4, 1e-3), (0, 1)]), "one .low, high. pair per free"),
        (dict(x0=[float("nan")]), r"x0\['detector.radius'\] is invalid: expected a finite value"),
        (dict(x0=["a"]), r"x0\['detector.radius'\] = 'a' is invalid"),
        (dict(method="fo"), "not available for optimize"),
        (dict(tolerance=-1.0), "tolerance = -1.0 is invalid"),
        (dict(objective="fov"), "objective = 'fov' is invalid"),
        (dict(free=[]), "expected 1 to 6"),
    ],
)
def test_hostile_inputs_are_refused_by_name(kwargs, match):
    args = dict(
        system=TABLE1,
        objective=lo.SmallestFieldOfView(),
        free=["detector.radius"],
        bounds=[(1e-4, 1e-3)],
    )
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        lo.optimize(
            args.pop("system"), args.pop("objective"), args.pop("free"), args.pop("bounds"), **args
        )


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: lo.SmallestFieldOfView(fraction=1.5), "fraction = 1.5"),
        (lambda: lo.SmallestFieldOfView(far_range=100.0), "far_range = 100.0 is invalid"),
        (lambda: lo.MaximumOverlapAt(range=float("nan")), "range = nan"),
        (lambda: lo.Objective("f"), "function = 'f' is invalid"),
        (lambda: lo.Objective(len, constraints=[len]), "constraints = .* is invalid"),
        (lambda: lo.Objective(len, ranges=[2.0, 1.0]), "strictly increasing"),
    ],
)
def test_bad_objectives_are_refused(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_a_nan_objective_and_missing_ranges_are_refused():
    with pytest.raises(ValueError, match="function returned nan"):
        lo.optimize(
            TABLE1,
            lo.Objective(lambda r: float("nan")),
            ["beam.tilt[0]"],
            [(-1e-3, 1e-3)],
            ranges=[100.0],
        )
    with pytest.raises(ValueError, match="ranges is required"):
        lo.optimize(TABLE1, lo.Objective(lambda r: 0.0), ["beam.tilt[0]"], [(-1e-3, 1e-3)])


NARROW = parameters.replace(
    TILTED, {"detector.radius": 0.2e-3}
)  # FOV 0.4 mrad: G(1 km) = 0.006 as misaligned
SIGNAL = dict(pulse_energy=20e-6, receiver_efficiency=0.3, range_resolution=7.5)


@pytest.mark.parametrize("search", ["raster", "gradient"])
def test_align_brings_g_within_one_percent_of_its_best(search):
    res = lo.align(NARROW, 1000.0, search=search, shots_per_step=100, signal=SIGNAL)
    assert res.overlap[-1] >= 0.99 * res.best_overlap and res.shots_to_within is not None
    assert res.shots_to_within <= res.shots[-1] == res.steps * 100
    assert np.hypot(*res.best_tilt) < 2e-5  # the best tilt cancels the misalignment


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(search="spiral"), "search = 'spiral' is invalid"),
        (dict(signal=None), "signal = None is invalid"),
        (dict(shots_per_step=0), "shots_per_step = 0 is invalid"),
        (dict(box=-1.0), "box = -1.0 is invalid"),
        (dict(resolution=1e-300), r"resolution = 1e-300 is invalid: expected from 1e-12 rad"),
        (dict(search="gradient", step=1e-300), r"step = 1e-300 is invalid: expected the gradient"),
        (dict(signal={**SIGNAL, "noise": True}), r"signal\['noise'\] is invalid"),
        (dict(signal={**SIGNAL, "shots": 3}), r"signal\['shots'\] is invalid"),
        (dict(signal={**SIGNAL, "seed": 3}), r"signal\['seed'\] is invalid"),
    ],
)
def test_align_refuses_bad_input(kwargs, match):
    args = dict(search="raster", signal=SIGNAL)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        lo.align(NARROW, 1000.0, **args)


def test_optimize_needs_scipy_but_not_xarray(monkeypatch):
    """A tilt grid goes through the core's alignment grid directly, not through lo.alignment_map's
    xarray Dataset: optimize needs only its documented extra."""
    monkeypatch.setitem(sys.modules, "xarray", None)
    best = lo.optimize(
        lo.paper_table1(), lo.MaximumOverlapAt(range=300.0), ["beam.tilt[0]"], [(-3e-4, 3e-4)]
    )
    assert best.values["beam.tilt[0]"] == pytest.approx(0.0, abs=2e-5)
    assert best.objective == pytest.approx(
        lo.overlap(lo.paper_table1(), [300.0]).overlap[0], abs=1e-6
    )
