"""xarray, imported when a dataset is built (maps, sensitivities, studies, telecover; the ``[io]``
extra), and the variables they share."""

from __future__ import annotations


def xarray(what: str):
    """The xarray module, or ImportError saying that ``what`` needs it and how to install it."""
    try:
        import xarray as xr
    except ImportError as exc:
        raise ImportError(
            f"{what} returns an xarray.Dataset and needs xarray: pip install 'lidar-overlap[io]'"
        ) from exc
    return xr


def range_coordinate(ranges):
    """The ``range`` coordinate (m) of a dataset."""
    return ("range", ranges, {"units": "m", "long_name": "range from the transmitting plane"})
