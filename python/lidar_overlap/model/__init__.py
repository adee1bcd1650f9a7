"""The model of a lidar: immutable value types checked on construction (system, beams, fields,
masks, aberrations, turbulence, atmosphere), their parameters by path, and the paper's Table 1
preset."""
