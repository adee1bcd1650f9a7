// Receiver geometry a user needs beside the overlap itself (paper Eq. 5). The ray geometry of the
// receiver, which the RT engine evaluates for every scatterer, is internal (cpp/src/geometry/).
#pragma once

namespace lidar_overlap {

// Eq. (5): range (m) best focused on a detector displaced by `defocus` (m) behind the focal plane.
// Infinite for defocus = 0; defocus must be >= 0.
double optimal_focus_range(double focal_length, double defocus);

}  // namespace lidar_overlap
