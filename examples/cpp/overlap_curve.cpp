// overlap_curve: the overlap function of a lidar described on the command line, as instrument
// software would compute it, and its full-overlap range (first range where G reaches 99 % of its
// maximum on the grid). SI units on the command line; defaults are the paper's Table 1 system.
//
//   overlap_curve [--wavelength 355e-9] [--waist 1e-3] [--divergence 0 (diffraction-limited)]
//                 [--diameter 0.15] [--focal-length 1.0] [--fov 0.9e-3] [--obstruction 0]
//                 [--obstruction-distance 0.7] [--defocus 0] [--beam-offset 0] [--tilt 0]
//                 [--from 5] [--to 1000] [--count 200] [--method rt|fo] [--table]
#include <lidar_overlap/lidar_overlap.hpp>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

using namespace lidar_overlap;

namespace {

std::map<std::string, std::string> parse(int argc, char** argv) {
  std::map<std::string, std::string> args{
      {"wavelength", "355e-9"}, {"waist", "1e-3"},       {"divergence", "0"},   {"diameter", "0.15"},
      {"focal-length", "1.0"},  {"fov", "0.9e-3"},       {"obstruction", "0"},  {"obstruction-distance", "0.7"},
      {"defocus", "0"},         {"beam-offset", "0"},    {"tilt", "0"},         {"from", "5"},
      {"to", "1000"},           {"count", "200"},        {"method", "rt"},      {"table", "no"}};
  for (int i = 1; i < argc; ++i) {
    const std::string key = std::string(argv[i]).substr(0, 2) == "--" ? std::string(argv[i]).substr(2) : "";
    if (!args.count(key)) throw std::invalid_argument(std::string("unknown option ") + argv[i]);
    if (key == "table") args[key] = "yes";
    else if (i + 1 < argc) args[key] = argv[++i];
    else throw std::invalid_argument("option --" + key + " needs a value");
  }
  return args;
}

double number(const std::map<std::string, std::string>& args, const std::string& key) {
  char* end = nullptr;
  const double v = std::strtod(args.at(key).c_str(), &end);
  if (end == args.at(key).c_str() || *end != '\0') throw std::invalid_argument("--" + key + " = '" + args.at(key) + "' is not a number");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const auto args = parse(argc, argv);
    LidarSystem system;
    system.beam.wavelength = number(args, "wavelength");
    system.beam.waist_radius = number(args, "waist");
    if (number(args, "divergence") > 0.0) system.beam.divergence = number(args, "divergence");
    system.beam.offset = {number(args, "beam-offset"), 0.0};
    system.beam.tilt = {number(args, "tilt"), 0.0};
    system.telescope.diameter = number(args, "diameter");
    system.telescope.focal_length = number(args, "focal-length");
    system.telescope.obstruction_radius = number(args, "obstruction");
    system.telescope.obstruction_distance = number(args, "obstruction-distance");
    system.detector = Detector::from_fov(number(args, "fov"), system.telescope.focal_length, number(args, "defocus"));

    const double from = number(args, "from"), to = number(args, "to");
    const int count = static_cast<int>(number(args, "count"));
    if (count < 2) throw std::invalid_argument("--count must be at least 2");
    std::vector<double> ranges(count);
    for (int i = 0; i < count; ++i) ranges[i] = from + (to - from) * i / (count - 1);

    std::vector<double> g;
    if (args.at("method") == "rt") g = overlap_rt(system, ranges).overlap;
    else if (args.at("method") == "fo") g = overlap_fo(system, ranges).overlap;
    else throw std::invalid_argument("--method = '" + args.at("method") + "': expected rt or fo");

    double peak = 0.0;
    for (double v : g) peak = std::max(peak, v);
    std::size_t full = 0;
    while (full < g.size() && g[full] < 0.99 * peak) ++full;
    if (args.at("table") == "yes")
      for (std::size_t i = 0; i < g.size(); ++i) std::cout << ranges[i] << " " << g[i] << "\n";
    std::cout << "lidar_overlap " << kVersion << " (" << args.at("method") << "): max G = " << peak
              << ", full overlap (G >= 0.99 max G) at " << ranges[full] << " m\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "overlap_curve: " << e.what() << "\n";
    return 2;
  }
}
