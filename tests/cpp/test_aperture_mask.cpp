// Aperture masks: the exact sector areas against closed forms and a grid count, partitions that add up to
// the full aperture (per scatterer and for G), the 1-D beam integral of a term with one moving disc against
// the scatterer-plane one, and the mask's checks.
#include <random>
#include <stdexcept>

#include "check.hpp"
#include "geometry/beam_integral.hpp"
#include "geometry/disc_sector_areas.hpp"
#include "geometry/moving_disc_integral.hpp"
#include "geometry/sector_area.hpp"
#include "lidar_overlap/pupil/aperture_mask.hpp"

using namespace lidar_overlap;

namespace {

// The area of the discs inside the sector, counted on a fine grid over the sector's bounding square.
double grid_area(const Disc* d, std::size_t n, const AnnularSector& s, int cells) {
  const double h = 2.0 * s.outer / cells;
  long inside = 0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const Vec2 p{-s.outer + (i + 0.5) * h, -s.outer + (j + 0.5) * h};
      const double rho = norm(p);
      double t = std::atan2(p.y, p.x) - s.start;
      t -= 2.0 * kPi * std::floor(t / (2.0 * kPi));
      bool in = rho >= s.inner && rho <= s.outer && t <= s.span;
      for (std::size_t k = 0; k < n && in; ++k) in = norm(p - d[k].center) <= d[k].radius;
      inside += in;
    }
  return inside * h * h;
}

ApertureMask quadrant(int k, double rotation = 0.0) {
  return {{Sector{rotation + k * 0.5 * kPi, rotation + (k + 1) * 0.5 * kPi}}};
}
}  // namespace

