"""Plan, then run: a plan computes no curve, running it computes each curve once (core calls
counted), method objects and shortcut strings are the same computation, and a plan run in parts
equals the plan run whole."""

import dataclasses
from collections import defaultdict

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _core, cli

Z = np.geomspace(20.0, 2000.0, 40)
TABLE1 = lo.paper_table1()
FIBRE = dataclasses.replace(
    TABLE1, detector=lo.Detector(radius=25e-6)
)  # RT misses ~1.6e-3: auto takes FO
ABERRATED = lo.with_aberrations(TABLE1, lo.Aberrations(zernike={11: 0.3e-6}))
CURVES = (
    "overlap_rt",
    "overlap_rt_batch",
    "overlap_rt_aberrated",
    "overlap_fo",
    "overlap_fo_field",
    "overlap_fo_radial",
    "overlap_fo_aberrated",
    "overlap_fo_turbulent",
)


@pytest.fixture
def calls(monkeypatch):
    """Every call of the core's overlap functions, as (the core's system, ranges) under the
    function's name."""
    seen = defaultdict(list)
    for name in CURVES:
        original = getattr(_core, name)

        def counted(*args, _name=name, _original=original, **kwargs):
            ranges = (
                args[2] if _name in ("overlap_rt_aberrated", "overlap_fo_aberrated") else args[1]
            )
            system = args[0][0] if _name == "overlap_rt_batch" else args[0]
            seen[_name].append((system, np.array(ranges, dtype=float)))
            return _original(*args, **kwargs)

        monkeypatch.setattr(_core, name, counted)
    return seen


def test_a_plan_computes_no_curve(calls, capsys):
    for system in (TABLE1, FIBRE):
        for method in ("rt", "fo", "auto", lo.Auto(1e-2), lo.FO(path="2d")):
            lo.plan(system, Z, method)
    lo.explain(TABLE1, Z, tolerance=1e-3)
    assert not calls


@pytest.mark.parametrize("system, tolerance, model", [(TABLE1, 1e-2, "rt"), (FIBRE, 1e-4, "fo")])
def test_auto_runs_one_curve(calls, system, tolerance, model):
    res = lo.overlap(system, Z, lo.Auto(tolerance))
    assert res.method == model
    name = "overlap_rt" if model == "rt" else "overlap_fo_radial"
    assert sum(len(v) for v in calls.values()) == 1 and len(calls[name]) == 1
    assert np.array_equal(calls[name][0][1], Z)


def test_aberrated_auto_runs_rt_once_beside_its_two_coarse_estimate_curves(calls):
    """The estimate takes two coarse curves (detector radius ± 1 %, at most 16 ranges); RT of the
    system itself runs once, over all ranges, and is the result."""
    res = lo.overlap(ABERRATED, Z, "auto", tolerance=1e-2)
    assert res.method == "rt"
    own = [z for system, z in calls["overlap_rt_aberrated"] if system is ABERRATED._native]
    estimates = [
        z for system, z in calls["overlap_rt_aberrated"] if system is not ABERRATED._native
    ]
    assert len(own) == 1 and np.array_equal(own[0], Z)
    assert len(estimates) == 2 and all(z.size <= 16 for z in estimates)
    assert sum(len(v) for v in calls.values()) == 3


def test_turbulent_rt_is_one_batched_core_call_equal_to_one_call_per_draw(calls):
    """K x N draws in one overlap_rt_batch call, each bit-identical to ray tracing that draw alone
    (the draws rebuilt here from the same seed with the documented wander law)."""
    from lidar_overlap.forward.backends.turbulent import beam_for

    z, k, seed = np.array([300.0, 900.0]), 3, 7
    turbulence = lo.Turbulence(1e-13)
    method = lo.Turbulent(turbulence, lo.RT(1e-6), realizations=k, seed=seed, paths="transmit")
    res = lo.overlap(TABLE1, z, method)
    assert len(calls["overlap_rt_batch"]) == 1 and not calls["overlap_rt"]
    rng, beam = np.random.default_rng(seed), TABLE1.beam
    options = _core.RtOptions()
    options.tolerance = 1e-6
    for i, zi in enumerate(z):
        st = turbulence.short_term_radius(
            wavelength=beam.wavelength, waist_radius=beam.waist_radius, path_length=zi
        )
        lt = turbulence.long_term_radius(
            wavelength=beam.wavelength, waist_radius=beam.waist_radius, path_length=zi
        )
        sigma = 0.5 * np.sqrt(lt**2 - st**2)
        for j in range(k):
            native = _core.LidarSystem(
                beam_for(beam, zi, st, rng.normal(0.0, sigma, 2))._native,
                TABLE1.telescope._native,
                TABLE1.detector._native,
            )
            assert _core.overlap_rt(native, [zi], options).overlap[0] == res.realizations[j, i]


