// Fourier propagation from C++: the scaled (chirp-z) DFT against the direct sum, and the TEM00 beam
// radius against Eq. (D1) for every method inside its region, with power conserved.
#include <cmath>
#include <random>

#include "check.hpp"
#include "lidar_overlap/fourier/propagate.hpp"
#include "core/constants.hpp"
#include "fourier/scaled_dft.hpp"

using namespace lidar_overlap;

int main() {
  // Scaled DFT of a random 16 x 16 array to 12 x 12 outputs against the defining double sum.
  const std::size_t n = 16, m = 12;
  const double alpha = 0.0371;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  ComplexBuffer in(n * n);
  for (Complex& v : in) v = {g(rng), g(rng)};
  const ComplexBuffer out = scaled_dft2d(in, n, m, alpha);
  double worst = 0.0;
  for (std::size_t my = 0; my < m; ++my)
    for (std::size_t mx = 0; mx < m; ++mx) {
      Complex direct{};
      for (std::size_t ny = 0; ny < n; ++ny)
        for (std::size_t nx = 0; nx < n; ++nx) {
          const double ph = -2.0 * kPi * alpha *
                            ((mx - m / 2.0) * (nx - n / 2.0) + (my - m / 2.0) * (ny - n / 2.0));
          direct += in[ny * n + nx] * Complex{std::cos(ph), std::sin(ph)};
        }
      worst = std::max(worst, std::abs(direct - out[my * m + mx]));
    }
  test::near("chirp-z against the direct DFT (max abs difference)", worst, 0.0, 1e-11);

  // TEM00, w0 = 5 mm, 355 nm on 256 x 256 samples spanning +-5 w0: D1 to 1e-9 (the sampled Gaussian's
  // moments are exact to ~1e-13; the margin covers FFT rounding).
  const double w0 = 5e-3, lambda = 355e-9, zr = kPi * w0 * w0 / lambda;
  const Field beam = Field::gaussian(lambda, w0, 256, 10.0 * w0 / 256);
  struct Case {
    PropagationMethod method;
    double z;
  };
  for (const Case c :
       {Case{PropagationMethod::angular_spectrum, 2.0}, Case{PropagationMethod::fresnel, 300.0},
        Case{PropagationMethod::automatic, 5e4}}) {
    const Propagated p = propagate(beam, c.z, c.method);
    const double expected = w0 * std::sqrt(1.0 + std::pow(c.z / zr, 2));
    test::near("D1 at z=" + std::to_string(c.z), p.field.beam_radius() / expected, 1.0, 1e-9);
    test::near("power at z=" + std::to_string(c.z), p.field.power(), 1.0, 1e-12);
  }
  // Fraunhofer far beyond the Rayleigh range: w = lambda z / (pi w0) to (zr / z)^2 / 2.
  const double zf = 1e3 * zr;
  test::near("Fraunhofer divergence",
             propagate(beam, zf, PropagationMethod::fraunhofer).field.beam_radius(),
             lambda * zf / (kPi * w0), 1e-6 * lambda * zf / (kPi * w0));
  test::throws(
      "Fresnel needs a positive distance",
      [&] { propagate(beam, -1.0, PropagationMethod::fresnel); }, "distance");
  return test::report("test_propagate");
}
