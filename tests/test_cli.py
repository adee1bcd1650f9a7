"""The command line: `run` on the bundled Table 1 scenario writes CSV, NetCDF and plot with the
numbers of lo.overlap to the last digit, --method overrides the file, bad scenarios exit with code 1
and a one-line message naming the key (command-line syntax errors with 2, Ctrl-C with 130), `demo`
writes the three Table 1 variants, and the module runs as a script. Failed computations and files:
test_cli_failures.py; hostile scenario files: test_cli_hostile.py; hostile options:
test_cli_hostile_options.py."""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from _cli_scenarios import csv_only

import lidar_overlap as lo
from lidar_overlap.cli import main
from lidar_overlap.io.scenario import load_scenario, table1_scenarios

SCENARIOS = Path(__file__).resolve().parents[1] / "examples" / "scenarios"
TABLE1 = SCENARIOS / "table1.toml"


pytestmark = pytest.mark.usefixtures("no_scene")  # conftest.py


def _read_columns(path):
    rows = [
        line for line in Path(path).read_text().splitlines() if line and not line.startswith("#")
    ]
    assert rows[0] == "range_m,overlap,error_estimate"
    return np.array([[float(v) for v in row.split(",")] for row in rows[1:]])


def test_run_table1_writes_the_files_with_exact_numbers(tmp_path, capsys):
    assert main(["run", str(TABLE1), "--out", str(tmp_path), "--quiet"]) == 0
    out, err = capsys.readouterr()
    for suffix in (".csv", ".nc", "_overlap.png"):
        assert (tmp_path / f"table1{suffix}").stat().st_size > 0, suffix
        assert f"table1{suffix}" in out
    assert "full overlap" in out and "first signal" in out and "method        rt" in out
    assert (
        "pyvista" in err and "table1_scene.png not written" in err
    )  # the note says what to install
    expected = lo.overlap(
        lo.paper_table1(), np.geomspace(5.0, 1000.0, 200), method="rt", tolerance=1e-4
    )
    data = _read_columns(tmp_path / "table1.csv")
    assert np.array_equal(data[:, 0], expected.ranges)
    assert np.array_equal(data[:, 1], expected.overlap)
    assert np.array_equal(data[:, 2], expected.error_estimate)
    read = lo.OverlapResult.from_netcdf(tmp_path / "table1.nc")
    assert np.array_equal(read.overlap, expected.overlap) and read.system == lo.paper_table1()
    assert f"{expected.full_overlap_range():.4g} m" in out


def test_bundled_file_is_the_built_in_scenario():
    from_file, built_in = load_scenario(TABLE1), table1_scenarios()[0]
    assert from_file.system == built_in.system == lo.paper_table1()
    assert np.array_equal(from_file.ranges, built_in.ranges)
    for key in ("name", "description", "method", "outputs"):
        assert getattr(from_file, key) == getattr(built_in, key), key
    assert from_file.method_object() == built_in.method_object() == lo.RT()  # Table 1 defined once


def test_aberrated_scenario_loads_and_refuses_bad_terms(tmp_path):
    scenario = load_scenario(SCENARIOS / "table1_aberrated.toml")
    ab = scenario.system.telescope.aberrations
    assert (
        ab.zernike == {6: 0.3e-6, 11: 0.5e-6} and ab.w131 == 0.2e-6 and ab.field_radius == 0.45e-3
    )
    assert scenario.model() == "rt"
    text = (SCENARIOS / "table1_aberrated.toml").read_text()
    for change, words in (
        (('"11" = 0.5e-6', '"eleven" = 0.5e-6'), "[telescope.aberrations.zernike] eleven"),
        (("w131 = 0.2e-6", "w132 = 0.2e-6"), "unknown key 'w132'"),
        (("field_radius = 0.45e-3", "field_radius = 0.0"), "field_radius"),
    ):
        path = tmp_path / "bad.toml"
        path.write_text(text.replace(*change))
        with pytest.raises(ValueError, match=re.escape(words)):
            load_scenario(path)


