// Texture decoding (sRGB, alpha, channel counts, 16 bit), bilinear lookup with
// repeat, and the uv of boxes, planes and spheres. Textured surfaces are lit by
// ambient 1 only, so a pixel equals c = tex.rgb.

#include "shading_support.hpp"

namespace prism::test {
namespace {

// The grid texture of GridTextureTest (shading_support.hpp): texel (i, j) =
// ((i+1)/8, (j+1)/8, (i + 4j)/16); a uv' on a texel centre ((i+0.5)/4, (j+0.5)/4)
// reads exactly texel (i, j).
class TextureTest : public GridTextureTest {};

constexpr const char* kUnitBox = R"({"type": "box", "half_size": [1, 1, 1], "material": "m"})";
constexpr const char* kUnitSphere = R"({"type": "sphere", "radius": 1, "material": "m"})";

TEST_P(TextureTest, BoxPlusZFaceTexel) {
  // Hit (0,0,1): +z face uv = ((0+1)/2, (1-0)/2) = (0.5, 0.5); uv' = uv + 0.125 =
  // (0.625, 0.625) -> texel (2, 2) = (0.375, 0.375, 0.625).
  Image image = render_grid(R"({"position": [0, 0, 5], "look_at": [0, 0, 0]})",
                            R"(, "uv_offset": [0.125, 0.125])", kUnitBox);
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.375, 0.375, 0.625}));
}

TEST_P(TextureTest, BoxPlusXFaceTexel) {
  // Hit (1, 0.25, 0.25): +x face uv = ((p.z+1)/2, (1-p.y)/2) = (0.625, 0.375)
  // -> texel (2, 1) = (0.375, 0.25, 0.375).
  Image image = render_grid(R"({"position": [5, 0.25, 0.25], "look_at": [0, 0.25, 0.25]})", "", kUnitBox);
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.375, 0.25, 0.375}));
}

TEST_P(TextureTest, BoxMinusYFaceTexel) {
  // Hit (-0.25, -1, 0.75) from below: y face uv = ((p.x+1)/2, (p.z+1)/2) =
  // (0.375, 0.875) -> texel (1, 3) = (0.25, 0.5, 0.8125).
  Image image = render_grid(R"({"position": [-0.25, -5, 0.75], "look_at": [-0.25, 0, 0.75], "up": [0, 0, -1]})",
                            "", kUnitBox);
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.25, 0.5, 0.8125}));
}

TEST_P(TextureTest, RotatedBoxUsesItsLocalFrame) {
  // Rotation 90 deg about +y (right hand): local -x faces world +z, and
  // R^-1 (x, y, z) = (-z, y, x). World hit (0.25, 0.75, 1) -> p = (-1, 0.75, 0.25):
  // -x face uv = ((p.z+1)/2, (1-p.y)/2) = (0.625, 0.125) -> texel (2, 0) =
  // (0.375, 0.125, 0.125). (Turning the wrong way shows texel (1, 0).)
  Image image = render_grid(R"({"position": [0.25, 0.75, 5], "look_at": [0.25, 0.75, 0]})", "",
                            R"({"type": "box", "half_size": [1, 1, 1], "material": "m",
                                "rotation": {"axis": [0, 1, 0], "degrees": 90}})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.375, 0.125, 0.125}));
}

TEST_P(TextureTest, PlaneUvFollowsTheGivenNormal) {
  // Normal (0,0,1): t1 = normalize(cross((0,1,0), m)) = (1,0,0), t2 = cross(m, t1)
  // = (0,1,0). Hit (0.625, 0.375, -5): uv = (0.625, 0.375) -> texel (2, 1) =
  // (0.375, 0.25, 0.375).
  Image image = render_grid(R"({"position": [0.625, 0.375, 0], "look_at": [0.625, 0.375, -1]})", "",
                            R"({"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "material": "m"})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.375, 0.25, 0.375}));
}

