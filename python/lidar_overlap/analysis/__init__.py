"""What is built on many overlap curves: alignment maps, sensitivities, fits, the telecover test,
design optimisation and automatic alignment, lidar signals, tolerance and turbulence studies."""
