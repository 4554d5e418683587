#pragma once
// Counter-based randomness: a variate is a pure function of its key (seed, position, step, ...),
// so that random initial data and thermal noise do not depend on the partition or on the
// order in which the cells are visited.

#include <cstdint>

namespace Membrane
{
  /// The splitmix64 finalizer: a bijection of 64-bit words with full avalanche.
  inline std::uint64_t splitmix64(std::uint64_t x)
  {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
  }
} // namespace Membrane
