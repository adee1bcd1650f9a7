// Fourier-optics overlap through a turbulent atmosphere (paper Section 3, step 2): the transmitted TEM00
// beam is carried through thin phase screens (modified von Karman statistics, lidar_overlap/
// atmosphere/phase_screen.hpp) placed along the path with the Fried parameters of their segments (Cn2Profile::
// place_screens), by split-step Fresnel propagation on grids that follow the beam's long-term radius, and
// the overlap is computed at each range from that realisation's irradiance exactly as in overlap_fo.
// That sum is linear in the irradiance, so it is made once per range as a map on the beam grid (n^2
// doubles per range) and costs each realisation one pass over its irradiance.
// Each realisation is one random draw of the atmosphere (frozen during the pulse): the statistics over
// realisations give the mean overlap and its spread. TurbulencePaths::transmit takes the return path as
// unperturbed; TurbulencePaths::both carries the receiver's light (reciprocity, atmosphere/return_path.hpp in
// cpp/src) through the same screens, so that G of a draw is the integral of the beam's irradiance times the
// receiver's sensitivity, both through one atmosphere: its mean may exceed 1 (backscatter amplification, at
// most 2, docs/turbulence.md).
// receiver_fields: the detector's sensitivity is the mean over M random-phase fields, unbiased for every M, and
// their speckle is an independent noise that the mean over realisations averages with the atmosphere's spread:
// Var(G of a draw) = s_atm^2 + s_rx^2 / M at a cost per draw c0 + M c1. At equal CPU time the standard error of
// the mean G barely depends on M (benchmarks/study_receiver_fields.py: the 5 cm, 0.28 mrad lidar of
// docs/turbulence.md, a detector of few coherence cells where s_rx is largest: SE x sqrt(CPU s) at 1000 m 0.213,
// 0.205, 0.187, 0.202 for M = 1, 2, 4, 8), and a wide field of view averages the speckle under the beam.
// M = 1 is the default: the cheapest draw (about twice a transmit-only one), more draws for the same time.
// A run (seed, screens, grid) is a fixed sequence of realisations: realisation k's screens depend only on
// (seed, k), never on the thread count or on the other realisations, so a call with first_realization = f and
// realizations = c gives rows f .. f + c - 1 of the run, bit for bit: the run splits into parts on many machines.
#pragma once

#include <cstdint>
#include <vector>

#include "lidar_overlap/atmosphere/turbulence.hpp"
#include "lidar_overlap/core/system.hpp"

namespace lidar_overlap {

// Bounds on the work one call may ask for (each realisation costs one split-step pass per screen).
inline constexpr std::size_t kMaxRealizations = 1000000;
inline constexpr std::size_t kMaxScreens = 1000;
inline constexpr std::size_t kMaxReceiverFields = 1000;

// Screen j's stream of draws in the run of `seed` (odd multiples of the 64-bit golden ratio keep the screens'
// streams apart).
inline constexpr std::uint64_t kScreenStreamStep = 0x9E3779B97F4A7C15ULL;
inline std::uint64_t screen_stream(std::uint64_t seed, int screen) {
  return seed ^ (kScreenStreamStep * static_cast<std::uint64_t>(screen + 1));
}

// Which paths cross the turbulence: the beam's only, or the beam's and the return path's.
enum class TurbulencePaths { transmit, both };

struct TurbulenceOptions {
  std::size_t realizations =
      20;                    // realisations computed: first_realization, first_realization + 1, ...
  std::size_t screens = 10;  // phase screens over [0, last range]
  std::uint64_t seed = 0;    // same seed, same screens, whatever the thread count
  std::size_t beam_grid = 256;  // samples per side of the propagated field
  double beam_window = 8.0;     // window in long-term radii (plus 8 rms wander) at every plane
  std::size_t max_spectrum_grid = 4096;
  int threads = 0;  // OpenMP threads across realisations; 0: all cores, per call. Callers that run
                    // calls from several threads pass 1 (or their share): core/limits.hpp
  std::size_t first_realization =
      0;  // index of the first in the run of `seed`; first + realizations <= kMaxRealizations
          // (last, so that braced initialisers of the fields above keep their meaning)
  TurbulencePaths paths =
      TurbulencePaths::transmit;  // both: the return path through the same screens
  std::size_t receiver_fields =
      1;  // both: random-phase fields standing for the incoherent detector (below)
};

struct TurbulentOverlap {
  std::vector<std::vector<double>> overlap;  // [realisation - first_realization][range]
  std::vector<double> wander_x, wander_y;    // m, beam centroid at the last range, per realisation
  std::vector<double> radius_last;  // m, second-moment radius at the last range, per realisation
  // paths = both: G of each draw's beam with the receiver's sensitivity through the other draw of its screen
  // pair (an independent atmosphere): the uncorrelated paths, whose mean the amplification divides by.
  std::vector<std::vector<double>>
      uncorrelated;  // [realisation - first_realization][range]; empty for transmit
  // paths = both: standard error of each draw's G from its receiver_fields random-phase fields (their spread over
  // sqrt(receiver_fields)); NaN with one field (no spread to measure); empty for transmit.
  std::vector<std::vector<double>> receiver_error;
  // paths = both: m, centroid of the receiver's sensitivity (its fields' summed irradiance) at the last range,
  // per realisation, on the beam's grid (centred on the beam's axis); its motion is the image's seen from the
  // sky (z times the angle of arrival for a receiver focused there). Empty for transmit.
  std::vector<double> receiver_x, receiver_y;
  // The run's screens: range (m), grid spacing (m) and Fried parameter (m) of screen j, whose draw for
  // realisation k is PhaseScreenGenerator(beam_grid, spacing, r0, outer, inner).generate(screen_stream(seed, j),
  // k) on the grid centred on the beam's axis at that range: enough to replay them.
  std::vector<double> screen_range, screen_spacing, screen_r0;
};

// Throws std::invalid_argument for a system or profile that is not valid, a beam that is not a
// diffraction-limited Gaussian, or options out of range (naming them).
TurbulentOverlap overlap_fo_turbulent(const LidarSystem& system, const std::vector<double>& ranges,
                                      const Cn2Profile& atmosphere,
                                      const TurbulenceOptions& options = {});

}  // namespace lidar_overlap
