// SPDX-License-Identifier: MIT
// SplitMix64 (G. L. Steele, D. Lea, C. H. Flood, "Fast splittable pseudorandom number
// generators", OOPSLA 2014): a small seeded generator whose sequence is the same on every
// machine, for procedural textures that must render the same every time.
#pragma once

#include <cstdint>

namespace inkline::core {

class SplitMix64 {
  public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}

    uint64_t next() {
        uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    // Uniform in [lo, hi), from the next value's top 53 bits.
    double uniform(double lo, double hi) { return lo + (hi - lo) * unit(next()); }

    // The first value of the generator seeded with x: a stateless hash of x.
    static uint64_t hash(uint64_t x) { return SplitMix64(x).next(); }
    // The top 53 bits of a value as a double in [0, 1).
    static double unit(uint64_t value) { return double(value >> 11) * 0x1.0p-53; }

  private:
    uint64_t state_;
};

}  // namespace inkline::core
