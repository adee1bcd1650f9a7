"""One contract for every public value and result type, checked here once for all of them.

A value is frozen; its arrays are read-only and its mappings cannot be changed; it pickles, copies
and deep-copies to an equal value; and two builds of the same value are equal (``==`` by value,
never an exception). Its constructor's check of every field: test_value_field_checks.py.

The registry (tests/_value_registry.py) holds one example of each public type and the fields where
NaN is a documented value. A public dataclass of ``lidar_overlap`` that is not registered fails
:func:`test_every_public_value_type_is_registered`.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle
import types
import warnings
from typing import Any, Iterator

import numpy as np
import pytest
from _value_registry import IDS, REGISTRY, TYPES, _cls, _name, example

import lidar_overlap as lo


def _public_value_types() -> Iterator[type]:
    for name in lo.__all__:
        obj = getattr(lo, name)
        if isinstance(obj, type) and dataclasses.is_dataclass(obj):
            yield obj


def test_every_public_value_type_is_registered():
    missing = sorted(c.__name__ for c in _public_value_types() if c not in REGISTRY)
    assert not missing, f"register these value types in tests/_value_registry.py: {missing}"


@pytest.mark.parametrize("cls", TYPES, ids=IDS)
def test_the_example_is_of_its_type_and_frozen(cls):
    value = example(cls)
    assert type(value) is _cls(cls)
    first = dataclasses.fields(value)[0].name
    with pytest.raises(dataclasses.FrozenInstanceError):
        setattr(value, first, getattr(value, first))


def _leaves(value: Any, depth: int = 0) -> Iterator[Any]:
    """Arrays and containers reachable from a field (not into other registered values, which are
    checked on their own)."""
    yield value
    if depth > 3 or type(value) in REGISTRY:
        return
    if isinstance(value, (tuple, list)):
        for v in value:
            yield from _leaves(v, depth + 1)
    elif isinstance(value, (dict, types.MappingProxyType)):
        for v in value.values():
            yield from _leaves(v, depth + 1)


@pytest.mark.parametrize("cls", TYPES, ids=IDS)
def test_arrays_are_read_only_and_mappings_cannot_change(cls):
    value = example(cls)
    for f in dataclasses.fields(value):
        for leaf in _leaves(getattr(value, f.name)):
            if isinstance(leaf, np.ndarray):
                assert not leaf.flags.writeable, f"{_name(cls)}.{f.name} is a writable array"
            assert not isinstance(leaf, (dict, list, set)), (
                f"{_name(cls)}.{f.name} holds a mutable {type(leaf).__name__}"
            )


@pytest.mark.parametrize("cls", TYPES, ids=IDS)
def test_pickle_copy_and_deepcopy_give_an_equal_value(cls):
    value = example(cls)
    for again in (pickle.loads(pickle.dumps(value)), copy.copy(value), copy.deepcopy(value)):
        assert type(again) is _cls(cls) and again == value


@pytest.mark.parametrize("cls", TYPES, ids=IDS)
def test_equality_is_by_value(cls):
    value = example(cls)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        again = REGISTRY[cls].build()
    assert again is not value and again == value and not (again != value)
