#include "lidar_overlap/receiver.hpp"

#include <cmath>
#include <limits>

#include "lidar_overlap/checks.hpp"

namespace lidar_overlap {

namespace {
constexpr double kPi = 3.14159265358979323846;

}  // namespace

double optimal_focus_range(double focal_length, double defocus) {
  checks::positive("focal_length", focal_length);
  checks::non_negative("defocus", defocus);
  if (defocus == 0.0) return std::numeric_limits<double>::infinity();
  return focal_length * (focal_length + defocus) / defocus;
}

Receiver::Receiver(const LidarSystem& system, double z) : z_(z) {
  system.validate();
  system.validate_range(z, "z");
  const Telescope& t = system.telescope;
  const Detector& det = system.detector;
  aperture_radius_ = 0.5 * t.diameter;
  focal_length_ = t.focal_length;
  detector_distance_ = t.focal_length + det.defocus;
  detector_offset_ = det.offset;
  const double d = detector_distance_;

  passing_[n_passing_++] = {0.0, {}, aperture_radius_};

  // Detector: m A - P d/z lands within r_d of the detector centre.
  const double m = 1.0 + d / z - d / t.focal_length;
  if (m != 0.0)
    passing_[n_passing_++] = {d / z / m, (1.0 / m) * det.offset, det.radius / std::abs(m)};
  else
    gates_[n_gates_++] = {-d / z, -1.0 * det.offset, det.radius};

  // Fibre NA: ray slope after the lens, A (1/z - 1/f) - P/z, within tan(asin NA).
  if (det.numerical_aperture) {
    const double na = *det.numerical_aperture;
    const double max_slope = na / std::sqrt(1.0 - na * na);
    const double k = 1.0 / z - 1.0 / t.focal_length;
    if (k != 0.0)
      passing_[n_passing_++] = {1.0 / (z * k), {}, max_slope / std::abs(k)};
    else
      gates_[n_gates_++] = {-1.0 / z, {}, max_slope};
  }

  // Obstruction shadow on the aperture: A (1 - z_obs/z) + P z_obs/z inside r_obs.
  if (t.obstruction_radius > 0.0) {
    const double gap = z - t.obstruction_distance;
    shadow_ = {-t.obstruction_distance / gap, {}, t.obstruction_radius * z / gap};
    has_shadow_ = true;
  }
}

double Receiver::coupling(Vec2 p) const {
  for (std::size_t g = 0; g < n_gates_; ++g) {
    const Vec2 q = gates_[g].scale * p + gates_[g].shift;
    if (norm(q) > gates_[g].radius) return 0.0;
  }
  std::array<Disc, 4> discs;
  for (std::size_t i = 0; i < n_passing_; ++i) discs[i] = passing_[i].at(p);
  const double passing = intersection_area(discs.data(), n_passing_);
  double blocked = 0.0;
  if (has_shadow_ && passing > 0.0) {
    discs[n_passing_] = shadow_.at(p);
    blocked = intersection_area(discs.data(), n_passing_ + 1);
  }
  return std::max(0.0, passing - blocked) / (kPi * aperture_radius_ * aperture_radius_);
}

std::size_t Receiver::kink_circles(Disc* out, std::size_t capacity) const {
  std::array<MovingDisc, 4> all;
  std::size_t n = 0;
  for (std::size_t i = 0; i < n_passing_; ++i) all[n++] = passing_[i];
  if (has_shadow_) all[n++] = shadow_;
  std::size_t written = 0;
  // |alpha P + beta| = rho is a circle of centre -beta/alpha and radius rho/|alpha| in P.
  auto add = [&](double alpha, Vec2 beta, double rho) {
    if (alpha != 0.0 && written < capacity) out[written++] = {(-1.0 / alpha) * beta, rho / std::abs(alpha)};
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const double alpha = all[i].scale - all[j].scale;
      const Vec2 beta = all[i].shift - all[j].shift;
      add(alpha, beta, all[i].radius + all[j].radius);
      add(alpha, beta, std::abs(all[i].radius - all[j].radius));
    }
  for (std::size_t g = 0; g < n_gates_; ++g) add(gates_[g].scale, gates_[g].shift, gates_[g].radius);
  return written;
}

std::optional<Vec2> Receiver::symmetry_center() const {
  // A constraint |scale P + shift ...| is symmetric about S = -shift / scale; all must agree.
  std::optional<Vec2> s;
  bool ok = true;
  auto agree = [&](double scale, Vec2 shift) {
    if (scale == 0.0) {
      ok = ok && shift.x == 0.0 && shift.y == 0.0;  // the aperture: fixed and centred
      return;
    }
    const Vec2 c = (-1.0 / scale) * shift;
    if (!s) s = c;
    else ok = ok && norm(c - *s) <= 1e-12 * (norm(c) + aperture_radius_);
  };
  for (std::size_t i = 0; i < n_passing_; ++i) agree(passing_[i].scale, passing_[i].shift);
  if (has_shadow_) agree(shadow_.scale, shadow_.shift);
  for (std::size_t g = 0; g < n_gates_; ++g) agree(gates_[g].scale, gates_[g].shift);
  if (!ok) return std::nullopt;
  return s ? *s : Vec2{};
}

Vec2 Receiver::detector_hit(Vec2 p, Vec2 a) const {
  const double d = detector_distance_;
  return (1.0 + d / z_ - d / focal_length_) * a - (d / z_) * p;
}

}  // namespace lidar_overlap