def test_the_cli_with_auto_computes_each_range_once(calls, tmp_path):
    """lidar-overlap run with auto: one plan, each range computed once (in chunks for the progress
    bar)."""
    scenario = tmp_path / "s.toml"
    scenario.write_text(
        'name = "s"\n[beam]\nwavelength = 355e-9\nwaist_radius = 1e-3\n'
        "[telescope]\ndiameter = 0.15\nfocal_length = 1.0\n[detector]\nfov = 0.9e-3\n"
        '[ranges]\nstart = 20.0\nstop = 2000.0\ncount = 120\n[run]\nmethod = "auto"\n'
        "tolerance = 1e-2\n[output]\ncsv = true\nnetcdf = false\nplot = false\nscene = false\n"
    )
    assert cli.main(["run", str(scenario), "--out", str(tmp_path / "out"), "--quiet"]) == 0
    computed = np.concatenate([z for _, z in calls["overlap_rt"]])
    assert computed.size == 120 and np.unique(computed).size == 120
    assert sum(len(v) for name, v in calls.items() if name != "overlap_rt") == 0


@pytest.mark.parametrize("method", ["rt", "fo", lo.FO(path="2d", beam_grid=128), lo.Auto(1e-3)])
def test_a_plan_run_in_parts_equals_the_plan_run_whole(method):
    p = lo.plan(TABLE1, Z[:12], method)
    whole = lo.run(p)
    parts = [lo.run(p.subset(slice(s, s + 5))) for s in range(0, 12, 5)]
    assert np.array_equal(np.concatenate([q.overlap for q in parts]), whole.overlap)


@pytest.mark.parametrize(
    "shortcut, options, method",
    [
        ("rt", dict(tolerance=1e-6), lo.RT(tolerance=1e-6)),
        ("fo", dict(fo_path="2d", beam_grid=128), lo.FO(path="2d", beam_grid=128)),
        ("auto", dict(tolerance=1e-3), lo.Auto(tolerance=1e-3)),
        (
            "rt",
            dict(turbulence=lo.Turbulence(1e-14), realizations=2, seed=1),
            lo.Turbulent(lo.Turbulence(1e-14), lo.RT(), realizations=2, seed=1),
        ),
    ],
)
def test_a_method_object_and_its_shortcut_are_the_same_computation(shortcut, options, method):
    z = Z[::8]
    by_string, by_object = lo.overlap(TABLE1, z, shortcut, **options), lo.overlap(TABLE1, z, method)
    assert np.array_equal(by_string.overlap, by_object.overlap)
    assert by_string.error_kind == by_object.error_kind


def test_defaults_are_the_cores():
    assert (lo.RT().tolerance, lo.RT().max_segments) == (
        _core.RtOptions().tolerance,
        _core.RtOptions().max_segments,
    )
    assert (lo.RT().rings, lo.RT().ring_rays) == (
        _core.RtAberratedOptions().rings,
        _core.RtAberratedOptions().ring_rays,
    )
    assert lo.FO().max_spectrum_grid == _core.FoOptions().max_spectrum_grid
    t = lo.Turbulent(lo.Turbulence(1e-14))
    assert (t.realizations, t.screens, t.seed) == (
        _core.TurbulenceOptions().realizations,
        _core.TurbulenceOptions().screens,
        _core.TurbulenceOptions().seed,
    )
    p = lo.plan(TABLE1, Z, lo.FO(path="2d"))
    assert (p.options.beam_grid, p.options.beam_window) == (
        _core.FoOptions().beam_grid,
        _core.FoOptions().beam_window,
    )


@pytest.mark.parametrize(
    "system, method, kind",
    [
        (TABLE1, "rt", "bound"),
        (TABLE1, "fo", "nominal"),
        (TABLE1, lo.Auto(1e-2), "bound"),
        (FIBRE, lo.Auto(1e-4), "nominal"),
        (
            TABLE1,
            lo.Turbulent(lo.Turbulence(1e-14), "fo", realizations=2, paths="transmit"),
            "standard_error",
        ),
    ],
)
def test_the_plan_states_the_kind_of_error_the_result_carries(system, method, kind):
    p = lo.plan(system, Z[-3:], method)
    assert p.error_kind == kind and lo.run(p).error_kind == kind


