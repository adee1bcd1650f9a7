#include "pupil/aberrated_pupil_integral.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/parallel.hpp"
#include "core/quadrature.hpp"
#include "core/special_functions.hpp"
#include "fourier/fft.hpp"

namespace lidar_overlap::detail {

// K(s): the share of a Gaussian image (1/e^2 radius w) centred s from the detector centre that falls on the
// detector (radius r_d), the Rice distribution's integral over [0, r_d]; tabulated at w/32 up to r_d + 6 w
// (beyond, below 1e-31) and interpolated by cubic Lagrange polynomials (error ~1e-8).
class ImageOnDetector {
 public:
  ImageOnDetector(double w, double r_d) : h_(w / 32.0), s_max_(r_d + 6.0 * w) {
    const double var = 0.25 * w * w;
    const std::size_t n =
        4 + checks::count_from(std::ceil(s_max_ / h_), std::size_t{1} << 20, "detector.radius", r_d,
                               "table points (32 per beam-image radius " + checks::number(w) +
                                   " m): the beam image is too small beside the detector for the "
                                   "aberrated ray-tracing table; use method 'fo'");
    table_.resize(n + 1);
    for (std::size_t i = 0; i <= n; ++i) {
      const double nu =
          std::abs((static_cast<double>(i) - 1.0) * h_);  // one node before 0: K is even
      auto density = [&](double rho) {
        const double d = rho - nu;
        return rho / var * std::exp(-0.5 * d * d / var) * scaled_bessel_i0(rho * nu / var);
      };
      const double lo = std::max(0.0, std::min(r_d, nu - 6.0 * w)),
                   hi = std::min(r_d, nu + 6.0 * w);
      const double points[2] = {lo, hi};
      table_[i] = hi > lo ? integrate(density, points, 2, 1e-13, 2000).value : 0.0;
    }
  }
  double operator()(double s) const {
    if (s >= s_max_) return 0.0;
    const double pos = s / h_ + 1.0;
    const std::size_t j = std::max<std::size_t>(1, checks::saturate(pos));
    const double t = pos - j, *p = &table_[j - 1];
    const double a = t + 1.0, b = t - 1.0, c = t - 2.0;
    return (-t * b * c * p[0] + 3.0 * a * b * c * p[1] - 3.0 * a * t * c * p[2] +
            a * t * b * p[3]) *
           (1.0 / 6.0);
  }

 private:
  double h_, s_max_;
  std::vector<double> table_;
};

namespace {

constexpr std::size_t kPanelNodes = 8;
constexpr std::size_t kMaxSteps = std::size_t{1} << 14;

struct Geometry {
  double d, to_image, scale, w;
  Vec2 s;
};

Geometry geometry(const LidarSystem& system, double z) {
  const Telescope& t = system.telescope;
  Geometry g;
  g.d = t.focal_length + system.detector.defocus;
  g.to_image = g.d / z;
  g.scale = 1.0 + g.d / z - g.d / t.focal_length;
  g.w = system.beam.radius(z) * g.to_image;
  g.s = (-g.to_image) * system.beam.center(z) - system.detector.offset;
  return g;
}

}  // namespace

AberratedPupilIntegral::AberratedPupilIntegral(const LidarSystem& system,
                                               const Aberrations& aberrations,
                                               const std::vector<double>& ranges, bool rotational)
    : system_(system), aberrations_(aberrations), ranges_(ranges) {
  const double radius = 0.5 * system.telescope.diameter;
  const double slope = aberrations.max_gradient() / radius;  // rad, largest |grad_a W|
  for (double z : ranges) {
    const Geometry g = geometry(system, z);
    const double sweep = std::abs(g.scale) * radius + g.d * slope;  // m, largest |D(a)|
    // Nodes every w_i / 4 of the sweep (powers of two, so few node sets serve all ranges).
    const std::size_t steps =
        next_power_of_two(std::min(kMaxSteps, checks::saturate(4.0 * sweep / g.w) + 1));
    const std::size_t panels = std::max<std::size_t>(4, steps / kPanelNodes);
    const bool one_angle = rotational && g.s.x == 0.0 && g.s.y == 0.0;
    keys_.push_back({panels, one_angle ? 1 : std::max<std::size_t>(64, 2 * steps)});
    coarse_in_rho_.push_back(one_angle);
  }
  // Memory of the node sets (a, slope, weight: 40 bytes a node), distinct keys counted once.
  std::map<Key, bool> distinct;
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    distinct[keys_[i]] = true;
    if (coarse_in_rho_[i]) distinct[{keys_[i].first / 2, 1}] = true;
  }
  double bytes = 0.0;
  for (const auto& [key, unused] : distinct)
    bytes += 40.0 * kPanelNodes * double(key.first) * double(key.second);
  checks::memory(
      "aberrations", aberrations.max_gradient(), bytes,
      "the pupil nodes resolve the beam image across the aberrated blur; use fewer ranges at the "
      "shortest distances or smaller aberrations");
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    nodes(keys_[i]);
    if (coarse_in_rho_[i]) nodes({keys_[i].first / 2, 1});
  }
}

