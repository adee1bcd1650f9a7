// Computes one overlap value of the paper's Table 1 system in the point-aperture limit and checks it
// against the closed form 1 - exp(-2 (alpha z)^2 / w(z)^2).
#include <lidar_overlap/lidar_overlap.hpp>

// The installed tree holds the public API only: no internal header, under its old flat path or its
// private one, can be included from here (a compile-time proof: the build fails otherwise).
#if __has_include(<lidar_overlap/checks.hpp>)
#error "installed but not part of the public API: <lidar_overlap/checks.hpp>"
#endif
#if __has_include(<lidar_overlap/constants.hpp>)
#error "installed but not part of the public API: <lidar_overlap/constants.hpp>"
#endif
#if __has_include(<lidar_overlap/special_functions.hpp>)
#error "installed but not part of the public API: <lidar_overlap/special_functions.hpp>"
#endif
#if __has_include(<lidar_overlap/quadrature.hpp>)
#error "installed but not part of the public API: <lidar_overlap/quadrature.hpp>"
#endif
#if __has_include(<lidar_overlap/circles.hpp>)
#error "installed but not part of the public API: <lidar_overlap/circles.hpp>"
#endif
#if __has_include(<lidar_overlap/coupling_term.hpp>)
#error "installed but not part of the public API: <lidar_overlap/coupling_term.hpp>"
#endif
#if __has_include(<lidar_overlap/otf.hpp>)
#error "installed but not part of the public API: <lidar_overlap/otf.hpp>"
#endif
#if __has_include(<lidar_overlap/fft.hpp>)
#error "installed but not part of the public API: <lidar_overlap/fft.hpp>"
#endif
#if __has_include(<lidar_overlap/scaled_dft.hpp>)
#error "installed but not part of the public API: <lidar_overlap/scaled_dft.hpp>"
#endif
#if __has_include(<lidar_overlap/receiver.hpp>)
#error "installed but not part of the public API: <lidar_overlap/receiver.hpp>"
#endif
#if __has_include(<lidar_overlap/overlap_fo.hpp>)
#error "installed but not part of the public API: <lidar_overlap/overlap_fo.hpp>"
#endif
#if __has_include(<lidar_overlap/system.hpp>)
#error "installed but not part of the public API: <lidar_overlap/system.hpp>"
#endif
#if __has_include(<lidar_overlap/core/checks.hpp>)
#error "installed but not part of the public API: <lidar_overlap/core/checks.hpp>"
#endif
#if __has_include(<lidar_overlap/core/constants.hpp>)
#error "installed but not part of the public API: <lidar_overlap/core/constants.hpp>"
#endif
#if __has_include(<lidar_overlap/core/special_functions.hpp>)
#error "installed but not part of the public API: <lidar_overlap/core/special_functions.hpp>"
#endif
#if __has_include(<lidar_overlap/core/quadrature.hpp>)
#error "installed but not part of the public API: <lidar_overlap/core/quadrature.hpp>"
#endif
#if __has_include(<lidar_overlap/core/parallel.hpp>)
#error "installed but not part of the public API: <lidar_overlap/core/parallel.hpp>"
#endif
#if __has_include(<lidar_overlap/geometry/circles.hpp>)
#error "installed but not part of the public API: <lidar_overlap/geometry/circles.hpp>"
#endif
#if __has_include(<lidar_overlap/geometry/coupling_term.hpp>)
#error "installed but not part of the public API: <lidar_overlap/geometry/coupling_term.hpp>"
#endif
#if __has_include(<lidar_overlap/geometry/receiver_coupling.hpp>)
#error "installed but not part of the public API: <lidar_overlap/geometry/receiver_coupling.hpp>"
#endif
#if __has_include(<lidar_overlap/fourier/fft.hpp>)
#error "installed but not part of the public API: <lidar_overlap/fourier/fft.hpp>"
#endif
#if __has_include(<lidar_overlap/fourier/scaled_dft.hpp>)
#error "installed but not part of the public API: <lidar_overlap/fourier/scaled_dft.hpp>"
#endif
#if __has_include(<lidar_overlap/fourier/otf.hpp>)
#error "installed but not part of the public API: <lidar_overlap/fourier/otf.hpp>"
#endif
#if __has_include(<lidar_overlap/fourier/fo_receiver.hpp>)
#error "installed but not part of the public API: <lidar_overlap/fourier/fo_receiver.hpp>"
#endif
#if __has_include(<lidar_overlap/fourier/overlap_fo_detail.hpp>)
#error "installed but not part of the public API: <lidar_overlap/fourier/overlap_fo_detail.hpp>"
#endif
#if __has_include(<lidar_overlap/fourier/gaussian_image_overlap.hpp>)
#error "installed, not public API: <lidar_overlap/fourier/gaussian_image_overlap.hpp>"
#endif
#if __has_include(<lidar_overlap/pupil/aberrated_pupil_integral.hpp>)
#error "installed, not public API: <lidar_overlap/pupil/aberrated_pupil_integral.hpp>"
#endif
#if __has_include(<lidar_overlap/pupil/sampled_pupil_overlap.hpp>)
#error "installed but not part of the public API: <lidar_overlap/pupil/sampled_pupil_overlap.hpp>"
#endif
#if __has_include(<lidar_overlap/pupil/seidel_gradient.hpp>)
#error "installed but not part of the public API: <lidar_overlap/pupil/seidel_gradient.hpp>"
#endif
#if __has_include(<core/checks.hpp>)
#error "installed but not part of the public API: <core/checks.hpp>"
#endif
#if __has_include(<fourier/fft.hpp>)
#error "installed but not part of the public API: <fourier/fft.hpp>"
#endif
#if !__has_include(<lidar_overlap/core/system.hpp>) || !__has_include(<lidar_overlap/version.hpp>) || \
    !__has_include(<lidar_overlap/pupil/aperture_mask.hpp>)
#error "the public API is not installed where expected"
#endif

#include <cmath>
#include <iostream>

int main() {
  using namespace lidar_overlap;
  LidarSystem system;
  system.detector = Detector::from_fov(0.9e-3, 1.0);
  system.telescope.diameter = 1e-7;
  const double z = 300.0;
  const double g = overlap_rt(system, {z}, {1e-9, 1, 4000}).overlap[0];
  const double w = system.beam.radius(z), az = system.detector.radius * z;
  const double expected = -std::expm1(-2.0 * az * az / (w * w));
  std::cout << "lidar_overlap " << kVersion << ": G(" << z << " m) = " << g << " (closed form "
            << expected << ")\n";
  return std::abs(g - expected) < 1e-7 ? 0 : 1;
}
