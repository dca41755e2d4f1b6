// GPU program caches, counted rather than timed: a backend that reports a
// `program_cache` in --stats must, on the second render of the same scene,
// make no compile or link call of its own (every counter named *compile* or
// *link* is 0) and report a cache hit with the same image; a cache file that
// is corrupt, truncated or stale (another driver version wrote it) is
// detected, rebuilt (compile calls again) and rewritten.
// Mesa's own shader cache is pointed at a fresh folder (llvmpipe offers a
// program-binary format only while its disk cache is on).
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "test_support.hpp"

namespace prism::cli_test {
namespace {

using nlohmann::json;

class ProgramCache : public CliTest, public testing::WithParamInterface<std::string> {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    ::setenv("MESA_SHADER_CACHE_DIR", path("mesa-cache").c_str(), 1);
    ::setenv("PRISM_CACHE_DIR", path("prism-cache").c_str(), 1);
  }

  // Renders the scene; returns its --stats, or null when the backend cannot run here.
  json render(const std::string& backend, const std::string& out) {
    RunResult r = run({"render", path("scene.json").string(), "-b", backend, "-o", path(out).string(), "--stats",
                       path(out + ".json").string()});
    if (!prism::test::backend_required(backend) && r.exited && r.status == 1) return nullptr;
    EXPECT_TRUE(ExitedWith(r, 0));
    last_err_ = r.err;
    return json::parse(read_file(path(out + ".json")));
  }

  // Whether the last render said, before compiling, that it compiles and why.
  bool said_compile(const std::string& backend, const std::string& why) const {
    return last_err_.find("prism: compiling the " + backend + " kernel for this scene (" + why + ")\u2026\n") !=
           std::string::npos;
  }