def test_biaxial_flat_top_scenario_loads():
    scenario = load_scenario(SCENARIOS / "biaxial_flat_top.toml")
    assert isinstance(scenario.system.beam, lo.FlatTopBeam) and scenario.system.beam.offset == (
        0.1,
        0.0,
    )
    assert scenario.model() == "fo" and scenario.ranges.size == 60


def test_method_override(tmp_path, capsys):
    text = (
        TABLE1.read_text()
        .replace("count = 200", "count = 8")
        .replace("start = 5.0", "start = 20.0")
    )
    (tmp_path / "small.toml").write_text(csv_only(text))
    assert (
        main(["run", str(tmp_path / "small.toml"), "--out", str(tmp_path), "--method", "fo"]) == 0
    )
    out = capsys.readouterr().out
    assert "method        fo" in out
    read = lo.OverlapResult.from_csv(tmp_path / "table1.csv")
    expected = lo.overlap(lo.paper_table1(), np.geomspace(20.0, 1000.0, 8), method="fo")
    assert read.method == "fo" and np.array_equal(read.overlap, expected.overlap)
    assert not (tmp_path / "table1.nc").exists() and not (tmp_path / "table1_overlap.png").exists()
    assert (
        main(
            [
                "run",
                str(tmp_path / "small.toml"),
                "--out",
                str(tmp_path),
                "--method",
                "auto",
                "--quiet",
            ]
        )
        == 0
    )
    # auto at the scenario's tolerance 1e-4: diffraction at the receiver (~1e-3) needs Fourier
    # optics.
    assert lo.OverlapResult.from_csv(tmp_path / "table1.csv").method == "fo"


@pytest.mark.parametrize(
    "change, words",
    [
        (
            ("waist_radius = 1e-3", "waist = 1e-3"),
            ["[beam]", "unknown key 'waist'", "valid: wavelength, waist_radius"],
        ),
        (("[output]", "[outputs]"), ["unknown key 'outputs'", "valid: name, description"]),
        (
            ("wavelength = 355e-9", 'wavelength = "355 nm"'),
            ["[beam] wavelength = '355 nm'", "expected a finite real number"],
        ),
        (("count = 200", "count = 12.5"), ["[ranges] count = 12.5", "expected an integer"]),
        (("[telescope]", "[telescope_]"), ["unknown key 'telescope_'"]),
        (("diameter = 0.15", ""), ["[telescope] missing key 'diameter'"]),
        (
            ("fov = 0.9e-3", "fov = -1"),
            ["table1.toml: [detector] fov = -1 is invalid: expected a finite value > 0"],
        ),
        (
            ("waist_radius = 1e-3", "waist_radius = -1e-3"),
            ["[beam] waist_radius = -0.001 is invalid", "> 0"],
        ),
        (
            ("obstruction_radius = 0.0", "obstruction_radius = 0.1"),
            ["[telescope] obstruction_radius", "aperture"],
        ),
        (
            ("fov = 0.9e-3", "fov = 0.9e-3\nradius = 0.45e-3"),
            ["[detector] fov and radius: both given", "expected exactly one"],
        ),
        (("fov = 0.9e-3", ""), ["[detector] fov and radius: neither given"]),
        (
            ('method = "rt"', 'method = "ray"'),
            ["[run] method = 'ray' is invalid", "'rt', 'fo', 'auto'"],
        ),
        (
            ('spacing = "log"', 'spacing = "logarithmic"'),
            ["[ranges] spacing = 'logarithmic'", "'linear', 'log'"],
        ),
        (("start = 5.0", "start = 0.5"), None),  # valid: no obstruction
    ],
)
def test_scenario_errors_exit_1_naming_the_key(tmp_path, capsys, change, words):
    text = TABLE1.read_text()
    assert change[0] in text
    path = tmp_path / "table1.toml"
    path.write_text(
        csv_only(text.replace(change[0], change[1], 1).replace("count = 200", "count = 20"))
    )
    code = main(["run", str(path), "--out", str(tmp_path / "out"), "--quiet"])
    out, err = capsys.readouterr()
    if words is None:
        assert code == 0, err
        return
    assert code == 1
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert err.startswith("lidar-overlap: error: ")
    for word in words:
        assert word in err, (word, err)
    assert not (tmp_path / "out").exists()


