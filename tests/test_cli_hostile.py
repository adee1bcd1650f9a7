"""Hostile scenario files: every one ends in exit code 1 and exactly one stderr line
``lidar-overlap: error: ...`` naming the file and the key, with no traceback and no output written.

Files the scenario loader refuses (bytes that are not UTF-8 TOML, missing sections, wrong types, NaN
and infinities in every numeric key, integers outside their bounds in every integer key, too many
ranges) run in-process. Extreme finite values that reach the compiled core run the command in a
subprocess with a memory cap and a timeout, so that a crash or a hang of the core fails the test
instead of the test run; for those a clean result (exit 0, G finite and within [0, 1]) is also
accepted."""

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from _cli_scenarios import csv_only

import lidar_overlap
from lidar_overlap.cli import main
from lidar_overlap.io.scenario_schema import INTEGER_LIMITS, MAX_FILE_BYTES, MAX_RANGES

ROOT = Path(__file__).resolve().parents[1]
PACKAGE_PARENT = str(Path(lidar_overlap.__file__).resolve().parents[1])
TABLE1 = (ROOT / "examples" / "scenarios" / "table1.toml").read_text()
FLAT_TOP = (ROOT / "examples" / "scenarios" / "biaxial_flat_top.toml").read_text()
#: Subprocess limits: a probe that hangs or allocates without bound fails fast.
PROBE_TIMEOUT_S = 120
PROBE_MEMORY_BYTES = 4 << 30


pytestmark = pytest.mark.usefixtures("no_scene")  # conftest.py


def _small(text: str) -> str:
    """20 ranges, CSV only: the base of every case (valid as it stands)."""
    return csv_only(text).replace("count = 200", "count = 20").replace("count = 60", "count = 2")


BASE, FLAT = _small(TABLE1), _small(FLAT_TOP).replace("# grid = 512", "grid = 64\n#")


def _set(text: str, section: str, key: str, value: str) -> str:
    """``key = value`` in ``[section]``, replacing the key's line or adding one."""
    lines = text.splitlines()
    start = lines.index(f"[{section}]")
    end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("[")), len(lines))
    hits = [i for i in range(start + 1, end) if re.match(rf"{re.escape(key)}\s*=", lines[i])]
    if hits:
        lines[hits[0]] = f"{key} = {value}"
    else:
        lines.insert(start + 1, f"{key} = {value}")
    return "\n".join(lines) + "\n"


def _without(text: str, section: str) -> str:
    lines = text.splitlines()
    start = lines.index(f"[{section}]")
    end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("[")), len(lines))
    return "\n".join(lines[:start] + lines[end:]) + "\n"


ABERRATED = BASE.replace(
    "[detector]",
    "[telescope.aberrations]\nw040 = 1e-7\nfield_radius = 0.45e-3\n\n"
    '[telescope.aberrations.zernike]\n"11" = 5e-8\n\n[detector]',
)
#: (section, key, base text) of every real-number key of a scenario.
REAL_KEYS = (
    [("beam", key, BASE) for key in ("wavelength", "waist_radius", "divergence")]
    + [
        ("telescope", key, BASE)
        for key in ("diameter", "focal_length", "obstruction_radius", "obstruction_distance")
    ]
    + [("detector", key, BASE) for key in ("fov", "defocus", "numerical_aperture")]
    + [("ranges", key, BASE) for key in ("start", "stop")]
    + [("run", key, BASE) for key in ("tolerance", "beam_window")]
    + [
        ("telescope.aberrations", key, ABERRATED)
        for key in ("w040", "w131", "w222", "w220", "w311", "field_radius")
    ]
    + [
        ("beam", key, FLAT)
        for key in (
            "waist_radius",
            "angular_diameter",
            "samples_per_waist",
            "edge_width",
            "tolerance",
            "max_error",
            "power",
        )
    ]
)
PAIR_KEYS = [("beam", "offset"), ("beam", "tilt"), ("detector", "offset")]
INTEGER_KEYS = [
    ("ranges", "count", BASE),
    ("run", "threads", BASE),
    ("run", "max_segments", BASE),
    ("run", "beam_grid", BASE),
    ("run", "max_spectrum_grid", BASE),
    ("beam", "grid", FLAT),
    ("beam", "max_iterations", FLAT),
]


