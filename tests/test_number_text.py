"""Numbers in files and on the command line are ASCII decimals with '.' as the decimal point: text
that Python's float() would also take (full-width or Arabic-Indic digits, '_' between digits) or a
decimal comma is refused naming the line, never read as another number; a result file cut short
is refused, even inside its last number."""

import math

import numpy as np
import pytest

import lidar_overlap as lo
from lidar_overlap import _reading
from lidar_overlap.io.overlap_curves import read_overlap_curve

#: Text float() reads as a number that the formats refuse.
LOOKALIKES = ["１００", "١٠٠", "1_00", "1_0.5", "１e3"]


@pytest.mark.parametrize("text", LOOKALIKES)
def test_lookalike_digits_are_not_numbers(text):
    assert float(text) > 0  # what Python alone would accept
    assert _reading.number(text) is None and _reading.integer(text) is None


@pytest.mark.parametrize(
    "text, value",
    [("100", 100.0), (" -1.5e-3 ", -1.5e-3), (".5", 0.5), ("5.", 5.0), ("+2E+2", 200.0)],
)
def test_ascii_decimals_read_exactly(text, value):
    assert _reading.number(text) == value


def test_nan_and_inf_read_as_floats_for_the_checks_that_follow():
    assert math.isnan(_reading.number("nan")) and _reading.number("-inf") == -math.inf


@pytest.mark.parametrize("text", LOOKALIKES)
def test_a_curve_with_lookalike_digits_is_refused_naming_line_and_column(tmp_path, text):
    f = tmp_path / "c.txt"
    f.write_text(f"height overlap\n100 0.5\n{text} 0.9\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"c\.txt: line 3, column 1: .* expected a number"):
        read_overlap_curve(f)


@pytest.mark.parametrize("row", ["150 0,250", "150\t0,25", "150;0,25", "150, 0,25"])
def test_a_decimal_comma_export_is_refused_not_read_as_three_columns(tmp_path, row):
    f = tmp_path / "c.txt"
    f.write_text(f"range overlap\n{row}\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"line 2: .* decimal comma"):
        read_overlap_curve(f)


def test_commas_as_separators_still_read(tmp_path):
    f = tmp_path / "c.csv"
    f.write_text("range_m,overlap,sigma\n150,0.25,0.01\n300,0.5,0.02\n")
    c = read_overlap_curve(f)
    assert c.overlap.tolist() == [0.25, 0.5] and c.sigma.tolist() == [0.01, 0.02]


@pytest.fixture
def result_csv(tmp_path):
    path = tmp_path / "g.csv"
    lo.overlap(lo.paper_table1(), [100.0, 300.0, 1000.0], "rt").to_csv(path)
    return path


def test_a_result_file_closes_with_its_row_count(result_csv):
    last = result_csv.read_text().splitlines()[-1]
    assert last == "# rows: 3"


@pytest.mark.parametrize("cut", [1, 5, 12, 30])
def test_a_result_file_cut_short_is_refused_even_inside_a_number(result_csv, cut):
    text = result_csv.read_text()
    result_csv.write_text(text[: -len("# rows: 3\n") - cut])
    with pytest.raises(ValueError, match="cut short|expected 3 numbers"):
        lo.OverlapResult.from_csv(result_csv)


def test_a_wrong_row_count_is_refused(result_csv):
    result_csv.write_text(result_csv.read_text().replace("# rows: 3", "# rows: 4"))
    with pytest.raises(ValueError, match="not the 3 rows it holds"):
        lo.OverlapResult.from_csv(result_csv)


def test_rows_after_the_count_are_refused(result_csv):
    result_csv.write_text(result_csv.read_text() + "2000.0,1.0,0.0\n")
    with pytest.raises(ValueError, match="nothing may follow"):
        lo.OverlapResult.from_csv(result_csv)


@pytest.mark.parametrize("text", LOOKALIKES)
def test_a_result_row_with_lookalike_digits_is_refused(result_csv, text):
    lines = result_csv.read_text().splitlines()
    z, g, e = lines[-2].split(",")
    lines[-2] = ",".join([z, g, text])
    result_csv.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match="expected 3 numbers"):
        lo.OverlapResult.from_csv(result_csv)


def test_header_numbers_with_underscores_stay_text(result_csv):
    r = lo.OverlapResult.from_csv(result_csv)
    text = result_csv.read_text().replace("# method: rt", "# method: rt\n# site_code: 1_00")
    result_csv.write_text(text)
    assert lo.OverlapResult.from_csv(result_csv) == r
    from lidar_overlap.forward.result_files import parse_value

    assert parse_value("1_00") == "1_00" and parse_value("100") == 100
    assert parse_value("１００") == "１００" and np.isclose(parse_value("1e2"), 100.0)
