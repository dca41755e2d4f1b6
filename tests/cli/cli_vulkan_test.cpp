// `prism list` and `prism render -b vulkan` on machines where Vulkan cannot
// run: the reason is named (no loader, no driver, no matching device), and a
// render that asks for vulkan there ends with exit status 1 and that reason.
#include <algorithm>
#include <cstdlib>
#include <sstream>

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

}  // namespace
}  // namespace prism::cli_test
