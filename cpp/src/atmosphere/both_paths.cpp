#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "lidar_overlap/atmosphere/turbulent_grid.hpp"
#include "atmosphere/phasor.hpp"
#include "atmosphere/return_path.hpp"
#include "atmosphere/turbulent_paths.hpp"
#include "core/checks.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "fourier/overlap_fo_detail.hpp"

namespace lidar_overlap::detail {

namespace {

// The receiver fields' seeds are drawn from the run's seed mixed with this: no screen's stream.
constexpr std::uint64_t kReceiverSeedMask = 0xD1B54A32D192ED03ULL;

// One task of both_paths: the draws 2 pair and 2 pair + 1, each a beam and `fields` receiver fields carried
// through the pair's screens, and the buffers their couplings are summed in.
struct DrawPair {
  DrawPair(const detail::ReturnPath& rx, std::uint64_t rx_seed, std::size_t pair,
           std::size_t fields, double lambda, double w0, std::size_t n, double dx0)
      : beams(2, Field::gaussian(lambda, w0, n, dx0)),
        back(2),
        phasor{ComplexBuffer(n * n), ComplexBuffer(n * n)},
        work(beams[0]),
        irradiance(2 * n * n),
        lines(2 * n),
        es(2 * fields),
        eu(2 * fields) {
    for (std::size_t c = 0; c < 2; ++c)
      for (std::size_t m = 0; m < fields; ++m)
        back[c].push_back(rx.pupil_field(rx_seed, 2 * pair + c, m));
  }

  // Every field from the segment's start: through its screen (one exp(i phase) per draw, shared by its beam and
  // receiver fields), or none for the transmitter's.
  void depart(const Segment& s,
              const std::vector<std::unique_ptr<PhaseScreenGenerator>>& generators,
              std::uint64_t seed, std::size_t pair) {
    const std::size_t n2 = irradiance.size() / 2;
    if (s.screen >= 0) {
      generators[s.screen]->generate_pair(screen_stream(seed, s.screen), pair, screens, spectrum);
      for (std::size_t c = 0; c < 2; ++c) detail::phasors(screens[c].data(), phasor[c].data(), n2);
    }
    for (std::size_t c = 0; c < 2; ++c) {
      const Complex* shared = s.screen >= 0 ? phasor[c].data() : nullptr;
      s.departure.execute(beams[c], nullptr, nullptr, shared);
      for (Field& v : back[c]) s.departure.execute(v, nullptr, nullptr, shared);
    }
  }

  // A field at `arrival`'s plane, read by columns; at the segment's end (`last`) also written back (it goes on).
  template <class Read>
  void reach(const detail::Arrival& arrival, bool last, Field& u, Read&& read) {
    arrival.execute(u, last ? u : work, last ? &u : nullptr, read);
  }

  // Every field carried to the segment's end through a plane where no G is wanted.
  void pass(const detail::Arrival& arrival) {
    for (std::size_t c = 0; c < 2; ++c) {
      reach(arrival, true, beams[c], [](std::size_t, const Complex*) {});
      for (Field& v : back[c]) reach(arrival, true, v, [](std::size_t, const Complex*) {});
    }
  }

  // G of each receiver field alone (their mean is the draw's G; their spread over sqrt(M) its random-phase
  // standard error), with this draw's beam and with the other draw's: each beam's irradiance once (by columns),
  // then each receiver field's sums with both, column by column as it arrives. Fills power, es and eu.
  void couple(const detail::Arrival& arrival, bool last) {
    const std::size_t n = lines.size() / 2, fields = es.size() / 2;
    power[0] = power[1] = 0.0;
    for (std::size_t c = 0; c < 2; ++c) {
      double* v = irradiance.data() + c * n * n;
      reach(arrival, last, beams[c], [&](std::size_t ix, const Complex* column) {
        double sum = 0.0;
        for (std::size_t iy = 0; iy < n; ++iy) sum += v[ix * n + iy] = std::norm(column[iy]);
        lines[ix] = sum;
      });
      for (std::size_t ix = 0; ix < n; ++ix) power[c] += lines[ix];
    }
    for (std::size_t c = 0; c < 2; ++c)
      for (std::size_t m = 0; m < fields; ++m) {
        const double* own = irradiance.data() + c * n * n;
        const double* other = irradiance.data() + (1 - c) * n * n;
        reach(arrival, last, back[c][m], [&](std::size_t ix, const Complex* column) {
          double so = 0.0, su = 0.0;
          for (std::size_t iy = 0; iy < n; ++iy) {
            const double w = std::norm(column[iy]);
            so += own[ix * n + iy] * w;
            su += other[ix * n + iy] * w;
          }
          lines[2 * ix] = so, lines[2 * ix + 1] = su;
        });
        double so = 0.0, su = 0.0;
        for (std::size_t ix = 0; ix < n; ++ix) so += lines[2 * ix], su += lines[2 * ix + 1];
        es[c * fields + m] = so, eu[(1 - c) * fields + m] = su;
      }
  }

