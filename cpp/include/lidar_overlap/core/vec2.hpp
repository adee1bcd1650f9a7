// Transverse 2-vector (x, y) used for positions (m) and paraxial angles (rad).
#pragma once

#include <cmath>

namespace lidar_overlap {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// sqrt, not hypot: lengths here are far from overflow and this sits in the innermost loop.
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }

}  // namespace lidar_overlap
