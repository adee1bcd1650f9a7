#include "lidar_overlap/geometry/receiver.hpp"
#include "geometry/receiver_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/checks.hpp"
#include "core/constants.hpp"

namespace lidar_overlap {

double optimal_focus_range(double focal_length, double defocus) {
  checks::length("focal_length", focal_length);
  checks::non_negative("defocus", defocus);
  checks::coordinate("defocus", defocus);
  if (defocus == 0.0) return std::numeric_limits<double>::infinity();
  const double z = focal_length * (focal_length + defocus) / defocus;
  if (!std::isfinite(z))  // a subnormal defocus: the range exists but no double holds it
    checks::fail(
        "defocus", defocus,
        "0 (focus at infinity) or a defocus whose focus range f (f + defocus) / defocus is "
        "below 1.8e308 m");
  return z;
}

Receiver::Receiver(const LidarSystem& system, double z) : z_(z) {
  system.validate();
  system.validate_range(z, "z");
  const Telescope& t = system.telescope;
  const Detector& det = system.detector;
  aperture_radius_ = 0.5 * t.diameter;
  const double d = t.focal_length + det.defocus;
  passing_.weight = 1.0 / (kPi * aperture_radius_ * aperture_radius_);

  passing_.add(MovingDisc{0.0, {}, aperture_radius_});  // first: terms() may drop it

  // Detector: m A - P d/z lands within r_d of the detector centre.
  const double m = 1.0 + d / z - d / t.focal_length;
  if (m != 0.0)
    passing_.add(MovingDisc{d / z / m, (1.0 / m) * det.offset, det.radius / std::abs(m)});
  else
    passing_.add(Gate{-d / z, -1.0 * det.offset, det.radius});

  // Fibre NA: ray slope after the lens, A (1/z - 1/f) - P/z, within tan(asin NA).
  if (det.numerical_aperture) {
    const double max_slope = det.max_ray_slope();
    const double k = 1.0 / z - 1.0 / t.focal_length;
    if (k != 0.0)
      passing_.add(MovingDisc{1.0 / (z * k), {}, max_slope / std::abs(k)});
    else
      passing_.add(Gate{-1.0 / z, {}, max_slope});
  }

  // Second stop, s behind the lens: the ray crosses its plane at A (1 + s/z - s/f) - P s/z (the detector's
  // form at distance s), within r_s of the axis.
  if (det.stop_radius) {
    const double s = det.stop_distance, ms = 1.0 + s / z - s / t.focal_length;
    if (ms != 0.0)
      passing_.add(MovingDisc{s / z / ms, {}, *det.stop_radius / std::abs(ms)});
    else
      passing_.add(Gate{-s / z, {}, *det.stop_radius});
  }

  // Obstruction shadow on the aperture: A (1 - z_obs/z) + P z_obs/z inside r_obs.
  if (t.obstruction_radius > 0.0) {
    const double gap = z - t.obstruction_distance;
    shadow_ = {-t.obstruction_distance / gap, {}, t.obstruction_radius * z / gap};
    has_shadow_ = true;
    blocked_ = passing_;
    blocked_.add(shadow_);
    blocked_.weight = -passing_.weight;
  }
}

double Receiver::coupling(Vec2 p) const {
  const double passing = passing_(p);
  if (!has_shadow_ || passing == 0.0) return passing;
  return std::max(0.0, passing + blocked_(p));
}

namespace {

// Leaves out of `term` (which starts with the aperture disc) every moving disc that holds the whole aperture for
// all |P - center| <= support: it bounds nothing there. A fibre whose NA exceeds the telescope's is such a disc at
// all but the nearest ranges; kept, its centre moves at another rate than the detector's and takes the term's
// centre of symmetry away (a detector offset then costs the beam integral 40 times the couplings).
void drop_discs_holding_the_aperture(CouplingTerm& term, Vec2 center, double support,
                                     double aperture_radius) {
  std::size_t kept = 1;
  for (std::size_t i = 1; i < term.n_discs; ++i) {
    const MovingDisc& d = term.discs[i];
    const bool holds = d.scale != 0.0 && norm(d.scale * center + d.shift) +
                                                 std::abs(d.scale) * support + aperture_radius <=
                                             d.radius;
    if (!holds) term.discs[kept++] = d;
  }
  term.n_discs = kept;
}

}  // namespace

std::size_t Receiver::terms(Vec2 center, double support, CouplingTerm* out) const {
  out[0] = passing_;
  drop_discs_holding_the_aperture(out[0], center, support, aperture_radius_);
  if (!has_shadow_) return 1;
  out[1] = blocked_;
  drop_discs_holding_the_aperture(out[1], center, support, aperture_radius_);
  // The shadow disc |A - scale P| <= r lies inside the aperture for all |P - center| <= support.
  if (std::abs(shadow_.scale) * (norm(center) + support) + shadow_.radius <= aperture_radius_) {
    for (std::size_t i = 1; i < out[1].n_discs; ++i) out[1].discs[i - 1] = out[1].discs[i];
    --out[1].n_discs;
  }
  return 2;
}

}  // namespace lidar_overlap
