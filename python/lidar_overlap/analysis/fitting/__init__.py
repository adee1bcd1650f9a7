"""Fits of measured overlap curves: one checked fit problem, its strategies (local, relative, global
search, model ladder), their results and verdicts.

Files: correction.py, families.py, fit.py, global_result.py, global_search.py, inputs.py, ladder.py,
normalization.py, problem.py, relative.py, relative_result.py, result.py, solve.py, verdict.py.
"""

__all__ = [
    "correction",
    "families",
    "fit",
    "global_result",
    "global_search",
    "inputs",
    "ladder",
    "normalization",
    "problem",
    "relative",
    "relative_result",
    "result",
    "solve",
    "verdict",
]
