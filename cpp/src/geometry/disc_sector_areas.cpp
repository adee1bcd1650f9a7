#include "geometry/disc_sector_areas.hpp"

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"

namespace lidar_overlap {

namespace {

constexpr double kTwoPi = 2.0 * kPi;

// Length (rad) of the intersection of the arcs [a, a + la] and [b, b + lb] of one circle (la, lb in [0, 2 pi]).
double arc_overlap(double a, double la, double b, double lb) {
  double d = b - a;
  d -= kTwoPi *
       std::floor(
           d / kTwoPi);  // in [0, 2 pi]: [d, d + lb] and [d - 2 pi, d - 2 pi + lb] against [0, la]
  return std::max(0.0, std::min(la, d + lb) - d) + std::max(0.0, std::min(la, d - kTwoPi + lb));
}

// atan2(s, c) from std::atan of a ratio at most 1 in size (within 2 ulp; glibc's atan2 and acos take 40-80 ns
// on some arguments, and each node of a telecover integral needs several).
double angle_of(double c, double s) {
  if (std::abs(s) <= std::abs(c)) {
    const double a = std::atan(s / c);
    return c > 0.0 ? a : (s >= 0.0 ? a + kPi : a - kPi);
  }
  const double a = std::atan(c / s);
  return s > 0.0 ? 0.5 * kPi - a : -0.5 * kPi - a;
}

// sqrt(1 - c^2) for c in [-1, 1], as sqrt((1 - c)(1 + c)), which keeps the digits near +-1.
double sine_of(double c) { return std::sqrt((1.0 - c) * (1.0 + c)); }

// acos(c) for c in [-1, 1], from c and s = sine_of(c) through angle_of; no atan at the ends.
double arc_cos(double c, double s) {
  if (c <= -1.0 || c >= 1.0) return c <= -1.0 ? kPi : 0.0;
  return angle_of(c, s);
}

// The arc [start, start + length] (rad) of the circle of radius rho about the origin inside disc(mu, q).
void circle_inside_disc(double rho, double m, double phi_mu, double q, double& start,
                        double& length) {
  start = 0.0;
  if (m == 0.0) {
    length = rho <= q ? kTwoPi : 0.0;
    return;
  }
  const double c = (rho * rho + m * m - q * q) / (2.0 * rho * m);
  if (c <= -1.0 || c >= 1.0) {
    length = c <= -1.0 ? kTwoPi : 0.0;
    return;
  }
  const double half = arc_cos(c, sine_of(c));
  start = phi_mu - half;
  length = 2.0 * half;
}

}  // namespace

DiscSectorAreas::DiscSectorAreas(Vec2 mu, const std::vector<AnnularSector>& sectors)
    : mu_(mu), m_(norm(mu)) {
  u_mu_ = m_ > 0.0 ? (1.0 / m_) * mu : Vec2{1.0, 0.0};
  phi_mu_ = m_ > 0.0 ? std::atan2(mu.y, mu.x) : 0.0;
  // Edges within rounding of each other (a quadrant's stop at 5 pi / 4 and the next one's start at -3 pi / 4)
  // are one ray: its crossings are found once, and the sectors on either side share it exactly.
  auto ray = [&](double angle) {
    const Vec2 u{std::cos(angle), std::sin(angle)};
    for (std::size_t i = 0; i < rays_.size(); ++i)
      if (norm(rays_[i].u - u) <= 1e-15) return i;
    rays_.push_back({u, dot(u, mu), u.x * mu.y - u.y * mu.x});
    return rays_.size() - 1;
  };
  for (const AnnularSector& s : sectors) {
    std::size_t a = 0;
    while (a < annuli_.size() && !(annuli_[a].inner == s.inner && annuli_[a].outer == s.outer)) ++a;
    if (a == annuli_.size()) annuli_.push_back({s.inner, s.outer});
    Wedge w{a, 0, 0, s.start, std::min(s.span, kTwoPi)};
    if (w.span < kTwoPi) {
      w.first = ray(s.start);
      w.second = ray(s.start + s.span);
    }
    wedges_.push_back(w);
  }
  annulus_state_.resize(annuli_.size());
  ray_state_.resize(rays_.size());
  pieces_.reserve(2 + 2 * rays_.size());
  sides_.resize(rays_.size());
}

DiscSectorAreas::OnCircle DiscSectorAreas::on_circle(double delta, double cos_delta,
                                                     double sin_delta) const {
  return {delta,
          {cos_delta * u_mu_.x - sin_delta * u_mu_.y, cos_delta * u_mu_.y + sin_delta * u_mu_.x}};
}

// The sign of cross(u, mu + q sum / |sum|) (the side of the ray's line the piece's middle lies on) from |sum|^2:
// cross(u, mu) |sum| + q cross(u, sum), its sign found without the square root.
double DiscSectorAreas::side(const Ray& r, Vec2 sum, double length2, double q) const {
  const double a = r.off, b = q * (r.u.x * sum.y - r.u.y * sum.x);
  if ((a >= 0.0) == (b >= 0.0)) return a + b;
  return a > 0.0 ? a * a * length2 - b * b : b * b - a * a * length2;
}

double DiscSectorAreas::arc_term(double q, const OnCircle& a, const OnCircle& b) const {
  return 0.5 *
         (q * q * (b.delta - a.delta) + q * (mu_.x * (b.e.y - a.e.y) - mu_.y * (b.e.x - a.e.x)));
}

bool DiscSectorAreas::in_wedge(const Wedge& w, double after_start, double before_end) const {
  return w.span <= kPi ? (after_start >= 0.0 && before_end >= 0.0)
                       : (after_start >= 0.0 || before_end >= 0.0);
}

void DiscSectorAreas::operator()(double q, double* areas) {
  if (!(q > 0.0)) {
    std::fill(areas, areas + wedges_.size(), 0.0);
    return;
  }
  // The disc's circle mu + q e(psi) lies in an annulus where cos(psi - phi_mu) is in [c_a, c_b].
  for (std::size_t j = 0; j < annuli_.size(); ++j) {
    const Annulus& an = annuli_[j];
    AnnulusState& st = annulus_state_[j];
    circle_inside_disc(an.outer, m_, phi_mu_, q, st.outer_start, st.outer_length);
    st.inner_length = 0.0;
    if (an.inner > 0.0)
      circle_inside_disc(an.inner, m_, phi_mu_, q, st.inner_start, st.inner_length);
    st.arcs = false;
    if (m_ == 0.0) continue;
    const double c_b = (an.outer * an.outer - m_ * m_ - q * q) / (2.0 * m_ * q);
    const double c_a = (an.inner * an.inner - m_ * m_ - q * q) / (2.0 * m_ * q);
    if (c_b < -1.0 || c_a > 1.0) continue;
    const double cos_lo = std::min(1.0, c_b), cos_hi = std::max(-1.0, c_a);
    const double sin_lo = sine_of(cos_lo), sin_hi = sine_of(cos_hi);
    const double lo = arc_cos(cos_lo, sin_lo), hi = arc_cos(cos_hi, sin_hi);
    if (!(hi > lo)) continue;
    st.arcs = true;
    st.ends[0][0] = on_circle(-hi, cos_hi, -sin_hi);
    st.ends[0][1] = on_circle(-lo, cos_lo, -sin_lo);
    st.ends[1][0] = on_circle(lo, cos_lo, sin_lo);
    st.ends[1][1] = on_circle(hi, cos_hi, sin_hi);
  }
  // Where the disc's circle crosses each edge ray t u (t > 0).
  for (std::size_t i = 0; i < rays_.size() && m_ > 0.0; ++i) {
    const Ray& r = rays_[i];
    RayState& rs = ray_state_[i];
    rs.n = 0;
    const double h2 = q * q - r.off * r.off;
    if (!(h2 > 0.0)) continue;
    const double h = std::sqrt(h2), inv_q = 1.0 / q;
    for (double t : {r.along - h, r.along + h}) {
      if (!(t > 0.0)) continue;
      const Vec2 e = inv_q * (t * r.u - mu_);
      rs.at[rs.n++] = {angle_of(dot(u_mu_, e), u_mu_.x * e.y - u_mu_.y * e.x), e};
    }
  }
  // The pieces of the disc's circle in each annulus between the crossings of its rays, each with its middle;
  // then each sector adds its circles' arcs and the pieces whose middle lies in its wedge.
  for (std::size_t k = 0; k < wedges_.size(); ++k) {
    const Wedge& w = wedges_[k];
    const Annulus& an = annuli_[w.annulus];
    const AnnulusState& st = annulus_state_[w.annulus];
    double area =
        0.5 * an.outer * an.outer * arc_overlap(st.outer_start, st.outer_length, w.start, w.span);
    if (an.inner > 0.0)
      area -=
          0.5 * an.inner * an.inner * arc_overlap(st.inner_start, st.inner_length, w.start, w.span);
    if (m_ == 0.0 && an.inner <= q && q <= an.outer) area += 0.5 * q * q * w.span;
    areas[k] = area;
  }
  for (std::size_t j = 0; j < annuli_.size() && m_ > 0.0; ++j) {
    const AnnulusState& st = annulus_state_[j];
    if (!st.arcs) continue;
    for (const auto& arc : st.ends) {
      pieces_.clear();
      pieces_.push_back(arc[0]);
      for (std::size_t i = 0; i < rays_.size(); ++i)
        for (std::size_t c = 0; c < ray_state_[i].n; ++c) {
          const OnCircle& p = ray_state_[i].at[c];
          if (p.delta > arc[0].delta && p.delta < arc[1].delta) pieces_.push_back(p);
        }
      std::sort(pieces_.begin() + 1, pieces_.end(),
                [](const OnCircle& a, const OnCircle& b) { return a.delta < b.delta; });
      pieces_.push_back(arc[1]);
      for (std::size_t p = 0; p + 1 < pieces_.size(); ++p) {
        const double term = arc_term(q, pieces_[p], pieces_[p + 1]);
        // The piece's middle lies along the chord's midpoint (a piece spans at most pi): its side of each ray
        // from the sum of the ends' directions; a piece of exactly pi by its middle angle.
        const Vec2 sum = pieces_[p].e + pieces_[p + 1].e;
        const double length2 = dot(sum, sum);
        if (length2 > 1e-12) {
          for (std::size_t i = 0; i < rays_.size(); ++i)
            sides_[i] = side(rays_[i], sum, length2, q);
        } else {
          const double mid = phi_mu_ + 0.5 * (pieces_[p].delta + pieces_[p + 1].delta);
          const Vec2 middle = mu_ + q * Vec2{std::cos(mid), std::sin(mid)};
          for (std::size_t i = 0; i < rays_.size(); ++i)
            sides_[i] = rays_[i].u.x * middle.y - rays_[i].u.y * middle.x;
        }
        for (std::size_t k = 0; k < wedges_.size(); ++k) {
          const Wedge& w = wedges_[k];
          if (w.annulus == j &&
              (w.span >= kTwoPi || in_wedge(w, sides_[w.first], -sides_[w.second])))
            areas[k] += term;
        }
      }
    }
  }
  for (std::size_t k = 0; k < wedges_.size(); ++k) areas[k] = std::max(areas[k], 0.0);
}

double disc_sector_area(Vec2 mu, double q, const AnnularSector& sector) {
  DiscSectorAreas areas(mu, {sector});
  double a = 0.0;
  areas(q, &a);
  return a;
}

}  // namespace lidar_overlap