TEST_P(TextureTest, FloorPlaneUvUsesTheXAxisHelper) {
  // Normal (0,1,0): |m.y| >= 0.999, so t1 = normalize(cross((1,0,0), m)) = (0,0,1),
  // t2 = cross(m, t1) = (1,0,0). Hit (0.125, 0, 0.625): uv = (0.625, 0.125)
  // -> texel (2, 0) = (0.375, 0.125, 0.125).
  Image image = render_grid(R"({"position": [0.125, 5, 0.625], "look_at": [0.125, 0, 0.625], "up": [0, 0, -1]})",
                            "", R"({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "m"})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.375, 0.125, 0.125}));
}

TEST_P(TextureTest, PlaneAndMaterialUvScalesCombine) {
  // Plane uv_scale 0.5: hit (0.5, 1.5, -5) -> uv = (0.25, 0.75). Material:
  // uv' = uv * (2, 0.5) + (0.125, 0) = (0.625, 0.375) -> texel (2, 1).
  Image image = render_grid(R"({"position": [0.5, 1.5, 0], "look_at": [0.5, 1.5, -1]})",
                            R"(, "uv_scale": [2, 0.5], "uv_offset": [0.125, 0])",
                            R"({"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "uv_scale": 0.5,
                                "material": "m"})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.375, 0.25, 0.375}));
}

TEST_P(TextureTest, SphereUv) {
  // p = (0,0,1): u = 0.5 + atan2(1, 0)/2pi = 0.75, v = 0.5 - asin(0)/pi = 0.5;
  // uv' = (0.875, 0.625) -> texel (3, 2) = (0.5, 0.375, 0.6875).
  EXPECT_TRUE(pixel_near(render_grid(R"({"position": [0, 0, 5], "look_at": [0, 0, 0]})",
                                     R"(, "uv_offset": [0.125, 0.125])", kUnitSphere),
                         0, 0, {0.5, 0.375, 0.6875}));
  // p = (0,0,-1): u = 0.5 + atan2(-1, 0)/2pi = 0.25 -> uv' = (0.375, 0.625)
  // -> texel (1, 2) = (0.25, 0.375, 0.5625).
  EXPECT_TRUE(pixel_near(render_grid(R"({"position": [0, 0, -5], "look_at": [0, 0, 0]})",
                                     R"(, "uv_offset": [0.125, 0.125])", kUnitSphere),
                         0, 0, {0.25, 0.375, 0.5625}));
}

TEST_P(TextureTest, RotatedSphereUvUsesItsLocalFrame) {
  // 90 deg about +y: world hit (0,0,1) -> p = (-1, 0, 0), u = 0.5 +- pi/2pi = 1 or 0
  // (the same texel column after the repeat wrap): uv' = (1.125 or 0.125, 0.625)
  // -> texel (0, 2) = (0.125, 0.375, 0.5).
  Image image = render_grid(R"({"position": [0, 0, 5], "look_at": [0, 0, 0]})", R"(, "uv_offset": [0.125, 0.125])",
                            R"({"type": "sphere", "radius": 1, "material": "m",
                                "rotation": {"axis": [0, 1, 0], "degrees": 90}})");
  EXPECT_TRUE(pixel_near(image, 0, 0, {0.125, 0.375, 0.5}));
}

TEST_P(TextureTest, BilinearFilterWrapsByEuclideanModulo) {
  // A 2x1 texture: t0 = (0.2, 0, 0), t1 = (1, 0, 1), on the plane z = -5
  // (uv = (P.x, P.y)); v = 0 gives y = -0.5, both rows = row 0.
  write_exr(dir_ / "pair.exr", 2, 1, 3, {0.2f, 0.0f, 0.0f, 1.0f, 0.0f, 1.0f});
  auto render_at = [&](double x) {
    const std::string pos = "[" + std::to_string(x) + ", 0, 0]";
    const std::string at = "[" + std::to_string(x) + ", 0, -1]";
    return render(load(R"({"prism": 1, "camera": {"position": )" + pos + R"(, "look_at": )" + at + R"(},
      "image": {"width": 1, "height": 1}, "ambient": [1, 1, 1],
      "textures": {"pair": "pair.exr"},
      "materials": {"m": {"color": [1, 1, 1], "texture": "pair"}},
      "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "material": "m"}]})",
                       dir_));
  };
  // u = 0.375: x = 0.25 -> 0.75 t0 + 0.25 t1 = (0.4, 0, 0.25).
  EXPECT_TRUE(pixel_near(render_at(0.375), 0, 0, {0.4, 0, 0.25}));
  // u = -0.125: x = -0.75, floor -1 -> texel 1, then texel 0, fraction 0.25:
  // 0.75 t1 + 0.25 t0 = (0.8, 0, 0.75).
  EXPECT_TRUE(pixel_near(render_at(-0.125), 0, 0, {0.8, 0, 0.75}));
}

