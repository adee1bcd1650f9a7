"""Scenario text for the command-line tests."""


def csv_only(text: str) -> str:
    """The scenario with its NetCDF, plot and scene outputs switched off (CSV only)."""
    for key in ("netcdf", "plot", "scene"):
        text = text.replace(f"{key} = true", f"{key} = false")
    return text
