#include "geometry/coupling_term.hpp"

#include <cmath>

namespace lidar_overlap {

double CouplingTerm::operator()(Vec2 p) const {
  for (std::size_t g = 0; g < n_gates; ++g)
    if (!gates[g].open(p)) return 0.0;
  std::array<Disc, kMaxMoving> at;
  for (std::size_t i = 0; i < n_discs; ++i) at[i] = discs[i].at(p);
  return weight * intersection_area(at.data(), n_discs);
}

std::size_t CouplingTerm::kink_circles(Disc* out, std::size_t capacity) const {
  std::size_t written = 0;
  // |alpha P + beta| = rho is a circle of centre -beta/alpha and radius rho/|alpha| in P.
  auto add_circle = [&](double alpha, Vec2 beta, double rho) {
    if (alpha != 0.0 && written < capacity)
      out[written++] = {(-1.0 / alpha) * beta, rho / std::abs(alpha)};
  };
  for (std::size_t i = 0; i < n_discs; ++i)
    for (std::size_t j = i + 1; j < n_discs; ++j) {
      const double alpha = discs[i].scale - discs[j].scale;
      const Vec2 beta = discs[i].shift - discs[j].shift;
      add_circle(alpha, beta, discs[i].radius + discs[j].radius);
      add_circle(alpha, beta, std::abs(discs[i].radius - discs[j].radius));
    }
  for (std::size_t g = 0; g < n_gates; ++g)
    add_circle(gates[g].scale, gates[g].shift, gates[g].radius);
  return written;
}

std::optional<Vec2> CouplingTerm::symmetry_center() const {
  std::optional<Vec2> s;
  bool ok = true;
  // Rotating P about S must rotate every relative position alpha P + beta (pairs of discs, gates)
  // about the origin: each must vanish at S = -beta/alpha. A constant one (alpha = 0) is allowed only
  // if it is zero, or if it is all there is (the term is then constant).
  auto agree = [&](double alpha, Vec2 beta, double scale) {
    if (alpha == 0.0) {
      ok = ok && ((beta.x == 0.0 && beta.y == 0.0) || (n_discs == 2 && n_gates == 0));
      return;
    }
    const Vec2 c = (-1.0 / alpha) * beta;
    if (!s)
      s = c;
    else
      ok = ok && norm(c - *s) <= 1e-12 * (norm(c) + scale);
  };
  for (std::size_t i = 0; i < n_discs; ++i)
    for (std::size_t j = i + 1; j < n_discs; ++j)
      agree(discs[i].scale - discs[j].scale, discs[i].shift - discs[j].shift,
            discs[i].radius + discs[j].radius);
  for (std::size_t g = 0; g < n_gates; ++g) agree(gates[g].scale, gates[g].shift, gates[g].radius);
  if (!ok) return std::nullopt;
  return s ? *s : Vec2{};
}

}  // namespace lidar_overlap
