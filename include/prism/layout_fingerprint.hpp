// A 64-bit fingerprint of a list of numbers (sizes, alignments, offsets,
// versions), computed at compile time. Two translation units that see the
// same layouts compute the same value; prism/backend_fingerprint.hpp uses
// it to tell whether a backend plugin was compiled against the core's view
// of the types that cross the backend boundary.
#pragma once

#include <cstdint>
#include <initializer_list>

namespace prism {

// FNV-1a (64-bit) parameters, as published by Fowler, Noll and Vo.
inline constexpr uint64_t kFnv1aOffsetBasis = 14695981039346656037ull;
inline constexpr uint64_t kFnv1aPrime = 1099511628211ull;

// FNV-1a over the numbers' bytes, each number as 8 bytes, least significant
// first: the value does not depend on the host's byte order, and the order
// of the numbers matters ({8, 16} and {16, 8} differ).
constexpr uint64_t layout_fingerprint(std::initializer_list<uint64_t> numbers) {
  uint64_t hash = kFnv1aOffsetBasis;
  for (const uint64_t number : numbers) {
    for (int byte = 0; byte < 8; ++byte) {
      hash ^= (number >> (8 * byte)) & 0xffu;
      hash *= kFnv1aPrime;
    }
  }
  return hash;
}

}  // namespace prism
