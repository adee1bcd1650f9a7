#include "lidar_overlap/atmosphere/phase_screen.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "lidar_overlap/core/limits.hpp"
#include "core/cancel_every.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/quadrature.hpp"
#include "core/xoshiro.hpp"
#include "fourier/fft.hpp"
#include "fourier/zeroed_buffer.hpp"

namespace lidar_overlap {

namespace {

// Kolmogorov phase PSD coefficient in cycles/m: with it, 4 pi int f Phi(f) [1 - J0(2 pi f r)] df equals
// 2 (24/5 Gamma(6/5))^(5/6) (r / r0)^(5/3) = 6.8839 (r / r0)^(5/3). Schmidt's 0.023 is this rounded.
constexpr double kPsdCoefficient = 0.022895587108555;
constexpr int kLevels = 3;  // subharmonic levels, frequency steps df / 3, df / 9, df / 27

// splitmix64's output function: a bijective 64-bit mixer, so that nearby (seed, pair) give unrelated
// generator states.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// int_a^b f to a relative 1e-10 (a first pass over [a, b] sets the scale).
template <class F>
double integral(F&& f, double a, double b) {
  const double points[2] = {a, b};
  const double scale = integrate(f, points, 2, std::numeric_limits<double>::infinity(), 1).value;
  return integrate(f, points, 2, 1e-10 * std::abs(scale), 2000).value;
}

// Phase-gradient variance of the cell of side w centred on (cx, cy) (cycles/m) expressed as the
// variance (rad^2) of its centre frequency: int_cell Phi(f) |f|^2 d^2f / |c|^2. Near f = 0 the PSD
// varies by orders of magnitude across a cell and its centre value misses most of the cell's power.
double cell_variance(const PhaseScreenGenerator& g, double cx, double cy, double w) {
  auto column = [&](double fx) {
    return integral([&](double fy) { return g.psd(std::hypot(fx, fy)) * (fx * fx + fy * fy); },
                    cy - 0.5 * w, cy + 0.5 * w);
  };
  return integral(column, cx - 0.5 * w, cx + 0.5 * w) / (cx * cx + cy * cy);
}

// int Phi(f) |f|^2 d^2f over the square |fx|, |fy| <= a, in polar coordinates by its 8-fold symmetry;
// f = rho u^3 makes the radial integrand smooth at f = 0, where Phi f^3 ~ f^(-2/3) for Kolmogorov.
double centre_gradient_variance(const PhaseScreenGenerator& g, double a) {
  auto ray = [&](double theta) {
    const double rho = a / std::cos(theta);
    return integral(
        [&](double u) {
          const double f = rho * u * u * u;
          return g.psd(f) * f * f * f * 3.0 * rho * u * u;
        },
        0.0, 1.0);
  };
  return 8.0 * integral(ray, 0.0, 0.25 * kPi);
}

// N(0, 1) deviates by the ziggurat method in Doornik's form (ZIGNOR: "An improved ziggurat method to
// generate normal random samples", 2005): 128 layers of equal area V under exp(-x^2 / 2), base layer
// and tail beyond R included. One 64-bit draw per attempt: its top 53 bits make u in [-1, 1), its low
// 7 bits the layer, so the two are independent. ~99 % of deviates cost one draw and one compare.
struct Ziggurat {
  static constexpr int kLayers = 128;
  static constexpr double kR = 3.442619855899, kV = 9.91256303526217e-3;
  double x[kLayers + 1];  // layer edges, x[0] = V / f(R) (the base layer as a rectangle), x[1] = R
  double ratio[kLayers];  // x[i + 1] / x[i]: |u| below it lies inside layer i's rectangle

