// Everything of the lidar_overlap C++ API. All quantities are SI (m, rad, W); see each header.
//
// Entry points: overlap_rt (ray tracing), overlap_fo (Fourier optics; Gaussian or any transmitted
// Field), emitter_coupling_rt/_fo, propagate (with choose_grid), design_flat_top. Invalid input throws
// std::invalid_argument naming the parameter and its valid range. Every entry point is thread-safe:
// FFTW planning is serialised and plans are shared through FFTW's new-array interface, so concurrent
// calls from several threads give the results of the same calls made one at a time, bit for bit
// (tests/cpp/test_thread_safety.cpp). No Python is needed: link LidarOverlap::lidar_overlap from
// find_package(LidarOverlap CONFIG) (examples/cpp).
#pragma once

#include "lidar_overlap/aberrations.hpp"
#include "lidar_overlap/beam.hpp"
#include "lidar_overlap/cancel.hpp"
#include "lidar_overlap/checks.hpp"
#include "lidar_overlap/circles.hpp"
#include "lidar_overlap/constants.hpp"
#include "lidar_overlap/coupling_term.hpp"
#include "lidar_overlap/fft.hpp"
#include "lidar_overlap/field.hpp"
#include "lidar_overlap/flat_top.hpp"
#include "lidar_overlap/grid_choice.hpp"
#include "lidar_overlap/limits.hpp"
#include "lidar_overlap/otf.hpp"
#include "lidar_overlap/overlap_fo.hpp"
#include "lidar_overlap/overlap_fo_aberrated.hpp"
#include "lidar_overlap/overlap_fo_radial.hpp"
#include "lidar_overlap/overlap_rt.hpp"
#include "lidar_overlap/overlap_rt_aberrated.hpp"
#include "lidar_overlap/overlap_turbulent.hpp"
#include "lidar_overlap/phase_screen.hpp"
#include "lidar_overlap/propagate.hpp"
#include "lidar_overlap/quadrature.hpp"
#include "lidar_overlap/receiver.hpp"
#include "lidar_overlap/scaled_dft.hpp"
#include "lidar_overlap/special_functions.hpp"
#include "lidar_overlap/system.hpp"
#include "lidar_overlap/turbulence.hpp"
#include "lidar_overlap/vec2.hpp"
#include "lidar_overlap/version.hpp"
#include "lidar_overlap/zernike.hpp"