int main() {
  // Closed forms: a disc centred at the origin over a quarter annulus; the full annulus.
  const Disc big{{0.0, 0.0}, 2.0};
  test::near("quarter annulus", sector_intersection_area(&big, 1, {0.3, 0.5 * kPi, 0.5, 1.0}),
             0.25 * kPi * (1.0 - 0.25), 1e-14);
  const Disc off{{0.4, -0.2}, 0.5};
  test::near("full turn = lens", sector_intersection_area(&off, 1, {1.0, 2.0 * kPi, 0.0, 1.0}),
             lens_area(off, {{0.0, 0.0}, 1.0}), 1e-14);

  // Small discs away from the origin over full turns with any start: the far arc between the tangents from the
  // origin spans more than pi about the disc's centre (once taken as a short arc, losing up to half the disc).
  std::mt19937 small_rng(7);
  std::uniform_real_distribution<double> v(0.0, 1.0);
  double worst_small = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    const double angle = 2.0 * kPi * v(small_rng), d = 0.1 + 0.8 * v(small_rng);
    const Disc small{{d * std::cos(angle), d * std::sin(angle)}, 0.05 + 0.5 * d * v(small_rng)};
    const AnnularSector turn{7.0 * v(small_rng) - 3.5, 2.0 * kPi, 0.0, 1.0};
    worst_small = std::max(worst_small, std::abs(sector_intersection_area(&small, 1, turn) -
                                                 lens_area(small, {{0.0, 0.0}, 1.0})));
  }
  test::near("small off-centre discs over full turns = lens", worst_small, 0.0, 1e-15);

  // Green's-theorem area of one disc against the angular sweep: random discs (containing the origin or not,
  // crossing the circles and edges or not) over random annular sectors, full turns and spans beyond pi.
  double worst_green = 0.0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double angle = 2.0 * kPi * v(small_rng), d = trial % 10 == 0 ? 0.0 : 1.2 * v(small_rng);
    const Disc disc{{d * std::cos(angle), d * std::sin(angle)}, 0.01 + 1.2 * v(small_rng)};
    const double inner = trial % 3 == 0 ? 0.0 : 0.5 * v(small_rng);
    const double span = trial % 7 == 0 ? 2.0 * kPi : 0.05 + (2.0 * kPi - 0.05) * v(small_rng);
    const AnnularSector s{20.0 * v(small_rng) - 10.0, span, inner,
                          inner + 0.01 + (1.0 - inner) * v(small_rng)};
    worst_green = std::max(worst_green, std::abs(disc_sector_area(disc.center, disc.radius, s) -
                                                 sector_intersection_area(&disc, 1, s)));
  }
  test::near("Green's-theorem area = angular sweep (20000 random cases, areas up to ~3)",
             worst_green, 0.0, 1e-13);
  // Several sectors sharing their circles and edge rays (rotated quadrants, a ring and an annular sector): each
  // area as the sweep's.
  double worst_shared = 0.0;
  for (int trial = 0; trial < 5000; ++trial) {
    const double rotation = 7.0 * v(small_rng) - 3.5;
    std::vector<AnnularSector> shared;
    for (int k = 0; k < 4; ++k) shared.push_back({rotation + k * 0.5 * kPi, 0.5 * kPi, 0.0, 1.0});
    shared.push_back({0.0, 2.0 * kPi, 0.3, 0.6});
    shared.push_back({rotation, 2.5, 0.3, 1.0});
    const double angle = 2.0 * kPi * v(small_rng), d = trial % 10 == 0 ? 0.0 : 1.2 * v(small_rng);
    const Vec2 mu{d * std::cos(angle), d * std::sin(angle)};
    const double q = 0.01 + 1.5 * v(small_rng);
    DiscSectorAreas areas(mu, shared);
    double got[6];
    areas(q, got);
    const Disc disc{mu, q};
    for (std::size_t k = 0; k < shared.size(); ++k)
      worst_shared =
          std::max(worst_shared, std::abs(got[k] - sector_intersection_area(&disc, 1, shared[k])));
  }
  test::near("shared circles and rays: each area = angular sweep (5000 cases)", worst_shared, 0.0,
             1e-13);

  // Random discs and sectors against a grid count (its error ~ perimeter x cell).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    Disc d[3];
    for (Disc& x : d) x = {{0.8 * u(rng), 0.8 * u(rng)}, 0.4 + 0.5 * std::abs(u(rng))};
    const AnnularSector s{3.0 * u(rng), 0.2 + 3.0 * std::abs(u(rng)), 0.2 * std::abs(u(rng)), 1.0};
    test::near("random sector vs grid " + std::to_string(trial), sector_intersection_area(d, 3, s),
               grid_area(d, 3, s, 1200), 2e-4);
  }

  // Quadrants (and a rotated set) partition the scatterer's coupling and G: a tilted, offset, obstructed,
  // defocused system with an NA and a detector offset.
  LidarSystem sys;
  sys.beam.tilt = {20e-6, -50e-6};
  sys.beam.offset = {0.01, 0.0};
  sys.telescope.obstruction_radius = 0.02;
  sys.telescope.obstruction_distance = 0.3;
  sys.detector.defocus = 2e-3;
  sys.detector.numerical_aperture = 0.22;
  sys.detector.offset = {5e-5, 0.0};
  for (double z : {30.0, 150.0}) {
    const Vec2 p{0.012, -0.004};
    double sum = 0.0, rotated = 0.0;
    for (int k = 0; k < 4; ++k) {
      sum += emitter_coupling_rt(sys, z, p, quadrant(k));
      rotated += emitter_coupling_rt(sys, z, p, quadrant(k, 0.3));
    }
    const double full = emitter_coupling_rt(sys, z, p);
    test::near("quadrant couplings add up at z = " + std::to_string(z), sum, full, 1e-13);
    test::near("rotated quadrant couplings add up", rotated, full, 1e-13);
  }
  const std::vector<double> ranges{40.0, 120.0, 400.0};
  RtOptions opt;
  opt.tolerance = 1e-4;
  const RtOverlap full = overlap_rt(sys, ranges, opt);
  std::vector<double> sum(ranges.size(), 0.0);
  for (int k = 0; k < 4; ++k) {
    const RtOverlap q = overlap_rt(sys, ranges, quadrant(k), opt);
    for (std::size_t i = 0; i < ranges.size(); ++i) sum[i] += q.overlap[i];
  }
  for (std::size_t i = 0; i < ranges.size(); ++i)
    test::near("quadrants add up to G at " + std::to_string(ranges[i]), sum[i], full.overlap[i],
               4e-4);

  // The 1-D form (moving_disc_integral.hpp) against the beam integral in the scatterer plane (directions x
  // radii, independent of the Marcum kernel), for a term aperture ∩ moving disc through sectors: an off-centre
  // beam image larger and smaller than the disc, a shifted disc, an annular sector and a union of two.
  struct Case {
    double scale;
    Vec2 shift;
    double radius, w;
    Vec2 center;
    std::vector<AnnularSector> sectors;
  };
  const std::vector<Case> cases{
      {1.0, {}, 0.02, 0.004, {0.003, -0.01}, {{0.3, 0.5 * kPi, 0.0, 0.075}}},
      {1.0, {}, 0.3, 0.2, {0.05, 0.02}, {{-0.4, 0.5 * kPi, 0.0, 0.075}}},
      {-0.8, {0.004, 0.0}, 0.01, 0.01, {0.0, -0.04}, {{1.0, 2.0, 0.02, 0.06}}},
      {2.0,
       {0.0, -0.01},
       0.05,
       0.003,
       {0.01, 0.01},
       {{0.0, 1.0, 0.0, 0.075}, {3.0, 4.5, 0.03, 0.075}}}};
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const Case& k = cases[c];
    CouplingTerm term;
    term.weight = 1.0 / (kPi * 0.075 * 0.075);
    term.add(MovingDisc{0.0, {}, 0.075});
    term.add(MovingDisc{k.scale, k.shift, k.radius});
    const auto one_d =
        beam_integral::moving_disc_integral(term, {k.sectors}, k.center, k.w, 1e-10, 4000);
    auto masked = [&](Vec2 p) {
      const Disc at[2] = {term.discs[0].at(p), term.discs[1].at(p)};
      double area = 0.0;
      for (const AnnularSector& s : k.sectors) area += sector_intersection_area(at, 2, s);
      return term.weight * area;
    };
    const beam_integral::Kinks kinks(term);
    const auto planar =
        beam_integral::planar_mean(masked, kinks, k.center, k.w, false, 1e-8, 20000);
    test::that("one moving disc takes the 1-D form, case " + std::to_string(c), one_d.has_value());
    if (one_d)
      test::near("1-D form = scatterer-plane integral, case " + std::to_string(c),
                 (*one_d)[0].value, planar.value, 1e-8);
  }
  CouplingTerm two_moving;
  two_moving.add(MovingDisc{1.0, {}, 0.01});
  two_moving.add(MovingDisc{0.5, {}, 0.01});
  test::that("two moving discs fall back to the scatterer plane",
             !beam_integral::moving_disc_integral(
                 two_moving, {{AnnularSector{0.0, 1.0, 0.0, 0.075}}}, {}, 0.01, 1e-6, 100));

  // Several masks in one call: the quadrants of a tilted Table 1 lidar share the 1-D integral's nodes and agree
  // with one call per quadrant to the tolerance; with an NA each mask is traced alone, bit for bit.
  LidarSystem table1;
  table1.beam.tilt = {0.0, 50e-6};
  const std::vector<double> tele_ranges{10.0, 35.0, 120.0, 600.0, 3000.0};
  const std::vector<ApertureMask> quadrants{quadrant(0), quadrant(1), quadrant(2), quadrant(3)};
  const std::vector<RtOverlap> together = overlap_rt(table1, tele_ranges, quadrants, opt);
  const RtOverlap table1_full = overlap_rt(table1, tele_ranges, opt);
  for (std::size_t i = 0; i < tele_ranges.size(); ++i) {
    double parts = 0.0;
    for (int k = 0; k < 4; ++k) {
      const RtOverlap alone = overlap_rt(table1, tele_ranges, quadrants[k], opt);
      test::near("quadrant " + std::to_string(k) + " together = alone at " +
                     std::to_string(tele_ranges[i]),
                 together[k].overlap[i], alone.overlap[i], 2e-4);
      parts += together[k].overlap[i];
    }
    test::near("quadrants together add up to G at " + std::to_string(tele_ranges[i]), parts,
               table1_full.overlap[i], 4e-4);
  }
  LidarSystem narrow_na =
      sys;  // an NA cone narrower than the telescope's: a second moving boundary
  narrow_na.detector.numerical_aperture = 0.05;
  const std::vector<RtOverlap> with_na =
      overlap_rt(narrow_na, ranges, {quadrant(0), quadrant(2)}, opt);
  const RtOverlap alone_na = overlap_rt(narrow_na, ranges, quadrant(2), opt);
  test::that("narrow NA: each mask traced alone, bit for bit",
             with_na[1].overlap == alone_na.overlap &&
                 with_na[1].error_estimate == alone_na.error_estimate);
  // An NA cone wider than the telescope's bounds nothing: left out, it gives the G of the system without an NA.
  LidarSystem wide_na = table1;
  wide_na.detector.numerical_aperture = 0.22;
  const std::vector<RtOverlap> wide = overlap_rt(wide_na, tele_ranges, quadrants, opt);
  for (int k = 0; k < 4; ++k)
    for (std::size_t i = 0; i < tele_ranges.size(); ++i)
      test::near("wide NA = no NA, quadrant " + std::to_string(k) + " at " +
                     std::to_string(tele_ranges[i]),
                 wide[k].overlap[i], together[k].overlap[i], 1e-12);
  test::throws(
      "no masks", [&] { overlap_rt(sys, ranges, std::vector<ApertureMask>{}, opt); }, "masks");
  test::throws(
      "a bad mask among several",
      [&] { overlap_rt(sys, ranges, {quadrant(0), ApertureMask{}}, opt); }, "masks[1].sectors");
  test::throws(
      "too many masks",
      [&] { overlap_rt(sys, ranges, std::vector<ApertureMask>(kMaxMasks + 1, quadrant(0)), opt); },
      "masks");

  // Rings keep the radial integral and add up too.
  const ApertureMask inner{{Sector{0.0, 2.0 * kPi, 0.0, 0.04}}},
      outer{{Sector{0.0, 2.0 * kPi, 0.04}}};
  const RtOverlap a = overlap_rt(sys, ranges, inner, opt), b = overlap_rt(sys, ranges, outer, opt);
  for (std::size_t i = 0; i < ranges.size(); ++i)
    test::near("rings add up", a.overlap[i] + b.overlap[i], full.overlap[i], 2e-4);

  // Fourier optics through the quadrants of Table 1 at 1 km: each near a quarter of the full G, their sum short
  // of it by the diffraction at the sectors' edges (~1e-3), and the sector geometry's point tests.
  {
    const LidarSystem table1;
    const double full_fo =
        overlap_fo(table1, {1000.0}, ApertureMask{{Sector{0.0, 2.0 * kPi}}}).overlap[0];
    double sum_fo = 0.0;
    for (int k = 0; k < 4; ++k) sum_fo += overlap_fo(table1, {1000.0}, quadrant(k, 0.2)).overlap[0];
    test::that("FO quadrants fall short of the full aperture by the edge diffraction",
               full_fo - sum_fo > 2e-4 && full_fo - sum_fo < 3e-3);
    const AnnularSector q{0.0, 0.5 * kPi, 0.01, 0.05};
    test::that("contains", sector_contains(q, {0.02, 0.02}) && !sector_contains(q, {-0.02, 0.02}) &&
                               !sector_contains(q, {0.005, 0.0}));
    test::near("distance to an edge", sector_boundary_distance(q, {0.03, 0.001}), 0.001, 1e-15);
  }

  // Checks.
  const Telescope& t = sys.telescope;
  test::throws("empty mask", [&] { ApertureMask{}.validate(t); }, "mask.sectors");
  test::throws(
      "NaN angle", [&] { ApertureMask{{Sector{std::nan(""), 1.0}}}.validate(t); },
      "mask.sectors[0].start_angle");
  test::throws(
      "reversed", [&] { ApertureMask{{Sector{1.0, 0.5}}}.validate(t); },
      "mask.sectors[0].stop_angle");
  test::throws(
      "more than a turn", [&] { ApertureMask{{Sector{0.0, 7.0}}}.validate(t); }, "stop_angle");
  test::throws(
      "beyond the aperture", [&] { ApertureMask{{Sector{0.0, 1.0, 0.0, 0.2}}}.validate(t); },
      "outer_radius");
  test::throws(
      "inside the obstruction", [&] { ApertureMask{{Sector{0.0, 1.0, 0.0, 0.01}}}.validate(t); },
      "obstruction");
  test::throws(
      "inner beyond outer", [&] { ApertureMask{{Sector{0.0, 1.0, 0.05, 0.04}}}.validate(t); },
      "inner_radius");
  test::throws(
      "overlap", [&] { ApertureMask{{Sector{0.0, 2.0}, Sector{1.0, 3.0}}}.validate(t); },
      "mask.sectors[1]");
  test::throws(
      "overlap across 2 pi",
      [&] { ApertureMask{{Sector{-0.5, 0.5}, Sector{6.0, 6.2}}}.validate(t); }, "mask.sectors[1]");
  ApertureMask{
      {Sector{0.0, 1.0}, Sector{1.0, 2.0}, Sector{2.0, 3.0, 0.0, 0.05}, Sector{2.0, 3.0, 0.05}}}
      .validate(t);  // touching sectors are fine
  test::throws("bad range", [&] { overlap_rt(sys, {-1.0}, quadrant(0), opt); }, "ranges[0]");
  return test::report("test_aperture_mask");
}