  Ziggurat() {
    double f = std::exp(-0.5 * kR * kR);
    x[0] = kV / f;
    x[1] = kR;
    x[kLayers] = 0.0;
    for (int i = 2; i < kLayers; ++i) {
      x[i] = std::sqrt(-2.0 * std::log(kV / x[i - 1] + f));
      f = std::exp(-0.5 * x[i] * x[i]);
    }
    for (int i = 0; i < kLayers; ++i) ratio[i] = x[i + 1] / x[i];
  }
};

// Uniform deviate in (0, 1] on a 2^-53 lattice (never 0: it goes into a logarithm).
double uniform(detail::Xoshiro256& rng) { return static_cast<double>((rng() >> 11) + 1) * 0x1p-53; }

const Ziggurat kZiggurat;

double normal(detail::Xoshiro256& rng);

// The ~1 % of attempts outside the layers' rectangles: the tail beyond R (layer 0) or a wedge.
[[gnu::noinline]] double normal_beyond(detail::Xoshiro256& rng, double u, int i) {
  const Ziggurat& z = kZiggurat;
  if (i == 0) {  // the tail beyond R (Marsaglia's exponential rejection)
    double t, y;
    do {
      t = std::log(uniform(rng)) / Ziggurat::kR;
      y = std::log(uniform(rng));
    } while (-2.0 * y < t * t);
    return u < 0.0 ? t - Ziggurat::kR : Ziggurat::kR - t;
  }
  // The wedge of layer i between x[i + 1] and x[i]: accept under the curve, else a new attempt.
  const double v = u * z.x[i], v2 = v * v;
  const double f0 = std::exp(-0.5 * (z.x[i] * z.x[i] - v2)),
               f1 = std::exp(-0.5 * (z.x[i + 1] * z.x[i + 1] - v2));
  if (f1 + uniform(rng) * (f0 - f1) < 1.0) return v;
  return normal(rng);
}

// Inlined into the loops that draw n^2 deviates: the common attempt keeps the generator in registers.
inline double normal(detail::Xoshiro256& rng) {
  const std::uint64_t bits = rng();
  // bits >> 11 < 2^53 converts exactly through a signed integer (a shorter instruction sequence).
  const double u = static_cast<double>(static_cast<std::int64_t>(bits >> 11)) * 0x1p-52 - 1.0;
  const int i = static_cast<int>(bits & 0x7f);
  if (std::abs(u) < kZiggurat.ratio[i]) return u * kZiggurat.x[i];
  return normal_beyond(rng, u, i);
}

// Two independent N(0, 1) deviates as one complex number.
Complex complex_normal(detail::Xoshiro256& rng) {
  const double re = normal(rng);
  return {re, normal(rng)};
}

}  // namespace

PhaseScreenGenerator::PhaseScreenGenerator(std::size_t n, double spacing, double r0,
                                           double outer_scale, double inner_scale,
                                           SubharmonicWeights weights)
    : n_(n),
      spacing_(spacing),
      r0_(r0),
      outer_scale_(outer_scale),
      inner_scale_(inner_scale),
      weights_(weights) {
  if (n < 8 || n % 2 != 0) checks::fail("n", static_cast<double>(n), "an even grid size >= 8");
  checks::grid("n", n, sizeof(Complex), 2);  // the spectrum and the screen pair
  checks::length("spacing", spacing);
  if (!(r0 >= kMinLength)) checks::fail("r0", r0, "a value >= 1e-10 m (infinity: no turbulence)");
  if (!(outer_scale >= kMinLength))
    checks::fail("outer_scale", outer_scale, "a value >= 1e-10 m (infinity: Kolmogorov)");
  if (!(inner_scale >= 0.0 && inner_scale <= kMaxLength))
    checks::fail("inner_scale", inner_scale, "a length from 0 to 1e10 m");
  if (weights != SubharmonicWeights::tilt_matched && weights != SubharmonicWeights::schmidt)
    checks::fail("weights", static_cast<double>(weights), "tilt_matched or schmidt");

  const std::size_t h = n / 2;
  const double df = 1.0 / (static_cast<double>(n) * spacing);
  amplitude_.resize((h + 1) * (h + 1));
  // f = 0 is skipped: the piston is not a phase aberration (and Phi(0) is infinite without an outer scale);
  // the subharmonics stand for that cell.
  for (std::size_t ky = 0; ky <= h; ++ky) {
    detail::cancellation_point();  // (n/2)^2 powers: seconds for the largest grids on a busy core
    for (std::size_t kx = 0; kx <= h; ++kx)
      amplitude_[ky * (h + 1) + kx] =
          kx + ky == 0 ? 0.0 : std::sqrt(psd(df * std::hypot(double(kx), double(ky)))) * df;
  }
  const bool tilt = weights == SubharmonicWeights::tilt_matched;
  if (tilt) {  // the FFT grid's own 3 x 3 block around f = 0 (|kx|, |ky| <= 1)
    amplitude_[1] = std::sqrt(cell_variance(*this, df, 0.0, df));
    amplitude_[h + 1] = amplitude_[1];
    amplitude_[h + 2] = std::sqrt(cell_variance(*this, df, df, df));
  }

  for (int p = 0; p < kLevels; ++p) {
    const double dfp = df / std::pow(3.0, p + 1);
    double edge = psd(dfp) * dfp * dfp,
           corner = psd(std::sqrt(2.0) * dfp) * dfp * dfp;  // Schmidt: Phi(centre) area
    if (tilt) {
      edge = cell_variance(*this, dfp, 0.0, dfp);
      corner = cell_variance(*this, dfp, dfp, dfp);
      if (p + 1 ==
          kLevels) {  // the centre cell left over, spread as equal gradient variance over the 8
        const double rest = centre_gradient_variance(*this, 0.5 * dfp) / 8.0;
        edge += rest / (dfp * dfp);
        corner += rest / (2.0 * dfp * dfp);
      }
    }
    for (int b = -1; b <= 1; ++b)
      for (int a = -1; a <= 1; ++a)
        sub_amplitude_[9 * p + 3 * (b + 1) + (a + 1)] =
            a == 0 && b == 0 ? 0.0 : std::sqrt(a != 0 && b != 0 ? corner : edge);
    sub_cos_[p].resize(n);
    sub_sin_[p].resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double phase =
          2.0 * kPi * dfp * (static_cast<double>(i) - static_cast<double>(h)) * spacing;
      sub_cos_[p][i] = std::cos(phase);
      sub_sin_[p][i] = std::sin(phase);
      sub_mean_[p] += Complex(sub_cos_[p][i], sub_sin_[p][i]) / static_cast<double>(n);
    }
  }
}

