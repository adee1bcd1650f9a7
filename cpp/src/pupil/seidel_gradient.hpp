// Gradient of the field-dependent Seidel terms, shared by Aberrations::gradient and the aberrated ray fan
// (overlap_rt_aberrated.cpp), which adds it per ray. Internal header, not installed.
#pragma once

#include "lidar_overlap/pupil/aberrations.hpp"
#include "lidar_overlap/core/vec2.hpp"

namespace lidar_overlap::detail {

// grad W = along_pupil p + along_field h (m per unit normalised pupil coordinate) of W131 rho^3 H cos +
// W222 H^2 rho^2 cos^2 + W220 H^2 rho^2 + W311 H^3 rho cos, with H rho cos = h.p: the field angle as the
// vector h = field / field_radius.
struct SeidelFieldGradient {
  double along_pupil, along_field;
};

inline SeidelFieldGradient seidel_field_gradient(const Aberrations& ab, Vec2 p, Vec2 h) {
  const double hp = dot(h, p), h2 = dot(h, h), r2 = dot(p, p);
  return {2.0 * ab.w131 * hp + 2.0 * ab.w220 * h2,
          ab.w131 * r2 + 2.0 * ab.w222 * hp + ab.w311 * h2};
}

}  // namespace lidar_overlap::detail
