// Object keeps a record of up to kInlineRecordBytes inside itself (one
// cache line with the descriptor and centre) and a larger one on the heap;
// either way record() is the zeroed, 16-byte aligned block reset_record
// returned, and copies of the object carry their own.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "prism/scene.hpp"

namespace prism {
namespace {

bool zeroed(const void* p, size_t bytes) {
  const auto* b = static_cast<const std::byte*>(p);
  for (size_t i = 0; i < bytes; ++i)
    if (b[i] != std::byte{0}) return false;
  return true;
}

bool inside(const Object& object, const void* p) {
  const auto* at = static_cast<const std::byte*>(p);
  const auto* begin = reinterpret_cast<const std::byte*>(&object);
  return at >= begin && at < begin + sizeof(Object);
}

// reset_record(bytes) returns record(), 16-byte aligned and zeroed, inside
// the object or not.
void expect_fresh_record(size_t bytes, bool inside_expected) {
  Object object;
  void* record = object.reset_record(bytes);
  EXPECT_EQ(record, object.record());
  EXPECT_EQ(inside(object, record), inside_expected) << bytes << " bytes";
  EXPECT_EQ(reinterpret_cast<uintptr_t>(record) % 16, 0u);
  EXPECT_TRUE(zeroed(record, bytes));
  EXPECT_EQ(reinterpret_cast<uintptr_t>(&object) % 64, 0u);
}

TEST(ObjectRecord, SmallRecordIsInlineZeroedAndAligned) { expect_fresh_record(32, true); }

TEST(ObjectRecord, LargeRecordIsOnTheHeapZeroedAndAligned) { expect_fresh_record(48, false); }

TEST(ObjectRecord, ResetClearsAnOldRecordOfEitherKind) {
  Object object;
  std::memset(object.reset_record(80), 0x5a, 80);
  void* small = object.reset_record(16);
  EXPECT_TRUE(zeroed(small, 32));
  std::memset(small, 0x5a, 16);
  EXPECT_TRUE(zeroed(object.reset_record(32), 32));
}

TEST(ObjectRecord, CopiesOwnTheirRecord) {
  for (const size_t bytes : {size_t(16), size_t(64)}) {
    Object original;
    std::memset(original.reset_record(bytes), 0x11, bytes);
    const Object copy = original;
    EXPECT_NE(copy.record(), original.record());
    EXPECT_EQ(std::memcmp(copy.record(), original.record(), bytes), 0);
  }
}

}  // namespace
}  // namespace prism
