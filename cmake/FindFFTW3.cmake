# Find module for FFTW3 (double precision) and its threads library, used by the build and installed with
# the package config (find_dependency(FFTW3) there). Defines FFTW3_FOUND and the targets FFTW3::fftw3 and
# FFTW3::fftw3_threads. FFTW3 comes from pkg-config; its threads library sits beside it and has no .pc
# file of its own on Debian, so it is looked up in the same directory.
include(FindPackageHandleStandardArgs)

find_package(PkgConfig QUIET)
if(PkgConfig_FOUND AND NOT TARGET PkgConfig::FFTW3)
  pkg_check_modules(FFTW3 QUIET IMPORTED_TARGET GLOBAL fftw3)
endif()
if(TARGET PkgConfig::FFTW3)
  find_library(FFTW3_THREADS_LIBRARY NAMES fftw3_threads HINTS ${FFTW3_LIBRARY_DIRS} ${FFTW3_LIBDIR})
endif()

find_package_handle_standard_args(FFTW3
  REQUIRED_VARS FFTW3_THREADS_LIBRARY
  REASON_FAILURE_MESSAGE "FFTW3 (pkg-config module fftw3) with libfftw3_threads beside it is needed. On Debian: apt-get install pkg-config libfftw3-dev")

if(FFTW3_FOUND)
  if(NOT TARGET FFTW3::fftw3)
    add_library(FFTW3::fftw3 INTERFACE IMPORTED GLOBAL)
    target_link_libraries(FFTW3::fftw3 INTERFACE PkgConfig::FFTW3)
  endif()
  if(NOT TARGET FFTW3::fftw3_threads)
    add_library(FFTW3::fftw3_threads UNKNOWN IMPORTED GLOBAL)
    set_target_properties(FFTW3::fftw3_threads PROPERTIES IMPORTED_LOCATION "${FFTW3_THREADS_LIBRARY}")
    target_link_libraries(FFTW3::fftw3_threads INTERFACE FFTW3::fftw3)
  endif()
endif()