def _refused_by_the_loader():
    """(id, file bytes, words the error must contain)."""
    cases = [
        ("random bytes", bytes(range(256)) * 4, ["not a TOML file", "not UTF-8"]),
        (
            "a non-UTF-8 key",
            BASE.encode().replace(b"name = ", b"\xff\xfe = 1\nname = "),
            ["byte", "0xff"],
        ),
        ("latin-1 text", BASE.replace("Mono-axial", "Mon\u00f6").encode("latin-1"), ["0xf6"]),
        ("UTF-16", BASE.encode("utf-16"), ["not UTF-8"]),
        ("nested arrays", b"v = " + b"[" * 100_000 + b"]" * 100_000, ["nested too deeply"]),
        ("nested tables", b"v = " + b"{a=" * 5000 + b"1" + b"}" * 5000, ["nested too deeply"]),
        ("a huge file", b"# " + b"x" * MAX_FILE_BYTES + b"\n", [f"{MAX_FILE_BYTES:,} bytes"]),
        ("an empty file", b"", ["missing section [beam]"]),
        ("a bad name", BASE.replace('"table1"', '"../x"').encode(), ["name = '../x'"]),
        (
            "a long name",
            BASE.replace('"table1"', '"' + "a" * 101 + '"').encode(),
            ["1 to 100 letters"],
        ),
    ]
    cases += [
        (f"no [{s}]", _without(BASE, s).encode(), [f"missing section [{s}]"])
        for s in ("beam", "telescope", "detector", "ranges")
    ]
    for section, key, base in REAL_KEYS:
        for value in ("nan", "-inf", "inf"):
            cases.append(
                (
                    f"{section}.{key} = {value}",
                    _set(base, section, key, value).encode(),
                    [f"[{section}] {key} = {value}", "finite"],
                )
            )
    for section, key in PAIR_KEYS:
        for value in (
            "[nan, 0.0]",
            "[0.0, inf]",
            "[true, false]",
            '["0", "0"]',
            "[0.0]",
            "[0.0, 0.0, 0.0]",
            "[[0.0, 0.0], 1.0]",
            "0.0",
        ):
            cases.append(
                (
                    f"{section}.{key} = {value}",
                    _set(BASE, section, key, value).encode(),
                    [f"[{section}] {key} = ", "pair of two finite numbers"],
                )
            )
    for section, key, base in INTEGER_KEYS:
        limit = INTEGER_LIMITS[f"{'flat_top' if base is FLAT else section}.{key}"]
        for value in (
            limit.low - 1,
            limit.high + 1,
            2**31,
            2**32,
            2**40,
            2**63 - 1,
            -(2**63),
            10**30,
        ):
            cases.append(
                (
                    f"{section}.{key} = {value}",
                    _set(base, section, key, str(value)).encode(),
                    [
                        f"[{section}] {key} = {value}",
                        f"an integer from {limit.low} to {limit.high}",
                    ],
                )
            )
        for value in ("2.0", "true", '"20"', "1e3"):
            cases.append(
                (
                    f"{section}.{key} = {value}",
                    _set(base, section, key, value).encode(),
                    [f"[{section}] {key} = ", "an integer from"],
                )
            )
    for section, key, value in (
        ("beam", "wavelength", "true"),
        ("beam", "wavelength", '"355 nm"'),
        ("beam", "wavelength", "1979-05-27T07:32:00Z"),
        ("beam", "wavelength", "[355e-9]"),
        ("beam", "wavelength", "{ value = 355e-9 }"),
        ("beam", "wavelength", str(10**400)),
        ("run", "method", "1"),
        ("output", "csv", "1"),
        ("ranges", "spacing", "true"),
        ("beam", "type", "3"),
        ("beam", "width_law", '"cubic"'),
    ):
        cases.append(
            (
                f"{section}.{key} = {value[:24]}",
                _set(BASE, section, key, value).encode(),
                [f"[{section}] {key} = "],
            )
        )
    no_ranges = _without(BASE, "ranges")
    for values, words in (
        ("[]", "1 to 100,000"),
        ("[nan, 100.0]", "finite"),
        ("[100.0, 5.0]", "increasing"),
        ("[-5.0, 100.0]", "> 0"),
        ("[true, 5.0]", "finite numbers"),
        (repr([float(v) for v in range(1, MAX_RANGES + 2)]), f"{MAX_RANGES + 1} values"),
    ):
        cases.append(
            (
                f"values = {values[:24]}",
                (no_ranges + f"[ranges]\nvalues = {values}\n").encode(),
                ["[ranges] values = ", words],
            )
        )
    cases.append(
        (
            "ranges not distinct",
            _set(
                _set(BASE, "ranges", "stop", "5.000000000001"), "ranges", "count", str(MAX_RANGES)
            ).encode(),
            ["not distinct"],
        )
    )
    cases.append(
        (
            "zernike nan",
            _set(ABERRATED, "telescope.aberrations.zernike", '"11"', "nan").encode(),
            ["[telescope.aberrations.zernike] 11 = nan"],
        )
    )
    return cases


LOADER_CASES = _refused_by_the_loader()


