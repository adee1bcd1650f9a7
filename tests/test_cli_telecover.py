"""`lidar-overlap telecover`: the scenario's telecover written as CSV (lo.telecover's numbers to the
last digit) and PNG with a summary; a fit round-trips deviations taken from such a CSV; bad files
and arguments fail with one line (exit 1, or 2 for the command line's syntax) and write nothing."""

import re
from pathlib import Path

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap.cli import main
from lidar_overlap.io.scenario import load_scenario

TABLE1 = Path(__file__).resolve().parents[1] / "examples" / "scenarios" / "table1.toml"
TILT_Y = 5e-5


def _scenario(path, tilt_y=0.0, count=6):
    text = (
        TABLE1.read_text()
        .replace("tilt = [0.0, 0.0]", f"tilt = [0.0, {tilt_y!r}]")
        .replace("count = 200 ", f"count = {count} ")
        .replace("start = 5.0 ", "start = 60.0 ")
        .replace("stop = 1000.0 ", "stop = 400.0 ")
    )
    path.write_text(text)
    return path


def _rows(path):
    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    return lines[0].split(","), np.array(
        [[float(v) for v in line.split(",")] for line in lines[1:]]
    )


@pytest.fixture(scope="module")
def computed(tmp_path_factory):
    """The telecover of a north-tilted Table 1 scenario, through the command line."""
    tmp = tmp_path_factory.mktemp("telecover")
    scenario = _scenario(tmp / "tilted.toml", TILT_Y)
    assert main(["telecover", str(scenario), "--out", str(tmp / "out")]) == 0
    return scenario, tmp / "out"


def test_telecover_writes_lo_telecover_to_the_last_digit_and_a_plot(computed, capsys):
    scenario, out = computed
    header, data = _rows(out / "table1_telecover.csv")
    names = ["north", "east", "south", "west"]
    assert header == ["range_m"] + [f"G_{n}" for n in names] + [f"deviation_{n}" for n in names]
    s = load_scenario(scenario)
    t = lo.telecover(s.system, s.ranges, tolerance=1e-4)
    assert np.array_equal(data[:, 0], t.ranges) and np.array_equal(data[:, 1:5], t.overlap.T)
    assert np.array_equal(data[:, 5:], t.deviation.T)
    assert "# sectors: north east south west" in (out / "table1_telecover.csv").read_text()
    assert (out / "table1_telecover.png").stat().st_size > 0


def test_summary_gives_the_largest_deviation_beyond_full_overlap(tmp_path, capsys):
    scenario = _scenario(tmp_path / "s.toml", TILT_Y)
    assert main(["telecover", str(scenario), "--sectors", "6", "--out", str(tmp_path / "o")]) == 0
    printed = capsys.readouterr().out
    assert "largest |deviation| beyond full overlap" in printed and "sector 5" in printed
    assert "deviation_sector_5" in (tmp_path / "o" / "table1_telecover.csv").read_text()
    assert (
        main(
            ["telecover", str(scenario), "--sectors", "6", "--quiet", "--out", str(tmp_path / "o")]
        )
        == 0
    )
    assert capsys.readouterr().out == ""


def _measurements(computed, path, sigma=None):
    header, data = _rows(computed[1] / "table1_telecover.csv")
    columns = [0, 5, 6, 7, 8]
    rows = [
        ",".join(repr(float(v)) for v in row) + (f",{sigma!r}" if sigma else "")
        for row in data[:, columns]
    ]
    path.write_text(
        "range_m,north,east,south,west"
        + (",sigma" if sigma else "")
        + "\n"
        + "\n".join(rows)
        + "\n"
    )
    return path


def test_fit_round_trips_deviations_from_a_written_telecover(computed, tmp_path, capsys):
    data = _measurements(computed, tmp_path / "m.csv", sigma=0.01)
    start = _scenario(tmp_path / "start.toml", 0.0)
    assert (
        main(
            [
                "telecover",
                str(start),
                "--measurements",
                str(data),
                "--free",
                "beam.tilt[1]",
                "--out",
                str(tmp_path / "o"),
            ]
        )
        == 0
    )
    assert "beam.tilt[1]" in capsys.readouterr().out
    rows = [
        line.split(",")
        for line in (tmp_path / "o" / "table1_telecover_fit.csv").read_text().splitlines()
        if not line.startswith("#")
    ]
    assert rows[0] == ["parameter", "value", "uncertainty", "unit", "start"]
    assert rows[1][0] == "beam.tilt[1]" and float(rows[1][1]) == pytest.approx(TILT_Y, rel=1e-3)
    assert (tmp_path / "o" / "table1_telecover_fit.png").stat().st_size > 0


