// The Vulkan runtime under the backend: the validation layer really is on
// in the test run (a deliberate misuse must be reported), glslang's errors
// point at lines of the generated source, device choice, and failures that
// must end with a clear message rather than a crash or a hang.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <string>

#include "prism/errors.hpp"
#include "test_support.hpp"
#include "vk_buffer.hpp"
#include "vk_compiler.hpp"
#include "vk_context.hpp"
#include "vk_pipeline.hpp"

namespace prism::vk {
namespace {

// A Context, or a skip (a failure where PRISM_REQUIRE_BACKENDS names vulkan).
std::unique_ptr<Context> context_or_skip(bool validation) {
  try {
    return std::make_unique<Context>(validation);
  } catch (const RuntimeError& e) {
    if (prism::test::backend_required("vulkan")) ADD_FAILURE() << e.what();
    else GTEST_LOG_(INFO) << "no Vulkan here: " << e.what();
    return nullptr;
  }
}

// Sets an environment variable for the life of the object.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_) ::setenv(name_, old_->c_str(), 1);
    else ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(VulkanValidation, TheTestRunTurnsItOn) { EXPECT_TRUE(validation_requested()); }

TEST(VulkanValidation, ADeliberateMisuseIsReported) {
  auto context = context_or_skip(true);
  if (!context) GTEST_SKIP();
  ASSERT_TRUE(context->validation());
  EXPECT_EQ(context->validation_message_count(), 0u);
  // A buffer with no usage flags breaks VUID-VkBufferCreateInfo-usage-requiredbitmask.
  auto info = make<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  info.size = 64;
  info.usage = 0;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = context->api().vkCreateBuffer(context->device(), &info, nullptr, &buffer);
  if (result == VK_SUCCESS) context->api().vkDestroyBuffer(context->device(), buffer, nullptr);
  ASSERT_GE(context->validation_message_count(), 1u);
  EXPECT_NE(context->validation_messages()[0].find("VUID-VkBufferCreateInfo-usage"), std::string::npos)
      << context->validation_messages()[0];
}

TEST(VulkanValidation, CorrectUseIsSilent) {
  auto context = context_or_skip(true);
  if (!context) GTEST_SKIP();
  Commands commands(*context);
  const double values[4] = {1, 2, 3, 4};
  Buffer stored = upload_storage(*context, commands, values, sizeof values, "test upload");
  EXPECT_EQ(stored.size(), sizeof values);
  EXPECT_EQ(context->validation_message_count(), 0u);
}

TEST(VulkanCompiler, CompilesAComputeShaderToSpirv) {
  CompileError error;
  const std::vector<uint32_t> spirv = compile_compute_shader(
      "#version 450\nlayout(local_size_x = 1) in;\n"
      "layout(std430, binding = 0) buffer B { double v[]; };\nvoid main() { v[0] = 2.0LF * v[1]; }\n",
      error);
  ASSERT_FALSE(spirv.empty()) << error.log;
  EXPECT_EQ(spirv[0], 0x07230203u);  // the SPIR-V magic number
}

// SPIR-V instructions with opcode `op` (the low half of each
// instruction's first word; the module's header is 5 words).
int count_opcode(const std::vector<uint32_t>& spirv, uint32_t op) {
  int count = 0;
  for (size_t at = 5; at < spirv.size(); at += spirv[at] >> 16) {
    if ((spirv[at] & 0xffffu) == op) ++count;
    if ((spirv[at] >> 16) == 0) break;  // malformed: a zero word count would loop forever
  }
  return count;
}

// A helper called twice is inlined and an uncalled one dropped: one
// function (main) and no call are left, in fewer words than glslang's.
TEST(VulkanCompiler, ShrinkingInlinesCallsAndDropsDeadFunctions) {
  const std::string source =
      "#version 450\nlayout(local_size_x = 1) in;\n"
      "layout(std430, binding = 0) buffer B { double v[]; };\n"
      "double twice(double x) { return 2.0LF * x; }\n"
      "double unused(double x) { return x * x; }\n"
      "void main() { v[0] = twice(v[1]) + twice(v[2]); }\n";
  CompileError error;
  const std::vector<uint32_t> plain = compile_compute_shader(source, error, Shrink::no);
  ASSERT_FALSE(plain.empty()) << error.log;
  const std::vector<uint32_t> shrunk = compile_compute_shader(source, error, Shrink::yes);
  ASSERT_FALSE(shrunk.empty()) << error.log;
  constexpr uint32_t kOpFunction = 54, kOpFunctionCall = 57;
  EXPECT_EQ(count_opcode(plain, kOpFunctionCall), 2);
  EXPECT_EQ(count_opcode(shrunk, kOpFunction), 1);
  EXPECT_EQ(count_opcode(shrunk, kOpFunctionCall), 0);
  EXPECT_LT(shrunk.size(), plain.size());
  EXPECT_EQ(shrunk[0], 0x07230203u);
}

TEST(VulkanCompiler, ErrorsNameTheLineOfTheGeneratedSource) {
  CompileError error;
  const std::vector<uint32_t> spirv =
      compile_compute_shader("#version 450\nlayout(local_size_x = 1) in;\nvoid main() {\n  float x = undefined_name;\n}\n", error);
  EXPECT_TRUE(spirv.empty());
  EXPECT_NE(error.log.find("kernel:4:"), std::string::npos) << error.log;
  EXPECT_NE(error.log.find("undefined_name"), std::string::npos) << error.log;
}

// Through the pipeline builder: the message carries the log and the saved
// source, whose line 4 is the faulty one.
TEST(VulkanCompiler, AFailedBuildSavesTheSourceItsLogRefersTo) {
  auto context = context_or_skip(false);
  if (!context) GTEST_SKIP();
  ScopedEnv cache("PRISM_CACHE_DIR", prism::test::fresh_temp_dir().string());
  PipelineLayout layout(*context);
  PipelineStats stats;
  const std::string source = "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {\n  int y = 1.5;\n}\n";
  try {
    build_pipeline(*context, layout, source, stats);
    FAIL() << "the faulty kernel built";
  } catch (const RuntimeError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("does not compile for Vulkan"), std::string::npos) << message;
    EXPECT_NE(message.find("kernel:4:"), std::string::npos) << message;
    const size_t at = message.find("source saved to ");
    ASSERT_NE(at, std::string::npos) << message;
    const std::string file = message.substr(at + 16, message.find(", line numbers") - at - 16);
    std::ifstream in(file);
    std::string line;
    for (int i = 0; i < 4; ++i) std::getline(in, line);
    EXPECT_EQ(line, "  int y = 1.5;");
  }
  EXPECT_EQ(stats.glslang_compile_calls, 1);
}

TEST(VulkanDevice, ChosenByIndexOrByAnyCaseOfPartOfItsName) {
  auto first = context_or_skip(false);
  if (!first) GTEST_SKIP();
  std::string name = first->properties().deviceName;
  std::string shouted;
  for (char c : name.substr(0, 5)) shouted += char(std::toupper(static_cast<unsigned char>(c)));
  {
    ScopedEnv device("PRISM_VULKAN_DEVICE", shouted);
    EXPECT_EQ(std::string(Context(false).properties().deviceName), name);
  }
  ScopedEnv device("PRISM_VULKAN_DEVICE", "no device is called this");
  try {
    Context context(false);
    FAIL() << "a device was chosen";
  } catch (const RuntimeError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("PRISM_VULKAN_DEVICE=no device is called this matches no Vulkan device"), std::string::npos)
        << message;
    EXPECT_NE(message.find("0: " + name), std::string::npos) << message;  // the list of what there is
  }
}

