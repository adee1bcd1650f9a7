// The lidar_overlap C++ API, and only the API. All quantities are SI (m, rad, W); see each header.
//
// Folders follow the architecture: core/ (the system, limits, cancellation), geometry/ (ray tracing),
// fourier/ (fields, propagation, Fourier-optics overlap), beams/ (flat-top design), atmosphere/
// (turbulence), pupil/ (the receiver pupil: aperture masks, wavefront aberrations, Zernike terms, and the
// overlap through an aberrated pupil). Internals (checks, quadrature, FFT plans, OTF, circle geometry, loops)
// live in cpp/src and are not installed.
//
// Entry points: overlap_rt (ray tracing; alignment_map over misalignment grids), overlap_fo (Fourier
// optics; Gaussian or any transmitted Field), overlap_fo_radial, overlap_fo_turbulent, overlap_rt_aberrated /
// overlap_fo_aberrated, emitter_coupling_rt/_fo, propagate (with choose_grid), design_flat_top. Invalid input throws
// std::invalid_argument naming the parameter and its valid range. Every entry point is thread-safe:
// FFTW planning is serialised and plans are shared through FFTW's new-array interface, so concurrent
// calls from several threads give the results of the same calls made one at a time, bit for bit
// (tests/cpp/test_thread_safety.cpp). Callers that are themselves multi-threaded pass threads = 1 (or
// their share of the cores) in each call's options: threads = 0 means all cores per call. No Python is
// needed: link LidarOverlap::lidar_overlap from find_package(LidarOverlap CONFIG) (examples/cpp).
#pragma once

#include "lidar_overlap/version.hpp"

#include "lidar_overlap/core/beam.hpp"
#include "lidar_overlap/core/cancel.hpp"
#include "lidar_overlap/core/limits.hpp"
#include "lidar_overlap/core/parameter_error.hpp"
#include "lidar_overlap/core/system.hpp"
#include "lidar_overlap/core/vec2.hpp"

#include "lidar_overlap/geometry/alignment_map.hpp"
#include "lidar_overlap/geometry/overlap_rt.hpp"
#include "lidar_overlap/geometry/receiver.hpp"

#include "lidar_overlap/fourier/complex_buffer.hpp"
#include "lidar_overlap/fourier/field.hpp"
#include "lidar_overlap/fourier/grid_choice.hpp"
#include "lidar_overlap/fourier/overlap_fo.hpp"
#include "lidar_overlap/fourier/overlap_fo_radial.hpp"
#include "lidar_overlap/fourier/propagate.hpp"

#include "lidar_overlap/beams/flat_top.hpp"

#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"
#include "lidar_overlap/atmosphere/phase_screen.hpp"
#include "lidar_overlap/atmosphere/turbulence.hpp"
#include "lidar_overlap/atmosphere/turbulent_grid.hpp"

#include "lidar_overlap/pupil/aberrations.hpp"
#include "lidar_overlap/pupil/aperture_mask.hpp"
#include "lidar_overlap/pupil/overlap_fo_aberrated.hpp"
#include "lidar_overlap/pupil/overlap_rt_aberrated.hpp"
#include "lidar_overlap/pupil/zernike.hpp"