// A textured plane at z = -5 (the one-pixel camera sees it) in front of a
// plane at z = -10 with Local (0.2, 0.4, 0.8); alpha a passes 1 - a through.
std::string alpha_png_scene(const std::string& texture_entry) {
  return one_pixel_scene(R"(
    "ambient": [1, 1, 1],
    "textures": {"t": )" + texture_entry + R"(},
    "materials": {"front": {"color": [1, 1, 1], "texture": "t"}, "back": {"color": [0.2, 0.4, 0.8]}},
    "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "material": "front"},
                {"type": "plane", "point": [0, 0, -10], "normal": [0, 0, 1], "material": "back"}])");
}

TEST_P(TextureTest, PngAlphaIsUnassociatedAndLinear) {
  // Bytes (255, 128, 64, 64): a = 64/255 = 0.250980392 whatever "srgb" says.
  write_png8(dir_ / "rgba.png", 1, 1, 4, {255, 128, 64, 64});
  // srgb false: c = (1, 128/255, 64/255) = (1, 0.501960784, 0.250980392);
  // a*c + (1-a)*(0.2, 0.4, 0.8) = (0.400784314, 0.425590158, 0.662206844).
  // (Premultiplied decoding would give c*a instead of c.)
  EXPECT_TRUE(pixel_near(render(load(alpha_png_scene(R"({"path": "rgba.png", "srgb": false})"), dir_)), 0, 0,
                         {0.400784314, 0.425590158, 0.662206844}));
  // srgb (default): c = (1, srgb_decode(128/255), srgb_decode(64/255))
  //   = (1, ((0.501960784+0.055)/1.055)^2.4, ((0.250980392+0.055)/1.055)^2.4)
  //   = (1, 0.2158605, 0.0512694584) -> (0.400784314, 0.353784596, 0.612083315).
  EXPECT_TRUE(pixel_near(render(load(alpha_png_scene(R"("rgba.png")"), dir_)), 0, 0,
                         {0.400784314, 0.353784596, 0.612083315}));
}

TEST_P(TextureTest, GreyAlphaPngChannels) {
  // Two channels = grey + alpha. Bytes (128, 64), srgb false: c = 0.501960784 (all
  // three), a = 0.250980392: a*c = 0.125982314;
  // + (1-a)*(0.2, 0.4, 0.8) -> (0.275786236, 0.425590158, 0.725198001).
  write_png8(dir_ / "ga.png", 1, 1, 2, {128, 64});
  EXPECT_TRUE(pixel_near(render(load(alpha_png_scene(R"({"path": "ga.png", "srgb": false})"), dir_)), 0, 0,
                         {0.275786236, 0.425590158, 0.725198001}));
}

TEST_P(TextureTest, SixteenBitPngIsSrgbDecodedToo) {
  // One grey channel, 32768/65535 = 0.50000763: decoded with the sRGB curve,
  // ((0.50000763 + 0.055)/1.055)^2.4 = 0.214048202 (all three channels).
  write_png16(dir_ / "grey16.png", 1, 1, 1, {32768});
  Scene scene = load(one_pixel_scene(R"(
    "ambient": [1, 1, 1],
    "textures": {"t": "grey16.png"},
    "materials": {"m": {"color": [1, 1, 1], "texture": "t"}},
    "objects": [{"type": "plane", "point": [0, 0, -5], "normal": [0, 0, 1], "material": "m"}])"),
                     dir_);
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.214048202, 0.214048202, 0.214048202}));
}

PRISM_INSTANTIATE_BACKEND_TESTS(TextureTest);

}  // namespace
}  // namespace prism::test