  // Draw c's G at `range` from couple()'s sums (`factor` = (lambda z)^2 / aperture area) into row `row` of out.
  void store(TurbulentOverlap& out, std::size_t row, std::size_t c, int range,
             double factor) const {
    const std::size_t fields = es.size() / 2;
    double sum = 0.0, sum2 = 0.0, unc = 0.0;
    for (std::size_t m = 0; m < fields; ++m) {
      const double g = es[c * fields + m] * factor / power[c];
      sum += g;
      sum2 += g * g;
      unc += eu[c * fields + m] * factor / power[c];
    }
    const double mean = sum / double(fields);
    out.overlap[row][range] = mean;
    out.uncorrelated[row][range] = unc / double(fields);
    out.receiver_error[row][range] =
        fields > 1
            ? std::sqrt(std::max(sum2 / double(fields) - mean * mean, 0.0) / double(fields - 1))
            : std::numeric_limits<double>::quiet_NaN();  // one field shows no spread
  }

  // Draw c's beam centroid and radius and the receiver's sensitivity centroid (its fields' summed irradiance) at
  // the last plane, into row `row` of out.
  void store_ends(TurbulentOverlap& out, std::size_t row, std::size_t c) const {
    const Vec2 centre = beams[c].centroid();
    out.wander_x[row] = centre.x;
    out.wander_y[row] = centre.y;
    out.radius_last[row] = beams[c].beam_radius();
    double total = 0.0, sx = 0.0, sy = 0.0;
    for (const Field& v : back[c]) {
      const double pv = v.power();
      const Vec2 cv = v.centroid();
      total += pv, sx += pv * cv.x, sy += pv * cv.y;
    }
    out.receiver_x[row] = total > 0.0 ? sx / total : 0.0;
    out.receiver_y[row] = total > 0.0 ? sy / total : 0.0;
  }

  std::vector<Field> beams;
  std::vector<std::vector<Field>> back;  // each draw's receiver fields
  std::array<ComplexBuffer, 2> phasor;   // a screen's exp(i phase) per draw
  ComplexBuffer spectrum;
  std::array<std::vector<double>, 2> screens;
  Field work;
  std::vector<double> irradiance, lines, es, eu;  // by columns
  double power[2] = {0.0, 0.0};                   // each beam's power at the plane
};

// Every G of both paths finite and >= 0, or an internal error naming the range.
void check_both_rows(const TurbulentOverlap& out, const std::vector<double>& ranges) {
  for (const auto& rows : {&out.overlap, &out.uncorrelated})
    for (const std::vector<double>& g : *rows)
      for (std::size_t i = 0; i < g.size(); ++i)
        if (!(g[i] >= 0.0 && std::isfinite(g[i])))
          checks::fail(detail::range_name(i), ranges[i],
                       "a range where the turbulent overlap is finite (internal error)");
}

}  // namespace

// Both paths (TurbulencePaths::both). Each task carries one pair of screen draws (2p, 2p + 1): both beams and
// both sets of receiver fields through the pair's screens, so that the uncorrelated G (a draw's beam with the
// other draw's receiver) costs no propagation of its own; the call's rows are taken from it. A draw's G
// depends on its screens and its receiver fields' seeds alone: the same in any part and on any thread.
TurbulentOverlap both_paths(const LidarSystem& system, const std::vector<double>& ranges,
                            const TurbulenceOptions& o, int threads, const TurbulentPlan& plan,
                            const std::vector<std::unique_ptr<PhaseScreenGenerator>>& generators,
                            double dx0) {
  const std::size_t n = o.beam_grid, fields = o.receiver_fields;
  const double lambda = system.beam.wavelength, w0 = system.beam.waist_radius;
  const detail::ReturnPath rx(system, n, dx0, fields);
  checks::memory("beam_grid", static_cast<double>(n),
                 turbulent_both_bytes(n, o.screens, fields, threads),
                 "lower beam_grid, receiver_fields or screens");

  TurbulentOverlap out = zero_rows(o.realizations, ranges.size(), true);
  const std::size_t first = o.first_realization, end = first + o.realizations, p0 = first / 2;
  const double area = rx.aperture_area();
  const std::uint64_t rx_seed = o.seed ^ kReceiverSeedMask;
  detail::parallel_for((end - 1) / 2 - p0 + 1, threads, [&](std::size_t t) {
    const std::size_t pair = p0 + t;
    auto in_part = [&](std::size_t c) { return 2 * pair + c >= first && 2 * pair + c < end; };
    DrawPair draws(rx, rx_seed, pair, fields, lambda, w0, n, dx0);
    for (const Segment& s : plan.segments) {
      draws.depart(s, generators, o.seed, pair);
      for (std::size_t j = 0; j < s.targets.size(); ++j) {
        const Plane& p = plan.planes[s.targets[j]];
        const bool last =
            j + 1 == s.targets.size();  // the segment's end: each field arrives in place
        if (p.range < 0) {
          if (last) draws.pass(s.arrivals[j]);
          continue;
        }
        draws.couple(s.arrivals[j], last);
        const double lz = lambda * p.z, factor = lz * lz / area;
        for (std::size_t c = 0; c < 2; ++c)
          if (in_part(c)) draws.store(out, 2 * pair + c - first, c, p.range, factor);
      }
    }
    for (std::size_t c = 0; c < 2; ++c)
      if (in_part(c)) draws.store_ends(out, 2 * pair + c - first, c);
  });
  check_both_rows(out, ranges);
  return out;
}

}  // namespace lidar_overlap::detail
