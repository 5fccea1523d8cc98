// splitmix64 (Steele, Lea and Flood 2014): a fast, well-mixed 64-bit stream per seed,
// for the pictures' seeded randomness (sensor noise, varied optics).
#pragma once

#include <cstdint>

namespace finflex::pictures {

struct SplitMix {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
};

}  // namespace finflex::pictures
