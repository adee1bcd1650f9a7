#include "lidar_overlap/pupil/aperture_mask.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "pupil/sampled_pupil_overlap.hpp"
#include "geometry/beam_integral.hpp"
#include "geometry/moving_disc_integral.hpp"
#include "geometry/receiver_coupling.hpp"
#include "geometry/rt_entry.hpp"
#include "geometry/sector_area.hpp"

namespace lidar_overlap {

namespace {

constexpr double kTwoPi = 2.0 * kPi;
// Angles beyond this (rad) are refused: their remainder modulo 2 pi would lose digits.
constexpr double kMaxMaskAngle = 1e3;
// Sectors may touch: quadrants built as rotation + k pi/2 meet to within rounding.
constexpr double kTouch = 1e-9;

std::string sector_name(std::size_t i) { return "mask.sectors[" + std::to_string(i) + "]"; }

AnnularSector annular(const Sector& s, double aperture_radius) {
  return {s.start_angle, std::min(s.stop_angle - s.start_angle, kTwoPi), s.inner_radius,
          s.outer_radius.value_or(aperture_radius)};
}

// Angular overlap (rad) of two sectors, modulo 2 pi.
double angular_overlap(const AnnularSector& a, const AnnularSector& b) {
  double start_a = std::fmod(a.start, kTwoPi), start_b = std::fmod(b.start, kTwoPi);
  if (start_a < 0.0) start_a += kTwoPi;
  if (start_b < 0.0) start_b += kTwoPi;
  double most = 0.0;
  for (double k : {-1.0, 0.0, 1.0}) {
    const double lo = std::max(start_a, start_b + k * kTwoPi);
    const double hi = std::min(start_a + a.span, start_b + b.span + k * kTwoPi);
    most = std::max(most, hi - lo);
  }
  return most;
}

// A coupling term restricted to the mask: its disc intersection measured inside each sector.
struct MaskedTerm {
  const CouplingTerm& term;
  const std::vector<AnnularSector>& sectors;
  double operator()(Vec2 p) const {
    for (std::size_t g = 0; g < term.n_gates; ++g)
      if (!term.gates[g].open(p)) return 0.0;
    Disc at[CouplingTerm::kMaxMoving];
    for (std::size_t i = 0; i < term.n_discs; ++i) at[i] = term.discs[i].at(p);
    double area = 0.0;
    for (const AnnularSector& s : sectors) area += sector_intersection_area(at, term.n_discs, s);
    return term.weight * area;
  }
};

// The term's kinks plus the mask's: a disc circle tangent to a sector's arcs, or passing through a corner
// (all circles in the scatterer plane). Tangencies with the straight edges are lines, left to the
// adaptive subdivision (the area is C1 there).
beam_integral::Kinks masked_kinks(const CouplingTerm& term,
                                  const std::vector<AnnularSector>& sectors) {
  beam_integral::Kinks k(term);
  auto add = [&](Vec2 center, double radius) {
    if (k.n < beam_integral::kMaxKinks) k.circles[k.n++] = {center, radius};
  };
  for (std::size_t i = 0; i < term.n_discs; ++i) {
    const MovingDisc& d = term.discs[i];
    if (d.scale == 0.0) continue;
    const double a = std::abs(d.scale);
    const Vec2 c =
        (-1.0 / d.scale) * d.shift;  // |scale P + shift - x| = rho: centre (x - shift)/scale
    for (const AnnularSector& s : sectors) {
      for (double arc : {s.outer, s.inner}) {
        if (arc == 0.0) continue;
        add(c, (d.radius + arc) / a);
        add(c, std::abs(d.radius - arc) / a);
      }
      if (s.span >= kTwoPi) continue;
      if (s.inner == 0.0) add(c, d.radius / a);
      for (double angle : {s.start, s.start + s.span})
        for (double radius : {s.inner, s.outer})
          if (radius > 0.0)
            add(c + (radius / d.scale) * Vec2{std::cos(angle), std::sin(angle)}, d.radius / a);
    }
  }
  return k;
}

// Rings (full-turn sectors) keep the rotation about the aperture centre: the term then has a centre of
// symmetry if it has one together with a disc fixed at that centre.
std::optional<Vec2> ring_symmetry_center(const CouplingTerm& term,
                                         const std::vector<AnnularSector>& sectors) {
  for (const AnnularSector& s : sectors)
    if (s.span < kTwoPi) return std::nullopt;
  if (term.n_discs >= CouplingTerm::kMaxMoving) return std::nullopt;
  CouplingTerm anchored = term;
  anchored.add(MovingDisc{0.0, {}, 1.0});
  return anchored.symmetry_center();
}

// G through each mask at the receiver's range: the 1-D integral of a term with one moving disc serves all the
// masks at once; any other term is integrated in the scatterer plane, mask by mask.
std::vector<detail::RtEntry> masked_overlaps_at(
    const LidarSystem& system, const Receiver& rx,
    const std::vector<std::vector<AnnularSector>>& masks, const RtOptions& opt) {
  return detail::sum_over_terms_many(
      system, rx, opt.tolerance, masks.size(),
      [&](const CouplingTerm& plain, Vec2 center, double w, double tol) {
        if (std::optional<std::vector<detail::RtEntry>> r =
                beam_integral::moving_disc_integral(plain, masks, center, w, tol, opt.max_segments))
          return *r;
        std::vector<detail::RtEntry> out;
        for (const std::vector<AnnularSector>& sectors : masks) {
          const MaskedTerm term{plain, sectors};
          const beam_integral::Kinks kinks = masked_kinks(plain, sectors);
          if (const std::optional<Vec2> s = ring_symmetry_center(plain, sectors))
            out.push_back(beam_integral::radial_integral(term, kinks, *s, norm(center - *s), w,
                                                         {1.0, 0.0}, tol, opt.max_segments));
          else
            out.push_back(
                beam_integral::planar_mean(term, kinks, center, w, false, tol, opt.max_segments));
        }
        return out;
      });
}

std::vector<AnnularSector> checked_sectors(const LidarSystem& system, const ApertureMask& mask) {
  system.validate();
  mask.validate(system.telescope);
  std::vector<AnnularSector> out;
  for (const Sector& s : mask.sectors) out.push_back(annular(s, 0.5 * system.telescope.diameter));
  return out;
}

}  // namespace

void ApertureMask::validate(const Telescope& telescope) const {
  if (sectors.empty())
    checks::fail("mask.sectors", 0, "at least one sector (an empty mask leaves nothing)");
  if (sectors.size() > kMaxMaskSectors)
    checks::fail("mask.sectors", static_cast<double>(sectors.size()),
                 "at most " + std::to_string(kMaxMaskSectors) + " sectors");
  const double aperture = 0.5 * telescope.diameter;
  std::vector<AnnularSector> checked;
  for (std::size_t i = 0; i < sectors.size(); ++i) {
    const Sector& s = sectors[i];
    const std::string name = sector_name(i);
    for (auto [what, angle] :
         {std::pair{".start_angle", s.start_angle}, std::pair{".stop_angle", s.stop_angle}})
      if (!(std::abs(angle) <= kMaxMaskAngle))
        checks::fail(name + what, angle, "a finite angle (rad) within +-1000");
    const double span = s.stop_angle - s.start_angle;
    if (!(span > 0.0) || span > kTwoPi * (1.0 + 1e-12))
      checks::fail(
          name + ".stop_angle", s.stop_angle,
          "an angle beyond start_angle = " + checks::number(s.start_angle) + " by at most 2 pi");
    const double outer = s.outer_radius.value_or(aperture);
    if (!(outer > 0.0) || outer > aperture)
      checks::fail(
          name + ".outer_radius", outer,
          "a radius in (0, D/2 = " + checks::number(aperture) + "] m (None: the aperture's edge)");
    if (!(outer > telescope.obstruction_radius))
      checks::fail(name + ".outer_radius", outer,
                   "a radius beyond the obstruction's radius " +
                       checks::number(telescope.obstruction_radius) +
                       " m (a sector inside the obstruction leaves nothing)");
    if (!(s.inner_radius >= 0.0) || !(s.inner_radius < outer))
      checks::fail(name + ".inner_radius", s.inner_radius,
                   "a radius in [0, outer_radius = " + checks::number(outer) + ") m");
    const AnnularSector a = annular(s, aperture);
    for (std::size_t j = 0; j < checked.size(); ++j) {
      const AnnularSector& b = checked[j];
      const double radial = std::min(a.outer, b.outer) - std::max(a.inner, b.inner);
      if (radial > kTouch * aperture && angular_overlap(a, b) > kTouch)
        checks::fail(
            name, static_cast<double>(i),
            "a sector that does not overlap " + sector_name(j) +
                " (a mask is a union of disjoint sectors; merge them or split the angles)");
    }
    checked.push_back(a);
  }
}

RtOverlap overlap_rt(const LidarSystem& system, const std::vector<double>& ranges,
                     const ApertureMask& mask, const RtOptions& options) {
  const std::vector<std::vector<AnnularSector>> masks{checked_sectors(system, mask)};
  return detail::rt_over_ranges(
      system, ranges, options,
      [&](const Receiver& rx) { return masked_overlaps_at(system, rx, masks, options)[0]; },
      "overlap_rt (masked)");
}

std::vector<RtOverlap> overlap_rt(const LidarSystem& system, const std::vector<double>& ranges,
                                  const std::vector<ApertureMask>& masks,
                                  const RtOptions& options) {
  if (masks.empty() || masks.size() > kMaxMasks)
    checks::fail("masks", static_cast<double>(masks.size()),
                 "from 1 to " + std::to_string(kMaxMasks) + " masks");
  std::vector<std::vector<AnnularSector>> sectors;
  for (std::size_t i = 0; i < masks.size(); ++i) {
    try {
      sectors.push_back(checked_sectors(system, masks[i]));
    } catch (const ParameterError& e) {
      if (e.parameter().rfind("mask.", 0) != 0) throw;  // the system's own error
      // "mask.sectors[0]..." becomes "masks[i].sectors[0]...", in the message that begins with it too
      const std::string parameter = "masks[" + std::to_string(i) + "]" + e.parameter().substr(4);
      throw ParameterError(parameter + std::string(e.what()).substr(e.parameter().size()),
                           parameter, e.value(), e.expected());
    }
  }
  detail::check_rt_options(options);
  const int threads = detail::checked_threads_and_ranges(system, ranges, options.threads);
  std::vector<Receiver> receivers;  // built before the parallel region: nothing throws inside it
  receivers.reserve(ranges.size());
  for (double z : ranges) receivers.emplace_back(system, z);
  std::vector<std::vector<detail::RtEntry>> at(ranges.size());
  detail::parallel_for(ranges.size(), threads, [&](std::size_t i) {
    at[i] = masked_overlaps_at(system, receivers[i], sectors, options);
  });
  std::vector<RtOverlap> out;
  for (std::size_t k = 0; k < masks.size(); ++k) {
    std::vector<detail::RtEntry> entries(ranges.size());
    for (std::size_t i = 0; i < ranges.size(); ++i) entries[i] = at[i][k];
    out.push_back(detail::collect_rt_entries(entries, ranges, options.tolerance,
                                             "overlap_rt (masks[" + std::to_string(k) + "])"));
    out.back().axisymmetric = system.is_axisymmetric();
  }
  return out;
}

FoAberratedOverlap overlap_fo(const LidarSystem& system, const std::vector<double>& ranges,
                              const ApertureMask& mask, const FoAberratedOptions& options) {
  return detail::overlap_fo_sampled(system, Aberrations{}, checked_sectors(system, mask), ranges,
                                    options, "overlap_fo (masked)");
}

double emitter_coupling_rt(const LidarSystem& system, double z, Vec2 position,
                           const ApertureMask& mask) {
  checks::coordinate("position", position);
  const std::vector<AnnularSector> sectors = checked_sectors(system, mask);
  const Receiver rx(system, z);
  CouplingTerm terms[2];
  const std::size_t n_terms = rx.terms(position, 0.0, terms);
  double c = 0.0;
  for (std::size_t t = 0; t < n_terms; ++t) c += MaskedTerm{terms[t], sectors}(position);
  std::vector<double> g{std::max(0.0, c)};
  checks::overlap_values(g, {z}, 1e-9,
                         "emitter_coupling_rt (masked)");  // exact geometry: round-off only
  return g[0];
}

}  // namespace lidar_overlap