def test_ranges_inside_the_obstruction_distance(tmp_path, capsys):
    text = TABLE1.read_text().replace("obstruction_radius = 0.0", "obstruction_radius = 0.02")
    (tmp_path / "s.toml").write_text(
        text.replace("start = 5.0", "start = 0.5").replace("count = 200", "count = 120")
    )
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "out"), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert "s.toml: [ranges] ranges[0] = 0.5" in err and "obstruction distance" in err
    assert len(err.splitlines()) == 1 and not (tmp_path / "out").exists()


def test_missing_section_bad_toml_and_bad_arguments(tmp_path, capsys):
    text = TABLE1.read_text()
    cut = text[: text.index("[ranges]")] + text[text.index("[run]") :]
    (tmp_path / "a.toml").write_text(cut)
    (tmp_path / "b.toml").write_text("name = 'twice'\n" + text)
    cases = [
        (["run", str(tmp_path / "a.toml")], "missing section [ranges]", 1),
        (["run", str(tmp_path / "b.toml")], "b.toml: invalid TOML", 1),
        (["run", str(tmp_path / "none.toml")], "none.toml: cannot read the scenario", 1),
        (["run", str(tmp_path)], "cannot read the scenario", 1),  # a directory
        (
            ["run", str(TABLE1), "--method", "exact"],
            "argument --method: invalid choice: 'exact'",
            2,
        ),
        (["run"], "required: scenario", 2),
        (["simulate"], "invalid choice: 'simulate'", 2),
        ([], "required", 2),
    ]
    for argv, words, code in cases:
        assert main(argv) == code, argv
        err = capsys.readouterr().err
        assert words in err and len(err.strip().splitlines()) == 1, (argv, err)


def test_version_and_help(capsys):
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"lidar-overlap {lo.__version__}"
    assert main(["run", "--help"]) == 0
    assert "--method" in capsys.readouterr().out


def test_progress_on_long_runs(tmp_path, capsys, monkeypatch):
    (tmp_path / "s.toml").write_text(csv_only(TABLE1.read_text()))
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path)]) == 0
    assert "table1" in capsys.readouterr().err  # tqdm bar or counter on stderr
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path), "--quiet"]) == 0
    assert capsys.readouterr().err == ""
    monkeypatch.setitem(sys.modules, "tqdm", None)  # without tqdm: a counter
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path)]) == 0
    assert "table1: 200/200 ranges" in capsys.readouterr().err


def test_without_xarray_the_csv_is_still_written(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)
    text = (
        TABLE1.read_text()
        .replace("plot = true", "plot = false")
        .replace("count = 200", "count = 20")
    )
    (tmp_path / "s.toml").write_text(text)
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path)]) == 0
    assert (tmp_path / "table1.csv").exists() and not (tmp_path / "table1.nc").exists()
    assert "pip install 'lidar-overlap[io]'" in capsys.readouterr().err


def test_scene_is_written_through_save_scene(tmp_path, capsys, monkeypatch):
    calls = []

    def save_scene(system, filename, **kwargs):
        calls.append((system, kwargs))
        Path(filename).write_bytes(b"png")

    monkeypatch.delitem(sys.modules, "pyvista")  # installed (the fake below stands for its scene)
    monkeypatch.setattr("lidar_overlap.cli.run.save_scene", save_scene)
    text = (
        TABLE1.read_text()
        .replace("netcdf = true", "netcdf = false")
        .replace("plot = true", "plot = false")
    )
    (tmp_path / "s.toml").write_text(text)
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path), "--quiet"]) == 0
    assert (
        tmp_path / "table1_scene.png"
    ).exists() and "table1_scene.png" in capsys.readouterr().out
    assert calls[0][0] == lo.paper_table1() and calls[0][1]["result"].ranges.size == 200


