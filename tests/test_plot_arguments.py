"""The plot helpers (views/plotting.py) refuse what they cannot draw before drawing anything: a
ParameterError naming the argument (a result, dataset or Axes of the wrong kind) and what was
expected, instead of matplotlib's or numpy's AttributeError, TypeError or KeyError."""

import numpy as np
import pytest

import lidar_overlap as lo

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
pytest.importorskip("xarray")

from lidar_overlap.views import plotting  # noqa: E402

Z = np.array([200.0, 500.0, 1000.0])
INSTRUMENT = dict(pulse_energy=0.05, receiver_efficiency=0.3, range_resolution=7.5)
#: Values that are no Axes: a number, a text, a list holding a number, a figure.
NOT_AXES = [3, "x", [1]]


@pytest.fixture(scope="module")
def made():
    import matplotlib.pyplot as plt

    s = lo.paper_table1()
    result = lo.overlap(s, Z, "rt", tolerance=1e-3)
    t = np.linspace(-3e-4, 3e-4, 3)
    figure, two = plt.subplots(2, 1)
    yield dict(
        system=s,
        result=result,
        signal=lo.signal(result, **INSTRUMENT),
        telecover=lo.telecover(s, Z, "quadrants", tolerance=1e-3),
        map=lo.alignment_map(s, [500.0], tilt_x=t, tolerance=1e-3),
        two=two,
        figure=figure,
    )
    plt.close("all")


def _draws(made, helper, **change):
    calls = {
        "plot_overlap": lambda a: plotting.plot_overlap(**{"result": made["result"], **a}),
        "plot_detector_image": lambda a: plotting.plot_detector_image(
            **{"system": made["system"], "z": 500.0, "n": 16, **a}
        ),
        "plot_signal": lambda a: plotting.plot_signal(**{"sig": made["signal"], **a}),
        "plot_telecover": lambda a: plotting.plot_telecover(**{"result": made["telecover"], **a}),
        "plot_alignment_map": lambda a: plotting.plot_alignment_map(**{"ds": made["map"], **a}),
    }
    return calls[helper](change)


@pytest.mark.parametrize(
    "helper", ["plot_overlap", "plot_detector_image", "plot_signal", "plot_alignment_map"]
)
@pytest.mark.parametrize("hostile", NOT_AXES + ["figure"])
def test_an_axes_of_the_wrong_kind_is_refused_naming_ax(made, helper, hostile):
    value = made["figure"] if hostile == "figure" else hostile
    with pytest.raises(lo.ParameterError, match=r"^ax = .* is invalid: expected a matplotlib Axes"):
        _draws(made, helper, ax=value)


def test_telecover_axes_are_two_axes(made):
    for hostile in (
        3,
        made["two"][0],
        [made["two"][0]],
        [made["two"][0], "x"],
        list(made["two"]) * 2,
    ):
        with pytest.raises(lo.ParameterError, match=r"^axes = .* expected 2 matplotlib Axes"):
            _draws(made, "plot_telecover", axes=hostile)
    top, bottom = _draws(made, "plot_telecover", axes=made["two"])  # the good call still draws
    assert top is made["two"][0] and len(top.lines) == len(made["telecover"].names) + 1
    with pytest.raises(lo.ParameterError, match=r"^band = -0.05 is invalid"):
        _draws(made, "plot_telecover", band=-0.05)


@pytest.mark.parametrize(
    "helper, argument, expected",
    [
        ("plot_overlap", "result", "the OverlapResult of lo.overlap"),
        ("plot_signal", "sig", "the LidarSignal of lo.signal"),
        ("plot_telecover", "result", "the TelecoverResult of lo.telecover"),
        ("plot_alignment_map", "ds", "an alignment map"),
    ],
)
def test_a_dataset_of_the_wrong_kind_is_refused_naming_it(made, helper, argument, expected):
    for hostile in (3, None, {"overlap": 1}, made["system"]):
        with pytest.raises(lo.ParameterError, match=rf"^{argument} = .* expected {expected}"):
            _draws(made, helper, **{argument: hostile})


def test_an_alignment_map_without_its_axes_or_at_a_bad_range_is_refused(made):
    ds = made["map"]
    with pytest.raises(lo.ParameterError, match=r"(?s)^ds = .* an alignment map"):
        plotting.plot_alignment_map(ds.drop_vars("overlap"))
    with pytest.raises(lo.ParameterError, match=r"(?s)^ds = .* an alignment map"):
        plotting.plot_alignment_map(ds.isel(tilt_x=0))  # G over range alone: no axis to draw
    for hostile in (float("nan"), "500", [500.0, float("inf")]):
        with pytest.raises(lo.ParameterError, match=r"^range"):
            plotting.plot_alignment_map(ds, range=hostile)


def test_a_series_plot_refuses_what_is_not_a_fit_series_dataset(made):
    for hostile in (3, None, {"value": 1}, made["map"]):
        with pytest.raises(lo.ParameterError, match=r"(?s)^ds = .* the dataset of lo.fit_series"):
            plotting.plot_series(hostile)
