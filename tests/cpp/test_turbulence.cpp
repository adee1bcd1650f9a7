// Turbulence along the path: constant-Cn^2 path integrals against their closed forms, HV5/7 against its
// defining r0 = 5 cm and theta0 = 7 urad at 0.5 um, the slant-path geometry, screen placement, beam
// wander and long-term spread (closed forms and a two-layer profile), and invalid input.
#include <cmath>
#include <limits>

#include "check.hpp"
#include "lidar_overlap/atmosphere/turbulence.hpp"
#include "core/constants.hpp"

using namespace lidar_overlap;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

double relative(double got, double expected) { return std::abs(got / expected - 1.0); }

void constant_closed_forms() {
  const double cn2 = 1e-14, lambda = 1064e-9, k = 2.0 * kPi / lambda, L = 2000.0;
  const Cn2Profile p = Cn2Profile::constant(cn2);
  // Quadrature to 1e-12 relative: the closed forms hold to rounding.
  test::near("r0 plane",
             relative(p.fried_parameter_plane(lambda, L), std::pow(0.423 * k * k * cn2 * L, -0.6)),
             0.0, 1e-10);
  test::near("r0 spherical",
             relative(p.fried_parameter_spherical(lambda, L),
                      std::pow(0.423 * k * k * cn2 * L * 3.0 / 8.0, -0.6)),
             0.0, 1e-10);
  const double rytov = p.rytov_variance(lambda, L);
  test::near(
      "Rytov 2.25 * 6/11",
      relative(rytov, 2.25 * 6.0 / 11.0 * cn2 * std::pow(k, 7.0 / 6.0) * std::pow(L, 11.0 / 6.0)),
      0.0, 1e-10);
  // 1.23 is 2.25 * 6 / 11 = 1.2273 rounded.
  test::near("Rytov 1.23",
             relative(rytov, 1.23 * cn2 * std::pow(k, 7.0 / 6.0) * std::pow(L, 11.0 / 6.0)), 0.0,
             3e-3);
  test::near("theta0",
             relative(p.isoplanatic_angle(lambda, L),
                      std::pow(2.91 * k * k * cn2 * std::pow(L, 8.0 / 3.0) * 3.0 / 8.0, -0.6)),
             0.0, 1e-10);
  test::that("no turbulence: infinite r0",
             Cn2Profile::constant(0.0).fried_parameter_plane(lambda, L) == kInf);
  // A callable returning the same constant gives the same numbers.
  const Cn2Profile same = Cn2Profile::custom([cn2](double) { return cn2; });
  test::near(
      "custom = constant",
      relative(same.fried_parameter_spherical(lambda, L), p.fried_parameter_spherical(lambda, L)),
      0.0, 1e-13);
}

void hufnagel_valley() {
  const Cn2Profile hv = Cn2Profile::hufnagel_valley();
  test::near("HV5/7 at the ground", hv.cn2_at_height(0.0), 2.7e-16 + 1.7e-14, 1e-30);
  // Integrated to 60 km (above it the model is below 1e-9 of its integrals): r0 = 4.96 cm and
  // theta0 = 6.9 urad, the model's nominal 5 cm and 7 urad to 1 and 2 %.
  const double r0 = hv.fried_parameter_plane(0.5e-6, 60e3),
               theta0 = hv.isoplanatic_angle(0.5e-6, 60e3);
  test::near("HV5/7 r0 at 0.5 um", r0, 0.05, 0.05 * 0.05);
  test::near("HV5/7 theta0 at 0.5 um", theta0, 7e-6, 0.05 * 7e-6);
  std::cout << "HV5/7 zenith, 0.5 um: r0 = " << r0 << " m, theta0 = " << theta0 << " rad\n";

  // Slant path: at 30 deg elevation the range to a height is twice the height, so the plane-wave r0
  // over twice the range is the zenith one times 2^(-3/5) (sec zeta scaling).
  Cn2Profile slant = hv;
  slant.elevation = kPi / 6.0;
  test::near("range to height", slant.cn2_at_range(3000.0) / hv.cn2_at_height(1500.0), 1.0,
             1e-14);  // sin(pi/6) rounds
  test::near("sec zeta scaling",
             relative(slant.fried_parameter_plane(0.5e-6, 120e3), r0 * std::pow(2.0, -0.6)), 0.0,
             1e-9);
  Cn2Profile raised = hv;
  raised.altitude = 1000.0;
  test::near("lidar altitude", raised.cn2_at_range(500.0), hv.cn2_at_height(1500.0), 0.0);
}

void screen_placement() {
  const double lambda = 1064e-9;
  const Cn2Profile hv = Cn2Profile::hufnagel_valley();
  const auto screens = hv.place_screens(lambda, 20e3, 10);
  double sum = 0.0;
  for (const ScreenPlacement& s : screens) sum += std::pow(s.r0, -5.0 / 3.0);
  test::near("screens combine to the path's r0",
             relative(sum, std::pow(hv.fried_parameter_plane(lambda, 20e3), -5.0 / 3.0)), 0.0,
             1e-9);
  test::near("screen at its segment's middle", screens[3].range, 7000.0, 1e-9);
  test::near("last segment ends at L", screens.back().end, 20e3, 0.0);
  const double cn2 = 2e-15, k = 2.0 * kPi / lambda;
  const auto uniform = Cn2Profile::constant(cn2).place_screens(lambda, 1000.0, 4);
  test::near("constant Cn^2: equal screens",
             relative(uniform[2].r0, std::pow(0.423 * k * k * cn2 * 250.0, -0.6)), 0.0, 1e-10);
  // Turbulence only beyond 600 m: the first two of four screens are empty.
  const auto step = Cn2Profile::custom([](double h) {
                      return h > 600.0 ? 1e-14 : 0.0;
                    }).place_screens(lambda, 1000.0, 4);
  test::that("empty segment: infinite r0",
             step[0].r0 == kInf && step[1].r0 == kInf && std::isfinite(step[2].r0));
  test::near("partly turbulent segment", relative(step[2].cn2_integral, 1e-14 * 150.0), 0.0, 1e-9);
}

