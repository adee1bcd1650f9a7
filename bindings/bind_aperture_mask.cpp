// Aperture masks (telecover): the mask value type and the masked RT entry points; the GIL is released around
// the compute only.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <optional>
#include <tuple>
#include <vector>

#include "interruptible.hpp"
#include "lidar_overlap/pupil/aperture_mask.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

void bind_aperture_mask(py::module_& m) {
  using SectorTuple = std::tuple<double, double, double, std::optional<double>>;
  py::class_<ApertureMask>(m, "ApertureMask", "A union of annular sectors of the aperture stop.")
      .def(py::init([](const std::vector<SectorTuple>& sectors) {
             ApertureMask mask;
             for (const auto& [start, stop, inner, outer] : sectors)
               mask.sectors.push_back({start, stop, inner, outer});
             return mask;
           }),
           py::arg("sectors"),
           "sectors: (start_angle, stop_angle, inner_radius, outer_radius or None) each.")
      .def(
          "validate", &ApertureMask::validate, py::arg("telescope"),
          "Raises ValueError naming mask.sectors[i] for a sector outside the aperture or overlapping another.");

  m.def(
      "overlap_rt_masked",
      [](const LidarSystem& system, const std::vector<double>& ranges, const ApertureMask& mask,
         const RtOptions& options) {
        Interruptible release;
        return overlap_rt(system, ranges, mask, options);
      },
      py::arg("system"), py::arg("ranges"), py::arg("mask"), py::arg("options") = RtOptions{},
      "G through the masked aperture, normalised to the full aperture.");

  m.def(
      "overlap_rt_masks",
      [](const LidarSystem& system, const std::vector<double>& ranges,
         const std::vector<ApertureMask>& masks, const RtOptions& options) {
        Interruptible release;
        return overlap_rt(system, ranges, masks, options);
      },
      py::arg("system"), py::arg("ranges"), py::arg("masks"), py::arg("options") = RtOptions{},
      "G through each mask (the sectors of a telecover test) in one pass, each normalised to the full aperture.");
  m.attr("MAX_MASKS") = kMaxMasks;

  m.def(
      "overlap_fo_masked",
      [](const LidarSystem& system, const std::vector<double>& ranges, const ApertureMask& mask,
         const FoAberratedOptions& options) {
        Interruptible release;
        return overlap_fo(system, ranges, mask, options);
      },
      py::arg("system"), py::arg("ranges"), py::arg("mask"),
      py::arg("options") = FoAberratedOptions{},
      "Fourier-optics G through the masked aperture (the sampled pupil), normalised to the full aperture.");

  m.def(
      "emitter_coupling_rt_masked",
      [](const LidarSystem& system, double z, std::array<double, 2> position,
         const ApertureMask& mask) {
        return emitter_coupling_rt(system, z, {position[0], position[1]}, mask);
      },
      py::arg("system"), py::arg("z"), py::arg("position"), py::arg("mask"));
}
