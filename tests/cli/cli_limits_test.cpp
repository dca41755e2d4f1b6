// The input limits through the command line: a scene over the size limit,
// nesting over the depth limit, a texture that is truncated or whose header
// claims more pixels than the limit, and a scene larger than a GPU device's
// storage buffers. Each ends with exit status 2, a message naming the JSON
// path (or the file) and the limit, and nothing written. The limits
// themselves are checked with literal numbers in tests/limits and
// gpu/gpu_limits_test.cpp.
#include <nlohmann/json.hpp>

#include <algorithm>

#include "cli_harness.hpp"
#include "prism/image_file.hpp"
#include "test_support.hpp"

namespace prism::cli_test {
namespace {

class InputLimits : public CliTest {
 protected:
  // `prism render` and `prism trace` of `scene` exit with 2 and `expect` in
  // the message, and leave the folder as it was.
  void expect_rejected(const fs::path& scene, const std::vector<std::string>& expect) {
    write("rays.csv", "0,0,-5,0,0,1\n");
    const auto before = list_folder(dir());
    RunResult render = run({"render", scene.string(), "-b", "reference", "-o", path("out.png").string()});
    EXPECT_TRUE(ExitedWith(render, 2));
    EXPECT_TRUE(StderrHas(render, expect));
    EXPECT_EQ(list_folder(dir()), before) << render;
    RunResult trace = run({"trace", scene.string(), "-b", "reference", "--rays", path("rays.csv").string(), "-o",
                           path("out.csv").string()});
    EXPECT_TRUE(ExitedWith(trace, 2));
    EXPECT_TRUE(StderrHas(trace, expect));
    EXPECT_EQ(list_folder(dir()), before) << trace;
  }
  // A scene whose material `m` on the sphere uses texture `name` from `file`.
  fs::path scene_with_texture(const std::string& name, const std::string& file) {
    SceneText s;
    s.extra = R"("textures": {")" + name + R"(": ")" + file + R"("}, "materials": {"m": {"texture": ")" + name + R"("}})";
    s.objects = R"([{"type": "sphere", "radius": 1, "material": "m"}])";
    return write("scene.json", s.text());
  }
};

// A sparse file: refused from its size without reading it.
// `--rays /dev/zero` grew by ~100 MB/s without end (one line, never a
// newline): a line longer than 1024 characters is refused at once.
TEST_F(InputLimits, RayFileWithoutNewlines) {
  const fs::path scene = write("scene.json", SceneText{}.text());
  const auto before = list_folder(dir());
  RunResult r = run({"trace", scene.string(), "-b", "reference", "--rays", "/dev/zero", "-o", path("out.csv").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"/dev/zero:1: longer than 1024 characters"}));
  EXPECT_EQ(list_folder(dir()), before) << r;
}

TEST_F(InputLimits, SceneFileOverTheSizeLimit) {
  const fs::path scene = write("big.json", "");
  fs::resize_file(scene, (std::uintmax_t(64) << 20) + 1);
  expect_rejected(scene, {"big.json", "the scene is 67108865 bytes", "limit of 67108864 bytes (64 MiB)"});
}

TEST_F(InputLimits, NestingDeeperThanTheLimit) {
  SceneText s;
  s.objects = std::string(100000, '[') + std::string(100000, ']');
  expect_rejected(write("scene.json", s.text()), {"objects[0][0]", "nested more than 64 levels deep (the limit)"});
}

TEST_F(InputLimits, TextureWhoseHeaderClaimsTooManyPixels) {
  write("huge.png", prism::test::png_claiming_size(100000, 100000));
  expect_rejected(scene_with_texture("huge", "huge.png"),
                  {"textures.huge", "huge.png", "100000x100000 = 10000000000 pixels", "limit of 268435456 pixels"});
}

// Half of a PNG of noise: the header reads, the pixel data ends early.
TEST_F(InputLimits, TruncatedTexture) {
  ImageFile image{64, 64, 3, {}, PixelFormat::UInt8, std::vector<float>(64 * 64 * 3)};
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float((i * 7919) % 251) / 251.0f;
  write_image_file(path("whole.png"), image, PixelFormat::UInt8);
  const std::string bytes = read_file(path("whole.png"));
  fs::remove(path("whole.png"));
  write("cut.png", bytes.substr(0, bytes.size() / 2));
  expect_rejected(scene_with_texture("cut", "cut.png"), {"textures.cut", "cut.png", "cannot decode"});
}

// A real device's limit, on whatever driver runs the tests: the device's
// largest storage buffer comes from --stats of a small render, then a
// texture one row of texels over it is refused before it is uploaded.
class GpuBufferLimit : public CliTest, public testing::WithParamInterface<std::string> {
 protected:
  // The device's storage-buffer limit in bytes, or 0 when the backend cannot run here.
  double device_limit() {
    write("small.json", SceneText{}.text());
    RunResult r = run({"render", path("small.json").string(), "-b", GetParam(), "-o", path("small.png").string(),
                       "--stats", path("small.stats.json").string()});
    EXPECT_TRUE(ExitedWith(r, 0));
    if (!r.exited || r.status != 0) return 0;
    const nlohmann::json stats = nlohmann::json::parse(read_file(path("small.stats.json")));
    fs::remove(path("small.png"));
    fs::remove(path("small.stats.json"));
    return stats.at("counters").at("max_storage_buffer_bytes").get<double>();
  }
};

TEST_P(GpuBufferLimit, TextureOverTheDevicesStorageBufferLimit) {
  const auto built = backends_built();
  if (std::find(built.begin(), built.end(), GetParam()) == built.end()) GTEST_SKIP() << GetParam() << " not built";
  if (!prism::test::require_backend_or_skip(GetParam())) return;
  const double limit = device_limit();
  ASSERT_GT(limit, 0);
  // llvmpipe and lavapipe allow 128 MiB; a texture over a much larger limit costs too much memory for a test.
  if (limit > double(size_t(1) << 29)) GTEST_SKIP() << "this device allows " << limit << "-byte storage buffers";
  const size_t width = 4096;
  const size_t height = (size_t(limit) / 16 + 1 + width - 1) / width;  // 16 bytes a texel
  ImageFile grey{int(width), int(height), 1, {}, PixelFormat::UInt8, std::vector<float>(width * height, 0.5f)};
  write_image_file(path("big.png"), grey, PixelFormat::UInt8);
  const fs::path scene = [&] {
    SceneText s;
    s.extra = R"("textures": {"big": "big.png"}, "materials": {"m": {"texture": "big"}})";
    s.objects = R"([{"type": "sphere", "radius": 1, "material": "m"}])";
    return write("scene.json", s.text());
  }();
  const auto before = list_folder(dir());
  RunResult r = run({"render", scene.string(), "-b", GetParam(), "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  const size_t texels = width * height;
  EXPECT_TRUE(StderrHas(r, {"scene.json: textures: " + std::to_string(texels) + " texels need a " +
                                std::to_string(texels * 16) + "-byte storage buffer",
                            "GL_MAX_SHADER_STORAGE_BLOCK_SIZE|maxStorageBufferRange",
                            "of " + std::to_string(size_t(limit)) + " bytes"}));
  EXPECT_EQ(list_folder(dir()), before) << r;
}

INSTANTIATE_TEST_SUITE_P(Gpu, GpuBufferLimit, testing::Values("opengl", "vulkan"),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace prism::cli_test
