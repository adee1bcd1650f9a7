#include "lidar_overlap/fourier/overlap_fo.hpp"

#include <algorithm>
#include <functional>
#include <optional>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lidar_overlap/core/limits.hpp"
#include "lidar_overlap/fourier/grid_choice.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "fourier/fft.hpp"
#include "fourier/fft_passes.hpp"
#include "fourier/fo_receiver.hpp"
#include "fourier/overlap_fo_detail.hpp"
#include "fourier/transfer_table.hpp"

namespace lidar_overlap {

namespace detail {

namespace {

// The Parseval sum of overlap_from_irradiance over the irradiance sample(iy, ix) (nb x nb samples of
// spacing dx, centred on index nb/2), of which rows [first, last) hold the power.
template <class Sample>
double parseval_sum(const LidarSystem& system, const FoReceiver& rx, double z, std::size_t np,
                    std::size_t nb, double dx, std::size_t first, std::size_t last,
                    Sample&& sample) {
  const double d = rx.detector_distance(), to_image = d / z;
  const Vec2 c = system.beam.center(z), o = system.detector.offset;
  // The irradiance zero-padded to np x np, transformed: only the rows that hold its power are transformed
  // along x (a far beam fills a few dozen of the nb); the spectrum of a real irradiance is Hermitian
  // (S(-f) = conj S(f)), so only the columns kx = 0 ... np/2 are transformed along y. At most a third of
  // the full 2-D transform.
  const std::size_t off = np / 2 - nb / 2, half = np / 2 + 1;
  const std::size_t used = last - first;
  ComplexBuffer rows(used * np, Complex{});
  for (std::size_t iy = first; iy < last; ++iy)
    for (std::size_t ix = 0; ix < nb; ++ix) rows[(iy - first) * np + ix + off] = sample(iy, ix);
  const int threads = fft_threads(np * np);
  detail::row_pass(rows.data(), used, np, FftDirection::forward, threads);
  ComplexBuffer spectrum(half * np, Complex{});  // column kx at spectrum[kx * np + ky]
  for (std::size_t k0 = 0; k0 < half;
       k0 += kFftBlock) {  // gathered in blocks of columns (cache lines)
    const std::size_t count = std::min(kFftBlock, half - k0);
    for (std::size_t iy = 0; iy < used; ++iy)
      for (std::size_t k = 0; k < count; ++k)
        spectrum[(k0 + k) * np + iy + first + off] = rows[iy * np + k0 + k];
  }
  detail::row_pass(spectrum.data(), half, np, FftDirection::forward, threads);
  const double e0 = spectrum[0].real();
  const double df = 1.0 / (np * dx);
  auto signed_index = [np](std::size_t k) {
    return k < np / 2 ? static_cast<double>(k) : static_cast<double>(k) - np;
  };

  // Frequencies where the beam spectrum exceeds 1e-13 of its peak bound the table of OTF x disc^
  // (a 1e-10 cut already moves G by 1e-6 at 1000 m); |f| is the same at -f.
  // Each column is searched from its highest |fy| down, and only while it can still raise the maximum.
  double f2_max = 0.0;
  for (std::size_t kx = 0; kx < half; ++kx) {
    detail::
        cancellation_point();  // np^2 / 2 samples at most: seconds for the largest grids on a busy core
    const double fx = signed_index(kx);
    const Complex* column = spectrum.data() + kx * np;
    for (std::size_t a = np / 2 + 1; a-- > 0;) {  // |fy| = a, rows a and np - a
      const double f2 = fx * fx + double(a) * double(a);
      if (f2 <= f2_max) break;
      if (std::norm(column[a]) > 1e-26 * e0 * e0 ||
          (a > 0 && a < np / 2 && std::norm(column[np - a]) > 1e-26 * e0 * e0)) {
        f2_max = f2;
        break;
      }
    }
  }
  const double q_max = std::min(df * std::sqrt(f2_max) / to_image, rx.cutoff());
  const TransferTable transfer(system, rx, q_max);

  // G = (z/d)^2 sum_f T(|f| z/d) Re[exp(2 pi i f.(c + o z/d)) (-1)^(kx+ky) conj(FFT E)] df^2 / (A E(0)),
  // the phase separable per axis. T depends on |f| only, so it is evaluated once for the four frequencies
  // (+-fx, +-fy): column kx in (0, np/2) also stands for its mirror np - kx, whose spectrum is conj(S) at
  // the opposite fy (Hermitian), and rows ky and np - ky share |fy|.
  const ShiftPhases phase(np, df, c + (1.0 / to_image) * o);
  // Per column: the rows' q (|f| z / d) and their transfer values first (a gather from the table), then the
  // terms in a loop the compiler vectorises.
  const std::size_t rows_half = np / 2 + 1;
  std::vector<double> fy2(rows_half), t(rows_half);
  for (std::size_t ky = 0; ky < rows_half; ++ky)
    fy2[ky] = (df * static_cast<double>(ky)) * (df * static_cast<double>(ky));
  const double inverse_to_image = 1.0 / to_image;
  double sum = 0.0;
  for (std::size_t kx = 0; kx < half; ++kx) {
    detail::cancellation_point();
    const double fx = df * signed_index(kx), fx2 = fx * fx;
    if (std::abs(fx) * inverse_to_image >= q_max)
      continue;               // every q in this column is beyond the table
    std::size_t rows_in = 0;  // rows ky < rows_in have q < q_max (q grows with ky)
    for (; rows_in < rows_half; ++rows_in) {
      const double q = std::sqrt(fx2 + fy2[rows_in]) * inverse_to_image;
      if (q >= q_max) break;
      t[rows_in] = transfer(q);
    }
    if (rows_in == 0) continue;
    // The mirror column's term at row np - ky is the conjugate product (its phases are the conjugates of
    // this column's at row ky, its spectrum conj(S)): the same real part, so each term counts twice.
    const double mirrored = (kx != 0 && kx != np / 2) ? 2.0 : 1.0;
    const Complex px = phase.x[kx];
    const Complex* column = spectrum.data() + kx * np;
    auto term = [&](std::size_t ky) {  // Re[px py conj(S)]
      const Complex p = detail::product(px, phase.y[ky]), s = column[ky];
      return p.real() * s.real() + p.imag() * s.imag();
    };
    // Rows ky and np - ky share |fy|: rows 0 and np/2 stand alone.
    double in_column = t[0] * term(0);
    const std::size_t paired_end = std::min(rows_in, np / 2);
    for (std::size_t ky = 1; ky < paired_end; ++ky) in_column += t[ky] * (term(ky) + term(np - ky));
    if (rows_in == rows_half) in_column += t[np / 2] * term(np / 2);
    sum += mirrored * in_column;
  }
  return sum * df * df / (to_image * to_image) / (rx.aperture_area() * e0);
}

}  // namespace

double overlap_from_irradiance(const LidarSystem& system, const FoReceiver& rx, const Field& at_z,
                               double z, std::size_t np) {
  if (np == 0 || !rx.passes_light()) return 0.0;
  const std::size_t nb = at_z.n;
  // Rows below 1e-20 of the total power (together at most nb 1e-20 of G) are left out of the transform.
  std::vector<double> row_power(nb, 0.0);
  double total = 0.0;
  for (std::size_t iy = 0; iy < nb; ++iy) {
    for (std::size_t ix = 0; ix < nb; ++ix) row_power[iy] += std::norm(at_z.values[iy * nb + ix]);
    total += row_power[iy];
  }
  std::size_t first = 0, last = nb;
  while (first < last && row_power[first] <= 1e-20 * total) ++first;
  while (last > first && row_power[last - 1] <= 1e-20 * total) --last;
  return parseval_sum(
      system, rx, z, np, nb, at_z.spacing, first, last,
      [&](std::size_t iy, std::size_t ix) { return std::norm(at_z.values[iy * nb + ix]); });
}

}  // namespace detail

namespace {

// How the beam reaches the ranges: its samples per side, its grid spacing at each range, a bound on its
// radius there (all but 1e-7 of the power inside), and the field itself (made inside the parallel loop).
struct BeamAtRanges {
  std::size_t n = 0;
  std::vector<double> spacing, radius_bound;
  std::function<Propagated(std::size_t)> at;
  // Or, for a beam known in closed form: G at range i for its receiver and spectrum size, and its report.
  std::function<double(std::size_t, const FoReceiver&, std::size_t)> overlap;
  std::vector<PropagationReport> reports;
};

FoOverlap overlap_over_ranges(const LidarSystem& system, const std::vector<double>& ranges,
                              const BeamAtRanges& beam_at, const FoOptions& options) {
  const int threads = detail::thread_count(options.threads);
  if (options.max_spectrum_grid < 16 || options.max_spectrum_grid > kMaxGridSide)
    checks::fail("max_spectrum_grid", static_cast<double>(options.max_spectrum_grid),
                 "a size from 16 to " + std::to_string(kMaxGridSide));
  const std::size_t n_ranges = ranges.size();
  // Everything that can fail is settled before the parallel loop: receivers and grid sizes.
  std::vector<FoReceiver> receivers;
  FoOverlap out;
  for (std::size_t i = 0; i < n_ranges; ++i) {
    const double z = ranges[i];
    receivers.emplace_back(system, z, detail::range_name(i));
    const FoReceiver& rx = receivers.back();
    const std::size_t np =
        detail::spectrum_grid(system, rx, z, beam_at.spacing[i], beam_at.radius_bound[i], beam_at.n,
                              options.max_spectrum_grid, i, 5e-7, true);
    out.spectrum_grid.push_back(np);
    // Each thread holds the beam field and its padded spectrum.
    checks::memory(
        "max_spectrum_grid", static_cast<double>(options.max_spectrum_grid),
        16.0 * threads * (double(np) * double(np) + double(beam_at.n) * double(beam_at.n)),
        detail::range_name(i) + " needs a " + std::to_string(np) +
            "^2 spectrum per thread: lower max_spectrum_grid (that range then raises), use fewer threads, "
            "or method 'rt' there");
  }

  out.overlap.assign(n_ranges, 0.0);
  out.beam_reports.assign(n_ranges, {});
  // Ranges in parallel; the work inside each runs on one thread (nested regions stay inactive).
  detail::parallel_for(n_ranges, threads, [&](std::size_t i) {
    if (out.spectrum_grid[i] == 0) return;  // no light reaches the detector plane: G = 0
    if (beam_at.overlap) {
      out.overlap[i] = beam_at.overlap(i, receivers[i], out.spectrum_grid[i]);
      out.beam_reports[i] = beam_at.reports[i];
      return;
    }
    Propagated at_z = beam_at.at(i);  // C1-C2, in the beam's own frame
    out.overlap[i] = detail::overlap_from_irradiance(system, receivers[i], at_z.field, ranges[i],
                                                     out.spectrum_grid[i]);
    out.beam_reports[i] = at_z.report;
  });
  checks::overlap_values(
      out.overlap, ranges, detail::kFoOverlapSlack, "overlap_fo", [&](std::size_t i) {
        const PropagationReport& r = out.beam_reports[i];
        const double loss = std::max({r.output_edge_power, r.input_edge_power, r.band_limit_loss});
        return loss > 1e-6
                   ? "the transmitted field loses " + checks::number(loss) +
                         " of its power to the window edge or the band limit: enlarge beam_window or beam_grid"
                   : std::string();
      });
  return out;
}

// Power of a Gaussian irradiance of radius w (m) outside the centred square of half-width a (m).
double outside_square(double a, double w) {
  const double e = std::erfc(std::sqrt(2.0) * a / w);
  return e * (2.0 - e);
}

// Power the sampled TEM00 path may lose to its window (cut at the waist, wrapped at a range) for the field
// it propagates to equal the Gaussian of radius w(z) sampled in closed form: the cut field's difference
// carries at most this power, so the irradiance moves by at most 2 sqrt(1e-20) = 2e-10 of its peak
// (measured: G within 1e-13 of the propagated field's at the default window).
constexpr double kNegligibleCut = 1e-20;

// The 2-D path of a TEM00 beam with the propagation (C1-C2) in closed form: the field at z is the Gaussian of
// radius w(z) on the grid that PropagationPlan would give it (the waist's spacing up to the critical distance
// nb dx0^2 / lambda, the Fresnel spacing lambda z / (nb dx0) beyond), its irradiance all the sum needs (its
// phase is left out), the reports' edge powers in closed form. The sampled field `waist` sets the radius
// bound as in the general path. Empty where the window cuts or wraps more than kNegligibleCut of the power:
// there the field is propagated, and its loss is reported.
std::optional<FoOverlap> tem00_in_closed_form(const LidarSystem& system,
                                              const std::vector<double>& ranges, const Field& waist,
                                              const FoOptions& options) {
  const GaussianBeam& beam = system.beam;
  const std::size_t nb = waist.n;
  const double dx0 = waist.spacing, critical = nb * dx0 * dx0 / beam.wavelength;
  const double border = static_cast<double>(std::max<std::size_t>(1, nb / 16)),
               half = 0.5 * static_cast<double>(nb);
  if (outside_square(half * dx0, beam.waist_radius) > kNegligibleCut) return std::nullopt;
  const GridChoice extent = choose_grid(waist, 0.0, PropagationMethod::automatic);
  BeamAtRanges b;
  b.n = nb;
  for (double z : ranges) {
    const bool as = z <= critical;
    const double spacing = as ? dx0 : beam.wavelength * z / (nb * dx0), w = beam.radius(z);
    if (outside_square(half * spacing, w) > kNegligibleCut) return std::nullopt;
    b.spacing.push_back(spacing);
    b.radius_bound.push_back(extent.input_radius + z * extent.angular_radius);
    PropagationReport r;
    r.method = as ? PropagationMethod::angular_spectrum : PropagationMethod::fresnel;
    r.critical_distance = critical;
    r.input_edge_power = outside_square((half - border) * dx0, beam.waist_radius);
    r.output_edge_power = outside_square((half - border) * spacing, w);
    b.reports.push_back(r);
  }
  b.overlap = [&](std::size_t i, const FoReceiver& rx, std::size_t np) {
    if (!rx.passes_light()) return 0.0;
    // exp(-2 x^2 / w^2) per axis; samples below 1e-40 of the peak are zero (rows of them are not transformed).
    const double w = beam.radius(ranges[i]), dx = b.spacing[i];
    std::vector<double> g(nb);
    double sum_g = 0.0;
    for (std::size_t k = 0; k < nb; ++k) {
      const double x = (static_cast<double>(k) - 0.5 * static_cast<double>(nb)) * dx,
                   v = std::exp(-2.0 * x * x / (w * w));
      g[k] = v < 1e-40 ? 0.0 : v;
      sum_g += g[k];
    }
    std::size_t first = 0,
                last = nb;  // rows below 1e-20 of the power are left out, as for a sampled field
    while (first < last && g[first] <= 1e-20 * sum_g) ++first;
    while (last > first && g[last - 1] <= 1e-20 * sum_g) --last;
    return detail::parseval_sum(system, rx, ranges[i], np, nb, dx, first, last,
                                [&](std::size_t iy, std::size_t ix) { return g[iy] * g[ix]; });
  };
  return overlap_over_ranges(system, ranges, b, options);
}

}  // namespace

FoOverlap overlap_fo(const LidarSystem& system, const std::vector<double>& ranges,
                     const FoOptions& options) {
  system.validate();
  const GaussianBeam& beam = system.beam;
  beam.validate_for_fourier_optics();
  if (options.beam_grid < 16 || options.beam_grid % 2)
    checks::fail("beam_grid", static_cast<double>(options.beam_grid), "an even grid size >= 16");
  checks::grid("beam_grid", options.beam_grid, sizeof(Complex),
               2 * detail::thread_count(options.threads));
  // A window that holds the waist (+-1 w0), sampled at least once per waist radius.
  if (!(options.beam_window >= 2.0 &&
        options.beam_window <= static_cast<double>(options.beam_grid)))
    checks::fail("beam_window", options.beam_window,
                 "a window from 2 to beam_grid = " + std::to_string(options.beam_grid) +
                     " waist radii, so that the waist is sampled at least once per radius");
  detail::checked_threads_and_ranges(system, ranges, options.threads);
  const std::size_t nb = options.beam_grid;
  const double theta_d = beam.wavelength / (kPi * beam.waist_radius);
  if (!beam.divergence || std::abs(*beam.divergence / theta_d - 1.0) <= 1e-9) {
    const double dx0 = options.beam_window * beam.waist_radius / nb;
    const Field waist = Field::gaussian(beam.wavelength, beam.waist_radius, nb, dx0);
    if (std::optional<FoOverlap> closed = tem00_in_closed_form(system, ranges, waist, options))
      return *closed;
    return overlap_fo(system, ranges, waist, options);
  }
  // M^2 > 1: a Gaussian Schell-model beam. Its coherent modes add incoherently to a Gaussian irradiance of
  // radius w(z)^2 = w0^2 + (theta z)^2 at every range, and the overlap needs only the irradiance.
  // Sampled like the TEM00 path's field: the waist's spacing while the beam is near its waist, then the
  // Fresnel spacing lambda z / (window w0) widened by M^2 (the far-field width over the TEM00's).
  const double m2 = *beam.divergence / theta_d, window = options.beam_window * beam.waist_radius;
  BeamAtRanges b;
  b.n = nb;
  for (double z : ranges) {
    b.spacing.push_back(std::max(window / nb, m2 * beam.wavelength * z / window));
    b.radius_bound.push_back(std::sqrt(std::log(1e7) / 2.0) * beam.radius(z));
  }
  b.at = [&](std::size_t i) {
    return Propagated{Field::gaussian(beam.wavelength, beam.radius(ranges[i]), nb, b.spacing[i]),
                      {}};
  };
  return overlap_over_ranges(system, ranges, b, options);
}

FoOverlap overlap_fo(const LidarSystem& system, const std::vector<double>& ranges,
                     const Field& given, const FoOptions& options) {
  system.validate();
  given.validate();
  // G does not depend on the field's power: carry it at unit power, so that no weak or strong field
  // underflows or overflows in the irradiance spectra.
  const double power = given.power();
  if (!(power > 0.0) || !std::isfinite(power))
    checks::fail("transmitted.power", power, "a field with finite power > 0");
  Field transmitted = given;
  const double to_unit = 1.0 / std::sqrt(power);
  for (Complex& v : transmitted.values) v *= to_unit;
  if (transmitted.wavelength != system.beam.wavelength)
    checks::fail("transmitted.wavelength", transmitted.wavelength,
                 "the system's beam wavelength " + std::to_string(system.beam.wavelength) + " m");
  detail::checked_threads_and_ranges(system, ranges, options.threads);
  // Radii holding all but 1e-7 of the power, in space and angle: r0 + z theta bounds the beam at z.
  const GridChoice extent = choose_grid(transmitted, 0.0, PropagationMethod::automatic);
  BeamAtRanges b;
  b.n = transmitted.n;
  std::vector<std::shared_ptr<const PropagationPlan>> plans;
  for (double z : ranges) {
    plans.push_back(PropagationPlan::cached(b.n, transmitted.spacing, transmitted.wavelength, z,
                                            PropagationMethod::automatic, 0.0));
    b.spacing.push_back(plans.back()->output_spacing());
    b.radius_bound.push_back(extent.input_radius + z * extent.angular_radius);
  }
  b.at = [&](std::size_t i) { return plans[i]->execute(transmitted); };
  return overlap_over_ranges(system, ranges, b, options);
}

double emitter_coupling_fo(const LidarSystem& system, double z, Vec2 position) {
  checks::coordinate("position", position);
  const FoReceiver rx(system, z);
  std::vector<double> g{
      rx.point_coupling(norm(system.detector.offset + (rx.detector_distance() / z) * position))};
  checks::overlap_values(g, {z}, 1e-6,
                         "emitter_coupling_fo");  // the integral's accuracy, ~1e-10 of the area
  return g[0];
}

}  // namespace lidar_overlap
