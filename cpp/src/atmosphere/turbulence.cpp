#include "lidar_overlap/atmosphere/turbulence.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "lidar_overlap/core/limits.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/quadrature.hpp"

namespace lidar_overlap {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

double wavenumber(double wavelength) {
  checks::length("wavelength", wavelength);
  return 2.0 * kPi / wavelength;
}

// Breakpoints of [a, b]: 256 equal segments, so that a layer thicker than about (b - a) / 4000 is seen
// by the 15 nodes of the first pass (otherwise the adaptive rule could not know it is there), refined
// geometrically towards both ends, where the weights z^(5/3) and (L - z)^(5/6) are not smooth and a
// ground layer (100 m scale height) is short next to a long path.
std::vector<double> breakpoints(double a, double b) {
  constexpr int kUniform = 256, kGeometric = 40;
  const double w = b - a;
  std::vector<double> p;
  p.reserve(kUniform + 2 * kGeometric + 1);
  for (int i = 0; i <= kUniform; ++i) p.push_back(a + w * i / kUniform);
  for (int i = 1; i <= kGeometric; ++i) {
    p.push_back(a + std::ldexp(w, -i));
    p.push_back(b - std::ldexp(w, -i));
  }
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  return p;
}

// int_a^b Cn^2(z) weight(z) dz to a relative 1e-12 (m^(1/3) times the weight's unit). The profile
// has been validated by the caller.
template <class Weight>
double path_integral(const Cn2Profile& profile, double a, double b, Weight weight) {
  const std::vector<double> points = breakpoints(a, b);
  auto f = [&](double z) { return profile.cn2_at_range(z) * weight(z); };
  // A first pass over the breakpoints sets the scale for the relative tolerance.
  const double scale = integrate(f, points.data(), points.size(), kInfinity, points.size()).value;
  return integrate(f, points.data(), points.size(), 1e-12 * std::abs(scale), 50 * points.size())
      .value;
}

void check_path(const Cn2Profile& profile, double path_length) {
  profile.validate();
  checks::length("path_length", path_length);
}

// [c k^2 integral]^(-3/5): the form of r0 and theta0; infinite without turbulence.
double minus_three_fifths(double c, double k, double integral) {
  return integral > 0.0 ? std::pow(c * k * k * integral, -0.6) : kInfinity;
}

// Diffraction-limited W^2 (m^2) at L of a collimated beam of waist w0 at 0, and Lambda = 2 L / (k W^2).
std::pair<double, double> diffraction_limited(double w0, double k, double path_length) {
  const double lambda0 = 2.0 * path_length / (k * w0 * w0);
  const double w2 = w0 * w0 * (1.0 + lambda0 * lambda0);
  return {w2, 2.0 * path_length / (k * w2)};
}

}  // namespace

Cn2Profile Cn2Profile::constant(double cn2) {
  Cn2Profile p;
  p.model = Cn2Model::constant;
  p.cn2 = cn2;
  p.validate();
  return p;
}

Cn2Profile Cn2Profile::hufnagel_valley(double ground, double wind) {
  Cn2Profile p;
  p.model = Cn2Model::hufnagel_valley;
  p.hv_ground = ground;
  p.hv_wind = wind;
  p.validate();
  return p;
}

Cn2Profile Cn2Profile::custom(std::function<double(double)> cn2_of_height) {
  Cn2Profile p;
  p.model = Cn2Model::custom;
  p.cn2_of_height = std::move(cn2_of_height);
  p.validate();
  return p;
}

namespace {
// Cn^2 from 0 to 1e-9 m^-2/3, a thousand times the strongest turbulence measured near the ground.
constexpr double kMaxCn2 = 1e-9;
void strength(const std::string& name, double value) {
  if (!(value >= 0.0 && value <= kMaxCn2))
    checks::fail(name, value, "a value from 0 to 1e-9 m^-2/3");
}
}  // namespace

void Cn2Profile::validate() const {
  switch (model) {
    case Cn2Model::constant:
      strength("cn2", cn2);
      break;
    case Cn2Model::hufnagel_valley:
      strength("hv_ground", hv_ground);
      if (!(hv_wind >= 0.0 && hv_wind <= 300.0))
        checks::fail("hv_wind", hv_wind, "a wind speed from 0 to 300 m/s");
      break;
    case Cn2Model::custom:
      if (!cn2_of_height)
        checks::fail("cn2_of_height", 0.0, "a callable giving Cn^2 (m^-2/3) at a height (m)");
      break;
    default:
      checks::fail("model", static_cast<double>(model), "constant, hufnagel_valley or custom");
  }
  if (!(elevation > 0.0 && elevation <= kPi / 2.0))
    checks::fail("elevation", elevation, "a value in (0, pi/2] rad");
  if (!(altitude >= 0.0 && altitude <= 1e5))
    checks::fail("altitude", altitude, "a height from 0 to 1e5 m");
  if (!(inner_scale >= 0.0 && inner_scale <= 1.0))
    checks::fail("inner_scale", inner_scale, "a length from 0 to 1 m");
  if (!(outer_scale > 0.0) || (std::isfinite(outer_scale) && outer_scale < kMinLength))
    checks::fail("outer_scale", outer_scale, "a value >= 1e-10 m (infinity: Kolmogorov)");
}

