// Globally adaptive Gauss-Kronrod (7-15) quadrature with known breakpoints: the integrals of the
// RT overlap are smooth between the kinks the geometry can predict, and the remaining kinks are
// found by bisecting the segment with the largest error estimate.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace lidar_overlap {

struct QuadratureResult {
  double value = 0.0;
  double error = 0.0;  // estimated absolute error
  std::size_t evaluations = 0;
  bool converged = true;  // false when max_segments was reached before the tolerance
};

namespace gauss_kronrod {
// Abscissae and weights of the 15-point Kronrod rule and its embedded 7-point Gauss rule on [-1, 1]
// (QUADPACK's qk15). Odd indices of kX are the Gauss nodes.
inline constexpr double kX[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
inline constexpr double kWK[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr double kWG[4] = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Segment {
  double a, b, value, error;
  bool operator<(const Segment& o) const { return error < o.error; }
};

// The 15-point rule on [a, b] from f at its centre (fc) and at c -+ h kX[j] (fv1[j], fv2[j]), with QUADPACK's
// error heuristic.
inline Segment from_values(double a, double b, double fc, const double* fv1, const double* fv2) {
  const double h = 0.5 * (b - a);
  double resk = kWK[7] * fc, resg = kWG[3] * fc, resabs = std::abs(resk);
  for (int j = 0; j < 7; ++j) {
    resk += kWK[j] * (fv1[j] + fv2[j]);
    resabs += kWK[j] * (std::abs(fv1[j]) + std::abs(fv2[j]));
    if (j % 2 == 1) resg += kWG[j / 2] * (fv1[j] + fv2[j]);
  }
  const double mean = 0.5 * resk;
  double resasc = kWK[7] * std::abs(fc - mean);
  for (int j = 0; j < 7; ++j)
    resasc += kWK[j] * (std::abs(fv1[j] - mean) + std::abs(fv2[j] - mean));
  const double ah = std::abs(h);
  resasc *= ah;
  resabs *= ah;
  double err = std::abs((resk - resg) * h);
  if (resasc != 0.0 && err != 0.0) {
    const double ratio =
        200.0 * err / resasc;  // QUADPACK's ratio^1.5, as ratio sqrt(ratio): pow is the slower call
    err = resasc * std::min(1.0, ratio * std::sqrt(ratio));
  }
  err = std::max(err, 50.0 * 2.220446049250313e-16 * resabs);
  return {a, b, resk * h, err};
}

// One 15-point rule on [a, b].
template <class F>
Segment rule(F& f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double fv1[7], fv2[7];
  for (int j = 0; j < 7; ++j) {
    fv1[j] = f(c - h * kX[j]);
    fv2[j] = f(c + h * kX[j]);
  }
  return from_values(a, b, fc, fv1, fv2);
}
}  // namespace gauss_kronrod

// Integrates f over [points[0], points[n-1]] (sorted breakpoints, n >= 2) until the summed error
// estimate is <= tolerance (absolute), bisecting the worst segment; stops at max_segments.
template <class F>
QuadratureResult integrate(F&& f, const double* points, std::size_t n, double tolerance,
                           std::size_t max_segments) {
  using gauss_kronrod::Segment;
  std::vector<Segment> heap;
  heap.reserve(std::max<std::size_t>(n, 16));
  QuadratureResult r;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (!(points[i + 1] > points[i])) continue;
    heap.push_back(gauss_kronrod::rule(f, points[i], points[i + 1]));
    r.evaluations += 15;
  }
  std::make_heap(heap.begin(), heap.end());
  auto total_error = [&] {
    double e = 0.0;
    for (const Segment& s : heap) e += s.error;
    return e;
  };
  double error = total_error();
  while (error > tolerance) {
    if (heap.size() >= max_segments) {
      r.converged = false;
      break;
    }
    std::pop_heap(heap.begin(), heap.end());
    const Segment worst = heap.back();
    heap.pop_back();
    const double mid = 0.5 * (worst.a + worst.b);
    if (!(mid > worst.a && mid < worst.b)) {  // cannot split further in double precision
      heap.push_back(worst);
      std::push_heap(heap.begin(), heap.end());
      r.converged = false;
      break;
    }
    for (const Segment& half :
         {gauss_kronrod::rule(f, worst.a, mid), gauss_kronrod::rule(f, mid, worst.b)}) {
      heap.push_back(half);
      std::push_heap(heap.begin(), heap.end());
    }
    r.evaluations += 30;
    error = total_error();  // re-summed: running sums drift when errors span many magnitudes
  }
  for (const Segment& s : heap) r.value += s.value;
  r.error = error;
  return r;
}

// The m integrals of f(x, out) (writing out[0..m)) over [points[0], points[n-1]] on one shared set of segments:
// each evaluation serves all m (the sectors of a telecover test share the nodes and their geometry). Bisects the
// segment with the largest error in the integral furthest over `tolerance` until each summed error estimate is
// within it; stops at max_segments. result[k] is integral k; evaluations count the shared calls of f.
template <class F>
std::vector<QuadratureResult> integrate_many(F&& f, std::size_t m, const double* points,
                                             std::size_t n, double tolerance,
                                             std::size_t max_segments) {
  using gauss_kronrod::kX;
  if (m == 0) return {};
  std::vector<double> nodes(15 * m);  // node j's m values at nodes[j * m]
  std::vector<double> ends, value,
      error;  // segment s: [ends[2s], ends[2s + 1]], its m values and errors at s * m
  std::size_t evaluations = 0;
  auto rule = [&](double a, double b,
                  std::size_t s) {  // writes segment s (appended when s is the count)
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    f(c, &nodes[14 * m]);
    for (int j = 0; j < 7; ++j) {
      f(c - h * kX[j], &nodes[j * m]);
      f(c + h * kX[j], &nodes[(7 + j) * m]);
    }
    evaluations += 15;
    if (2 * s == ends.size()) {
      ends.resize(ends.size() + 2);
      value.resize(value.size() + m);
      error.resize(error.size() + m);
    }
    ends[2 * s] = a;
    ends[2 * s + 1] = b;
    double fv1[7], fv2[7];
    for (std::size_t k = 0; k < m; ++k) {
      for (int j = 0; j < 7; ++j) {
        fv1[j] = nodes[j * m + k];
        fv2[j] = nodes[(7 + j) * m + k];
      }
      const gauss_kronrod::Segment seg =
          gauss_kronrod::from_values(a, b, nodes[14 * m + k], fv1, fv2);
      value[s * m + k] = seg.value;
      error[s * m + k] = seg.error;
    }
  };
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (points[i + 1] > points[i]) rule(points[i], points[i + 1], ends.size() / 2);
  std::vector<QuadratureResult> out(m);
  std::vector<double> total(m);
  while (true) {
    const std::size_t segments = ends.size() / 2;
    std::fill(total.begin(), total.end(), 0.0);
    for (std::size_t s = 0; s < segments; ++s)
      for (std::size_t k = 0; k < m; ++k) total[k] += error[s * m + k];
    const std::size_t worst =
        static_cast<std::size_t>(std::max_element(total.begin(), total.end()) - total.begin());
    if (segments == 0 || total[worst] <= tolerance) break;
    std::size_t split = 0;
    for (std::size_t s = 1; s < segments; ++s)
      if (error[s * m + worst] > error[split * m + worst]) split = s;
    const double a = ends[2 * split], b = ends[2 * split + 1], mid = 0.5 * (a + b);
    if (segments >= max_segments ||
        !(mid > a && mid < b)) {  // out of segments or of double precision
      for (std::size_t k = 0; k < m; ++k) out[k].converged = total[k] <= tolerance;
      break;
    }
    rule(a, mid, split);
    rule(mid, b, segments);
  }
  for (std::size_t k = 0; k < m; ++k) {
    for (std::size_t s = 0; s < ends.size() / 2; ++s) out[k].value += value[s * m + k];
    out[k].error = total[k];
    out[k].evaluations = evaluations;
  }
  return out;
}

// Gauss-Legendre rule with N nodes on [-1, 1] (Newton on P_N), made once per N.
struct GaussLegendreRule {
  std::vector<double> x, w;
};
template <std::size_t N>
const GaussLegendreRule& gauss_legendre() {
  static const GaussLegendreRule rule = [] {
    GaussLegendreRule r{std::vector<double>(N), std::vector<double>(N)};
    for (std::size_t i = 0; i < (N + 1) / 2; ++i) {
      double x = std::cos(3.141592653589793 * (i + 0.75) / (N + 0.5)), dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = x;
        for (std::size_t j = 2; j <= N; ++j) {
          const double p2 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j;
          p0 = p1;
          p1 = p2;
        }
        dp = N * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      r.x[i] = -x;
      r.x[N - 1 - i] = x;
      r.w[i] = r.w[N - 1 - i] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    return r;
  }();
  return rule;
}

}  // namespace lidar_overlap
