#pragma once
// Owen's nested uniform scrambling of a (0,1) coordinate in base 2 (Owen 1995, "Randomly permuted
// (t,m,s)-nets and (t,s)-sequences"): bit b of the scrambled value is bit b of the input flipped by a
// random bit that depends only on the bits ABOVE b (the node of the binary tree the value sits in).
// The random bits come from a hash of (seed, dimension, node) (splitmix64), so the design is the same
// on every platform and for every sample size. Nested scrambling keeps a (t,m,s)-net a (t,m,s)-net and
// makes each point uniform on [0,1): the origin of the raw Sobol' sequence becomes a random point.
// 32 bits are scrambled (GSL's Sobol' points carry 30); the result is (k + 1/2) / 2^32, never 0 or 1.
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace ver::sens {

/// splitmix64's finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mix.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class OwenScramble {
 public:
  OwenScramble(std::uint64_t seed, std::size_t dimension) : key_(mix64(mix64(seed) ^ mix64(0x5eed0000ULL + dimension))) {}

  /// u in [0, 1): its first 32 bits scrambled.
  double operator()(double u) const {
    const auto x = static_cast<std::uint32_t>(std::ldexp(u, 32));  // exact for GSL's k / 2^30
    std::uint32_t out = 0;
    for (int b = 31; b >= 0; --b) {
      const int depth = 31 - b;  // bits above b
      const std::uint64_t prefix = depth == 0 ? 0 : static_cast<std::uint64_t>(x) >> (b + 1);
      const std::uint64_t node = (std::uint64_t{1} << depth) | prefix;  // unique per tree node
      const std::uint32_t flip = static_cast<std::uint32_t>(mix64(key_ ^ mix64(node)) >> 63);
      out |= (((x >> b) & 1u) ^ flip) << b;
    }
    return std::ldexp(static_cast<double>(out) + 0.5, -32);
  }

 private:
  std::uint64_t key_;
};

}  // namespace ver::sens
