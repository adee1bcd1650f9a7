"""The value contract's field checks, for every registered public type (tests/_value_registry.py):
its constructor checks every field, so that ``dataclasses.replace`` cannot smuggle in NaN, a wrong
kind or an unknown name: a hostile field is refused with a ValueError that names it. The rest of
the contract (frozen, read-only, pickling, equality): test_value_contract.py."""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Iterator, Tuple

import numpy as np
import pytest
from _value_registry import REGISTRY, TYPES, _cls, _name, example
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st


def _replaceable(cls: type) -> Iterator[Tuple[type, str]]:
    value = example(cls)
    for f in dataclasses.fields(value):
        if f.init and isinstance(getattr(value, f.name), (float, np.ndarray)):
            yield cls, f.name


def _optional(cls: type, name: str) -> bool:
    default = next(f for f in dataclasses.fields(_cls(cls)) if f.name == name).default
    return default is None or name in REGISTRY[cls].none_ok


NUMERIC = [pair for cls in TYPES for pair in _replaceable(cls)]


@pytest.mark.parametrize("cls, name", NUMERIC, ids=[f"{_name(c)}.{n}" for c, n in NUMERIC])
@pytest.mark.parametrize("hostile", ["x", None, {"a": 1.0}])
def test_a_field_of_the_wrong_kind_is_refused_by_name(cls, name, hostile):
    value = example(cls)
    if hostile is None and _optional(cls, name):
        return  # None is a documented value
    with pytest.raises(ValueError, match=name):
        dataclasses.replace(value, **{name: hostile})


@pytest.mark.parametrize("cls, name", NUMERIC, ids=[f"{_name(c)}.{n}" for c, n in NUMERIC])
def test_an_array_of_another_shape_is_refused(cls, name):
    value = example(cls)
    old = getattr(value, name)
    if not isinstance(old, np.ndarray):
        return
    with pytest.raises(ValueError):
        dataclasses.replace(value, **{name: np.zeros(old.shape + (2,))})


WITH_NUMBERS = sorted({c for c, _ in NUMERIC}, key=_name)


@pytest.mark.parametrize("cls", WITH_NUMBERS, ids=[_name(c) for c in WITH_NUMBERS])
@settings(
    max_examples=30,
    derandomize=True,
    database=None,
    deadline=None,
    suppress_health_check=list(HealthCheck),
)
@given(data=st.data())
def test_nan_or_inf_is_refused_by_name_unless_documented(cls, data):
    name = data.draw(st.sampled_from([n for c, n in NUMERIC if c is cls]), label="field")
    bad = data.draw(st.sampled_from([math.nan, math.inf, -math.inf]), label="value")
    value = example(cls)
    old = getattr(value, name)
    if isinstance(old, np.ndarray):
        if old.size == 0:
            return
        kind = complex if np.iscomplexobj(old) else float  # a complex field keeps its phase
        new: Any = np.array(old, dtype=kind, copy=True)
        new.flat[data.draw(st.integers(0, old.size - 1), label="index")] = bad
    else:
        new = bad
    entry = REGISTRY[cls]
    documented = entry.nan_ok if math.isnan(bad) else entry.inf_ok if bad > 0 else frozenset()
    if name in documented:
        dataclasses.replace(value, **{name: new})  # accepted: a documented value here
        return
    with pytest.raises(ValueError, match=name):
        dataclasses.replace(value, **{name: new})
