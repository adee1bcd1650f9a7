"""The command line reads its files whole or refuses them (no silent truncation, no hang on a FIFO,
a UTF-8 byte-order mark accepted) and never exits 0 on numbers that are not numbers."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from lidar_overlap.cli import main
from lidar_overlap.io.overlap_curves import read_measurements

TABLE1 = Path(__file__).resolve().parents[1] / "examples" / "scenarios" / "table1.toml"


def _scenario(path: Path, tilt=(0.0, 0.0), count=6, start=60.0) -> Path:
    text = (
        TABLE1.read_text()
        .replace("tilt = [0.0, 0.0]", f"tilt = [{tilt[0]!r}, {tilt[1]!r}]")
        .replace("count = 200 ", f"count = {count} ")
        .replace("start = 5.0 ", f"start = {start!r} ")
        .replace("stop = 1000.0 ", "stop = 400.0 ")
    )
    path.write_text(text)
    return path


def test_measurements_after_a_long_comment_block_are_read_to_the_last_digit(tmp_path):
    path = tmp_path / "m.csv"
    comments = "".join(f"# {'x' * 200} {i}\n" for i in range(60_000))  # 12 MB of comments
    path.write_text(comments + "range_m,overlap\n500.0,0.5\n1000.0,0.987654321\n")
    z, g, sigma = read_measurements(path)
    assert z.tolist() == [500.0, 1000.0] and g.tolist() == [0.5, 0.987654321] and sigma is None


def test_a_measurements_file_beyond_the_limit_is_refused_not_cut(tmp_path, monkeypatch):
    from lidar_overlap.io import overlap_curves

    monkeypatch.setattr(overlap_curves, "MAX_CSV_BYTES", 100)
    path = tmp_path / "m.csv"
    path.write_text("range_m,overlap\n" + "".join(f"{z}.0,0.5\n" for z in range(100, 200)))
    with pytest.raises(ValueError, match="larger than 100 bytes"):
        read_measurements(path)


def test_a_utf8_bom_is_accepted_in_toml_and_csv(tmp_path, capsys):
    scenario = _scenario(tmp_path / "bom.toml")
    scenario.write_bytes(b"\xef\xbb\xbf" + scenario.read_bytes())
    assert main(["run", str(scenario), "--out", str(tmp_path / "out"), "--quiet"]) == 0
    csv = tmp_path / "m.csv"
    csv.write_bytes(b"\xef\xbb\xbf" + b"range_m,overlap\n500.0,0.5\n1000.0,0.9\n")
    assert read_measurements(csv)[1].tolist() == [0.5, 0.9]


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs")
def test_a_fifo_is_refused_at_once(tmp_path, capsys):
    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)
    assert main(["run", str(fifo), "--out", str(tmp_path / "out")]) == 1
    assert "not a regular file" in capsys.readouterr().err
    with pytest.raises(ValueError, match="not a regular file"):
        read_measurements(fifo)


def test_telecover_of_a_dark_scenario_fails_instead_of_writing_nan(tmp_path, capsys):
    scenario = _scenario(tmp_path / "dark.toml", tilt=(0.5, 0.0))
    assert main(["telecover", str(scenario), "--out", str(tmp_path / "out")]) == 1
    assert "no sector receives light" in capsys.readouterr().err
    assert not (tmp_path / "out" / "table1_telecover.csv").exists()


def test_telecover_leaves_undefined_deviations_empty_never_nan(tmp_path, capsys):
    # A biaxial-like tilt: no light at the nearest ranges, light farther out.
    scenario = _scenario(tmp_path / "near.toml", tilt=(1e-3, 0.0), count=12, start=5.0)
    assert main(["telecover", str(scenario), "--out", str(tmp_path / "out"), "--quiet"]) == 0
    text = (tmp_path / "out" / "table1_telecover.csv").read_text()
    assert "nan" not in text.lower()
    rows = [line.split(",") for line in text.splitlines() if line and not line.startswith("#")]
    values = [cell for row in rows[1:] for cell in row if cell]
    assert all(np.isfinite(float(v)) for v in values)


def test_telecover_fit_refuses_a_method_it_would_ignore(tmp_path, capsys):
    scenario = _scenario(tmp_path / "t.toml")
    code = main(
        ["telecover", str(scenario), "--measurements", "m.csv", "--free", "beam.tilt"]
        + ["--method", "fo"]
    )
    assert code == 2 and "--method fo is invalid" in capsys.readouterr().err
