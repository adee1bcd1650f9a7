// Optical transfer function of the receiver seen by one point scatterer (paper Appendix C, steps 4-5,
// in Fourier space): the pupil is the aperture disc minus the obstruction's shadow disc, with the
// quadratic phase psi |a|^2 that the scatterer's spherical wave, the lens and the propagation to the
// detector plane leave (psi = 0 when the scatterer is imaged onto the detector plane). The image of a
// point, |h|^2, has the Fourier transform OTF(q) = int P(a) P*(a - lambda d q) da (m^2; OTF(0) is the
// pupil area), which for this rotationally symmetric pupil depends on |q| only.
#pragma once

namespace lidar_overlap {

struct AnnularPupil {
  double outer;  // m, aperture radius (or the NA cone's, if smaller)
  double inner;  // m, shadow radius of the obstruction (0: none), < outer
  double psi;    // rad/m^2, quadratic phase across the pupil
};

// OTF at a pupil shift v = lambda d |q| (m): the overlap of the pupil with itself shifted by v,
// weighted by exp(2 i psi x v) across it, computed exactly on its boundary arcs (Jacobi-Anger series, closed form per arc).
double annular_otf(const AnnularPupil& pupil, double shift);

// Fourier transform of the indicator of a disc of radius r at spatial frequency q (1/m): r J1(2 pi q r) / q.
double disc_transform(double r, double q);

}  // namespace lidar_overlap
