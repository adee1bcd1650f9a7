"""Hostile command-line options: numbers written with digits other than ASCII, with '_' or ',',
fractions where whole seconds are meant, ports out of range, an output folder that is a file. Each
is a usage error (exit code 2) naming the option, before anything is served or fitted. Hostile
scenario files: test_cli_hostile.py."""

from pathlib import Path

import pytest

from lidar_overlap.cli import main

TABLE1 = (
    Path(__file__).resolve().parents[1] / "examples" / "scenarios" / "table1.toml"
).read_text()


pytestmark = pytest.mark.usefixtures("no_scene")  # conftest.py


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--timeout", "0.5"], "'0.5' is invalid: expected whole seconds"),
        (["--timeout", "-1"], "'-1' is invalid: expected whole seconds"),
        (["--timeout", "１０"], "expected whole seconds"),
        (["--port", "8_080"], "'8_080' is invalid: expected a port"),
        (["--port", "70000"], "expected a port, an integer from 0 to 65535"),
    ],
)
def test_view_options_are_read_as_written(tmp_path, capsys, argv, words):
    """A fraction of a second was never honoured (the view waited for ever); digits other than
    ASCII or '_' would have read as another number."""
    scenario = tmp_path / "t.toml"
    scenario.write_text(TABLE1)
    assert main(["view", str(scenario), "--no-browser", *argv]) == 2
    assert words in capsys.readouterr().err


def test_view_refuses_an_output_path_that_is_a_file_before_serving(tmp_path, capsys):
    scenario, taken = tmp_path / "t.toml", tmp_path / "taken"
    scenario.write_text(TABLE1)
    taken.write_text("not a folder")
    assert main(["view", str(scenario), "--no-browser", "--out", str(taken)]) == 2
    assert "--out" in capsys.readouterr().err and taken.read_text() == "not a folder"


@pytest.mark.parametrize("value", ["1,5", "١٠٠", "1_000", "nan"])
def test_fit_normalize_takes_ascii_decimals(tmp_path, capsys, value):
    scenario = tmp_path / "t.toml"
    scenario.write_text(TABLE1)
    code = main(["fit", str(scenario), "--measurements", "m.csv", "--free", "beam.tilt",
                 "--normalize", value, "3000"])  # fmt: skip
    assert code == 2 and "is invalid: expected a finite number" in capsys.readouterr().err
