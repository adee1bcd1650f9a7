"""G of many variants of a system on one plan's model and ranges, in one core call where the model
allows: the single place the searches of the fits evaluate candidates, so it can move to the
forward layer's runner for many variants without touching them."""

from __future__ import annotations

import dataclasses

import numpy as np

from .. import _checks, _core
from ..forward.compute import run
from ..model import parameters as _parameters


def curves(p, systems) -> np.ndarray:
    """G of each system in ``systems`` (None for a candidate outside the model's range: its row
    is NaN) on plan ``p``: shape (len(systems), ranges). Ray tracing: one ``overlap_rt_batch``
    call for all of them; any other backend: one run of ``p`` per system."""
    z = p.ranges
    out = np.full((len(systems), z.size), np.nan)
    valid = [i for i, s in enumerate(systems) if s is not None]
    if not valid:
        return out
    if p.backend != "rt":
        for i in valid:
            out[i] = run(dataclasses.replace(p, system=systems[i])).overlap
        return out
    _checks.check_memory(
        "candidates", len(valid), 64.0 * len(valid) * z.size, "use a smaller population"
    )
    raw = _core.overlap_rt_batch(
        [systems[i]._native for i in valid for _ in z], np.tile(z, len(valid)), p.options
    )
    out[valid] = raw.overlap.reshape(len(valid), z.size)
    return out


def variants(system, paths, values) -> list:
    """``system`` with ``paths`` set to each row of ``values`` (S, k); None where the model refuses
    the values (a candidate outside its valid range costs infinity, it is not an error)."""
    out = []
    for row in np.asarray(values, dtype=float):
        try:
            out.append(_parameters.replace(system, dict(zip(paths, row.tolist()))))
        except ValueError:
            out.append(None)
    return out
