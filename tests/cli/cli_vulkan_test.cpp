// `prism list` and `prism render -b vulkan` on machines where Vulkan cannot
// run: the reason is named (no loader, no driver, no matching device), and a
// render that asks for vulkan there ends with exit status 1 and that reason.
#include <algorithm>
#include <cstdlib>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "test_support.hpp"

namespace prism::cli_test {
namespace {

struct Unavailable {
  const char* variable;
  const char* value;
  const char* reason;  // what `prism list` must say
};

class VulkanUnavailable : public CliTest, public testing::WithParamInterface<Unavailable> {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    const auto built = backends_built();
    if (std::find(built.begin(), built.end(), "vulkan") == built.end()) GTEST_SKIP() << "no vulkan backend built";
    ::setenv(GetParam().variable, GetParam().value, 1);
    if (std::string(GetParam().variable) == "VK_ICD_FILENAMES") ::setenv("VK_DRIVER_FILES", GetParam().value, 1);
  }
};

std::string vulkan_line(const std::string& out) {
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("  vulkan ", 0) == 0) return line;
  return "";
}

TEST_P(VulkanUnavailable, ListSaysWhy) {
  RunResult r = run({"list"});
  ASSERT_TRUE(ExitedWith(r, 0));
  const std::string line = vulkan_line(r.out);
  EXPECT_NE(line.find("not usable here: "), std::string::npos) << r;
  EXPECT_NE(line.find(GetParam().reason), std::string::npos) << r;
}

TEST_P(VulkanUnavailable, RenderExitsWithTheReason) {
  write("scene.json", SceneText().text());
  RunResult r = run({"render", path("scene.json").string(), "-b", "vulkan", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 1));
  EXPECT_TRUE(StderrHas(r, {"vulkan", GetParam().reason}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, VulkanUnavailable,
    testing::Values(Unavailable{"PRISM_VULKAN_LOADER", "/nonexistent/libvulkan.so.1", "no Vulkan loader"},
                    Unavailable{"VK_ICD_FILENAMES", "/nonexistent/icd.json", "no Vulkan driver"},
                    Unavailable{"PRISM_VULKAN_DEVICE", "no device is called this", "matches no Vulkan device"}),
    [](const testing::TestParamInfo<Unavailable>& info) {
      return std::string(info.param.variable == std::string("PRISM_VULKAN_LOADER") ? "NoLoader"
                         : info.param.variable == std::string("VK_ICD_FILENAMES")  ? "NoDriver"
                                                                                    : "NoMatchingDevice");
    });

// PRISM_VULKAN_TIMEOUT=inf made every tile "not finish within -2147483648 s",
// and a value that is not a number was ignored: both are refused by name.
class VulkanTimeoutValue : public CliTest, public testing::WithParamInterface<std::string> {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    if (!prism::test::require_backend_or_skip("vulkan")) GTEST_SKIP();
    ::setenv("PRISM_VULKAN_TIMEOUT", GetParam().c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("PRISM_VULKAN_TIMEOUT");
    CliTest::TearDown();
  }
};

TEST_P(VulkanTimeoutValue, IsRefusedByName) {
  write("scene.json", SceneText().text());
  RunResult r = run({"render", path("scene.json").string(), "-b", "vulkan", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"PRISM_VULKAN_TIMEOUT: must be a number in [0.001, 86400], got '" + GetParam() + "'"}));
  EXPECT_FALSE(fs::exists(path("out.png")));
}

INSTANTIATE_TEST_SUITE_P(Values, VulkanTimeoutValue, testing::Values("inf", "ten", "0"),
                         [](const testing::TestParamInfo<std::string>& info) { return "case" + std::to_string(info.index); });

// A device without shaderFloat64, played by this machine's device with the
// feature hidden (PRISM_VULKAN_HIDE_FLOAT64=1): the backend starts, `prism
// list` says what the device lacks, a plain scene renders in float with no
// warning, and a scene the precision rule sends to double renders anyway,
// with a warning naming the objects and the expected error. The showcase's
// conformance on such a device is the CTest test
// conform.showcase.vulkan_without_float64.
class VulkanWithoutFloat64 : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    if (!prism::test::require_backend_or_skip("vulkan")) GTEST_SKIP();
    ::setenv("PRISM_VULKAN_HIDE_FLOAT64", "1", 1);
  }
  void TearDown() override {
    ::unsetenv("PRISM_VULKAN_HIDE_FLOAT64");
    CliTest::TearDown();
  }

  // Renders `scene` on vulkan (exit 0 expected) and returns its --stats info.
  nlohmann::json render(const fs::path& scene) {
    last_ = run({"render", scene.string(), "-b", "vulkan", "-o", path("out.png").string(), "--stats",
                 path("stats.json").string()});
    EXPECT_TRUE(ExitedWith(last_, 0));
    if (!fs::exists(path("stats.json"))) return nlohmann::json::object();
    return nlohmann::json::parse(read_file(path("stats.json")))["info"];
  }

  RunResult last_;
};

TEST_F(VulkanWithoutFloat64, ListNamesTheMissingFeature) {
  RunResult r = run({"list"});
  ASSERT_TRUE(ExitedWith(r, 0));
  const std::string line = vulkan_line(r.out);
  EXPECT_NE(line.find("no shaderFloat64"), std::string::npos) << r;
  EXPECT_EQ(line.find("not usable here"), std::string::npos) << r;
}

TEST_F(VulkanWithoutFloat64, APlainSceneRendersInFloatWithoutAWarning) {
  write("scene.json", SceneText().text());
  const nlohmann::json info = render(path("scene.json"));
  EXPECT_EQ(info.value("precision", ""), "float") << last_;
  EXPECT_FALSE(info.contains("precision_warning")) << info.dump(2);
  EXPECT_NE(info.value("device", "").find("no shaderFloat64"), std::string::npos) << info.dump(2);
  EXPECT_EQ(last_.err.find("warning"), std::string::npos) << last_;
}

TEST_F(VulkanWithoutFloat64, ASceneThatNeedsDoubleRendersInFloatWithAWarning) {
  // The far camera (1e5 away, a 0.0022 rad view): the rule wants double for
  // its three bounded objects (docs/numerics.md, "Float or double on the GPU").
  const nlohmann::json info = render(prism::test::source_dir() / "scenes/conformance/far_camera.json");
  EXPECT_EQ(info.value("precision", ""), "float") << last_;
  EXPECT_TRUE(StderrHas(last_, {"prism: vulkan: warning: the device has no double precision (shaderFloat64)",
                                "object 1 (sphere): hit-point error", "object 3 (torus)"}));
  EXPECT_NE(info.value("precision_warning", "").find("object 2 (sphere)"), std::string::npos) << info.dump(2);
  EXPECT_TRUE(fs::exists(path("out.png")));
}

TEST_F(VulkanWithoutFloat64, AskingForDoubleWarnsAndRendersInFloat) {
  write("scene.json", SceneText().text());
  RunResult r = run({"render", path("scene.json").string(), "-b", "vulkan", "--precision", "double", "-o",
                     path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(StderrHas(r, {"runs in float although double was asked for"}));
}

}  // namespace
}  // namespace prism::cli_test