@pytest.mark.parametrize(
    "content, message",
    [
        (
            "range_m,north,south\n100,0.1,-0.1\n",
            r"m.csv: line 1: header 'range_m,north,south' is invalid: expected "
            r"'range_m,north,east,south,west'",
        ),
        ("# nothing\n", r"m.csv: no header"),
        ("range_m,north,east,south,west\n", r"m.csv: no data"),
        (
            "range_m,north,east,south,west\n100,0.1,0,nan,0\n",
            r"line 2, column 4 \(south\): 'nan' is invalid",
        ),
        (
            "range_m,north,east,south,west,sigma\n100,0.1,0,-0.1,0,0\n",
            r"line 2, column 6 \(sigma\): '0' is invalid",
        ),
        (
            "range_m,north,east,south,west\n200,0,0,0,0\n100,0,0,0,0\n",
            r"line 3, column 1 \(range_m\): 100 does not",
        ),
        ("range_m,north,east,south,west\n100,0,0,0\n", r"line 2: 4 values, expected 5"),
        (
            "range_m,north,east,south,west\n100,0,0,0,0\n",
            r"measured has 3 independent points for 3 free",
        ),
    ],
)
def test_bad_measurement_files_fail_with_one_line(tmp_path, capsys, content, message):
    (tmp_path / "m.csv").write_text(content)
    scenario = _scenario(tmp_path / "s.toml")
    assert (
        main(
            [
                "telecover",
                str(scenario),
                "--measurements",
                str(tmp_path / "m.csv"),
                "--free",
                "beam.tilt",
                "beam.offset[0]",
                "--out",
                str(tmp_path / "out"),
            ]
        )
        == 1
    )
    err = capsys.readouterr().err.strip()
    assert (
        err.count("\n") == 0
        and err.startswith("lidar-overlap: error: ")
        and re.search(message, err)
    ), err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    "arguments, code, message",
    [
        (["--sectors", "1"], 2, r"--sectors: invalid value '1'"),
        (["--sectors", "octants"], 2, r"expected 'quadrants' or a number of sectors"),
        (["--free", "beam.tilt"], 2, r"--measurements and --free go together"),
        (["--measurements", "m.csv"], 2, r"--measurements and --free go together"),
        (["--measurements", "missing.csv", "--free", "beam.tilt"], 1, r"missing.csv: cannot read"),
        (["--method", "exact"], 2, r"--method: invalid choice"),
    ],
)
def test_bad_arguments_fail_with_one_line(tmp_path, capsys, monkeypatch, arguments, code, message):
    monkeypatch.chdir(tmp_path)
    scenario = _scenario(tmp_path / "s.toml")
    assert main(["telecover", str(scenario), *arguments]) == code
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and re.search(message, err), err
    assert not (tmp_path / "table1").exists()


def test_bad_free_path_and_scenario_fail_with_one_line(computed, tmp_path, capsys):
    data = _measurements(computed, tmp_path / "m.csv")
    assert (
        main(
            [
                "telecover",
                str(_scenario(tmp_path / "s.toml")),
                "--measurements",
                str(data),
                "--free",
                "beam.tilted",
                "--out",
                str(tmp_path / "o"),
            ]
        )
        == 1
    )
    assert "free: parameter 'beam.tilted' is invalid" in capsys.readouterr().err
    assert main(["telecover", str(tmp_path / "none.toml")]) == 1
    assert "none.toml" in capsys.readouterr().err


def test_help_lists_telecover(capsys):
    assert main(["--help"]) == 0
    assert "telecover" in capsys.readouterr().out
    assert main(["telecover", "--help"]) == 0
    assert "range_m,<sector>" in capsys.readouterr().out


def test_a_fit_at_ranges_outside_ray_tracings_validity_fails_unless_asked_to_go_on(
    tmp_path, capsys
):
    # 1-2 mm from the aperture: the paraxial error of the rays is 1e5 % (it exited 0 with a fit)
    start = _scenario(tmp_path / "start.toml", 0.0)
    data = tmp_path / "mm.csv"
    rows = [f"{z!r},0.01,0.0,-0.01,0.0" for z in (0.001, 0.0015, 0.002)]
    data.write_text("range_m,north,east,south,west\n" + "\n".join(rows) + "\n")
    args = ["telecover", str(start), "--measurements", str(data), "--free", "beam.tilt[1]"]
    assert main(args + ["--out", str(tmp_path / "refused")]) == 1
    said = capsys.readouterr().err
    assert re.search(r"mm.csv: range_m: ray tracing outside its validity: at 0.001 m", said)
    assert "--outside-validity" in said and not (tmp_path / "refused").exists()
    assert main(args + ["--out", str(tmp_path / "o"), "--outside-validity"]) == 0
    assert "outside its validity" in capsys.readouterr().err  # still warned
    assert (tmp_path / "o" / "table1_telecover_fit.csv").exists()