def test_the_base_scenarios_are_valid(tmp_path, capsys):
    for name, text in (("table1", BASE), ("aberrated", ABERRATED)):
        path = tmp_path / f"{name}.toml"
        path.write_text(text)
        assert main(["run", str(path), "--out", str(tmp_path / name), "--quiet"]) == 0, (
            capsys.readouterr().err
        )
        assert (tmp_path / name / "table1.csv").exists()


@pytest.mark.parametrize("case, data, words", LOADER_CASES, ids=[c[0] for c in LOADER_CASES])
def test_the_loader_refuses_in_one_line(tmp_path, capsys, case, data, words):
    path = tmp_path / "hostile.toml"
    path.write_bytes(data)
    code = main(["run", str(path), "--out", str(tmp_path / "out"), "--quiet"])
    out, err = capsys.readouterr()
    _assert_one_clean_line(code, err)
    assert "hostile.toml" in err
    for word in words:
        assert word in err, (word, err)
    assert not (tmp_path / "out").exists() and out == ""


#: Finite but absurd values that pass the loader and reach the core (one subprocess each, ~1 s):
#: (id, section the error must name if the run fails, file text).
CORE_CASES = (
    [
        (f"{s}.{k} = {v}", s, _set(base, s, k, v))
        for s, k, base in REAL_KEYS
        if base is BASE
        for v in ("1e300", "1e-300")
    ]
    + [
        (f"{s}.{k} = 1e300", s, _set(ABERRATED, s, k, "1e300"))
        for s, k, base in REAL_KEYS
        if base is ABERRATED
    ]
    + [(f"{s}.{k} = [-1e300, 0.0]", s, _set(BASE, s, k, "[-1e300, 0.0]")) for s, k in PAIR_KEYS]
    + [
        (
            "flat_top angular_diameter = 1e300",
            "beam",
            _set(FLAT, "beam", "angular_diameter", "1e300"),
        ),
        (
            "flat_top samples_per_waist = 1e-300",
            "beam",
            _set(FLAT, "beam", "samples_per_waist", "1e-300"),
        ),
        (
            "zernike 1e300",
            "telescope.aberrations.zernike",
            _set(ABERRATED, "telescope.aberrations.zernike", '"11"', "1e300"),
        ),
        (
            "fo beam_grid at its bound",
            "run",
            _set(_set(BASE, "run", "method", '"fo"'), "run", "beam_grid", "16"),
        ),
        ("ranges start 1e-10", "ranges", _set(BASE, "ranges", "start", "1e-10")),
        ("ranges stop 1e10", "ranges", _set(BASE, "ranges", "stop", "1e10")),
    ]
)


def _limit_memory():  # pragma: no cover - runs in the child
    import resource

    resource.setrlimit(resource.RLIMIT_AS, (PROBE_MEMORY_BYTES, PROBE_MEMORY_BYTES))


@pytest.mark.parametrize("case, section, text", CORE_CASES, ids=[c[0] for c in CORE_CASES])
def test_extreme_values_in_a_subprocess(tmp_path, case, section, text):
    path = tmp_path / "hostile.toml"
    path.write_text(text)
    env = dict(
        os.environ, PYTHONPATH=PACKAGE_PARENT
    )  # the package this test run imports, built or installed
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "lidar_overlap.cli",
            "run",
            str(path),
            "--out",
            str(tmp_path / "out"),
            "--quiet",
        ],
        capture_output=True,
        text=True,
        env=env,
        timeout=PROBE_TIMEOUT_S,
        cwd=tmp_path,
        preexec_fn=_limit_memory if sys.platform.startswith("linux") else None,
    )
    assert done.returncode in (0, 1), (
        done.returncode,
        done.stderr[-2000:],
    )  # a negative code is a crash
    assert "Traceback" not in done.stderr, done.stderr
    if done.returncode == 1:
        _assert_one_clean_line(1, done.stderr)
        assert f"hostile.toml: [{section}]" in done.stderr
        assert not (tmp_path / "out").exists()
        return
    data = _csv_columns(tmp_path / "out")
    assert np.all(np.isfinite(data[:, 1])) and np.all((data[:, 1] >= 0) & (data[:, 1] <= 1)), case


def _csv_columns(out: Path) -> np.ndarray:
    (csv,) = out.glob("*.csv")
    rows = [line for line in csv.read_text().splitlines() if line and not line.startswith("#")]
    assert rows[0] == "range_m,overlap,error_estimate"
    return np.array([[float(v) for v in row.split(",")] for row in rows[1:]])


def _assert_one_clean_line(code: int, err: str) -> None:
    assert code == 1, err
    assert "Traceback" not in err, err
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("lidar-overlap: error: "), err
