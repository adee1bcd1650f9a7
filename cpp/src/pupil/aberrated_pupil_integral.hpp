// Ray-tracing overlap with aberrations as one pupil integral per range (used by overlap_rt_aberrated.cpp;
// not installed). When every ray's displacement on the detector plane,
//   D(a) = a (1 + d/z - d/f) + d grad_a W(a),
// is the same for every scatterer (Zernike terms and W040, no NA cone, obstruction absent or in the aperture
// plane), the beam integral can be done first: a scatterer whose geometric image lies x from the beam image's
// centre sends the ray through a onto the detector when |x + D(a) + s| < r_d (s: the beam image's centre from
// the detector centre), and over the Gaussian beam image that happens with probability K(|D(a) + s|), the
// Rice integral of a Gaussian of radius w_i = w(z) d / z over the detector disc. So
//   G = (1 / pi R^2) int_pupil K(|D(a) + s|) da,
// a smooth integrand (K varies on the scale w_i / 2) done by Gauss-Legendre panels in rho and the trapezoid
// rule in theta, with a node every w_i / 4 of D's sweep in rho and every 0.8 w_i in theta (the trapezoid rule is
// spectral on these smooth periodic rows: 1e-9 against 8x the angles). The wavefront slopes are computed once
// per node set and shared by all ranges.
#pragma once

#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "lidar_overlap/pupil/aberrations.hpp"
#include "lidar_overlap/core/system.hpp"

namespace lidar_overlap::detail {

class ImageOnDetector;

class AberratedPupilIntegral {
 public:
  // `rotational`: the aberrations and the scene are rotationally symmetric (one angle per ring suffices).
  AberratedPupilIntegral(const LidarSystem& system, const Aberrations& aberrations,
                         const std::vector<double>& ranges, bool rotational);
  // G at ranges[i] and its change when the rule is coarsened (every other angle, or half the panels).
  std::pair<double, double> at(std::size_t i) const;

 private:
  struct Nodes {
    std::vector<Vec2> a, slope;  // m: pupil point, and d grad_a W there
    std::vector<double> weight;  // share of the full aperture's area
    std::size_t angles = 1;
  };
  using Key = std::pair<std::size_t, std::size_t>;  // (panels, angles)
  const Nodes& nodes(Key key);
  double sum(const Nodes& n, double scale, Vec2 s, const ImageOnDetector& k_of,
             bool every_other_angle) const;

  const LidarSystem& system_;
  const Aberrations& aberrations_;
  const std::vector<double>& ranges_;
  std::vector<Key> keys_;
  std::vector<bool> coarse_in_rho_;
  std::map<Key, Nodes> node_sets_;
};

}  // namespace lidar_overlap::detail
