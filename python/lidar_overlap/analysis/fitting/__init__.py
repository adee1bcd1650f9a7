"""Fits of measured overlap curves: one checked fit problem, its strategies (local, relative, global
search, model ladder), their results and verdicts.

Files: correction.py, drift.py, drift_result.py, families.py, fit.py, global_result.py,
global_search.py, inputs.py, joint.py, joint_auto.py, joint_result.py, ladder.py, multi_curve.py,
multi_inputs.py, multi_result.py, multi_search.py, normalization.py, problem.py, relative.py,
relative_result.py, result.py, solve.py, verdict.py.
"""

__all__ = [
    "correction",
    "drift",
    "drift_result",
    "families",
    "fit",
    "global_result",
    "global_search",
    "inputs",
    "joint",
    "joint_auto",
    "joint_result",
    "ladder",
    "multi_curve",
    "multi_inputs",
    "multi_result",
    "multi_search",
    "normalization",
    "problem",
    "relative",
    "relative_result",
    "result",
    "solve",
    "verdict",
]
