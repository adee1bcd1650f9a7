// The turbulent atmosphere along a lidar's line of sight: a Cn^2 profile (constant, Hufnagel-Valley or
// any function of height), the path geometry, the inner and outer scales used by the phase screens,
// and the path-integrated quantities of weak-fluctuation theory (Kolmogorov spectrum): Fried parameter,
// Rytov variance, isoplanatic angle, the split of the path into phase screens, and the long-term spread
// and wander of a collimated Gaussian beam. The path runs from the lidar (range 0) to range L; every
// integral over it is an adaptive Gauss-Kronrod quadrature of Cn^2 times a weight.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

namespace lidar_overlap {

enum class Cn2Model { constant, hufnagel_valley, custom };

// One thin phase screen standing for a segment of the path.
struct ScreenPlacement {
  double range = 0.0;         // m, the screen's position: the middle of its segment
  double start = 0.0;         // m, the segment [start, end)
  double end = 0.0;           // m
  double cn2_integral = 0.0;  // m^(1/3), integral of Cn^2 over the segment
  double r0 = 0.0;  // m, the segment's plane-wave Fried parameter (infinite where Cn^2 = 0)
};

struct Cn2Profile {
  Cn2Model model = Cn2Model::constant;
  double cn2 = 0.0;                             // m^(-2/3), Cn2Model::constant
  double hv_ground = 1.7e-14;                   // m^(-2/3), Hufnagel-Valley ground term A (HV5/7)
  double hv_wind = 21.0;                        // m/s, Hufnagel-Valley rms upper wind speed (HV5/7)
  std::function<double(double)> cn2_of_height;  // m^(-2/3) at a height above ground (m), custom
  double elevation = 1.57079632679489661923;  // rad, in (0, pi/2]; pi/2 (the default) is the zenith
  double altitude = 0.0;                      // m, the lidar's height above ground (>= 0)
  double inner_scale = 0.0;                   // m, l0 of the phase screens; 0: none
  double outer_scale = std::numeric_limits<double>::infinity();  // m, L0; infinity: Kolmogorov

  static Cn2Profile constant(double cn2);
  // Hufnagel-Valley: Cn^2(h) = 0.00594 (v / 27)^2 (1e-5 h)^10 exp(-h / 1000) + 2.7e-16 exp(-h / 1500)
  // + A exp(-h / 100), h in m. The defaults (HV5/7) give r0 = 5 cm and theta0 = 7 urad at 0.5 um
  // looking up from the ground.
  static Cn2Profile hufnagel_valley(double ground = 1.7e-14, double wind = 21.0);
  static Cn2Profile custom(std::function<double(double)> cn2_of_height);

  // Throws std::invalid_argument naming the first invalid member.
  void validate() const;

  double cn2_at_height(double height) const;  // m^(-2/3) at `height` (m) above ground
  double cn2_at_range(
      double range) const;  // m^(-2/3) at `range` (m): height altitude + range sin(elevation)

  // Fried parameter (m) at `wavelength` (m) over the path [0, path_length] (m):
  // plane wave r0 = [0.423 k^2 int Cn^2(z) dz]^(-3/5); spherical wave from a point source at the lidar
  // observed at path_length, r0 = [0.423 k^2 int Cn^2(z) (z / L)^(5/3) dz]^(-3/5).
  double fried_parameter_plane(double wavelength, double path_length) const;
  double fried_parameter_spherical(double wavelength, double path_length) const;

  // Plane-wave Rytov variance at path_length: 2.25 k^(7/6) int Cn^2(z) (L - z)^(5/6) dz
  // (1.23 Cn^2 k^(7/6) L^(11/6) for a constant Cn^2; 1.23 is 2.25 * 6 / 11 rounded).
  double rytov_variance(double wavelength, double path_length) const;

  // Isoplanatic angle (rad) seen from the lidar, plane wave: [2.91 k^2 int Cn^2(z) z^(5/3) dz]^(-3/5).
  double isoplanatic_angle(double wavelength, double path_length) const;

  // `count` equal segments of [0, path_length], each a screen at its middle whose r0 is the plane-wave
  // one of its segment, so that the sum of r0_i^(-5/3) is fried_parameter_plane^(-5/3).
  std::vector<ScreenPlacement> place_screens(double wavelength, double path_length,
                                             std::size_t count) const;

  // Collimated TEM00 beam of waist radius `waist_radius` (m) at range 0, weak fluctuations (Rytov
  // variance below ~1), infinite outer scale, waist much larger than the inner scale; after Andrews &
  // Phillips, "Laser Beam Propagation through Random Media" (2nd ed., 2005). W is the diffraction-limited
  // radius at L, W^2 = w0^2 (1 + Lambda0^2) with Lambda0 = 2 L / (k w0^2), and Lambda = 2 L / (k W^2).
  //
  // Beam-wander variance (m^2): <r_c^2> = 2.42 W0^(-1/3) 3 int Cn^2(z) (L - z)^2 dz, i.e.
  // 2.42 Cn^2 L^3 W0^(-1/3) for a constant Cn^2. A tilt picked up at z moves the beam at L by (L - z)
  // times it, and the tilt variance of a layer is Cn^2 dz W0^(-1/3) (the beam stays ~W0 wide). This is
  // A&P's large-scale part of W_LT^2 (eddies filtered by exp(-kappa^2 W0^2)); the centroid of the
  // irradiance-weighted tilt (exp(-kappa^2 W0^2 / 4)), which the FO screens give, has 2^(-2/3) of it.
  double beam_wander_variance(double waist_radius, double wavelength, double path_length) const;

  // Long-term radius (m): W_LT^2 = W^2 (1 + 1.33 sigma^2 Lambda^(5/6)), the Gaussian core of the mean
  // irradiance, from its value on the axis (its second moment is larger). For a constant Cn^2, sigma^2 is
  // the Rytov variance; for a profile it is the same expression with Cn^2 replaced by its average
  // weighted by (1 - z / L)^(5/3), i.e. 2.25 k^(7/6) L^(5/6) (16 / 11) int Cn^2(z) (1 - z / L)^(5/3) dz.
  // This weight is the one of the Kolmogorov path integral behind 1.33 sigma_R^2 Lambda^(5/6),
  // 4 pi^2 k^2 int dz int kappa Phi_n(kappa, z) [1 - exp(-Lambda L kappa^2 (1 - z / L)^2 / k)] dkappa,
  // evaluated with Cn^2(z) inside (its constant-Cn^2 value, 1.632 Cn^2 k^(7/6) L^(11/6) Lambda^(5/6),
  // matches 1.33 x 1.227 to 0.04 %): turbulence near the lidar spreads the beam most.
  double long_term_radius(double waist_radius, double wavelength, double path_length) const;

  // Short-term (beam-wander-corrected) radius (m): W_ST^2 = W_LT^2 - <r_c^2>.
  double short_term_radius(double waist_radius, double wavelength, double path_length) const;
};

}  // namespace lidar_overlap