const AberratedPupilIntegral::Nodes& AberratedPupilIntegral::nodes(Key key) {
  auto found = node_sets_.find(key);
  if (found != node_sets_.end()) return found->second;
  Nodes& n = node_sets_[key];
  const auto [panels, angles] = key;
  n.angles = angles;
  const Telescope& t = system_.telescope;
  const double radius = 0.5 * t.diameter, inner = t.obstruction_radius,
               d = t.focal_length + system_.detector.defocus;
  const GaussLegendreRule& rule = gauss_legendre<kPanelNodes>();
  for (std::size_t p = 0; p < panels; ++p) {
    cancellation_point();
    const double lo = inner + (radius - inner) * p / panels,
                 hi = inner + (radius - inner) * (p + 1) / panels;
    for (std::size_t i = 0; i < kPanelNodes; ++i) {
      const double rho = 0.5 * (lo + hi) + 0.5 * (hi - lo) * rule.x[i];
      const double ring_weight =
          0.5 * (hi - lo) * rule.w[i] * rho * 2.0 / (radius * radius * angles);
      for (std::size_t k = 0; k < angles; ++k) {
        const double theta = 2.0 * kPi * k / angles;
        const Vec2 a{rho * std::cos(theta), rho * std::sin(theta)};
        n.a.push_back(a);
        n.slope.push_back((d / radius) * aberrations_.gradient((1.0 / radius) * a));
        n.weight.push_back(ring_weight);
      }
    }
  }
  return n;
}

double AberratedPupilIntegral::sum(const Nodes& n, double scale, Vec2 s,
                                   const ImageOnDetector& k_of, bool every_other_angle) const {
  double total = 0.0;
  const std::size_t step = every_other_angle ? 2 : 1;
  for (std::size_t j = 0; j < n.a.size(); j += step)
    total += n.weight[j] * k_of(norm(scale * n.a[j] + n.slope[j] + s));
  return total * static_cast<double>(step);
}

std::pair<double, double> AberratedPupilIntegral::at(std::size_t i) const {
  const Geometry g = geometry(system_, ranges_[i]);
  const Nodes& n = node_sets_.at(keys_[i]);
  const ImageOnDetector k_of(g.w,
                             system_.detector.radius);  // shared by the rule and its coarse twin
  const double value = sum(n, g.scale, g.s, k_of, false);
  const double coarse = coarse_in_rho_[i]
                            ? sum(node_sets_.at({keys_[i].first / 2, 1}), g.scale, g.s, k_of, false)
                            : sum(n, g.scale, g.s, k_of, true);
  return {value, std::abs(value - coarse)};
}

}  // namespace lidar_overlap::detail
