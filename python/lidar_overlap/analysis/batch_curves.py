"""G of many variants of a system on one plan's model and ranges, through the forward layer's runner
for many variants (one core call on ray tracing): the single place the searches of the fits evaluate
candidates."""

from __future__ import annotations

from typing import List, Optional

import numpy as np

from .. import _checks
from ..forward.backends import many
from ..model import parameters as _parameters
from ..model.system import LidarSystem


def curves(p, systems) -> np.ndarray:
    """G of each system in ``systems`` (None for a candidate outside the model's range: its row is
    NaN) on plan ``p``: shape (len(systems), ranges). Ray tracing: one batched core call for all of
    them; any other backend: one run of ``p`` re-targeted at each system."""
    z = p.ranges
    out = np.full((len(systems), z.size), np.nan)
    valid = [i for i, s in enumerate(systems) if s is not None]
    if not valid:
        return out
    _checks.check_memory(
        "candidates", len(valid), 64.0 * len(valid) * z.size, "use a smaller population"
    )
    curves = many.systems(p, [systems[i] for i in valid], warn=False)
    out[valid] = curves.overlap
    return out


def variants(system, paths, values) -> list:
    """``system`` with ``paths`` set to each row of ``values`` (S, k); None where the model refuses
    the values (a candidate outside its valid range costs infinity, it is not an error)."""
    out: List[Optional[LidarSystem]] = []
    for row in np.asarray(values, dtype=float):
        try:
            out.append(_parameters.replace(system, dict(zip(paths, row.tolist()))))
        except ValueError:
            out.append(None)
    return out
