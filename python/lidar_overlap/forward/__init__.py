"""The overlap function: methods (RT, FO, Auto, Turbulent), the plan that decides a computation, the
backends that run it (the only callers of the core's compute functions) and the result.

Files: backends/, auto.py, compute.py, coupling.py, methods.py, planners.py, planning.py, plans.py,
result.py, result_checks.py, result_files.py, validity.py.
"""

__all__ = [
    "backends",
    "auto",
    "compute",
    "coupling",
    "methods",
    "planners",
    "planning",
    "plans",
    "result",
    "result_checks",
    "result_files",
    "validity",
]
