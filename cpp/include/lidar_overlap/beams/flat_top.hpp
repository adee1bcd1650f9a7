// Flat-top beams (paper Section 4C, Figs. 6-7): a TEM00 laser through a phase plate designed with the
// Gerchberg-Saxton algorithm so that its far-field irradiance is a uniform disc. A waist w0 can only be
// spread, and only to within its diffraction angle lambda / (pi w0): the target disc has a soft edge of
// a chosen 10-90 % width, and its plateau gets flatter the softer that edge is.
#pragma once

#include <string>
#include <vector>

#include "lidar_overlap/fourier/field.hpp"

namespace lidar_overlap {

struct FlatTopOptions {
  std::size_t grid = 512;          // samples per side of the plate (even, >= 64)
  double samples_per_waist = 8.0;  // plate sampling, w0 / spacing
  double edge_width = 0.0;  // rad, 10-90 % width of the target's edge; 0: 1.5 lambda / (pi w0)
  std::size_t max_iterations = 300;
  double tolerance = 1e-4;  // stop once an iteration lowers the error by less than this fraction
  double max_error = 0.05;  // an error still above this when it stops improving is a stagnation
  double power = 1.0;       // W
};

enum class FlatTopStop { converged, stagnated, max_iterations };

struct FlatTopDesign {
  Field transmitted;               // W^0.5/m at z = 0: TEM00 amplitude times exp(i phase)
  std::vector<double> phase;       // rad, n x n, the plate, centred like the field
  std::vector<double> target;      // W/sr, n x n far-field target, centred (index n/2 is angle 0)
  std::vector<double> far_field;   // W/sr, n x n far-field radiant intensity the plate achieves
  double angular_spacing = 0.0;    // rad per far-field sample: lambda / (n spacing)
  double edge_width_target = 0.0;  // rad, the 10-90 % edge width asked of the target
  std::vector<double>
      history;  // amplitude error || |V| - B || / || B || per iteration (monotone in GS)
  FlatTopStop stop = FlatTopStop::max_iterations;
  bool monotone = true;     // the error never rose (beyond rounding)
  double efficiency = 0.0;  // fraction of the power inside the nominal disc (half the diameter)
  double uniformity_rms =
      0.0;  // std / mean of the far field where the target is >= 90 % of its peak
  double uniformity_pv = 0.0;  // (max - min) / mean over the same plateau
  double edge_width = 0.0;     // rad, achieved 10-90 % width of the azimuthally averaged far field
};

// Designs the plate for a waist `waist_radius` (m) at `wavelength` (m) and a far-field disc of full
// angular diameter `angular_diameter` (rad, at half the plateau irradiance). Throws std::invalid_argument
// naming the parameter when the target is below the waist's diffraction limit or the grid cannot hold it.
FlatTopDesign design_flat_top(double wavelength, double waist_radius, double angular_diameter,
                              const FlatTopOptions& options = {});

const char* to_string(FlatTopStop stop);

}  // namespace lidar_overlap