double Cn2Profile::cn2_at_height(double height) const {
  switch (model) {
    case Cn2Model::constant:
      return cn2;
    case Cn2Model::hufnagel_valley: {
      const double v = hv_wind / 27.0;
      return 0.00594 * v * v * std::pow(1e-5 * height, 10) * std::exp(-height / 1000.0) +
             2.7e-16 * std::exp(-height / 1500.0) + hv_ground * std::exp(-height / 100.0);
    }
    default: {
      const double c = cn2_of_height(height);
      if (!(c >= 0.0 && c <= kMaxCn2))
        checks::fail("cn2_of_height", c,
                     "a value from 0 to 1e-9 m^-2/3 (at height " + std::to_string(height) + " m)");
      return c;
    }
  }
}

double Cn2Profile::cn2_at_range(double range) const {
  if (!(range >= 0.0 && range <= kMaxLength))
    checks::fail("range", range, "a range from 0 to 1e10 m");
  return cn2_at_height(altitude + range * std::sin(elevation));
}

double Cn2Profile::fried_parameter_plane(double wavelength, double path_length) const {
  const double k = wavenumber(wavelength);
  check_path(*this, path_length);
  return minus_three_fifths(0.423, k,
                            path_integral(*this, 0.0, path_length, [](double) { return 1.0; }));
}

double Cn2Profile::fried_parameter_spherical(double wavelength, double path_length) const {
  const double k = wavenumber(wavelength);
  check_path(*this, path_length);
  const double integral = path_integral(
      *this, 0.0, path_length, [&](double z) { return std::pow(z / path_length, 5.0 / 3.0); });
  return minus_three_fifths(0.423, k, integral);
}

double Cn2Profile::rytov_variance(double wavelength, double path_length) const {
  const double k = wavenumber(wavelength);
  check_path(*this, path_length);
  const double integral = path_integral(
      *this, 0.0, path_length, [&](double z) { return std::pow(path_length - z, 5.0 / 6.0); });
  return 2.25 * std::pow(k, 7.0 / 6.0) * integral;
}

double Cn2Profile::isoplanatic_angle(double wavelength, double path_length) const {
  const double k = wavenumber(wavelength);
  check_path(*this, path_length);
  const double integral =
      path_integral(*this, 0.0, path_length, [](double z) { return std::pow(z, 5.0 / 3.0); });
  return minus_three_fifths(2.91, k, integral);
}

std::vector<ScreenPlacement> Cn2Profile::place_screens(double wavelength, double path_length,
                                                       std::size_t count) const {
  const double k = wavenumber(wavelength);
  check_path(*this, path_length);
  if (count < 1) checks::fail("count", 0.0, "at least 1 screen");
  std::vector<ScreenPlacement> screens(count);
  const double width = path_length / static_cast<double>(count);
  for (std::size_t i = 0; i < count; ++i) {
    ScreenPlacement& s = screens[i];
    s.start = width * static_cast<double>(i);
    s.end = i + 1 == count ? path_length : width * static_cast<double>(i + 1);
    s.range = 0.5 * (s.start + s.end);
    s.cn2_integral = path_integral(*this, s.start, s.end, [](double) { return 1.0; });
    s.r0 = minus_three_fifths(0.423, k, s.cn2_integral);
  }
  return screens;
}

double Cn2Profile::beam_wander_variance(double waist_radius, double wavelength,
                                        double path_length) const {
  checks::length("waist_radius", waist_radius);
  wavenumber(
      wavelength);  // validated for a uniform interface; the geometric-optics wander does not use it
  check_path(*this, path_length);
  const double integral = path_integral(*this, 0.0, path_length, [&](double z) {
    const double lever = path_length - z;
    return lever * lever;
  });
  return 2.42 * 3.0 * integral * std::pow(waist_radius, -1.0 / 3.0);
}

double Cn2Profile::long_term_radius(double waist_radius, double wavelength,
                                    double path_length) const {
  checks::length("waist_radius", waist_radius);
  const double k = wavenumber(wavelength);
  check_path(*this, path_length);
  const auto [w2, lambda] = diffraction_limited(waist_radius, k, path_length);
  const double integral = path_integral(*this, 0.0, path_length, [&](double z) {
    return std::pow(1.0 - z / path_length, 5.0 / 3.0);
  });
  // 16/11 = (6/11) / (3/8): the weighted mean Cn^2 is integral / (3 L / 8).
  const double sigma2 =
      2.25 * std::pow(k, 7.0 / 6.0) * std::pow(path_length, 5.0 / 6.0) * (16.0 / 11.0) * integral;
  return std::sqrt(w2 * (1.0 + 1.33 * sigma2 * std::pow(lambda, 5.0 / 6.0)));
}

double Cn2Profile::short_term_radius(double waist_radius, double wavelength,
                                     double path_length) const {
  const double lt = long_term_radius(waist_radius, wavelength, path_length);
  // Stays above W: since (L - z)^2 <= L^2 (1 - z / L)^(5/3) and L / (k w0 W) <= 1/2, the wander is at
  // most 0.74 of the turbulent spread W_LT^2 - W^2 on any path.
  return std::sqrt(lt * lt - beam_wander_variance(waist_radius, wavelength, path_length));
}

}  // namespace lidar_overlap
