# Dependencies of the lidar_overlap core, shared by the build tree and the installed package config.
# FFTW3 (double precision) comes from pkg-config; its threads library sits beside it and has no .pc
# file of its own on Debian, so it is looked up in the same directory.
include(CMakeFindDependencyMacro)

find_package(PkgConfig REQUIRED)
if(NOT TARGET PkgConfig::FFTW3)
  pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET GLOBAL fftw3)
endif()
if(NOT TARGET FFTW3::fftw3)
  add_library(FFTW3::fftw3 INTERFACE IMPORTED GLOBAL)
  target_link_libraries(FFTW3::fftw3 INTERFACE PkgConfig::FFTW3)
endif()
if(NOT TARGET FFTW3::fftw3_threads)
  find_library(FFTW3_THREADS_LIBRARY NAMES fftw3_threads HINTS ${FFTW3_LIBRARY_DIRS} ${FFTW3_LIBDIR})
  if(NOT FFTW3_THREADS_LIBRARY)
    message(FATAL_ERROR "FFTW3 threads library (libfftw3_threads) not found next to FFTW3 in "
                        "'${FFTW3_LIBDIR}'. On Debian: apt-get install libfftw3-dev")
  endif()
  add_library(FFTW3::fftw3_threads UNKNOWN IMPORTED GLOBAL)
  set_target_properties(FFTW3::fftw3_threads PROPERTIES IMPORTED_LOCATION "${FFTW3_THREADS_LIBRARY}")
  target_link_libraries(FFTW3::fftw3_threads INTERFACE FFTW3::fftw3)
endif()

find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(Threads REQUIRED)
