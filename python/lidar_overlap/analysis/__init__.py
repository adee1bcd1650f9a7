"""What is built on many overlap curves, in rooms above a shared floor: ``fitting`` (fits of
measured curves), ``studies`` (tolerance and turbulence studies, the telecover test and its fit,
lidar signals) and ``design`` (alignment maps, optimisation, automatic alignment, realignment); the
shared floor holds what every room uses (sensitivities, batched curves, engines, datasets, the
method an analysis runs).

Files: design/, fitting/, studies/, batch_curves.py, datasets.py, engines.py, method_choice.py,
sensitivity.py.
"""

__all__ = [
    "design",
    "fitting",
    "studies",
    "batch_curves",
    "datasets",
    "engines",
    "method_choice",
    "sensitivity",
]
