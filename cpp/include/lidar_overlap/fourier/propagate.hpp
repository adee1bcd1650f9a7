// Free-space propagation of a Field (paper Appendix A): angular spectrum (A1, exact transfer function,
// band-limited), Fresnel (A5, single FFT or scaled to any output spacing) and Fraunhofer (A7). Every
// call reports the sampling and validity quantities of the method it used, so that callers can tell
// an aliased, clipped or out-of-region result from a good one.
#pragma once

#include <memory>
#include <vector>

#include "lidar_overlap/fourier/field.hpp"

namespace lidar_overlap {

enum class PropagationMethod { automatic, angular_spectrum, fresnel, fraunhofer };

struct PropagationReport {
  PropagationMethod method = PropagationMethod::automatic;  // the method actually used
  double critical_distance = 0.0;  // m, n dx^2 / lambda: AS below it, single-FFT Fresnel above
  double band_limit_loss = 0.0;  // AS: fraction of power outside the band-limited transfer function
  double input_edge_power = 0.0;  // fraction of the input power in the outer n/16 of the window
  double output_edge_power =
      0.0;  // the same for the output (wrap-around, aliasing; clipping if scaled)
  bool scaled_output = false;  // Fresnel/Fraunhofer by chirp-z to a chosen spacing (no wrap-around)
  double chirp_phase_step =
      0.0;  // rad, Fresnel: phase step of the input chirp at the field's edge (<= pi)
  double fresnel_phase_error =
      0.0;  // rad, Fresnel: (pi / (4 lambda)) rho^4 / z^3 over the fields (A3)
  double fraunhofer_phase = 0.0;  // rad, Fraunhofer: neglected input phase pi a^2 / (lambda z) (A6)
};

struct Propagated {
  Field field;
  PropagationReport report;
};

// Everything about a propagation that does not depend on the field's values: the method chosen, the
// transfer function (angular spectrum) or the separable chirps (Fresnel, Fraunhofer). Made once per
// geometry and executed on any number of fields; execute() is thread-safe.
class PropagationPlan {
 public:
  // n samples of `spacing` (m) at `wavelength` (m) over `distance` (m; > 0 for Fresnel and Fraunhofer,
  // any sign for AS). `output_spacing` (m) of 0 means the method's natural one: the input spacing for
  // AS, lambda z / (n dx) otherwise. automatic: AS when distance <= the critical distance n dx^2 / lambda
  // and no other output spacing is asked for, else Fresnel.
  PropagationPlan(std::size_t n, double spacing, double wavelength, double distance,
                  PropagationMethod method = PropagationMethod::automatic,
                  double output_spacing = 0.0);

  // A plan for these parameters from a small process-wide cache (made on first use).
  static std::shared_ptr<const PropagationPlan> cached(std::size_t n, double spacing,
                                                       double wavelength, double distance,
                                                       PropagationMethod method,
                                                       double output_spacing);

  // Works in place on `in` (pass an rvalue to avoid a copy of the field).
  Propagated execute(Field in) const;

  // The n x n row-major values `in` propagated into `out` (n x n, FFTW-aligned like any ComplexBuffer;
  // `out` may be `in`). `in` is only read, by the first pass, which writes `out`: no copy of the field is
  // made on the way. The output's spacing is output_spacing().
  PropagationReport execute(const Complex* in, Complex* out) const;

  PropagationMethod method() const { return method_; }
  double output_spacing() const { return output_spacing_; }
  double critical_distance() const { return critical_distance_; }

 private:
  std::size_t n_;
  double spacing_, wavelength_, distance_, output_spacing_, critical_distance_;
  PropagationMethod method_;
  ComplexBuffer transfer_;  // AS: n x n, zero outside the band limit
  // Fresnel: exp(i k x^2 / 2z) per axis, centring sign folded in; then the same on the output grid. Each
  // as its n real parts followed by its n imaginary parts (the product loops read them without shuffles).
  std::vector<double> chirp_in_;
  std::vector<double> chirp_out_;
  Complex front_{1.0, 0.0};  // exp(ikz) / (i lambda z) dx^2
  bool single_fft_ = false;  // Fresnel/Fraunhofer at the natural spacing: one FFT

  // The chirp-z path (Fresnel/Fraunhofer to another spacing), in place on u (n x n).
  PropagationReport scaled(ComplexBuffer& u) const;
};

// One-shot propagation through a cached plan; see PropagationPlan for the arguments. The field is
// copied; pass an rvalue to let the propagation reuse its memory.
Propagated propagate(Field in, double distance,
                     PropagationMethod method = PropagationMethod::automatic,
                     double output_spacing = 0.0);

}  // namespace lidar_overlap