void beam() {
  const double cn2 = 1e-15, lambda = 1064e-9, k = 2.0 * kPi / lambda, w0 = 5e-3, L = 3000.0;
  const Cn2Profile p = Cn2Profile::constant(cn2);
  const double wander = p.beam_wander_variance(w0, lambda, L);
  test::near("wander 2.42 Cn^2 L^3 W0^(-1/3)",
             relative(wander, 2.42 * cn2 * L * L * L * std::pow(w0, -1.0 / 3.0)), 0.0, 1e-10);
  const double lambda0 = 2.0 * L / (k * w0 * w0), w2 = w0 * w0 * (1.0 + lambda0 * lambda0),
               big_lambda = 2.0 * L / (k * w2);
  const double rytov = p.rytov_variance(lambda, L);
  const double lt = p.long_term_radius(w0, lambda, L);
  test::near("W_LT^2 = W^2 (1 + 1.33 sigma_R^2 Lambda^(5/6))",
             relative(lt * lt, w2 * (1.0 + 1.33 * rytov * std::pow(big_lambda, 5.0 / 6.0))), 0.0,
             1e-10);
  const double st = p.short_term_radius(w0, lambda, L);
  test::near("W_ST^2 = W_LT^2 - <r_c^2>", relative(st * st, lt * lt - wander), 0.0, 1e-12);
  test::that("W < W_ST < W_LT", std::sqrt(w2) < st && st < lt);
  std::cout << "beam w0 = 5 mm, 1064 nm, 3 km, Cn^2 = 1e-15: sigma_R^2 = " << rytov
            << ", W = " << std::sqrt(w2) << " m, W_LT = " << lt << " m, W_ST = " << st
            << " m, rms wander = " << std::sqrt(wander) << " m\n";

  // Cn^2 only over the first or only over the second half of the path: wander weighted by (L - z)^2
  // and spread by (1 - z / L)^(5/3), both integrated in closed form.
  Cn2Profile near_half = Cn2Profile::custom([L](double h) { return h < 0.5 * L ? 1e-15 : 0.0; });
  Cn2Profile far_half = Cn2Profile::custom([L](double h) { return h < 0.5 * L ? 0.0 : 1e-15; });
  test::near("wander, first half",
             relative(near_half.beam_wander_variance(w0, lambda, L), wander * 7.0 / 8.0), 0.0,
             1e-10);
  test::near("wander, second half",
             relative(far_half.beam_wander_variance(w0, lambda, L), wander / 8.0), 0.0, 1e-10);
  const double near_share =
      1.0 - std::pow(0.5, 8.0 / 3.0);  // of int (1 - z/L)^(5/3) dz over the path
  const double lt_near = near_half.long_term_radius(w0, lambda, L);
  test::near("spread, first half", relative(lt_near * lt_near - w2, (lt * lt - w2) * near_share),
             0.0, 1e-10);
  test::that("turbulence near the lidar spreads more",
             lt_near > far_half.long_term_radius(w0, lambda, L));
}

void invalid_input() {
  const Cn2Profile hv = Cn2Profile::hufnagel_valley();
  test::throws("negative Cn^2", [] { Cn2Profile::constant(-1e-15); }, "cn2");
  test::throws("negative HV ground term", [] { Cn2Profile::hufnagel_valley(-1e-14); }, "hv_ground");
  test::throws("no callable", [] { Cn2Profile::custom(nullptr); }, "cn2_of_height");
  const Cn2Profile negative = [] {
    Cn2Profile c;
    c.model = Cn2Model::custom;
    c.cn2_of_height = [](double) { return -1.0; };
    return c;
  }();
  test::throws(
      "callable returning < 0", [&] { negative.fried_parameter_plane(1e-6, 100.0); },
      "cn2_of_height");
  for (double e : {0.0, -0.1, kPi / 2.0 + 1e-9}) {
    Cn2Profile bad = hv;
    bad.elevation = e;
    test::throws(
        "elevation outside (0, pi/2]", [&] { bad.fried_parameter_plane(1e-6, 100.0); },
        "elevation");
  }
  Cn2Profile bad = hv;
  bad.altitude = -1.0;
  test::throws("negative altitude", [&] { bad.rytov_variance(1e-6, 100.0); }, "altitude");
  bad = hv;
  bad.outer_scale = 0.0;
  test::throws("zero outer scale", [&] { bad.validate(); }, "outer_scale");
  bad = hv;
  bad.inner_scale = -1e-3;
  test::throws("negative inner scale", [&] { bad.validate(); }, "inner_scale");
  test::throws("zero path", [&] { hv.isoplanatic_angle(1e-6, 0.0); }, "path_length");
  test::throws("zero wavelength", [&] { hv.fried_parameter_spherical(0.0, 100.0); }, "wavelength");
  test::throws("no screens", [&] { hv.place_screens(1e-6, 100.0, 0); }, "count");
  test::throws("zero waist", [&] { hv.long_term_radius(0.0, 1e-6, 100.0); }, "waist_radius");
  test::throws("infinite path", [&] { hv.beam_wander_variance(1e-3, 1e-6, kInf); }, "path_length");
}

}  // namespace

int main() {
  constant_closed_forms();
  hufnagel_valley();
  screen_placement();
  beam();
  invalid_input();
  return test::report("test_turbulence");
}