# --------------------------------------------------------------------------------- hostile input
@pytest.mark.parametrize(
    "method, message",
    [
        (lo.RT(), "^tolerance given beside method = RT"),
        ("magic", "^method = 'magic' is invalid"),
        (3, "^method = 3 is invalid"),
        (None, "^method = None is invalid"),
    ],
)
def test_bad_methods_and_options_beside_a_method_object_are_refused_by_name(method, message):
    with pytest.raises(ValueError, match=message):
        lo.overlap(TABLE1, Z, method, tolerance=1e-3 if isinstance(method, lo.RT) else None)


@pytest.mark.parametrize(
    "build, message",
    [
        (lambda: lo.RT(tolerance=0.0), "^tolerance = 0.0 is invalid"),
        (lambda: lo.RT(tolerance=float("nan")), "^tolerance = nan is invalid"),
        (lambda: lo.RT(max_segments=0), "^max_segments = 0 is invalid"),
        (lambda: lo.RT(rings=2**63), "^rings = .* is invalid"),
        (lambda: lo.FO(path="3d"), "^path = '3d' is invalid"),
        (lambda: lo.FO(beam_grid=8), "^beam_grid = 8 is invalid"),
        (lambda: lo.FO(path="radial", beam_grid=128), "apply to the 2-D FO path only"),
        (lambda: lo.FO(beam_window=float("inf")), None),
        (lambda: lo.Auto(tolerance=1.0), "^tolerance = 1.0 is invalid"),
        (lambda: lo.Auto(rt="rt"), "^rt = 'rt' is invalid"),
        (lambda: lo.Turbulent(1e-14), "^turbulence = 1e-14 is invalid"),
        (
            lambda: lo.Turbulent(lo.Turbulence(1e-14), realizations=0),
            "^realizations = 0 is invalid",
        ),
        (lambda: lo.Turbulent(lo.Turbulence(1e-14), seed=-1), "^seed = -1 is invalid"),
        (lambda: lo.Turbulent(lo.Turbulence(1e-14), method="fast"), "^method = 'fast' is invalid"),
    ],
)
def test_method_objects_refuse_bad_options_by_name(build, message):
    if message is None:  # accepted here, refused by the core when the plan runs, naming it
        with pytest.raises(ValueError, match="beam_window"):
            lo.overlap(TABLE1, Z[-2:], build())
        return
    with pytest.raises(ValueError, match=message):
        build()


def test_method_objects_are_immutable():
    with pytest.raises(dataclasses.FrozenInstanceError):
        lo.RT().tolerance = 0.5
    p = lo.plan(TABLE1, Z, "rt")
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.method = "fo"


def test_run_refuses_what_is_not_a_plan():
    with pytest.raises(ValueError, match="^plan = 'rt' is invalid"):
        lo.run("rt")
    p = lo.plan(TABLE1, Z, "rt")
    for changes, message in (
        (dict(backend="gpu"), "^backend = 'gpu' is invalid"),
        (dict(ranges=np.array([-1.0, 2.0])), r"^ranges\[0\] = -1"),
        (dict(system="x"), "^system = 'x' is invalid: expected a LidarSystem"),
        (dict(options=None), "^options = None is invalid"),
        (dict(request="rt"), "^request = 'rt' is invalid"),
        (dict(tolerance=float("inf")), "^tolerance = inf is invalid"),
        (dict(reasons=None), "^reasons = None is invalid"),
    ):  # refused by name when the plan is edited, not inside a backend
        with pytest.raises(ValueError, match=message):
            dataclasses.replace(p, **changes)


QUADRANT = lo.ApertureMask.quadrants().split()[0]
MASKED = dataclasses.replace(TABLE1, telescope=dataclasses.replace(TABLE1.telescope, mask=QUADRANT))
Z8 = np.geomspace(150.0, 3000.0, 8)


def test_no_plan_computes_a_curve_whatever_the_system(calls):
    """Plain, masked, aberrated (auto defers its two-curve estimate to the run) and turbulent."""
    turbulence = lo.Turbulence(1e-14)
    for system in (TABLE1, MASKED, ABERRATED):
        for method in ("rt", "fo", "auto", lo.Auto(1e-2)):
            lo.plan(system, Z8, method)
    for model in (lo.RT(), lo.FO(), lo.Auto(1e-2)):
        lo.plan(TABLE1, Z8, lo.Turbulent(turbulence, model, realizations=4))
    deferred = lo.plan(ABERRATED, Z8, "auto", tolerance=1e-2)
    assert deferred.method == "auto" and "when the plan runs" in str(deferred)
    assert not calls
    assert lo.run(deferred).method == "rt"
    assert calls["overlap_rt_aberrated"]


