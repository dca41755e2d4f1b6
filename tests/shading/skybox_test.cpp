// The cube-map background: face choice (ties x before y before z), the
// OpenGL (sc, tc, ma) table, and clamping to the face's edge texels.
#include <array>

#include "shading_support.hpp"

namespace prism::test {
namespace {

// Face f (0..5 = +x -x +y -y +z -z) is a 2x2 EXR whose texel (column i, row j)
// is ((f+1)/8, 0.25 + 0.5 i, 0.25 + 0.5 j). On a 2x2 face, s = 0.25 / 0.75
// gives x = 2s - 0.5 = 0 / 1 exactly: one texel (likewise t and rows).
class SkyboxTest : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    dir_ = fresh_temp_dir();
    for (int f = 0; f < 6; ++f) {
      std::vector<float> texels;
      for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) texels.insert(texels.end(), {(f + 1) / 8.0f, 0.25f + 0.5f * i, 0.25f + 0.5f * j});
      }
      write_exr(dir_ / ("face" + std::to_string(f) + ".exr"), 2, 2, 3, texels);
    }
  }

  // The colour of a miss along `d`: a one-pixel camera at the origin looking along d.
  glm::dvec3 sky(const std::array<double, 3>& d, const std::string& up = "[0, 1, 0]") {
    std::string look_at = "[" + std::to_string(d[0]) + ", " + std::to_string(d[1]) + ", " + std::to_string(d[2]) + "]";
    Scene scene = load(R"({"prism": 1,
      "camera": {"position": [0, 0, 0], "look_at": )" + look_at + R"(, "up": )" + up + R"(},
      "image": {"width": 1, "height": 1},
      "background": {"cubemap": ["f0", "f1", "f2", "f3", "f4", "f5"]},
      "textures": {"f0": "face0.exr", "f1": "face1.exr", "f2": "face2.exr",
                   "f3": "face3.exr", "f4": "face4.exr", "f5": "face5.exr"}})",
                       dir_);
    return pixel(render(scene), 0, 0);
  }

  std::filesystem::path dir_;
};

void expect_colour(glm::dvec3 got, glm::dvec3 expected) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5) << "channel " << c;
}

TEST_P(SkyboxTest, EachFaceAndItsOrientation) {
  // For each face, a direction with (sc/|ma|, tc/|ma|) = (+-0.5, +-0.5), i.e.
  // (s, t) on one texel centre; the texel's (column, row) follows from s, t.
  // +x: (sc, tc) = (-dz, -dy) = (-0.5, 0.5) for d = (1, -0.5, 0.5): s = 0.25, t = 0.75 -> (0, 1).
  expect_colour(sky({1, -0.5, 0.5}), {0.125, 0.25, 0.75});
  // -x: (dz, -dy) = (0.5, -0.5) for d = (-1, 0.5, 0.5) -> texel (1, 0).
  expect_colour(sky({-1, 0.5, 0.5}), {0.25, 0.75, 0.25});
  // +y: (dx, dz) = (0.5, 0.5) for d = (0.5, 1, 0.5) -> texel (1, 1).
  expect_colour(sky({0.5, 1, 0.5}), {0.375, 0.75, 0.75});
  // -y: (dx, -dz) = (-0.5, 0.5) for d = (-0.5, -1, -0.5) -> texel (0, 1).
  expect_colour(sky({-0.5, -1, -0.5}), {0.5, 0.25, 0.75});
  // +z: (dx, -dy) = (0.5, -0.5) for d = (0.5, 0.5, 1) -> texel (1, 0).
  expect_colour(sky({0.5, 0.5, 1}), {0.625, 0.75, 0.25});
  // -z: (-dx, -dy) = (-0.5, -0.5) for d = (0.5, 0.5, -1) -> texel (0, 0).
  expect_colour(sky({0.5, 0.5, -1}), {0.75, 0.25, 0.25});
}

TEST_P(SkyboxTest, LookupClampsToTheFaceEdge) {
  // d = (1, 0.5, 0.8) on +x: sc = -0.8, tc = -0.5 -> s = 0.1, t = 0.25.
  // x = 2s - 0.5 = -0.3: clamped, both columns are column 0 (a wrap would mix
  // in 30 % of column 1); row 0. Texel (0, 0) = (0.125, 0.25, 0.25).
  expect_colour(sky({1, 0.5, 0.8}), {0.125, 0.25, 0.25});
}

TEST_P(SkyboxTest, TiesPickXBeforeYBeforeZ) {
  // d = (1, 1, 0): |dx| = |dy| -> +x. sc = 0, tc = -1: s = 0.5 (x = 0.5: half
  // column 0, half column 1), t = 0 (y = -0.5, clamped to row 0):
  // (0.125, 0.5*(0.25 + 0.75), 0.25) = (0.125, 0.5, 0.25).
  expect_colour(sky({1, 1, 0}), {0.125, 0.5, 0.25});
  // d = (0, -1, 1): |dy| = |dz| -> -y. sc = dx = 0, tc = -dz = -1: the same
  // texel pair on face 3: (0.5, 0.5, 0.25).
  expect_colour(sky({0, -1, 1}), {0.5, 0.5, 0.25});
}

PRISM_INSTANTIATE_BACKEND_TESTS(SkyboxTest);

}  // namespace
}  // namespace prism::test
