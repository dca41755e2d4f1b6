// A region of the image (a tile of an MPI render) renders exactly the pixels
// of the whole image it covers, bit for bit, AOVs too; a region outside the
// image is refused.
#include <cstring>

#include "prism/errors.hpp"
#include "shading_support.hpp"

namespace prism::test {
namespace {

class RegionTest : public BackendTest {};


TEST_P(RegionTest, ARegionIsTheSamePixelsAsTheWholeImage) {
  const Scene scene = load(read_file(source_dir() / "scenes" / "conformance" / "glass.json"),
                           source_dir() / "scenes" / "conformance");
  RenderSettings whole;
  whole.image = scene.image;
  whole.image.width = 72;
  whole.image.height = 40;
  whole.image.spp = 2;
  whole.aov_id = true;
  whole.aov_path = true;
  whole.aov_depth = whole.aov_normal = whole.aov_albedo = true;
  const Image full = render(scene, whole);
  // Odd offsets and sizes: no tile or work-group boundary lines up.
  RenderSettings part = whole;
  part.region = PixelRect{13, 7, 29, 17};
  const Image tile = render(scene, part);
  ASSERT_EQ(tile.width, 29);
  ASSERT_EQ(tile.height, 17);
  size_t differing = 0;
  for (int y = 0; y < 17; ++y)
    for (int x = 0; x < 29; ++x) {
      const size_t t = size_t(y) * 29 + size_t(x), f = size_t(y + 7) * 72 + size_t(x + 13);
      differing += std::memcmp(&tile.rgb[t * 3], &full.rgb[f * 3], 3 * sizeof(float)) != 0;
      differing += tile.id[t] != full.id[f];
      differing += std::memcmp(&tile.path[t], &full.path[f], sizeof(float)) != 0;
      differing += std::memcmp(&tile.depth[t], &full.depth[f], sizeof(float)) != 0;
      differing += std::memcmp(&tile.normal[t * 3], &full.normal[f * 3], 3 * sizeof(float)) != 0;
      differing += std::memcmp(&tile.albedo[t * 3], &full.albedo[f * 3], 3 * sizeof(float)) != 0;
    }
  EXPECT_EQ(differing, 0u);
}

TEST_P(RegionTest, ARegionOutsideTheImageIsRefused) {
  const Scene scene = load(R"({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
                               "image": {"width": 16, "height": 8}})");
  RenderSettings settings;
  settings.image = scene.image;
  for (const PixelRect bad : {PixelRect{10, 0, 7, 8}, PixelRect{0, 0, 0, 8}, PixelRect{-1, 0, 4, 4},
                              PixelRect{0, 5, 16, 4}}) {
    settings.region = bad;
    try {
      render(scene, settings);
      ADD_FAILURE() << "accepted a region " << bad.width << "x" << bad.height << " at " << bad.x << "," << bad.y;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("is not a non-empty part of the 16x8 image"), std::string::npos) << e.what();
    }
  }
}

PRISM_INSTANTIATE_BACKEND_TESTS(RegionTest);

}  // namespace
}  // namespace prism::test
