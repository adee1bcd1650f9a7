// Areas of one disc, centred at a fixed point mu with a varying radius q, inside each of a list of annular
// sectors: the masked beam integral's Lambda(q) (moving_disc_integral.hpp) at every node. Internal header, not
// installed.
//
// By Green's theorem, area = 1/2 closed-integral of (x dy - y dx) over the region's boundary: arcs of the
// sector's circles about the origin (1/2 rho^2 per radian inside the disc and the wedge, the inner one run
// backwards), arcs of the disc's circle between its crossings with the sector's circles and edge rays
// (1/2 [q^2 dpsi + q (mu_x d sin psi - mu_y d cos psi)]), and pieces of the edge rays, which add nothing (x dy =
// y dx along a ray from the origin). No angular sweep: a few acos and one atan2 per crossing. What depends on mu
// alone is made once; the circles' and rays' crossings are shared by the sectors with the same radii or edges
// (the four quadrants of a telecover test share one annulus and four rays).
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/sector_area.hpp"

namespace lidar_overlap {

class DiscSectorAreas {
 public:
  DiscSectorAreas(Vec2 mu, const std::vector<AnnularSector>& sectors);
  // areas[i] (m^2) = area of disc(mu, q) ∩ sectors[i], for q (m) >= 0. Not thread-safe (scratch space).
  void operator()(double q, double* areas);

 private:
  struct Annulus {
    double inner, outer;
  };
  struct Ray {
    Vec2 u;
    double along, off;  // dot(u, mu), cross(u, mu)
  };
  struct Wedge {
    std::size_t annulus, first, second;  // the sector's annulus and edge rays
    double start, span;                  // rad; span >= 2 pi: a full turn (no rays)
  };
  // A point of the disc's circle at psi = phi_mu + delta, e = (cos psi, sin psi).
  struct OnCircle {
    double delta;
    Vec2 e;
  };
  struct AnnulusState {  // per node
    double outer_start, outer_length, inner_start,
        inner_length;     // the sector circles' arcs inside the disc
    bool arcs;            // the disc's circle meets the annulus
    OnCircle ends[2][2];  // the disc's circle in the annulus: delta in [-hi, -lo] and [lo, hi]
  };
  struct RayState {
    std::size_t n;
    OnCircle at[2];
  };

  OnCircle on_circle(double delta, double cos_delta, double sin_delta) const;
  double arc_term(double q, const OnCircle& a, const OnCircle& b) const;
  double side(const Ray& r, Vec2 sum, double length2, double q) const;
  bool in_wedge(const Wedge& w, double after_start, double before_end) const;

  Vec2 mu_, u_mu_;
  double m_, phi_mu_;
  std::vector<Annulus> annuli_;
  std::vector<Ray> rays_;
  std::vector<Wedge> wedges_;
  std::vector<AnnulusState> annulus_state_;
  std::vector<RayState> ray_state_;
  std::vector<OnCircle> pieces_;
  std::vector<double> sides_;  // per ray: the sign of cross(u, the piece's middle)
};

// The area of disc(mu, q) ∩ sector for one disc and sector (DiscSectorAreas of one sector).
double disc_sector_area(Vec2 mu, double q, const AnnularSector& sector);

}  // namespace lidar_overlap
