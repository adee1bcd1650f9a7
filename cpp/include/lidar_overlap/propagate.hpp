// Free-space propagation of a Field (paper Appendix A): angular spectrum (A1, exact transfer function,
// band-limited), Fresnel (A5, single FFT or scaled to any output spacing) and Fraunhofer (A7). Every
// call reports the sampling and validity quantities of the method it used, so that callers can tell
// an aliased, clipped or out-of-region result from a good one.
#pragma once

#include "lidar_overlap/field.hpp"

namespace lidar_overlap {

enum class PropagationMethod { automatic, angular_spectrum, fresnel, fraunhofer };

struct PropagationReport {
  PropagationMethod method = PropagationMethod::automatic;  // the method actually used
  double critical_distance = 0.0;    // m, n dx^2 / lambda: AS below it, single-FFT Fresnel above
  double band_limit_loss = 0.0;      // AS: fraction of power outside the band-limited transfer function
  double input_edge_power = 0.0;     // fraction of the input power in the outer n/16 of the window
  double output_edge_power = 0.0;    // the same for the output (wrap-around, aliasing)
  double chirp_phase_step = 0.0;     // rad, Fresnel: phase step of the input chirp at the field's edge (<= pi)
  double fresnel_phase_error = 0.0;  // rad, Fresnel: (pi / (4 lambda)) rho^4 / z^3 over the fields (A3)
  double fraunhofer_phase = 0.0;     // rad, Fraunhofer: neglected input phase pi a^2 / (lambda z) (A6)
};

struct Propagated {
  Field field;
  PropagationReport report;
};

// Propagates `in` over `distance` (m; > 0 for Fresnel and Fraunhofer, any sign for AS). `output_spacing`
// (m) of 0 means the method's natural one: the input spacing for AS, lambda z / (n dx) otherwise.
// automatic: AS when distance <= critical distance and no other output spacing is asked for, else Fresnel.
Propagated propagate(const Field& in, double distance, PropagationMethod method = PropagationMethod::automatic,
                     double output_spacing = 0.0);

}  // namespace lidar_overlap
