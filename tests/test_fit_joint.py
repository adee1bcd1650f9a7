"""lo.fit_joint: two channels that share the geometry constrain it better than either alone (the
shared values recovered, their uncertainties below each single fit's); without shared parameters
the joint fit is the separate fits; the per-curve results add up to the joint one; the joint
search and the family choice; bad input is a clear error naming the argument."""

import warnings

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.model.instruments import pollyxt

pytest.importorskip("scipy")

FAST = dict(method="rt", tolerance=2e-4, threads=1)
Z = np.geomspace(150.0, 2500.0, 24)
INTERVAL = (1500.0, 2500.0)
SIGMA = (0.009, 0.015)
SHARED = ["beam.offset[0]", "beam.tilt[0]"]
TRUE = {"beam.offset[0]": 0.26, "beam.tilt[0]": -0.35e-3}
DIVERGENCE = (0.15e-3, 0.25e-3)
#: A fitted value is within this many of its stated standard deviations of the truth (a 4-sigma
#: miss has probability 6e-5 per value).
PULL = 4.0


def _systems(true=True):
    values = TRUE if true else {"beam.offset[0]": 0.24, "beam.tilt[0]": -0.3e-3}
    return [
        parameters.replace(
            pollyxt("far", wl, divergence=d if true else 0.2e-3),
            values,
        )
        for wl, d in zip((355e-9, 532e-9), DIVERGENCE)
    ]


def _curves(seed, method="rt", tolerance=1e-6):
    """The two channels' relative curves with noise, computed by ``method``."""
    rng = np.random.default_rng(seed)
    out = []
    for system, sigma in zip(_systems(), SIGMA):
        g = lo.overlap(system, Z, method, tolerance=tolerance).overlap
        out.append(g / g[Z >= INTERVAL[0]].mean() + rng.normal(0.0, sigma, Z.size))
    return out


def _joint(curves, **options):
    options = {"shared": SHARED, "per_curve": ["beam.divergence"], **options}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lo.DegeneracyWarning)
        return lo.fit_joint(
            _systems(False), [Z, Z], curves, sigma=list(SIGMA), normalize=INTERVAL, **options,
            **FAST,
        )  # fmt: skip


def _single(i, curve):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", lo.DegeneracyWarning)
        return lo.fit(
            _systems(False)[i], Z, curve, SIGMA[i], free=SHARED + ["beam.divergence"],
            normalize=INTERVAL, **FAST,
        )  # fmt: skip


@pytest.mark.parametrize("seed", [1, 2])
def test_shared_geometry_recovered_with_smaller_uncertainties_than_either_single_fit(seed):
    curves = _curves(seed)
    joint = _joint(curves)
    singles = [_single(i, c) for i, c in enumerate(curves)]
    assert isinstance(joint, lo.JointFitResult) and joint.converged
    assert list(joint.parameters) == SHARED + ["beam.divergence@0", "beam.divergence@1"]
    for path in SHARED:
        sd = joint.uncertainties[path]
        assert abs(joint.parameters[path] - TRUE[path]) < PULL * sd
        assert all(sd < s.uncertainties[path] for s in singles), (path, sd)
    for i, d in enumerate(DIVERGENCE):
        name = f"beam.divergence@{i}"
        assert abs(joint.parameters[name] - d) < PULL * joint.uncertainties[name]
        # each curve's own result holds its paths at the joint solution
        assert joint.curves[i].parameters["beam.divergence"] == joint.parameters[name]
        assert joint.curves[i].parameters["beam.tilt[0]"] == joint.parameters["beam.tilt[0]"]
    # fewer parameters than two separate fits (4 against 6)
    assert len(joint.parameters) < sum(len(s.parameters) for s in singles)


