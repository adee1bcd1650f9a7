// xoshiro256++ (D. Blackman and S. Vigna, "Scrambled linear pseudorandom number generators", ACM TOMS 47,
// 2021): 64-bit outputs from 256 bits of state, about 1 ns each where std::mt19937_64 takes several, with
// no known statistical flaw at the sizes used here. Seeded by splitmix64 from one 64-bit key, as its
// authors advise; the same key gives the same stream on any platform. Internal header, not installed.
#pragma once

#include <cstdint>
#include <limits>

namespace lidar_overlap::detail {

class Xoshiro256 {
 public:
  using result_type = std::uint64_t;
  explicit Xoshiro256(std::uint64_t key) {
    for (std::uint64_t& word : s_) {  // splitmix64
      key += 0x9e3779b97f4a7c15ULL;
      std::uint64_t z = key;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      word = z ^ (z >> 31);
    }
  }
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }
  result_type operator()() {
    const std::uint64_t out = rotl(s_[0] + s_[3], 23) + s_[0], t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return out;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

}  // namespace lidar_overlap::detail
