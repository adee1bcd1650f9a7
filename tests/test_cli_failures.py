"""The command line's failures and files: a failed computation (NaN, an exception) exits 1 with one
line naming the cause, warnings are printed once after success and never on failure, a full disk or
a link to /dev/full leaves no partial file, an output directory that is a file is an error, and
text from a scenario cannot drive the terminal."""

import errno
import os
from pathlib import Path

import numpy as np
import pytest
from _cli_scenarios import csv_only

import lidar_overlap as lo
from lidar_overlap.cli import main

SCENARIOS = Path(__file__).resolve().parents[1] / "examples" / "scenarios"
TABLE1 = SCENARIOS / "table1.toml"


pytestmark = pytest.mark.usefixtures("no_scene")  # conftest.py


def _small_scenario(tmp_path, outputs=("csv",), start=5.0, stop=1000.0):
    text = TABLE1.read_text().replace("count = 200", "count = 20")
    text = text.replace("start = 5.0", f"start = {start!r}").replace(
        "stop = 1000.0", f"stop = {stop!r}"
    )
    for key in ("csv", "netcdf", "plot", "scene"):
        if key not in outputs:
            text = text.replace(f"{key} = true", f"{key} = false")
    path = tmp_path / "s.toml"
    path.write_text(text)
    return path


def _one_error_line(err, *words):
    lines = err.splitlines()
    assert (
        len(lines) == 1 and lines[0].startswith("lidar-overlap: error: ") and "Traceback" not in err
    ), err
    for word in words:
        assert word in lines[0], (word, err)


def test_a_nan_curve_is_a_failure_not_a_file(tmp_path, capsys, monkeypatch):
    """A computation that returns NaN (as the core once did for extreme inputs) ends in exit 1: the
    result refuses it on construction, and nothing is written."""
    from lidar_overlap.io import scenario as scenario_module

    def nan_overlap(plan):
        z = plan.ranges
        return lo.OverlapResult(
            ranges=z,
            overlap=np.full(z.size, np.nan),
            method="rt",
            error_estimate=np.zeros(z.size),
            system=plan.system,
            tolerance=1e-4,
        )

    monkeypatch.setattr(scenario_module, "run", nan_overlap)
    path = _small_scenario(tmp_path, outputs=("csv", "netcdf", "plot"))
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--quiet"]) == 1
    out, err = capsys.readouterr()
    _one_error_line(err, "s.toml: [run] overlap[0] = nan at range 5.0 m (method 'rt') is invalid")
    assert out == "" and not (tmp_path / "out").exists()


def test_the_summary_prints_no_range_that_does_not_exist(tmp_path, capsys):
    # G = 0 everywhere: the obstruction (20 mm) hides the receiver's central rays, the only ones
    # that reach the detector from these short ranges, from the whole Table 1 beam up to 20 m
    text = TABLE1.read_text().replace("obstruction_radius = 0.0", "obstruction_radius = 0.02")
    text = text.replace("count = 200", "count = 20").replace("start = 5.0", "start = 1.0")
    (tmp_path / "s.toml").write_text(csv_only(text.replace("stop = 1000.0", "stop = 20.0")))
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path), "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "max G = 0" in out
    assert "full overlap  none (G >= 0.99 max G nowhere on the grid)" in out
    assert "first signal  none (G >= 1e-3 nowhere on the grid)" in out


def test_warnings_are_printed_once_after_success_and_not_on_failure(tmp_path, capsys):
    path = _small_scenario(tmp_path, outputs=("csv", "plot"), stop=40.0)  # G still rising at 40 m
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--quiet"]) == 0
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if "still rising" in line]
    assert (
        len(lines) == 1
        and lines[0].startswith("warning: full_overlap_range:")
        and "extend the ranges" in err
    )
    path.write_text(
        path.read_text()
        .replace("obstruction_radius = 0.0", "obstruction_radius = 0.02")
        .replace("start = 5.0", "start = 0.5")
    )  # now ranges inside the obstruction distance
    assert main(["run", str(path), "--out", str(tmp_path / "out2"), "--quiet"]) == 1
    _one_error_line(capsys.readouterr().err, "obstruction distance")


def test_a_full_disk_fails_in_one_line_and_leaves_no_partial_file(tmp_path, capsys, monkeypatch):
    from matplotlib.figure import Figure

    def half_then_full(self, path, **kwargs):
        Path(path).write_bytes(b"\x89PNG\r\n")
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(Figure, "savefig", half_then_full)
    out = tmp_path / "out"
    assert (
        main(
            [
                "run",
                str(_small_scenario(tmp_path, outputs=("csv", "plot"))),
                "--out",
                str(out),
                "--quiet",
            ]
        )
        == 1
    )
    _one_error_line(
        capsys.readouterr().err,
        f"cannot write {out / 'table1_overlap.png'}",
        "No space left on device",
    )
    assert sorted(p.name for p in out.iterdir()) == [
        "table1.csv"
    ]  # complete, written before; no temporary
    assert lo.OverlapResult.from_csv(out / "table1.csv").ranges.size == 20


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full on this system")
def test_writing_through_a_link_to_dev_full(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "table1.csv").symlink_to("/dev/full")
    assert main(["run", str(_small_scenario(tmp_path)), "--out", str(out), "--quiet"]) == 1
    _one_error_line(capsys.readouterr().err, "No space left on device")
    assert (
        sorted(p.name for p in out.iterdir()) == ["table1.csv"]
        and (out / "table1.csv").is_symlink()
    )


@pytest.mark.parametrize(
    "raised, code, words",
    [
        (KeyboardInterrupt(), 130, "interrupted"),
        (RuntimeError("unexpected\nstate"), 1, "internal error: RuntimeError: unexpected state"),
        (MemoryError(), 1, "out of memory"),
        (
            ValueError("threads = 5 is invalid: expected at most 4"),
            1,
            "[run] threads = 5 is invalid",
        ),
    ],
)
def test_every_failure_is_one_line(tmp_path, capsys, monkeypatch, raised, code, words):
    from lidar_overlap.io import scenario as scenario_module

    def fail(*args, **kwargs):
        raise raised

    monkeypatch.setattr(scenario_module, "run", fail)
    assert (
        main(["run", str(_small_scenario(tmp_path)), "--out", str(tmp_path / "out"), "--quiet"])
        == code
    )
    _one_error_line(capsys.readouterr().err, words)
    assert not (tmp_path / "out").exists()


def test_an_output_directory_that_is_a_file(tmp_path, capsys):
    (tmp_path / "taken").write_text("")
    assert (
        main(["run", str(_small_scenario(tmp_path)), "--out", str(tmp_path / "taken"), "--quiet"])
        == 1
    )
    _one_error_line(capsys.readouterr().err, "cannot write", "taken")


def test_text_from_the_scenario_cannot_drive_the_terminal(tmp_path, capsys):
    path = _small_scenario(tmp_path)
    path.write_text(
        path.read_text().replace(
            'description = "Mono-axial', 'description = "\\u001b[2J\\u0007Mono-axial'
        )
    )
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\x07" not in out and "table1: [2J Mono-axial lidar" in out
