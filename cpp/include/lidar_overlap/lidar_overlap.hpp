// Everything of the lidar_overlap C++ API. All quantities are SI (m, rad); see each header.
#pragma once

#include "lidar_overlap/beam.hpp"
#include "lidar_overlap/checks.hpp"
#include "lidar_overlap/circles.hpp"
#include "lidar_overlap/constants.hpp"
#include "lidar_overlap/coupling_term.hpp"
#include "lidar_overlap/fft.hpp"
#include "lidar_overlap/field.hpp"
#include "lidar_overlap/overlap_rt.hpp"
#include "lidar_overlap/propagate.hpp"
#include "lidar_overlap/quadrature.hpp"
#include "lidar_overlap/receiver.hpp"
#include "lidar_overlap/scaled_dft.hpp"
#include "lidar_overlap/system.hpp"
#include "lidar_overlap/vec2.hpp"
#include "lidar_overlap/version.hpp"
