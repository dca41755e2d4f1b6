// The uv of the curved primitives and of the quadric, read back through the
// grid texture (shading_support.hpp): each case lands on one texel centre.
#include "shading_support.hpp"

namespace prism::test {
namespace {

class PrimitiveUvTest : public GridTextureTest {};

// Looking straight down needs an up vector other than +y.
std::string camera_above(const std::string& x, const std::string& z) {
  return R"({"position": [)" + x + ", 5, " + z + R"(], "look_at": [)" + x + ", 0, " + z + R"(], "up": [0, 0, -1]})";
}

TEST_P(PrimitiveUvTest, SpherePoleTakesAtan2OfZeroZeroAsZero) {
  // Straight down onto the north pole: p = (0, 1, 0), u = 0.5 + atan2(0, 0)/2pi
  // = 0.5, v = 0.5 - asin(1)/pi = 0; uv' = (0.625, 0.125) -> texel (2, 0) =
  // (0.375, 0.125, 0.125). (atan2 = pi would give u = 1 -> texel (0, 0).)
  Image image = render_grid(camera_above("0", "0"), R"(, "uv_offset": [0.125, 0.125])",
                            R"({"type": "sphere", "radius": 1, "material": "m"})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.375, 0.125, 0.125}));
}

TEST_P(PrimitiveUvTest, TorusUv) {
  // R = 2, r = 0.5. From above at (0, 5, 2): p = (0, 0.5, 2), the top of the
  // tube. u = 0.5 + atan2(2, 0)/2pi = 0.75; v = 0.5 + atan2(0.5, 2 - 2)/2pi = 0.75.
  // uv' = (0.875, 0.875) -> texel (3, 3) = (0.5, 0.5, 0.9375).
  Image image = render_grid(camera_above("0", "2"), R"(, "uv_offset": [0.125, 0.125])",
                            R"({"type": "torus", "major_radius": 2, "minor_radius": 0.5, "material": "m"})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.5, 0.5, 0.9375}));
}

TEST_P(PrimitiveUvTest, RingUv) {
  // inner 1, outer 2. From above at (0, 5, 1.625): p = (0, 0, 1.625).
  // u = (1.625 - 1)/(2 - 1) = 0.625; v = 0.5 + atan2(1.625, 0)/2pi = 0.75.
  // uv' = (0.625, 0.875) -> texel (2, 3) = (0.375, 0.5, 0.875).
  Image image = render_grid(camera_above("0", "1.625"), R"(, "uv_offset": [0, 0.125])",
                            R"({"type": "ring", "inner_radius": 1, "outer_radius": 2, "material": "m"})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.375, 0.5, 0.875}));
}

TEST_P(PrimitiveUvTest, CylinderUv) {
  // radius 1, height 2. From (0, 1.25, 5) along -z: p = (0, 1.25, 1).
  // u = 0.5 + atan2(1, 0)/2pi = 0.75; v = 1.25/2 = 0.625.
  // uv' = (0.875, 0.625) -> texel (3, 2) = (0.5, 0.375, 0.6875).
  Image image = render_grid(R"({"position": [0, 1.25, 5], "look_at": [0, 1.25, 0]})", R"(, "uv_offset": [0.125, 0])",
                            R"({"type": "cylinder", "radius": 1, "height": 2, "material": "m"})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.5, 0.375, 0.6875}));
}

TEST_P(PrimitiveUvTest, ConeUv) {
  // radius 1, height 1 (x^2 + z^2 = y^2). From (0, 0.625, 5) along -z:
  // p = (0, 0.625, 0.625). u = 0.75, v = 0.625/1.
  // uv' = (0.875, 0.625) -> texel (3, 2) = (0.5, 0.375, 0.6875).
  Image image = render_grid(R"({"position": [0, 0.625, 5], "look_at": [0, 0.625, 0]})", R"(, "uv_offset": [0.125, 0])",
                            R"({"type": "cone", "radius": 1, "height": 1, "material": "m"})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.5, 0.375, 0.6875}));
}

TEST_P(PrimitiveUvTest, QuadricUvIsZero) {
  // uv = (0, 0) everywhere; uv' = (0.625, 0.375) -> texel (2, 1) = (0.375, 0.25, 0.375).
  Image image = render_grid(R"({"position": [0, 0, 5], "look_at": [0, 0, 0]})", R"(, "uv_offset": [0.625, 0.375])",
                            R"({"type": "quadric", "coefficients": [1, 1, 1, 0, 0, 0, 0, 0, 0, -1], "material": "m"})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.375, 0.25, 0.375}));
}

PRISM_INSTANTIATE_BACKEND_TESTS(PrimitiveUvTest);

}  // namespace
}  // namespace prism::test
