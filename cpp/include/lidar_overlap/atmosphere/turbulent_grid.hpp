// The grids of the turbulent FO overlap (overlap_turbulent.hpp), stated once: the side each plane's grid
// spans, the least beam_grid a call accepts and the memory paths = both allocates. overlap_fo_turbulent
// builds its grids and refusals from these; planners ask them before choosing Fourier optics.
// Every plane's grid (a phase screen's or a range's) spans the beam's window: beam_window long-term radii
// plus 8 rms wander (the beam of any realisation stays inside it). With paths = both it also holds the
// receiver's light about the receiver's axis: 1.25 times its geometric footprint plus the spread by eddies of
// r0, 2 lambda z / r0. Its spacing (side / beam_grid) never shrinks along the path, and between two screens
// (from the transmitter to the first, from the last to the furthest range) it grows linearly with range, so
// that one forward transform at a screen serves every plane up to the next: each such segment ends at the
// least side that keeps every plane in it at or above its window. On both paths every plane's
// spacing must also sample the receiver's light: its largest angle plus lambda / r0, below lambda / (2
// spacing); so beam_grid >= side x 2 (angle + lambda / r0) / lambda at every plane, whatever beam_grid (the
// side does not depend on it).
#pragma once

#include <cstddef>
#include <vector>

#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"
#include "lidar_overlap/atmosphere/turbulence.hpp"
#include "lidar_overlap/core/system.hpp"

namespace lidar_overlap {

// lambda / r0 (rad): the spread by eddies of the plane-wave Fried parameter over [0, z] (m); 0 at z = 0 or
// in calm air.
double turbulent_seeing(const LidarSystem& system, const Cn2Profile& atmosphere, double z);

// Largest angle (rad) of the receiver's light leaving the pupil: the field of view (detector radius plus
// offset over the detector distance), the convergence to the conjugate range and the beam's tilt (the
// grid drifts with the beam).
double receiver_max_angle(const LidarSystem& system);

// Side (m) the grid of the plane at range z (m) needs, before the segments' linear growth: spacing times
// beam_grid.
double turbulent_window(const LidarSystem& system, const Cn2Profile& atmosphere, double beam_window,
                        TurbulencePaths paths, double z);

struct TurbulentGrid {
  std::vector<double>
      plane_range;  // m, the planes in propagation order: screens, then ranges at equal range
  std::vector<double>
      window;  // m, each plane's grid side (spacing x beam_grid), linear in range between screens
  double pupil_window = 0.0;       // m, the transmitter plane's (z = 0)
  std::size_t min_beam_grid = 32;  // least (even) beam_grid the call accepts for these paths
};

// The grids overlap_fo_turbulent would use for (system, ranges, atmosphere, options): options.beam_grid is
// not read (the sides do not depend on it). Throws std::invalid_argument for invalid inputs.
TurbulentGrid turbulent_grid(const LidarSystem& system, const std::vector<double>& ranges,
                             const Cn2Profile& atmosphere, const TurbulenceOptions& options);

// Bytes a paths = both call allocates: the screens' spectra and, per thread, the pair's two beams and
// 2 x receiver_fields fields plus working buffers.
double turbulent_both_bytes(std::size_t beam_grid, std::size_t screens, std::size_t receiver_fields,
                            int threads);

}  // namespace lidar_overlap
