// Complex samples in FFTW-aligned memory: the storage of every Field, so that each buffer can use FFTW's
// SIMD plans. Part of the public API because Field holds one; the transforms themselves are internal.
#pragma once

#include <complex>
#include <cstddef>
#include <new>
#include <vector>

namespace lidar_overlap {

using Complex = std::complex<double>;

// Memory from FFTW's aligned allocator (fftw_malloc / fftw_free).
void* fftw_aligned_alloc(std::size_t bytes);
void fftw_aligned_free(void* p) noexcept;

// Allocator returning FFTW-aligned memory.
template <class T>
struct FftwAllocator {
  using value_type = T;
  FftwAllocator() = default;
  template <class U>
  FftwAllocator(const FftwAllocator<U>&) {}
  T* allocate(std::size_t n) {
    void* p = fftw_aligned_alloc(n * sizeof(T));
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) noexcept { fftw_aligned_free(p); }
  template <class U>
  bool operator==(const FftwAllocator<U>&) const {
    return true;
  }
  template <class U>
  bool operator!=(const FftwAllocator<U>&) const {
    return false;
  }
};

using ComplexBuffer = std::vector<Complex, FftwAllocator<Complex>>;

}  // namespace lidar_overlap
