"""The stored benchmark results are strict JSON (RFC 8259), readable by any parser: a failed or
undefined value is null, never NaN or Infinity (which Python writes by default and strict parsers
such as JavaScript's JSON.parse or jq reject)."""

import importlib.util
import json
import math
from pathlib import Path

import numpy as np
import pytest

BENCHMARKS = Path(__file__).resolve().parent.parent / "benchmarks"
STORED = sorted((BENCHMARKS / "results").glob("*.json"))


def _reject(constant):
    raise ValueError(f"{constant} is not JSON")


def _common():
    spec = importlib.util.spec_from_file_location("_bench_common", BENCHMARKS / "_common.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_results_are_stored():
    assert len(STORED) >= 10  # the glob found the folder


@pytest.mark.parametrize("path", STORED, ids=lambda p: p.name)
def test_stored_result_is_strict_json(path):
    json.loads(path.read_text(), parse_constant=_reject)


def test_json_text_writes_non_finite_values_as_null():
    record = {
        "rms": math.nan,
        "nested": [1.5, -math.inf, (np.float64(math.inf), np.float64(2.0))],
        "fine": {"x": 0.1, "n": 3, "name": "a", "none": None, "flag": True},
    }
    text = _common().json_text(record, indent=1)
    assert json.loads(text, parse_constant=_reject) == {
        "rms": None,
        "nested": [1.5, None, [None, 2.0]],
        "fine": {"x": 0.1, "n": 3, "name": "a", "none": None, "flag": True},
    }
    assert text.endswith("}\n")