double PhaseScreenGenerator::psd(double f) const {
  const double f0 = 1.0 / outer_scale_;  // 0 for an infinite outer scale
  const double inner =
      inner_scale_ > 0.0 ? std::exp(-std::pow(f * 2.0 * kPi * inner_scale_ / 5.92, 2)) : 1.0;
  return kPsdCoefficient * std::pow(r0_, -5.0 / 3.0) * inner /
         std::pow(f * f + f0 * f0, 11.0 / 6.0);
}

std::vector<double> PhaseScreenGenerator::generate(std::uint64_t seed, std::size_t index) const {
  return std::move(generate_pair(seed, index / 2)[index % 2]);
}

std::array<std::vector<double>, 2> PhaseScreenGenerator::generate_pair(std::uint64_t seed,
                                                                       std::size_t pair) const {
  std::array<std::vector<double>, 2> out;
  ComplexBuffer spectrum;
  generate_pair(seed, pair, out, spectrum);
  return out;
}

void PhaseScreenGenerator::generate_pair(std::uint64_t seed, std::size_t pair,
                                         std::array<std::vector<double>, 2>& out,
                                         ComplexBuffer& spectrum) const {
  const std::size_t n = n_, h = n / 2;
  detail::Xoshiro256 rng(mix(mix(seed) ^ static_cast<std::uint64_t>(pair)));
  // Every element of the three buffers is written below: their earlier contents never matter.
  if (spectrum.size() != n * n) spectrum = detail::zeroed_buffer(n * n);
  for (std::vector<double>& screen : out)
    if (screen.size() != n * n) screen = detail::zeroed_buffer<std::vector<double>>(n * n);

  // High frequencies, in FFT order: frequency index i is i or i - n, so |k| = min(i, n - i).
  for (std::size_t iy = 0; iy < n; ++iy) {
    detail::cancellation_point();  // n^2 normal deviates
    const double* row = &amplitude_[std::min(iy, n - iy) * (h + 1)];
    for (std::size_t ix = 0; ix < n; ++ix)
      spectrum[iy * n + ix] = complex_normal(rng) * row[std::min(ix, n - ix)];
  }
  std::array<Complex, 27> sub;
  for (std::size_t j = 0; j < sub.size(); ++j) sub[j] = complex_normal(rng) * sub_amplitude_[j];
  fft2d(spectrum, n,
        FftDirection::backward);  // unnormalised sum of c exp(+i 2 pi f x): the screen itself

  // Low frequencies, separably: sum_{a,b} c_ab e_a(x) e_b(y) = sum_a e_a(x) g_a(y) with
  // g_a(y) = sum_b c_ab e_b(y) per row, and e_{+-1} = cos +- i sin. Then per pixel and level,
  // g_1 e_1 + g_-1 e_-1 = (g_1 + g_-1) cos + i (g_1 - g_-1) sin. Schmidt removes the mean of this part
  // over the grid (the FFT part has none: its f = 0 is zero); it is sum_ab c_ab <e_a> <e_b>, known
  // beforehand, so that one pass over the pixels adds both parts.
  Complex mean{};
  for (int p = 0; p < kLevels; ++p) {
    const Complex m[3] = {std::conj(sub_mean_[p]), 1.0, sub_mean_[p]};
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < 3; ++a) mean += sub[9 * p + 3 * b + a] * m[a] * m[b];
  }
  for (std::size_t iy = 0; iy < n; ++iy) {
    detail::cancellation_point();
    Complex g0 = -mean, s[kLevels], d[kLevels];
    for (int p = 0; p < kLevels; ++p) {
      const Complex ey(sub_cos_[p][iy], sub_sin_[p][iy]);
      Complex g[3];
      for (int a = 0; a < 3; ++a) {
        const Complex* c = &sub[9 * p + a];  // c[3 (b + 1)] is c_ab
        g[a] = c[3] + c[6] * ey + c[0] * std::conj(ey);
      }
      g0 += g[1];
      s[p] = g[2] + g[0];
      d[p] = g[2] - g[0];
    }
    const Complex* hi = &spectrum[iy * n];
    double* re = &out[0][iy * n];
    double* im = &out[1][iy * n];
    for (std::size_t ix = 0; ix < n; ++ix) {
      double r = g0.real() + hi[ix].real(), i = g0.imag() + hi[ix].imag();
      for (int p = 0; p < kLevels; ++p) {
        const double c = sub_cos_[p][ix], sn = sub_sin_[p][ix];
        r += s[p].real() * c - d[p].imag() * sn;
        i += s[p].imag() * c + d[p].real() * sn;
      }
      re[ix] = r;
      im[ix] = i;
    }
  }
}

void apply_phase_screen(Field& field, const std::vector<double>& screen) {
  field.validate();
  if (screen.size() != field.n * field.n)
    checks::fail("screen", static_cast<double>(screen.size()),
                 "n * n = " + std::to_string(field.n * field.n) + " values");
  for (std::size_t i = 0; i < screen.size(); ++i) {
    detail::cancellation_point_every(i);  // a sine and a cosine per sample
    field.values[i] *= Complex(std::cos(screen[i]), std::sin(screen[i]));
  }
}

}  // namespace lidar_overlap
