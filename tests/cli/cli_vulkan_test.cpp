// `prism list` and `prism render -b vulkan` on machines where Vulkan cannot
// run: the reason is named (no loader, no driver, no matching device), and a
// render that asks for vulkan there ends with exit status 1 and that reason.
#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "cli_harness.hpp"

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

}  // namespace
}  // namespace prism::cli_test