TEST(VulkanDevice, AMissingLoaderIsNamed) {
  ScopedEnv loader("PRISM_VULKAN_LOADER", "/nonexistent/libvulkan.so.1");
  try {
    Context context(false);
    FAIL() << "a context was created";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("no Vulkan loader (/nonexistent/libvulkan.so.1"), std::string::npos) << e.what();
  }
}

TEST(VulkanDevice, AMissingDriverIsNamed) {
  ScopedEnv icd("VK_ICD_FILENAMES", "/nonexistent/icd.json");
  ScopedEnv driver("VK_DRIVER_FILES", "/nonexistent/icd.json");
  try {
    Context context(false);
    FAIL() << "a context was created";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("no Vulkan driver"), std::string::npos) << e.what();
  }
}

TEST(VulkanMemory, ABufferLargerThanTheHeapIsOutOfDeviceMemory) {
  auto context = context_or_skip(true);
  if (!context) GTEST_SKIP();
  try {
    Buffer huge(*context, VkDeviceSize(1) << 60, VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::Device, "test allocation");
    FAIL() << "an exabyte buffer was allocated";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("Vulkan failed during test allocation: out of device memory"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(context->validation_message_count(), 0u);
}

TEST(VulkanMemory, AStorageBufferBeyondTheDeviceRangeIsRefused) {
  auto context = context_or_skip(false);
  if (!context) GTEST_SKIP();
  const VkDeviceSize limit = context->properties().limits.maxStorageBufferRange;
  try {
    Buffer big(*context, limit + 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, Memory::Device, "test allocation");
    FAIL() << "a storage buffer beyond maxStorageBufferRange was made";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("this device allows " + std::to_string(limit)), std::string::npos) << e.what();
  }
}

TEST(VulkanErrors, DeviceLossAndOutOfMemoryAreToldInWords) {
  try {
    check(VK_ERROR_DEVICE_LOST, "rendering");
    FAIL();
  } catch (const RuntimeError& e) {
    EXPECT_STREQ(e.what(),
                 "Vulkan failed during rendering: the device was lost (the driver crashed, reset the GPU or hit its "
                 "watchdog) (VK_ERROR_DEVICE_LOST)");
  }
  try {
    check(VK_ERROR_OUT_OF_DEVICE_MEMORY, "upload of the BVH");
    FAIL();
  } catch (const RuntimeError& e) {
    EXPECT_STREQ(e.what(), "Vulkan failed during upload of the BVH: out of device memory (VK_ERROR_OUT_OF_DEVICE_MEMORY)");
  }
  EXPECT_NO_THROW(check(VK_SUCCESS, "anything"));
}

}  // namespace
}  // namespace prism::vk
