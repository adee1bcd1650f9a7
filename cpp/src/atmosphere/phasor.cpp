#include "atmosphere/phasor.hpp"

namespace lidar_overlap::detail {

namespace {

double inside(double x) { return std::abs(x) <= kPhasorReach ? x : 0.0; }

// Lanes of V at a time; the tail and the phases beyond reach by phasor().
template <class V, class W, std::size_t L>
__attribute__((always_inline)) inline void phasors_by(const double* phase, Complex* out,
                                                      std::size_t count) {
  std::size_t j = 0;
  for (; j + L <= count; j += L) {
    V x, re, im;
    for (std::size_t l = 0; l < L; ++l) x[l] = inside(phase[j + l]);
    phasor_kernel::reduced<V, W>(x, re, im);
    for (std::size_t l = 0; l < L; ++l) out[j + l] = {re[l], im[l]};
  }
  for (; j < count; ++j) out[j] = phasor(inside(phase[j]));
  bool far = false;
  for (std::size_t i = 0; i < count; ++i) far |= !(std::abs(phase[i]) <= kPhasorReach);
  if (far)
    for (std::size_t i = 0; i < count; ++i)
      if (!(std::abs(phase[i]) <= kPhasorReach)) out[i] = phasor(phase[i]);
}

#if defined(__x86_64__) && defined(__GNUC__)
using Doubles4 = double __attribute__((vector_size(32)));
using Words4 = std::uint64_t __attribute__((vector_size(32)));

// AVX2 without FMA: the same operations as the two-lane path, twice as many at once.
__attribute__((target("avx2"))) void phasors_avx2(const double* phase, Complex* out,
                                                  std::size_t count) {
  phasors_by<Doubles4, Words4, 4>(phase, out, count);
}

bool has_avx2() {
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
}
#endif

}  // namespace

void phasors(const double* phase, Complex* out, std::size_t count) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (has_avx2()) return phasors_avx2(phase, out, count);
#endif
  phasors_by<phasor_kernel::Doubles, phasor_kernel::Words, 2>(phase, out, count);
}

}  // namespace lidar_overlap::detail