def test_per_curve_results_add_up_to_the_joint_fit():
    joint = _joint(_curves(3))
    total = sum(c.chi_square for c in joint.curves)
    assert total == pytest.approx(joint.chi_square, rel=1e-9)
    for c, z in zip(joint.curves, (Z, Z)):
        assert isinstance(c, lo.RelativeFitResult)
        assert c.fitted.shape == c.measured.shape == z.shape
        # the covariance of a curve's paths is the joint one mapped: its shared entries equal it
        i = list(c.parameters).index("beam.tilt[0]")
        assert c.uncertainties["beam.tilt[0]"] == pytest.approx(
            joint.uncertainties["beam.tilt[0]"], rel=1e-12
        )
        assert c.covariance[i, i] == pytest.approx(joint.covariance[1, 1], rel=1e-12)
    # n - 1 independent points per interval-normalised curve, 4 parameters
    assert joint.degrees_of_freedom == 2 * (Z.size - 1) - 4
    assert all(0.0 <= p <= 1.0 for p in joint.runs_p)
    assert "curve 1" in joint.summary()


def test_without_shared_parameters_the_joint_fit_is_the_separate_fits():
    curves = _curves(4)
    joint = lo.fit_joint(
        _systems(False), [Z, Z], curves, sigma=list(SIGMA), shared=(),
        per_curve=["beam.tilt[0]", "beam.divergence"], normalize=INTERVAL, **FAST,
    )  # fmt: skip
    for i, curve in enumerate(curves):
        single = lo.fit(
            _systems(False)[i], Z, curve, SIGMA[i], free=["beam.tilt[0]", "beam.divergence"],
            normalize=INTERVAL, **FAST,
        )  # fmt: skip
        for path in single.parameters:
            sd = single.uncertainties[path]
            # one minimum, found by two optimisers: equal within a small part of its width
            assert abs(joint.parameters[f"{path}@{i}"] - single.parameters[path]) < 0.05 * sd
            assert joint.uncertainties[f"{path}@{i}"] == pytest.approx(sd, rel=0.02)
        assert joint.curves[i].chi_square == pytest.approx(single.chi_square, rel=1e-3)


def test_joint_global_search_reports_its_search():
    joint = _joint(_curves(5), search="global", seed=2, population=12, generations=4, minima=2)
    assert joint.search is not None and joint.search.candidates >= 12
    assert set(joint.search.bounds) == set(joint.parameters)
    # the tilt's search box is the table's: a few fields of view, not the fit's ±10 mrad
    low, high = joint.search.bounds["beam.tilt[0]"]
    assert high - low < 5e-3
    for path in SHARED:
        assert abs(joint.parameters[path] - TRUE[path]) < PULL * joint.uncertainties[path]


def test_parameters_ending_on_a_bound_are_named():
    joint = _joint(_curves(6), bounds={"beam.offset[0]": (0.2, 0.25)})
    assert "beam.offset[0]" in joint.at_bounds
    assert joint.parameters["beam.offset[0]"] == pytest.approx(0.25, abs=1e-6)
    assert "on a bound" in joint.summary()


def _bad(**changes):
    args = dict(
        systems=_systems(False), ranges=[Z, Z], curves=_curves(7), sigma=list(SIGMA),
        shared=SHARED, per_curve=["beam.divergence"], normalize=INTERVAL,
    )  # fmt: skip
    args.update(changes)
    systems, ranges, curves = args.pop("systems"), args.pop("ranges"), args.pop("curves")
    return lambda: lo.fit_joint(systems, ranges, curves, **args, **FAST)


