// Plans for the 1-D block transforms (fourier/fft.hpp) chosen once by timing and shipped with the source as
// FFTW wisdom. FFTW_ESTIMATE depends on the shape alone but picks slower algorithms than FFTW_MEASURE (at
// 512 points, 8 rows: 20 % slower), while FFTW_MEASURE picks by timing, differently in each process. Plans
// measured once, kept in fft_wisdom.inc and imported before each plan is made, are both: fast, and the same
// in every process that uses the same FFTW build (FFTW refuses wisdom from another version or configuration,
// and a plan whose SIMD codelets the CPU lacks; those shapes get estimated plans, as every shape the
// wisdom does not hold). scripts/make_fft_wisdom.py measures the wisdom anew. Internal header, not
// installed.
#pragma once

#include <fftw3.h>

#include <cstddef>
#include <string>
#include <vector>

namespace lidar_overlap::detail {

// One 1-D FFTW problem the library plans: `count` rows of `length`, `distance` apart, in place or from one
// array to another of the same layout.
struct BlockProblem {
  std::size_t length, count;
  int sign;  // FFTW_FORWARD or FFTW_BACKWARD
  std::size_t distance;
  bool out_of_place;
};

// Every problem the transforms of `length` plan (RowTransform and BlockTransform, both directions).
std::vector<BlockProblem> block_problems(std::size_t length);

// Registers FFTW's threaded solvers once (other FFTW users in the process may plan with threads). Wisdom
// carries a signature of the solvers registered where it was measured and imports only where the same are:
// both measure_fft_wisdom and plan_from_wisdom call this first. The caller holds fftw_planner_mutex().
void init_fftw_threads();

// FFTW's plan for `problem` with planner `flags`, made on fresh FFTW-aligned scratch memory (the alignment of
// every buffer it is run on), single-threaded. Null when FFTW makes none (FFTW_WISDOM_ONLY without wisdom).
// The caller holds fftw_planner_mutex().
fftw_plan plan_block(const BlockProblem& problem, unsigned flags);

// The plan `wisdom` holds for `problem`, or null: the wisdom does not import into this FFTW, holds no plan
// for the problem, or its plan does not run on this CPU. All wisdom is forgotten before and after, so that
// neither timings of other FFTW users in the process nor this wisdom steer other plans. The caller holds
// fftw_planner_mutex().
fftw_plan plan_from_wisdom(const BlockProblem& problem, const char* wisdom);

// The plan `wisdom` holds for `problem`, else FFTW_ESTIMATE's on forgotten wisdom (and forgotten after):
// either depends on the shape and the wisdom alone. Throws when FFTW makes no plan. The caller holds
// fftw_planner_mutex().
fftw_plan plan_from_wisdom_or_estimate(const BlockProblem& problem, const char* wisdom);

// The wisdom shipped in fft_wisdom.inc, and the version string (fftw_version) of the FFTW it was measured
// with: an FFTW of that string imports it.
const char* shipped_fft_wisdom();
const char* shipped_fft_wisdom_fftw();

// Least time (s) over `repeats` of a forward 2-D transform of n x n values on the calling thread, made the
// two ways the library makes it (in place: fft2d; out of place: propagate and the split steps), with the
// block plans `wisdom` gives (estimated plans for the problems it gives none): how
// scripts/make_fft_wisdom.py chooses between measured candidates. Takes the planner's lock to plan.
double block_transform_seconds(std::size_t n, const char* wisdom, int repeats);

// Wisdom for every block problem of each length, measured now (FFTW_MEASURE) on forgotten wisdom: the text
// of fft_wisdom.inc. Takes seconds per length from 4096 points up.
std::string measure_fft_wisdom(const std::vector<std::size_t>& lengths);

// The wisdom of all `texts` in one (each must import into this FFTW).
std::string merge_fft_wisdom(const std::vector<std::string>& texts);

}  // namespace lidar_overlap::detail
