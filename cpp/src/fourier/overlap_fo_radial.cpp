#include "lidar_overlap/fourier/overlap_fo_radial.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lidar_overlap/fourier/overlap_fo.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/special_functions.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "core/quadrature.hpp"
#include "fourier/fo_receiver.hpp"
#include "fourier/gaussian_image_overlap.hpp"
#include "fourier/overlap_fo_detail.hpp"

namespace lidar_overlap {

double gaussian_image_overlap(const LidarSystem& system, double z, double periods_per_panel,
                              std::size_t* evaluations, const std::string& parameter) {
  const FoReceiver rx(system, z, parameter);
  const double q_cut = rx.cutoff();
  if (q_cut == 0.0) return 0.0;
  const double to_image = rx.detector_distance() / z, w_image = system.beam.radius(z) * to_image;
  const double offset = norm((-to_image) * system.beam.center(z) - system.detector.offset);
  // exp(-pi^2 w_i^2 q^2 / 2) < 1e-16 beyond q = sqrt(2 ln 1e16) / (pi w_i).
  const double q_end = std::min(q_cut, std::sqrt(2.0 * std::log(1e16)) / (kPi * w_image));
  // Fastest oscillation: disc^ (period 1/r_d) times the OTF (1/blur); the OTF's own scale is q_cut.
  const double frequency = system.detector.radius + rx.blur_radius() + offset + 4.0 / q_cut;
  const std::size_t panels =
      1 + checks::count_from(q_end * frequency / periods_per_panel, kMaxRadialPanels, parameter, z,
                             "quadrature panels: the detector, blur and image offset span " +
                                 checks::number(frequency) + " m against an image resolution of " +
                                 checks::number(1.0 / q_end) +
                                 " m; the image is geometric there, where method 'rt' is exact");
  checks::count_from(24.0 * double(panels) * rx.otf_cost(),
                     static_cast<std::size_t>(FoReceiver::kMaxOtfWork), parameter, z,
                     "Bessel terms (" + std::to_string(panels) +
                         " panels of 24 OTF evaluations with a defocus phase of " +
                         checks::number(rx.otf_cost()) +
                         " rad across the pupil); the image is geometric there, where "
                         "method 'rt' is exact");
  // The annular OTF has kinks where one shifted disc leaves the other: shifts R -+ r_obs and 2 r_obs.
  std::vector<double> edges;
  for (std::size_t i = 0; i <= panels; ++i)
    edges.push_back(q_end * static_cast<double>(i) / panels);
  const double to_q = 1.0 / (system.beam.wavelength * rx.detector_distance());
  const AnnularPupil& p = rx.pupil();
  for (double v : {p.outer - p.inner, p.outer + p.inner, 2.0 * p.inner})
    if (p.inner > 0.0 && v * to_q > 0.0 && v * to_q < q_end) edges.push_back(v * to_q);
  std::sort(edges.begin(), edges.end());

  const GaussLegendreRule& rule = gauss_legendre<24>();
  const double r_d = system.detector.radius, g2 = 0.5 * kPi * kPi * w_image * w_image;
  double sum = 0.0;
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    const double mid = 0.5 * (edges[k + 1] + edges[k]), half = 0.5 * (edges[k + 1] - edges[k]);
    if (!(half > 0.0)) continue;
    detail::cancellation_point();
    double panel = 0.0;
    for (std::size_t i = 0; i < rule.x.size(); ++i) {
      const double q = mid + half * rule.x[i];
      const double shift = offset > 0.0 ? bessel_j0(2.0 * kPi * q * offset) : 1.0;
      panel += rule.w[i] * rx.otf(q) * disc_transform(r_d, q) * std::exp(-g2 * q * q) * shift * q;
    }
    sum += half * panel;
    if (evaluations) *evaluations += rule.x.size();
  }
  return 2.0 * kPi * sum / rx.aperture_area();
}

RadialFoOverlap overlap_fo_radial(const LidarSystem& system, const std::vector<double>& ranges,
                                  const RadialFoOptions& options) {
  system.validate();
  const GaussianBeam& beam = system.beam;
  beam.validate_for_fourier_optics();
  checks::positive("periods_per_panel", options.periods_per_panel);
  const int threads = detail::checked_threads_and_ranges(system, ranges, options.threads);

  RadialFoOverlap out;
  out.overlap.assign(ranges.size(), 0.0);
  out.evaluations.assign(ranges.size(), 0);
  detail::parallel_for(ranges.size(), threads, [&](std::size_t i) {
    out.overlap[i] = gaussian_image_overlap(system, ranges[i], options.periods_per_panel,
                                            &out.evaluations[i], detail::range_name(i));
  });
  checks::overlap_values(out.overlap, ranges, detail::kFoOverlapSlack, "overlap_fo_radial");
  return out;
}

}  // namespace lidar_overlap