@pytest.mark.parametrize(
    "changes, name",
    [
        (dict(curves=[_curves(7)[0], _curves(7)[1][:-2]]), r"curves\[1\]"),
        (dict(curves=[_curves(7)[0]], ranges=[Z], systems=_systems()[:1]), "at least two"),
        (dict(ranges=[Z]), "ranges"),
        (dict(sigma=[0.01, None]), r"sigma\[1\]"),
        (dict(sigma=[0.01, np.nan]), "sigma"),
        (dict(sigma=[0.01, 0.0]), "sigma"),
        (dict(sigma=[0.01, 1e300]), "sigma"),
        (dict(shared=["beam.offset[0]", "beam.tilt[9]"]), "shared"),
        (dict(shared=["beam.nothing"]), "shared"),
        (dict(per_curve=["beam.tilt[0]"]), "per_curve"),
        (dict(systems=[_systems()[0], "x"]), r"systems\[1\]"),
        (dict(normalize=[INTERVAL]), "normalize"),
        (dict(normalize=(3000.0, 4000.0)), "normalize"),
        (dict(ranges=[Z, Z * np.nan]), r"ranges\[1\]"),
        (dict(shared=None), "shared"),
        (dict(free="all"), "free"),
        (dict(bounds={"detector.radius": (0.0, 1.0)}), "bounds"),
    ],
)
def test_bad_input_is_a_clear_error_naming_it(changes, name):
    with pytest.raises(ValueError, match=name):
        _bad(**changes)()


def test_a_shared_parameter_absent_from_one_system_is_named():
    systems = [_systems(False)[0], pollyxt("far", 532e-9, numerical_aperture=0.2)]
    systems[1] = parameters.replace(systems[1], {"beam.offset[0]": 0.24})
    with pytest.raises(ValueError, match=r"numerical_aperture does not exist in systems\[0\]"):
        lo.fit_joint(
            systems, [Z, Z], _curves(7), sigma=list(SIGMA), normalize=INTERVAL,
            shared=["detector.numerical_aperture"], **FAST,
        )  # fmt: skip


def test_auto_chooses_the_family_and_splits_the_divergence_per_channel():
    # the channels differ in divergence only (0.15 and 0.25 mrad): the choice on the joint data is
    # the beam family with a per-curve divergence (seed 8; the focus family with a per-curve
    # defocus ends within the BIC tie, and the simpler family is preferred)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        joint = lo.fit_joint(
            _systems(False), [Z, Z], _curves(8), sigma=list(SIGMA), free="auto",
            normalize=INTERVAL, seed=1, population=10, generations=4, **FAST,
        )  # fmt: skip
    assert joint.family == "alignment + beam"
    assert joint.per_curve == ("beam.divergence",)
    assert set(joint.shared) == {"beam.offset[0]", "beam.tilt[0]", "detector.radius"}
    assert any(line.startswith("chosen") for line in joint.choices)
    for i, d in enumerate(DIVERGENCE):
        name = f"beam.divergence@{i}"
        assert abs(joint.parameters[name] - d) < PULL * joint.uncertainties[name]


def _fo_curves(seed):
    """The two channels' relative curves on Fourier optics (auto's plan for these systems)."""
    return _curves(seed, "fo", 1e-4)


#: A planned-on-FO fit's settings: auto's plan (Fourier optics for the PollyXT receiver).
ON_FO = dict(method="auto", tolerance=2e-3, threads=1)


def test_a_search_planned_on_fo_runs_on_rt_and_refines_its_best_on_fo():
    curves = _fo_curves(9)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        joint = lo.fit_joint(
            _systems(False), [Z, Z], curves, sigma=list(SIGMA), shared=SHARED,
            per_curve=["beam.divergence"], normalize=INTERVAL, search="global", seed=3,
            population=10, generations=3, minima=2, **ON_FO,
        )  # fmt: skip
        # the same fit, local on FO from the search's best (ray-traced) minimum
        best = joint.search.minima[0].parameters
        systems = [parameters.replace(s, {p: best[p] for p in SHARED}) for s in _systems(False)]
        systems = [
            parameters.replace(s, {"beam.divergence": best[f"beam.divergence@{i}"]})
            for i, s in enumerate(systems)
        ]
        local = lo.fit_joint(
            systems, [Z, Z], curves, sigma=list(SIGMA), shared=SHARED,
            per_curve=["beam.divergence"], normalize=INTERVAL, **ON_FO,
        )  # fmt: skip
    assert "ray traced" in joint.search.method
    assert all(c.plan.method == "fo" for c in joint.curves)
    assert joint.chi_square == pytest.approx(local.chi_square, rel=1e-9)
    # the refinement is counted among the search's local evaluations
    assert joint.search.local_evaluations > sum(m.evaluations for m in joint.search.minima)
    for path in SHARED:
        assert abs(joint.parameters[path] - TRUE[path]) < PULL * joint.uncertainties[path]


