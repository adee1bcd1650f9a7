// NumPy arrays for results the core writes whole (a propagated field): memory that is never zero-filled,
// on transparent huge pages when large (as NumPy places its own large arrays), and reused once the caller
// has released an earlier result of the same size. A fresh 64 MiB array otherwise has its pages faulted in
// and zeroed by the kernel on every call (9.5 ms of a 2048^2 Fresnel call's 120 ms of CPU).
#pragma once

#include <cstddef>

#include "bind_field.hpp"

// An n x n complex array with FFTW's alignment (and 2 MiB alignment from kLargeResultBytes on), its values
// unset: the caller writes every one of them.
ComplexArray result_array(std::size_t n);

// Bytes from which a result is placed on huge pages and kept for reuse when released (the 2 MiB pages are
// worth it from here, as NumPy reckons; below it glibc's heap reuses released memory by itself).
inline constexpr std::size_t kLargeResultBytes = std::size_t{4} << 20;

// Bytes of released large results kept for reuse, at most (the least recently released go first).
inline constexpr std::size_t kResultPoolBytes = std::size_t{128} << 20;
