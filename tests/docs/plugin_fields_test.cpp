// The field table generator of `prism plugin fields` on made-up plugins:
// each kind of range, default, null and escape once, with the text written
// out by hand.
#include <cmath>

#include <gtest/gtest.h>

#include "plugin_fields.hpp"

namespace prism::cli {
namespace {

constexpr double kInf = INFINITY;
const double kWeights[] = {0.5, 2.0};
const double kClip[] = {-kInf, 1.0, -kInf};
const double kTolerance[] = {2.5e-8};
const double kScale[] = {1.0};

const PrismField kDemoFields[] = {
    {"size", PRISM_FIELD_NUMBER, 1, PRISM_FIELD_REQUIRED | PRISM_FIELD_MIN_EXCLUSIVE | PRISM_FIELD_LENGTH, 0.0, kInf,
     0.0, nullptr, "the size | in metres"},
    {"weights", PRISM_FIELD_ARRAY, 2, PRISM_FIELD_NONZERO, -kInf, kInf, 0.0, kWeights, "two weights"},
    {"clip", PRISM_FIELD_ARRAY_OR_NULL, 3, PRISM_FIELD_LENGTH, -kInf, kInf, -kInf, kClip, "a corner"},
    {"tolerance", PRISM_FIELD_NUMBER, 1, PRISM_FIELD_MIN_EXCLUSIVE, 0.0, kInf, 0.0, kTolerance, "how close"},
    {"scale", PRISM_FIELD_NUMBER, 1, 0, -kInf, 1e20, 0.0, kScale, "a factor"},
    {"level", PRISM_FIELD_NUMBER, 1, 0, 1.0, 100.0, 0.0, nullptr, "no default, so required"},
};

const PrismField kFlatFields[] = {
    {"offset", PRISM_FIELD_NUMBER, 1, 0, -kInf, kInf, 0.0, kScale, "any number"},
};

PrismPrimitiveDesc descriptor(const char* type, uint32_t flags, const PrismField* fields, uint32_t count) {
  PrismPrimitiveDesc d{};
  d.abi_version = PRISM_PRIMITIVE_ABI_VERSION;
  d.type_name = type;
  d.plugin_version = "1.0.0";
  d.flags = flags;
  d.field_count = count;
  d.fields = fields;
  return d;
}

TEST(PluginFields, MarkdownTableHasARowPerFieldAndOneForTheTransform) {
  const PrismPrimitiveDesc demo = descriptor("demo", PRISM_PRIMITIVE_TRANSFORMABLE, kDemoFields, 6);
  const PrismPrimitiveDesc flat = descriptor("flat", 0, kFlatFields, 1);
  EXPECT_EQ(fields_markdown({&demo, &flat}),
            "<!-- Generated from the plugins' field tables by `prism plugin fields --markdown`: edit the plugins' doc "
            "strings, not this table. -->\n"
            "\n"
            "| object type | key | value | default | meaning |\n"
            "|---|---|---|---|---|\n"
            "| `demo` | `size` | number in (0, 1e7] | required | the size \\| in metres |\n"
            "|  | `weights` | 2 numbers, not all 0 | `[0.5,2]` | two weights |\n"
            "|  | `clip` | 3 entries, each null (read as -inf) or a number in [-1e7, 1e7] | `[null,1,null]` | a corner |\n"
            "|  | `tolerance` | number > 0 | `2.5e-8` | how close |\n"
            "|  | `scale` | number ≤ 1e20 | `1` | a factor |\n"
            "|  | `level` | number in [1, 100] | required | no default, so required |\n"
            "|  | `center`, `rotation` | vec3, each in [-1e7, 1e7]; Rotation | `[0,0,0]`; the identity | where the local "
            "frame lies and how it is turned: `world = center + R · local` |\n"
            "| `flat` | `offset` | number | `1` | any number |\n");
}

TEST(PluginFields, TextHasALinePerField) {
  const PrismPrimitiveDesc flat = descriptor("flat", 0, kFlatFields, 1);
  EXPECT_EQ(fields_text(flat), "  offset         number; default 1: any number\n");
}

}  // namespace
}  // namespace prism::cli