def test_demo_writes_the_three_table1_variants(tmp_path, capsys):
    assert main(["demo", "--out", str(tmp_path), "--quiet"]) == 0
    out = capsys.readouterr().out
    for name in ("table1", "table1_obstruction_20mm", "table1_defocus_5mm"):
        for suffix in (".csv", ".nc", "_overlap.png"):
            assert (tmp_path / f"{name}{suffix}").stat().st_size > 0, (name, suffix)
    assert (tmp_path / "table1_variants_overlap.png").exists()
    obstructed = lo.OverlapResult.from_csv(tmp_path / "table1_obstruction_20mm.csv")
    assert obstructed.system == lo.paper_table1(obstruction_radius=0.02)
    assert obstructed.overlap[-1] == pytest.approx(1 - (0.02 / 0.075) ** 2, abs=1e-3)
    defocused = lo.OverlapResult.from_csv(tmp_path / "table1_defocus_5mm.csv")
    assert (
        defocused.full_overlap_range()
        < lo.OverlapResult.from_csv(tmp_path / "table1.csv").full_overlap_range()
    )
    assert out.count("full overlap") == 3 and f"written to {tmp_path}" in out


def test_subprocess(tmp_path):
    (tmp_path / "s.toml").write_text(
        csv_only(TABLE1.read_text()).replace("count = 200", "count = 10")
    )
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "lidar_overlap.cli",
            "run",
            str(tmp_path / "s.toml"),
            "--out",
            str(tmp_path / "out"),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert "full overlap" in done.stdout and (tmp_path / "out" / "table1.csv").exists()
    bad = subprocess.run(
        [sys.executable, "-m", "lidar_overlap.cli", "run", str(tmp_path / "none.toml")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert bad.returncode == 1 and "Traceback" not in bad.stderr and "cannot read" in bad.stderr


def test_a_scenario_through_turbulence_is_lo_overlap_to_the_last_digit(tmp_path, capsys):
    path = SCENARIOS / "table1_turbulence.toml"
    assert main(["run", str(path), "--out", str(tmp_path), "--quiet"]) == 0
    captured = capsys.readouterr()
    assert "amplification" in captured.out and "isoplanatic" in captured.err
    read = lo.OverlapResult.from_csv(tmp_path / "table1_turbulence.csv")
    scenario = load_scenario(path)
    draws = lo.Turbulent(
        lo.Turbulence(cn2=1e-15), lo.Auto(tolerance=1e-2), realizations=200, seed=1
    )
    with pytest.warns(RuntimeWarning, match="isoplanatic"):  # the command printed it too
        expected = lo.overlap(scenario.system, scenario.ranges, draws)
    assert isinstance(read, lo.TurbulentOverlapResult) and read.paths == "both"
    assert np.array_equal(read.overlap, expected.overlap)
    assert np.array_equal(read.error_estimate, expected.error_estimate)


@pytest.mark.parametrize(
    "line, words",
    [
        ('cn2 = "strong"', ["[turbulence] cn2", "hv57"]),
        ("cn2 = -1e-14", ["[turbulence] cn2"]),
        ('paths = "Both"', ["[turbulence] paths", "both"]),
        ("realizations = 0", ["[turbulence] realizations", "from 1 to 100000"]),
        ("seed = -1", ["[turbulence] seed"]),
        ("wind = 3.0", ["[turbulence] unknown key", "cn2"]),
    ],
)
def test_bad_turbulence_keys_name_the_key(tmp_path, capsys, line, words):
    text = (SCENARIOS / "table1_turbulence.toml").read_text()
    key = line.split(" =")[0]
    kept = [x for x in text.splitlines() if not x.startswith(f"{key} =")]
    text = "\n".join(kept).replace("[turbulence]", f"[turbulence]\n{line}")
    (tmp_path / "s.toml").write_text(text)
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path), "--quiet"]) == 1
    err = capsys.readouterr().err
    for word in words:
        assert word in err, (word, err)
