// Concurrent calls from several threads (as an instrument's acquisition and display threads would make):
// RT and FO overlap curves (plain, aberrated, RT through an aperture mask), propagations and a flat-top design run at once on shared
// plan caches, and
// each result is bit-for-bit the one computed alone.
#include <thread>
#include <vector>

#include "check.hpp"
#include "lidar_overlap/lidar_overlap.hpp"

using namespace lidar_overlap;

namespace {
struct Results {
  std::vector<double> rt, fo, propagated, rt_aberrated, fo_aberrated, rt_masked;
  std::vector<double> plate;
};

Results compute(int variant) {
  LidarSystem s;
  s.detector.defocus =
      1e-3 * variant;  // each thread its own scene, so caches see different keys too
  std::vector<double> ranges;
  for (int i = 0; i < 24; ++i) ranges.push_back(20.0 + 40.0 * i);
  Results r;
  r.rt = overlap_rt(s, ranges, {1e-6, 1, 4000}).overlap;
  FoOptions fo;
  fo.threads = 1;
  r.fo = overlap_fo(s, ranges, fo).overlap;
  const Propagated p = propagate(Field::gaussian(355e-9, 1e-3, 128, 1e-3 / 12), 50.0 + variant);
  for (const Complex& v : p.field.values) r.propagated.push_back(std::norm(v));
  FlatTopOptions ft;
  ft.grid = 128;
  r.plate = design_flat_top(355e-9, 1e-3, 0.36e-3 * (1.0 + 0.5 * variant), ft).phase;
  Aberrations ab;
  ab.zernike = {0.0, 0.0, 0.0, 0.0, 0.0, 0.2e-6 * (1 + variant), 0.0, 0.0, 0.0, 0.0, 0.3e-6};
  RtAberratedOptions rta;
  rta.threads = 1;
  r.rt_aberrated = overlap_rt_aberrated(s, ab, ranges, rta).overlap;
  FoAberratedOptions foa;
  foa.threads = 1;
  r.fo_aberrated = overlap_fo_aberrated(s, ab, {1000.0}, foa).overlap;
  r.rt_masked =
      overlap_rt(s, {100.0, 300.0}, ApertureMask{{Sector{0.3, 1.8}}}, {1e-4, 1, 4000}).overlap;
  return r;
}
}  // namespace

int main() {
  constexpr int kThreads = 4;
  std::vector<Results> alone(kThreads), together(kThreads);
  for (int v = 0; v < kThreads; ++v) alone[v] = compute(v);
  for (int round = 0; round < 2; ++round) {
    std::vector<std::thread> pool;
    for (int v = 0; v < kThreads; ++v) pool.emplace_back([&, v] { together[v] = compute(v); });
    for (auto& t : pool) t.join();
    for (int v = 0; v < kThreads; ++v) {
      const std::string tag =
          " (thread " + std::to_string(v) + ", round " + std::to_string(round) + ")";
      test::near("RT identical" + tag, together[v].rt == alone[v].rt ? 0.0 : 1.0, 0.0, 0.0);
      test::near("FO identical" + tag, together[v].fo == alone[v].fo ? 0.0 : 1.0, 0.0, 0.0);
      test::near("propagation identical" + tag,
                 together[v].propagated == alone[v].propagated ? 0.0 : 1.0, 0.0, 0.0);
      test::near("flat-top plate identical" + tag, together[v].plate == alone[v].plate ? 0.0 : 1.0,
                 0.0, 0.0);
      test::near("aberrated RT identical" + tag,
                 together[v].rt_aberrated == alone[v].rt_aberrated ? 0.0 : 1.0, 0.0, 0.0);
      test::near("aberrated FO identical" + tag,
                 together[v].fo_aberrated == alone[v].fo_aberrated ? 0.0 : 1.0, 0.0, 0.0);
      test::near("masked RT identical" + tag,
                 together[v].rt_masked == alone[v].rt_masked ? 0.0 : 1.0, 0.0, 0.0);
    }
  }
  return test::report("test_thread_safety");
}