def test_a_retargeted_plan_runs_the_new_system():
    """with_system keeps the decisions for a system of the same kind (a misaligned one)."""
    p = lo.plan(TABLE1, Z8, "rt", tolerance=1e-6)
    tilted = lo.parameters.replace(TABLE1, {"beam.tilt[0]": 2e-4})
    assert lo.run(p.with_system(tilted)) == lo.run(lo.plan(tilted, Z8, "rt", tolerance=1e-6))


@pytest.mark.parametrize(
    "system, message",
    [
        (MASKED, "telescope.mask"),
        (ABERRATED, "aberrations"),
        (
            dataclasses.replace(TABLE1, beam=lo.FlatTopBeam(355e-9, 1e-3, 1e-3, grid=64)),
            "FlatTopBeam",
        ),
        (lo.paper_table1(width_law="linear"), "width_law"),
    ],
)
def test_a_plan_refuses_a_system_of_another_kind_by_name(system, message):
    """The reproducers of a plan edited by hand: a quadrant mask (G 0.25, not 1.0), aberrations
    (0.826, not 1.0) and a flat-top beam are other computations, refused naming what changed."""
    for method in ("rt", "fo"):
        p = lo.plan(TABLE1, Z8, method)
        with pytest.raises(ValueError, match=message):
            p.with_system(system)


def test_the_refused_reproducers_give_the_right_curves_planned_afresh():
    g_quadrant = lo.overlap(MASKED, Z8, "rt").overlap[-1]
    g_aberrated = lo.overlap(
        lo.with_aberrations(TABLE1, lo.Aberrations(zernike={11: 2e-6})), Z8, "rt"
    ).overlap[-1]
    assert g_quadrant == pytest.approx(0.25, abs=1e-3)
    assert g_aberrated == pytest.approx(0.826, abs=2e-3)


def test_a_plan_at_other_ranges_keeps_its_decisions():
    p = lo.plan(TABLE1, Z8, lo.Auto(1e-2))
    near = np.geomspace(20.0, 100.0, 5)
    q = p.at(near)
    assert q.backend == p.backend and q.options is p.options and np.array_equal(q.ranges, near)
    assert lo.run(q).overlap == pytest.approx(
        lo.overlap(TABLE1, near, "rt", tolerance=p.rt_quadrature_tolerance).overlap, abs=0
    )
    with pytest.raises(ValueError, match="ranges"):
        p.at([100.0, 50.0])


def test_a_plan_holds_each_decision_once():
    p = lo.plan(TABLE1, Z8, "fo")
    fields = {f.name for f in dataclasses.fields(p)}
    assert not fields & {"method", "fo_path", "error_kind", "turbulence", "rt_quadrature_tolerance"}
    assert (p.method, p.fo_path, p.error_kind) == ("fo", "radial", "nominal")


@pytest.mark.parametrize("method", ["rt", "fo"])
def test_a_plan_edited_by_hand_for_a_system_of_another_kind_is_refused_when_run(method):
    """The reproducers: dataclasses.replace(plan, system=...) with a quadrant mask or aberrations
    would run the old model on the new system (G 1.0 where 0.25 and 0.826 are right)."""
    p = lo.plan(TABLE1, Z8, method)
    aberrated = lo.with_aberrations(TABLE1, lo.Aberrations(zernike={11: 2e-6}))
    for system, message in ((MASKED, "telescope.mask"), (aberrated, "aberrations")):
        for planned_on in (None, system, TABLE1):  # whatever planned_on says
            edited = dataclasses.replace(p, system=system, planned_on=planned_on)
            with pytest.raises(ValueError, match="built or edited by hand"):
                lo.run(edited)
        with pytest.raises(ValueError, match=message):
            p.with_system(system)
    for request in (lo.FO(), lo.RT(1e-6)):  # another request is refused, not run as the old one
        with pytest.raises(ValueError, match="built or edited by hand"):
            lo.run(dataclasses.replace(p, request=request))
    hand_built = lo.Plan(**{f: getattr(p, f) for f in ("system", "ranges", "request", "backend",
                                                       "options", "tolerance")})  # fmt: skip
    with pytest.raises(ValueError, match="built or edited by hand"):
        lo.run(hand_built)
    assert np.array_equal(lo.run(p.at(Z8[2:])).overlap, lo.run(p).overlap[2:])


@pytest.mark.parametrize("index", [slice(5, 2), slice(10, None), 1, "a"])
def test_a_subset_selecting_no_range_is_refused_by_name(index):
    p = lo.plan(lo.paper_table1(), [100.0, 200.0, 300.0], "rt")
    with pytest.raises(ValueError, match=r"^index = .* expected a slice that selects at least one"):
        p.subset(index)
