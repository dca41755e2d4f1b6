// `mpirun -np 3 prism render ... --mpi` on this machine: the tiles dealt out
// over the ranks make exactly the picture a single process makes, for every
// backend, frames too; a rank that cannot start its backend leaves its tiles
// to the others; a rank killed mid-render ends the run with no output file.
#include <unistd.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <regex>

#include "prism/image_file.hpp"
#include "test_support.hpp"

namespace prism::test {
namespace {

namespace fs = std::filesystem;

fs::path prism() { return binary_dir() / "bin" / "prism"; }
fs::path scene() { return source_dir() / "scenes" / "conformance" / "showcase.json"; }

std::string host_name() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

struct Outcome {
  int status = -1;
  std::string out, err;
};

Outcome run(const std::vector<std::string>& args, const fs::path& folder) {
  static int runs = 0;
  const int n = ++runs;
  const CapturedRun r = run_captured(args, {}, folder / ("out." + std::to_string(n)), folder / ("err." + std::to_string(n)));
  EXPECT_TRUE(r.started) << r.start_error;
  return {r.exited ? r.status : 128 + r.signal, r.out, r.err};
}

std::vector<std::string> mpirun(int ranks) {
  return {PRISM_MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", std::to_string(ranks)};
}

// Render arguments after `prism`: small, 2 spp, every channel in the EXR.
std::vector<std::string> render_args(const std::string& backend, const fs::path& out) {
  return {prism().string(), "render", scene().string(), "-b", backend, "-o", out.string(),
          "--width", "80", "--height", "45", "--spp", "2", "--aov", "id,path,depth,normal,albedo"};
}

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Channel values (RGB and every AOV) that differ in their bits.
size_t differing(const fs::path& a, const fs::path& b) {
  const ImageFile x = read_image_file(a), y = read_image_file(b);
  if (x.width != y.width || x.height != y.height || x.channels != y.channels) return size_t(-1);
  size_t n = 0;
  for (size_t i = 0; i < x.pixels.size(); ++i) n += std::memcmp(&x.pixels[i], &y.pixels[i], sizeof(float)) != 0;
  return n;
}

class MpiRender : public testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!require_backend_or_skip(GetParam())) return;
    dir_ = fresh_temp_dir();
  }
  fs::path dir_;
};

TEST_P(MpiRender, TilesFromThreeRanksEqualOneProcess) {
  const Outcome single = run(render_args(GetParam(), dir_ / "single.exr"), dir_);
  ASSERT_EQ(single.status, 0) << single.err;
  const Outcome mpi = run(mpirun(3) + render_args(GetParam(), dir_ / "mpi.exr") + std::vector<std::string>{"--mpi", "--tile", "24"}, dir_);
  ASSERT_EQ(mpi.status, 0) << mpi.err;
  EXPECT_NE(mpi.err.find("3 ranks, 2 rendering: 8 tiles of 24 px"), std::string::npos) << mpi.err;
  EXPECT_EQ(differing(dir_ / "single.exr", dir_ / "mpi.exr"), 0u);
}

// Frames are dealt out the same way on every backend; Vulkan, which takes
// 12 s here (each rank builds its pipeline), shares the GPU tile path with OpenGL.
TEST_P(MpiRender, FramesFromThreeRanksEqualOneProcess) {
  if (GetParam() == "vulkan") GTEST_SKIP() << "covered by opengl: the same tiles, the same kernel";
  const std::vector<std::string> frames = {"--frames", "3", "--orbit", "60"};
  ASSERT_EQ(run(render_args(GetParam(), dir_ / "single_##.exr") + frames, dir_).status, 0);
  const Outcome mpi = run(mpirun(3) + render_args(GetParam(), dir_ / "mpi_##.exr") + frames +
                          std::vector<std::string>{"--mpi", "--tile", "32"}, dir_);
  ASSERT_EQ(mpi.status, 0) << mpi.err;
  for (const char* n : {"0000", "0001", "0002"}) {
    const fs::path single = dir_ / ("single_" + std::string(n) + ".exr"), distributed = dir_ / ("mpi_" + std::string(n) + ".exr");
    ASSERT_TRUE(fs::exists(distributed)) << distributed;
    EXPECT_EQ(differing(single, distributed), 0u) << n;
  }
  EXPECT_NE(differing(dir_ / "single_0000.exr", dir_ / "single_0001.exr"), 0u) << "the camera did not move";
}

PRISM_INSTANTIATE_BACKEND_TESTS(MpiRender);

class MpiFaults : public testing::Test {
 protected:
  void SetUp() override { dir_ = fresh_temp_dir(); }
  fs::path dir_;
};

