// The planes the turbulent FO path passes and the segments it propagates them in (overlap_turbulent.cpp).
// Internal header, not installed.
#pragma once

#include <cstddef>
#include <vector>

#include "atmosphere/scaled_step.hpp"

namespace lidar_overlap::detail {

// A plane the beam passes: a phase screen or a range where the overlap is wanted.
struct Plane {
  double z;         // m
  int screen = -1;  // index into the screens, or -1
  int range = -1;   // index into the ranges, or -1
};

// From a screen's plane (or the transmitter's) to the next screen's (or the last plane): one Departure, then
// an Arrival per plane reached, in range order but the segment's end last (it may overwrite the spectrum).
struct Segment {
  int screen;  // the screen applied on departure, or -1 (the transmitter)
  Departure departure;
  std::vector<std::size_t> targets;  // indices into the planes, one per arrival
  std::vector<Arrival> arrivals;
};

struct TurbulentPlan {
  std::vector<Plane>
      planes;  // screens, then ranges, stably sorted by range (as turbulent_grid orders them)
  std::vector<Segment> segments;  // in propagation order
  std::vector<double> spacing;  // m, each plane's grid spacing (its side in turbulent_grid over n)
};

// The plan for screens at screen_ranges and the ranges (both m), from turbulent_grid's sides of the same
// planes (`windows`, in the planes' order) and of the transmitter's plane, on n x n grids.
TurbulentPlan plan_propagation(const std::vector<double>& screen_ranges,
                               const std::vector<double>& ranges,
                               const std::vector<double>& windows, double pupil_window,
                               std::size_t n, double lambda);

}  // namespace lidar_overlap::detail
