"""`lidar-overlap fit`: a scenario and a measurements CSV give <name>_fit.csv (the parameters of
lo.fit to the last digit) and <name>_fit.png; bad files exit with code 1 and one line naming the
file, line and column; a fit that does not converge is a failure, not a file."""

import sys
from pathlib import Path

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import parameters
from lidar_overlap.cli import main
from lidar_overlap.io.overlap_curves import read_measurements
from lidar_overlap.io.scenario import load_scenario

pytest.importorskip("scipy")
TABLE1 = Path(__file__).resolve().parents[1] / "examples" / "scenarios" / "table1.toml"
TRUE = {"beam.tilt[0]": 3e-4, "detector.defocus": 2e-3}
SIGMA = 0.005


@pytest.fixture
def scenario(tmp_path):
    """Table 1 started off the truth (and off tilt 0, where G is even in the tilt)."""
    text = (
        TABLE1.read_text()
        .replace("tilt = [0.0, 0.0]", "tilt = [1e-4, 0.0]")
        .replace("defocus = 0.0 ", "defocus = 1e-3 ")
    )
    path = tmp_path / "start.toml"
    path.write_text(text)
    return path


def _measurements(path, sigma=True, z=None):
    z = np.geomspace(150.0, 2000.0, 15) if z is None else z
    g = lo.overlap(parameters.replace(lo.paper_table1(), TRUE), z, "rt", tolerance=1e-7).overlap
    g = g + np.random.default_rng(0).normal(0.0, SIGMA, z.size)
    rows = [f"{float(a)!r},{float(b)!r}" + (f",{SIGMA!r}" if sigma else "") for a, b in zip(z, g)]
    path.write_text(
        "# synthetic\nrange_m,overlap" + (",sigma" if sigma else "") + "\n" + "\n".join(rows) + "\n"
    )
    return path


@pytest.mark.parametrize("sigma", [True, False])
def test_fit_writes_the_parameters_of_lo_fit_and_a_plot(tmp_path, scenario, capsys, sigma):
    data = _measurements(tmp_path / "m.csv", sigma)
    out = tmp_path / "out"
    assert (
        main(
            [
                "fit",
                str(scenario),
                str(data),
                "--free",
                "beam.tilt[0]",
                "detector.defocus",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    printed = capsys.readouterr().out
    assert "converged" in printed and "beam.tilt[0]" in printed and "reduced" in printed
    s = load_scenario(scenario)
    z, g, w = read_measurements(data)
    f = lo.fit(s.system, z, g, w, free=list(TRUE), method=lo.RT(tolerance=1e-4))
    rows = [
        line.split(",")
        for line in (out / "table1_fit.csv").read_text().splitlines()
        if not line.startswith("#")
    ]
    assert rows[0] == ["parameter", "value", "uncertainty", "unit", "start"]
    assert [(r[0], float(r[1]), float(r[2])) for r in rows[1:]] == [
        (p, f.parameters[p], f.uncertainties[p]) for p in TRUE
    ]
    assert (out / "table1_fit.png").stat().st_size > 0


@pytest.mark.parametrize(
    "content, message",
    [
        ("range,overlap\n100,0.5\n", r"m.csv: line 1: header 'range,overlap' is invalid"),
        ("# only a comment\n", r"m.csv: no header"),
        ("range_m,overlap\n", r"m.csv: no data"),
        (
            "range_m,overlap\n100,0.5\n200,abc\n",
            r"m.csv: line 3, column 2 \(overlap\): 'abc' is invalid",
        ),
        (
            "range_m,overlap,sigma\n100,0.5,0.01\n200,0.6,0\n",
            r"line 3, column 3 \(sigma\): '0' is invalid",
        ),
        ("range_m,overlap\n100,0.5\n200,nan\n", r"line 3, column 2 \(overlap\): 'nan' is invalid"),
        (
            "range_m,overlap\n200,0.5\n100,0.6\n",
            r"line 3, column 1 \(range_m\): 100 does not follow 200",
        ),
        ("range_m,overlap\n100,0.5,1\n", r"line 2: 3 values, expected 2"),
    ],
)
def test_bad_measurement_files_fail_with_one_line_naming_line_and_column(
    tmp_path, scenario, capsys, content, message
):
    (tmp_path / "m.csv").write_text(content)
    assert (
        main(
            [
                "fit",
                str(scenario),
                str(tmp_path / "m.csv"),
                "--free",
                "beam.tilt[0]",
                "--out",
                str(tmp_path / "out"),
            ]
        )
        == 1
    )
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("lidar-overlap: error: ")
    assert __import__("re").search(message, err), err
    assert not (tmp_path / "out").exists()


def test_library_refusals_and_non_convergence_fail_with_one_line(
    tmp_path, scenario, capsys, monkeypatch
):
    data = _measurements(tmp_path / "m.csv")
    assert (
        main(
            ["fit", str(scenario), str(data), "--free", "beam.tilted", "--out", str(tmp_path / "o")]
        )
        == 1
    )
    assert "free: parameter 'beam.tilted' is invalid" in capsys.readouterr().err
    assert (
        main(["fit", str(scenario), str(tmp_path / "missing.csv"), "--free", "beam.tilt[0]"]) == 1
    )
    assert "missing.csv: cannot read" in capsys.readouterr().err
    import lidar_overlap.cli.fit as cli_fit

    real = cli_fit.fit
    monkeypatch.setattr(cli_fit, "fit", lambda *a, **k: real(*a, **{**k, "max_evaluations": 1}))
    assert (
        main(
            [
                "fit",
                str(scenario),
                str(data),
                "--free",
                "beam.tilt[0]",
                "--out",
                str(tmp_path / "o"),
            ]
        )
        == 1
    )
    err = capsys.readouterr().err
    assert "fit did not converge" in err and err.count("\n") == 1 and not (tmp_path / "o").exists()


def test_free_is_required(tmp_path, scenario, capsys):
    assert main(["fit", str(scenario), "m.csv"]) == 2
    assert "--free" in capsys.readouterr().err


def test_module_help_lists_fit(capsys):
    assert main(["fit", "--help"]) == 0
    assert "range_m,overlap[,sigma]" in capsys.readouterr().out
    assert sys.modules["lidar_overlap.cli"].main is main
