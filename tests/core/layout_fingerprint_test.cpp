// The fingerprint behind the backend boundary's load-time check
// (prism/layout_fingerprint.hpp, prism/backend_fingerprint.hpp). The
// expected values are FNV-1a-64 of the numbers' bytes (8 each, least
// significant first), worked out independently of this code from the
// published parameters; FNV-1a-64 of the one byte "a" is 0xaf63dc4c8601ec8c.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>

#include "prism/backend_fingerprint.hpp"
#include "prism/layout_fingerprint.hpp"

namespace prism {
namespace {

TEST(LayoutFingerprint, OfNoNumbersIsTheOffsetBasis) {
  EXPECT_EQ(layout_fingerprint({}), 0xcbf29ce484222325ull);
}

TEST(LayoutFingerprint, OfOneIsFnv1aOfItsEightBytes) {
  // The bytes 01 00 00 00 00 00 00 00.
  EXPECT_EQ(layout_fingerprint({1}), 0x89cd31291d2aefa4ull);
}

TEST(LayoutFingerprint, OrderOfTheNumbersMatters) {
  EXPECT_EQ(layout_fingerprint({8, 16}), 0xefbd3e8aa89cc87dull);
  EXPECT_EQ(layout_fingerprint({16, 8}), 0x6fd7b482e9cb397dull);
}

// Two versions of one struct: the second member went from double to float.
struct Before {
  int32_t a;
  double b;
};
struct After {
  int32_t a;
  float b;
};

TEST(LayoutFingerprint, ChangesWhenALayoutChanges) {
  // {sizeof, alignof, offset of a, size of a, offset of b, size of b}.
  // Before: {16, 8, 0, 4, 8, 8}; After: {8, 4, 0, 4, 4, 4}.
  const uint64_t before = layout_fingerprint(
      {sizeof(Before), alignof(Before), offsetof(Before, a), sizeof(Before::a), offsetof(Before, b), sizeof(Before::b)});
  const uint64_t after = layout_fingerprint(
      {sizeof(After), alignof(After), offsetof(After, a), sizeof(After::a), offsetof(After, b), sizeof(After::b)});
  EXPECT_EQ(before, layout_fingerprint({16, 8, 0, 4, 8, 8}));
  EXPECT_EQ(after, layout_fingerprint({8, 4, 0, 4, 4, 4}));
  EXPECT_NE(before, after);
}

TEST(LayoutFingerprint, ChangesWhenOnlyTheLastMemberSizeChanges) {
  // An offset list alone would miss a member that grows at the end.
  EXPECT_EQ(layout_fingerprint({16, 8, 0, 4, 8, 8}), 0x0a5f697bbf0f1d79ull);
  EXPECT_EQ(layout_fingerprint({16, 8, 0, 4, 8, 4}), 0x8e744d579351f4f5ull);
}

// backend_desc fills in what the registry checks first.
void no_probe(PrismBackendProbe*) {}
Backend* no_create() { return nullptr; }

TEST(BackendFingerprint, BackendDescCarriesThisBuildsFingerprint) {
  constexpr PrismBackendDesc desc = backend_desc("mine", "1.0.0", 7, no_probe, no_create);
  EXPECT_EQ(desc.abi_version, 9u);
  EXPECT_EQ(desc.desc_size, sizeof(PrismBackendDesc));
  EXPECT_EQ(desc.layout_fingerprint, backend_layout_fingerprint());
  EXPECT_EQ(offsetof(PrismBackendDesc, layout_fingerprint), 8u);
  EXPECT_EQ(desc.speed_rank, 7);
}

}  // namespace
}  // namespace prism
