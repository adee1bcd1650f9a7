"""Reading measured overlap curves (the published two-column text of lidar networks, the command
line's CSV) and the far-range noise estimate against a known Gaussian noise level."""

import dataclasses
import math
import pickle
from pathlib import Path

import numpy as np
import pytest

from lidar_overlap.io.overlap_curves import OverlapCurve, far_range_noise, read_overlap_curve

DATA = Path(__file__).resolve().parent.parent / "examples" / "data"
#: The MAD-based estimate from N points scatters by about 1.65 / sqrt(2 N) of sigma (the MAD's
#: efficiency is 37%); 2000 points: 2.6%, so 10% is a 3.8-sigma band.
NOISE_POINTS, NOISE_RELATIVE = 2000, 0.10


def test_published_default_curve_is_read_with_its_header():
    c = read_overlap_curve(DATA / "pollynet_default_overlap.txt")
    assert c.header == ("height(m)   overlap",)
    assert c.ranges[0] == pytest.approx(3.75) and c.overlap[0] == pytest.approx(1.288713e-6)
    assert c.ranges.size == 402 and c.sigma is None
    assert np.all(np.diff(c.ranges) > 0)
    assert np.diff(c.ranges) == pytest.approx(np.full(401, 7.47146), abs=1e-3)  # 6 decimals


def test_dushanbe_csv_pair_shares_its_ranges():
    """The two channels of one measurement: the same 402 heights (7.47 m apart, as the PollyNET
    text files), converted to the command line's CSV."""
    a = read_overlap_curve(DATA / "pollyxt_dushanbe_overlap_355.csv")
    b = read_overlap_curve(DATA / "pollyxt_dushanbe_overlap_532.csv")
    assert a.header == b.header == ("range_m,overlap",)
    assert a.ranges.size == 402 and np.array_equal(a.ranges, b.ranges)
    assert a.ranges[-1] == pytest.approx(2999.805664) and a.overlap[0] == pytest.approx(2.535109e-6)
    assert np.diff(a.ranges) == pytest.approx(np.full(401, 7.47146), abs=1e-3)


def test_curve_with_a_count_line_as_header_and_no_spaces():
    c = read_overlap_curve(DATA / "pollyxt_ift_overlap_532.txt")
    assert c.header == ("height overlap,",) and c.ranges[:2] == pytest.approx([39.0, 68.885841])


def test_csv_with_sigma_and_comments(tmp_path):
    f = tmp_path / "m.csv"
    f.write_text("# site A\nrange_m,overlap,sigma\n100,0.5,0.01\n200, 0.9 ,0.02\n")
    c = read_overlap_curve(f)
    assert c.ranges.tolist() == [100.0, 200.0] and c.sigma.tolist() == [0.01, 0.02]
    assert c.within(100, 250).overlap.tolist() == [0.5, 0.9]
    with pytest.raises(ValueError, match="holds 1 points"):
        c.within(150, 250)


@pytest.mark.parametrize(
    "text, message",
    [
        ("h g\n1, 0.1\n1, 0.2\n", "line 3, column 1 (range)"),
        ("h g\n1, 0.1\nfoo\n", "line 3"),
        ("h g\n1, 0.1\n2, nan\n", "line 3, column 2"),
        ("h g\n1, 0.1\n2, 0.2, 0.3, 4\n", "line 3: 4 values"),
        ("h g\n", "no data"),
        ("h g\n-1, 0.1\n", "ranges > 0"),
    ],
)
def test_bad_files_name_the_line(tmp_path, text, message):
    f = tmp_path / "bad.txt"
    f.write_text(text)
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        read_overlap_curve(f)


def test_far_range_noise_recovers_a_known_sigma_despite_a_trend_and_spikes():
    rng = np.random.default_rng(7)
    z = np.linspace(500.0, 3000.0, NOISE_POINTS)
    sigma = 0.01
    g = 1.0 - 0.05 * np.exp(-z / 800.0) + rng.normal(0.0, sigma, z.size)
    g[::200] += 0.5  # spikes (a cloud bin)
    est = far_range_noise(z, g, (500.0, 3000.0))
    assert math.isclose(est, sigma, rel_tol=NOISE_RELATIVE)


def test_far_range_noise_refuses_bad_intervals_and_clipped_curves():
    z = np.linspace(100.0, 1000.0, 50)
    with pytest.raises(ValueError, match="interval .* holds 2 points"):
        far_range_noise(z, np.ones(50), (100.0, 120.0))
    with pytest.raises(ValueError, match="expected low < high"):
        far_range_noise(z, np.ones(50), (900.0, 100.0))
    with pytest.raises(ValueError, match="no scatter"):
        far_range_noise(z, np.ones(50), (100.0, 1000.0))


def test_a_curve_is_a_value_checked_on_construction():
    c = OverlapCurve([100.0, 200.0], [0.5, 0.9], [0.01, 0.02], ("h",), "m.csv")
    for name in ("ranges", "overlap", "sigma"):
        with pytest.raises(ValueError, match="read-only"):
            getattr(c, name)[0] = 3.0
    assert pickle.loads(pickle.dumps(c)) == c and c != OverlapCurve(
        [100.0, 200.0], [0.5, 0.9], None
    )
    for fields, name in [
        (([100.0, float("nan")], [0.5, 0.9], None), "ranges"),
        (([200.0, 100.0], [0.5, 0.9], None), "ranges"),
        (([100.0, 200.0], [0.5], None), "overlap"),
        (([100.0, 200.0], [0.5, float("inf")], None), "overlap"),
        (([100.0, 200.0], [0.5, 0.9], [0.1, -1.0]), "sigma"),
        (([100.0, 200.0], "xy", None), "overlap"),
    ]:
        with pytest.raises(ValueError, match=f"^{name}"):
            OverlapCurve(*fields)
    with pytest.raises(ValueError, match="^sigma"):
        dataclasses.replace(c, sigma=[float("nan"), 1.0])
    with pytest.raises(ValueError, match="^z_low = '100' is invalid"):
        c.within("100", "3000")


@pytest.mark.parametrize(
    "ranges, overlap, interval, message",
    [
        (
            [1.0, 2.0],
            [0.5, float("nan")],
            (0.0, 3.0),
            r"^overlap\[1\] = nan is invalid \(range 2 m\)",
        ),
        ([1.0, float("inf")], [0.5, 0.6], (0.0, 3.0), r"^ranges\[1\] = inf is invalid"),
        ([1.0, 2.0], [0.5], (0.0, 3.0), "overlap has 1 values for 2 ranges"),
        ([[1.0, 2.0]], [[0.5, 0.6]], (0.0, 3.0), "ranges has shape"),
        ([1.0, 2.0], [0.5, 0.6], 3.0, "interval = 3.0 is invalid"),
        ([1.0, 2.0], [0.5, 0.6], ("1", "3"), "interval = '1' is invalid"),
    ],
)
def test_far_range_noise_names_bad_inputs(ranges, overlap, interval, message):
    with pytest.raises(ValueError, match=message):
        far_range_noise(ranges, overlap, interval)
