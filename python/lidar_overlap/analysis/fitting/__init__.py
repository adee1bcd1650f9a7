"""Fits of measured overlap curves: one checked fit problem, its strategies (local, relative, global
search, model ladder, joint and drift fits of many curves), their results and verdicts.

Files: correction.py, curve_set.py, diffraction.py, drift.py, drift_basis.py, drift_inputs.py,
drift_names.py, drift_prediction.py, drift_reference.py, drift_result.py, families.py, fit.py,
global_result.py, global_search.py, inputs.py, joint.py, joint_auto.py, joint_result.py, ladder.py,
multi_curve.py, multi_inputs.py, multi_result.py, multi_search.py, normalization.py, problem.py,
relative.py, relative_result.py, result.py, solve.py, verdict.py.
"""

__all__ = [
    "correction",
    "curve_set",
    "diffraction",
    "drift",
    "drift_basis",
    "drift_inputs",
    "drift_names",
    "drift_prediction",
    "drift_reference",
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