  std::string last_err_;  // stderr of the last render
};

double compile_and_link_calls(const json& stats) {
  double calls = 0;
  if (!stats.contains("counters")) return 0;
  for (const auto& [name, value] : stats["counters"].items())
    if (name.find("compile") != std::string::npos || name.find("link") != std::string::npos) calls += value.get<double>();
  return calls;
}

uint64_t fnv1a64(const std::string& bytes, size_t from) {
  uint64_t h = 14695981039346656037ull;
  for (size_t i = from; i < bytes.size(); ++i) {
    h ^= static_cast<unsigned char>(bytes[i]);
    h *= 1099511628211ull;
  }
  return h;
}

// Rewrites a cache file as if another driver version had written it;
// false for a format this test does not know.
bool make_stale(std::string& file) {
  if (file.compare(0, 8, "PRISMGLB") == 0) {
    // backends/opengl/gl_program.cpp: a 48-byte header with an FNV-1a
    // checksum of the binary at offset 24. A binary the driver refuses.
    for (size_t i = 48; i < file.size(); ++i) file[i] = char(i * 7);
    const uint64_t h = fnv1a64(file, 48);
    file.replace(24, 8, reinterpret_cast<const char*>(&h), 8);
    return true;
  }
  if (file.compare(0, 8, "PRISMVKC") == 0) {
    // backends/vulkan/vk_pipeline.cpp: the writing driver's pipeline-cache
    // UUID at offset 48 (16 bytes), outside the checksummed payload.
    for (size_t i = 48; i < 64; ++i) file[i] = char(~file[i]);
    return true;
  }
  return false;
}

TEST_P(ProgramCache, SecondRenderCompilesNothingAndCorruptFilesAreRebuilt) {
  const std::string backend = GetParam();
  SceneText scene;
  scene.image = R"({"width": 32, "height": 24})";
  write("scene.json", scene.text());
  json first = render(backend, "first.png");
  if (first.is_null()) GTEST_SKIP() << backend << " cannot run here";
  if (!first.contains("info") || !first["info"].contains("program_cache"))
    GTEST_SKIP() << backend << " keeps no program cache";
  ASSERT_NE(first["info"]["program_cache"], "unsupported") << "the driver offers no program binary format";
  EXPECT_EQ(first["info"]["program_cache"], "miss");
  EXPECT_GT(compile_and_link_calls(first), 0);
  EXPECT_TRUE(said_compile(backend, "cached afterwards")) << last_err_;

  json second = render(backend, "second.png");
  EXPECT_EQ(second["info"]["program_cache"], "hit");
  EXPECT_EQ(compile_and_link_calls(second), 0);
  EXPECT_EQ(last_err_.find("compiling"), std::string::npos) << last_err_;
  EXPECT_EQ(read_file(path("first.png")), read_file(path("second.png")));

  // Corrupt the cached program: flip bytes in its middle.
  const fs::path cache_file = second["info"]["program_cache_file"].get<std::string>();
  std::string bytes = read_file(cache_file);
  ASSERT_GT(bytes.size(), 64u);
  for (size_t i = bytes.size() / 2; i < bytes.size() / 2 + 16; ++i) bytes[i] = char(~bytes[i]);
  write_file(cache_file, bytes);
  json third = render(backend, "third.png");
  EXPECT_EQ(third["info"]["program_cache"], "corrupt");
  EXPECT_TRUE(said_compile(backend, "its program-cache entry was damaged; cached afterwards")) << last_err_;
  EXPECT_GT(compile_and_link_calls(third), 0);
  EXPECT_EQ(read_file(path("first.png")), read_file(path("third.png")));

  // A truncated file is caught too, and the rewritten cache hits again.
  write_file(cache_file, bytes.substr(0, 10));
  EXPECT_EQ(render(backend, "fourth.png")["info"]["program_cache"], "corrupt");
  EXPECT_EQ(render(backend, "fifth.png")["info"]["program_cache"], "hit");

  // A well-formed file another driver version wrote (as after a driver
  // update) is "stale", and is rebuilt.
  std::string file = read_file(cache_file);
  ASSERT_TRUE(make_stale(file)) << "this test knows no stale form of " << backend << "'s cache files";
  write_file(cache_file, file);
  json stale = render(backend, "sixth.png");
  EXPECT_EQ(stale["info"]["program_cache"], "stale");
  EXPECT_TRUE(said_compile(backend, "the driver changed since it was cached; cached afterwards")) << last_err_;
  EXPECT_GT(compile_and_link_calls(stale), 0);
  EXPECT_EQ(read_file(path("first.png")), read_file(path("sixth.png")));
}

// A cache entry that is not a plausible file: a folder (the render failed),
// a link to /dev/zero or a 2 GB file (read whole: 15.8 GB, then bad_alloc).
// Each is a miss and the kernel is compiled again; the folder cannot be
// replaced, which is said once on stderr. A cache folder that cannot be
// written is said once too, not silently ignored.
// Both GPU backends read and write entries through gpu/program_cache.cpp:
// one of them is enough, and each case costs a kernel compile.
TEST_P(ProgramCache, OddEntriesAreMissesAndAnUnwritableCacheIsSaid) {
  const std::string backend = GetParam();
  if (backend != "opengl") GTEST_SKIP() << "run on opengl only (the cache code is shared)";
  SceneText scene;
  scene.image = R"({"width": 8, "height": 6})";
  write("scene.json", scene.text());
  json first = render(backend, "first.png");
  if (first.is_null()) GTEST_SKIP() << backend << " cannot run here";
  if (!first.contains("info") || !first["info"].contains("program_cache_file"))
    GTEST_SKIP() << backend << " keeps no program cache";
  const fs::path cache_file = first["info"]["program_cache_file"].get<std::string>();
  ASSERT_TRUE(fs::is_regular_file(cache_file));

  const auto render_with_entry = [&](const std::string& what, const std::function<void()>& make) {
    SCOPED_TRACE(what);
    fs::remove_all(cache_file);
    make();
    RunResult r = run({"render", path("scene.json").string(), "-b", backend, "-o", path("odd.png").string(), "--stats",
                       path("odd.json").string()});
    EXPECT_TRUE(ExitedWith(r, 0));
    const json stats = json::parse(read_file(path("odd.json")));
    EXPECT_EQ(stats["info"]["program_cache"], "miss");
    EXPECT_GT(compile_and_link_calls(stats), 0);
    return r;
  };
  RunResult folder = render_with_entry("a folder", [&] { fs::create_directory(cache_file); });
  EXPECT_TRUE(StderrHas(folder, {"warning: the program cache is not written"}));
  // A link to an endless stream that is not a regular file: a FIFO of the
  // test's own, not /dev/zero, which a writer that followed the link would
  // have replaced for the whole machine. The entry is replaced, not the FIFO.
  const fs::path fifo = path("endless-fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  render_with_entry("a link to a FIFO", [&] { fs::create_symlink(fifo, cache_file); });
  EXPECT_TRUE(fs::is_fifo(fifo));
  render_with_entry("a 2 GB file", [&] {
    write_file(cache_file, "");
    fs::resize_file(cache_file, std::uintmax_t(2) << 30);  // sparse: no disk space is used
  });
  fs::remove_all(cache_file);

  // PRISM_CACHE_DIR under a regular file: nothing can be created there.
  write_file(path("not-a-folder"), "");
  ::setenv("PRISM_CACHE_DIR", path("not-a-folder").c_str(), 1);
  RunResult r = run({"render", path("scene.json").string(), "-b", backend, "-o", path("nocache.png").string()});
  ::setenv("PRISM_CACHE_DIR", path("prism-cache").c_str(), 1);
  EXPECT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(StderrHas(r, {"warning: the program cache is not written"}));
  EXPECT_EQ(r.err.find("warning"), r.err.rfind("warning")) << "said more than once\n" << r;
}

INSTANTIATE_TEST_SUITE_P(Backends, ProgramCache, testing::ValuesIn(backends_built()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace prism::cli_test