// Rank 2 runs with no Vulkan driver (VK_ICD_FILENAMES names no file): it
// says so, and ranks 1 renders every tile.
TEST_F(MpiFaults, ARankThatCannotStartItsBackendLeavesItsTilesToTheOthers) {
  if (!require_backend_or_skip("vulkan")) return;
  ASSERT_EQ(run(render_args("vulkan", dir_ / "single.exr"), dir_).status, 0);
  const std::vector<std::string> mpi = {"--mpi", "--tile", "16"};
  const Outcome r = run(std::vector<std::string>{PRISM_MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", "2"} +
                        render_args("vulkan", dir_ / "mpi.exr") + mpi +
                        std::vector<std::string>{":", "-np", "1", "env", "VK_ICD_FILENAMES=/nonexistent/icd.json"} +
                        render_args("vulkan", dir_ / "mpi.exr") + mpi,
                    dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("rank 2 on " + host_name() + " cannot start its backend"), std::string::npos) << r.err;
  EXPECT_EQ(differing(dir_ / "single.exr", dir_ / "mpi.exr"), 0u);
}

// Rank 2 is killed (SIGKILL) two seconds in, mid-render: Open MPI ends the
// job, mpirun names the rank and host, and no output file, whole or partial,
// is left in the output folder. The render would take some 20 s whole (at
// 640x360, 16 spp it once finished in 1.4 s, before the kill).
TEST_F(MpiFaults, AKilledRankEndsTheRunWithNoPartialFile) {
  const fs::path out = dir_ / "out";
  fs::create_directory(out);
  const std::vector<std::string> args = {prism().string(), "render", scene().string(), "-b", "reference",
                                         "-o", (out / "big.png").string(), "--width", "1280", "--height", "720",
                                         "--spp", "64", "--mpi", "--tile", "32"};
  const Outcome r = run(std::vector<std::string>{PRISM_MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", "2"} +
                        args + std::vector<std::string>{":", "-np", "1", "timeout", "-s", "KILL", "2"} + args,
                    dir_);
  EXPECT_NE(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("rank 2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(host_name()), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(out)) << "left behind: " << fs::directory_iterator(out)->path();
}

TEST_F(MpiFaults, ABadSceneStopsEveryRankWithTheLoadersError) {
  write_file(dir_ / "bad.json", R"({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
                                     "objects": [{"type": "sphere", "radius": -1}]})");
  const Outcome r = run(mpirun(3) + std::vector<std::string>{prism().string(), "render", (dir_ / "bad.json").string(), "-b",
                                                         "reference", "-o", (dir_ / "x.png").string(), "--mpi"},
                    dir_);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("objects[0].radius: must be > 0, got -1"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

// The summary line of any render, printed once, by rank 0, after the MPI
// report; --threads holds on every rendering rank; the ranks' rays add up
// to what one process traces for the same image.
class MpiSummary : public testing::Test {
 protected:
  void SetUp() override { dir_ = fresh_temp_dir(); }
  std::vector<std::string> args(const fs::path& out) const {
    return {prism().string(), "render", scene().string(), "-b", "reference", "-o", out.string(),
            "--width", "80", "--height", "45", "--spp", "2"};
  }
  fs::path dir_;
};

const std::string kTimeAndRate = R"([0-9]+(\.[0-9])? m?s, [0-9]+\.[0-9] [kM]rays/s)";

size_t occurrences(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST_F(MpiSummary, ThreeRanksEndWithTheSummaryLineAndKeepToThreads) {
  const Outcome single = run(args(dir_ / "single.png") + std::vector<std::string>{"--stats", (dir_ / "single.json").string()}, dir_);
  ASSERT_EQ(single.status, 0) << single.err;
  const fs::path out = dir_ / "mpi.png";
  const Outcome mpi = run(mpirun(3) + args(out) +
                              std::vector<std::string>{"--mpi", "--tile", "24", "--threads", "1", "--stats",
                                                       (dir_ / "mpi.json").string()},
                          dir_);
  ASSERT_EQ(mpi.status, 0) << mpi.err;
  EXPECT_EQ(occurrences(mpi.err, "wrote "), 1u) << mpi.err;
  EXPECT_TRUE(std::regex_search(mpi.err, std::regex("prism: mpi: 3 ranks, .*\nwrote " + out.string() +
                                                    ": reference, 80x45, 2 spp, " + kTimeAndRate + "\n$")))
      << mpi.err;
  const auto stats = nlohmann::json::parse(read_file(dir_ / "mpi.json"));
  ASSERT_EQ(stats["workers"].size(), 2u) << stats;
  uint64_t rays = 0;
  for (const auto& worker : stats["workers"]) {
    EXPECT_EQ(worker["threads"], 1) << worker;
    rays += worker["rays"].get<uint64_t>();
  }
  const auto whole = nlohmann::json::parse(read_file(dir_ / "single.json"));
  EXPECT_EQ(rays, whole["rays"].get<uint64_t>());
}

TEST_F(MpiSummary, OneRankPrintsTheSummaryLineToo) {
  const fs::path out = dir_ / "one.png";
  const Outcome r = run(mpirun(1) + args(out) + std::vector<std::string>{"--mpi"}, dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::regex_match(r.err, std::regex("wrote " + out.string() + ": reference, 80x45, 2 spp, " + kTimeAndRate + "\n")))
      << r.err;
}

TEST_F(MpiSummary, QuietLeavesTheSummaryOut) {
  const Outcome r = run(mpirun(3) + args(dir_ / "q.png") + std::vector<std::string>{"--mpi", "-q"}, dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("wrote "), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "q.png"));
}

// A bad count is said once, by rank 0, and every rank stops.
TEST_F(MpiSummary, BadThreadsAreRejectedOnce) {
  const Outcome r = run(mpirun(3) + args(dir_ / "x.png") + std::vector<std::string>{"--mpi", "--threads", "0"}, dir_);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(occurrences(r.err, "prism: error: --threads: must be at least 1, got 0\n"), 1u) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

}  // namespace
}  // namespace prism::test
