// The deterministic transforms (cpp/src/fourier/fft.cpp): each is the DFT (against a direct sum and
// a plane wave's closed form), and its bits do not depend on the thread count, inside a caller's
// team or not; the team each size gets on a busy machine.
#include <omp.h>

#include <cmath>
#include <complex>
#include <cstring>
#include <string>

#include "check.hpp"
#include "fft_values.hpp"
#include "core/constants.hpp"
#include "core/parallel.hpp"
#include "fourier/fft.hpp"

using namespace lidar_overlap;

namespace {

using test::kRoundOff;
using test::pseudo_random;

bool same_bits(const ComplexBuffer& a, const ComplexBuffer& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Complex)) == 0;
}

ComplexBuffer transformed(const ComplexBuffer& in, std::size_t n, int threads, FftDirection d) {
  ComplexBuffer out = in;
  omp_set_num_threads(threads);
  fft2d(out, n, d);
  return out;
}

// The team a transform gets while a late team holds `threads = 0` to one thread
// (core/parallel.hpp): from 256^2 points the calling thread's full team size (omp_set_num_threads
// honoured; the passes' team never waits for a late thread), below it one thread, and one inside a
// caller's team at any size. The hold-off (grown to a second) is armed again before each query, so
// the checks do not depend on how soon they run.
void teams_on_a_busy_machine() {
  // A team of 2 one of whose threads waited 10 ms of a 10 ms region.
  const auto hold_off = [] {  // five late teams in a row: the hold grows from 0.1 s to its 1 s
    for (int team = 0; team < 5; ++team) detail::note_team_wait(2, 10'000'000, 10'000'000);
  };
  const std::size_t large = std::size_t{1} << 20;
  for (int team : {3, 2}) {
    const std::string with = " (team of " + std::to_string(team) + ")";
    omp_set_num_threads(team);
    hold_off();
    test::that("held off: threads = 0 means one thread" + with, detail::all_cores() == 1);
    // 2048^2, 2048 x 512, 1024^2, 512^2, 256^2
    for (const std::size_t points : {large * 4, large * 2, large, large / 4, large / 16}) {
      hold_off();
      test::that("held off: " + std::to_string(points) + " points keep the full team" + with,
                 fft_threads(points) == team);
    }
    hold_off();
    test::that("held off: fewer than 256^2 points run on one thread" + with,
               fft_threads(large / 16 - 1) == 1);
  }
  int nested = -1;
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    nested = fft_threads(large);
  }
  test::that("inside a caller's team a 1024^2 transform runs on one thread", nested == 1);
}

}  // namespace

int main() {
  const int cores = omp_get_num_procs();
  for (std::size_t n :
       {8, 12, 64, 250, 256, 512, 1024}) {  // 12 and 250: sizes kFftBlock does not divide
    const std::string at = " (n = " + std::to_string(n) + ")";
    // A plane wave exp(2 pi i (a x + b y) / n) transforms to n^2 at (a, b) and 0 elsewhere.
    const std::size_t a = 3 % n, b = (n / 2 + 1) % n;
    ComplexBuffer wave(n * n);
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x)
        wave[y * n + x] = std::polar(
            1.0, 2.0 * kPi * static_cast<double>(a * x + b * y) / static_cast<double>(n));
    const ComplexBuffer spectrum = transformed(wave, n, 1, FftDirection::forward);
    double worst = 0.0;
    for (std::size_t k = 0; k < n * n; ++k)
      worst = std::max(
          worst, std::abs(spectrum[k] - (k == b * n + a ? Complex(double(n * n)) : Complex{})));
    test::near("plane wave -> n^2 delta" + at, worst / double(n * n), 0.0, kRoundOff);

    // Forward then backward is n^2 times the input; bits equal for 1, 2 and all cores, and the
    // same inside a caller's OpenMP team (where the transform runs on one thread).
    const ComplexBuffer in = pseudo_random(n * n);
    const ComplexBuffer one = transformed(in, n, 1, FftDirection::forward);
    bool same = true;
    for (int t : {2, cores, 3})
      same = same && same_bits(one, transformed(in, n, t, FftDirection::forward));
    ComplexBuffer nested;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
      {
        nested = in;
        fft2d(nested, n, FftDirection::forward);
      }
    }
    test::that("forward transform: same bits for 1, 2, 3 and all threads and inside a team" + at,
               same && same_bits(one, nested));
    ComplexBuffer back = one;
    fft2d(back, n, FftDirection::backward);
    double err = 0.0;
    for (std::size_t k = 0; k < n * n; ++k)
      err = std::max(err, std::abs(back[k] / double(n * n) - in[k]));
    test::near("backward(forward(u)) / n^2 = u" + at, err, 0.0, kRoundOff);
  }

  // fft_rows against a direct sum on rows of a length that kFftBlock does not divide (and 13 rows).
  const std::size_t rows = 13, length = 40;
  const ComplexBuffer in = pseudo_random(rows * length);
  ComplexBuffer out = in;
  fft_rows(out, rows, length, FftDirection::backward);
  double worst = 0.0;
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t k = 0; k < length; ++k)
      worst = std::max(
          worst, std::abs(test::direct_dft(&in[r * length], length, k, +1) - out[r * length + k]));
  test::near("fft_rows = direct sum, exp(+2 pi i jk/n)", worst, 0.0, kRoundOff);
  teams_on_a_busy_machine();  // last: it leaves threads = 0 held to one thread for a second
  return test::report("test_fft");
}