def test_auto_planned_on_fo_chooses_on_rt_and_fits_the_chosen_family_on_fo():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        joint = lo.fit_joint(
            _systems(False), [Z, Z], _fo_curves(8), sigma=list(SIGMA), free="auto",
            normalize=INTERVAL, seed=1, population=10, generations=3, **ON_FO,
        )  # fmt: skip
    assert all(c.plan.method == "fo" for c in joint.curves)
    assert "beam.divergence" in joint.per_curve
    # every fit of the choice is counted: the search's candidates alone are 10 per generation
    assert joint.evaluations > 10 * 3
    for i, d in enumerate(DIVERGENCE):
        name = f"beam.divergence@{i}"
        assert abs(joint.parameters[name] - d) < PULL * joint.uncertainties[name]


def test_an_unconstrained_per_curve_parameter_is_infinite_only_where_it_is_used():
    # an acceptance of 0.45 cuts no ray of these systems: the data cannot constrain it, which
    # makes its uncertainty infinite, and the shared and the other curve's own values keep theirs
    systems = [parameters.replace(s, {"detector.numerical_aperture": 0.45}) for s in _systems()]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        joint = lo.fit_joint(
            systems, [Z, Z], _curves(10), sigma=list(SIGMA), shared=SHARED,
            per_curve=["detector.numerical_aperture"], normalize=INTERVAL, **FAST,
        )  # fmt: skip
    for i in range(2):
        assert joint.uncertainties[f"detector.numerical_aperture@{i}"] == np.inf
        assert joint.curves[i].uncertainties["detector.numerical_aperture"] == np.inf
        assert not np.isnan(joint.curves[i].uncertainties["beam.tilt[0]"])


def test_mapped_covariance_leaves_out_the_terms_of_zero_weight():
    from lidar_overlap.analysis.fitting.multi_curve import mapped_covariance

    cov = np.array([[4.0, 1.0, 0.0], [1.0, 9.0, np.inf], [0.0, np.inf, np.inf]])
    shared_and_own = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])  # θ0 shared, θ1 this curve's
    # θ2 (unconstrained) is another curve's: this curve's covariance is the plain product's block
    np.testing.assert_array_equal(mapped_covariance(shared_and_own, cov), cov[:2, :2])
    drift = np.array([[0.0, 1.0, 2.0]])  # θ1 + 2 θ2: it uses the unconstrained one
    assert mapped_covariance(drift, cov)[0, 0] == np.inf
    finite = np.array([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0]])
    np.testing.assert_allclose(
        mapped_covariance(finite, cov), finite[:, :2] @ cov[:2, :2] @ finite[:, :2].T, rtol=1e-15
    )


def test_auto_splits_per_curve_only_the_paths_allowed():
    # the data ask for a per-curve divergence (the test above); allowed only the tilt per curve,
    # the choice keeps the divergence shared and never tries it per curve
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        joint = lo.fit_joint(
            _systems(False), [Z, Z], _curves(8), sigma=list(SIGMA), free="auto",
            per_curve=["beam.tilt[0]"], normalize=INTERVAL, seed=1, population=10,
            generations=4, **FAST,
        )  # fmt: skip
    assert set(joint.per_curve) <= {"beam.tilt[0]"}
    tried = [line for line in joint.choices if line.strip().startswith("per-curve")]
    assert tried and all(line.split(":")[0].strip() == "per-curve beam.tilt[0]" for line in tried)


def test_auto_with_an_unknown_per_curve_path_is_a_clear_error():
    with pytest.raises(ValueError, match="per_curve"):
        lo.fit_joint(
            _systems(False), [Z, Z], _curves(8), sigma=list(SIGMA), free="auto",
            per_curve=["beam.nothing"], normalize=INTERVAL, **FAST,
        )  # fmt: skip
