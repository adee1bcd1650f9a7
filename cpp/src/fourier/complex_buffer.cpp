#include "lidar_overlap/fourier/complex_buffer.hpp"

#include <fftw3.h>

namespace lidar_overlap {

void* fftw_aligned_alloc(std::size_t bytes) { return fftw_malloc(bytes); }
void fftw_aligned_free(void* p) noexcept { fftw_free(p); }

}  // namespace lidar_overlap
