// Output safety: SIGINT or SIGTERM during `prism render` / `prism trace`
// stops the run within a tile or a dispatch, exits 130 / 143, removes its
// temporary file and leaves an older output byte for byte as it was; an
// output that cannot be written is refused before anything is rendered.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "cli_harness.hpp"
#include "test_support.hpp"

extern char** environ;

namespace prism::cli_test {
namespace {

using Clock = std::chrono::steady_clock;

// A run started in the background.
struct Started {
  int pid = -1;
  fs::path out, err;
  std::string command;
};

// CPU seconds (user + system) process `pid` has used; -1 when it cannot be read.
double cpu_seconds(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t paren = text.rfind(')');  // the command name may hold spaces
  if (paren == std::string::npos) return -1;
  std::istringstream fields(text.substr(paren + 2));
  std::string skip;
  for (int field = 3; field < 14; ++field) fields >> skip;  // state .. cmajflt
  long utime = 0, stime = 0;
  fields >> utime >> stime;
  return double(utime + stime) / double(::sysconf(_SC_CLK_TCK));
}

// The slow scene: the base scene at 2048x2048 and 64 spp (minutes on every
// backend here), so a run that ends within seconds was stopped.
std::string slow_scene() {
  SceneText s;
  s.image = R"({"width": 2048, "height": 2048, "spp": 64})";
  return s.text();
}

// 4,000 spheres in a grid: the reference backend tests each ray against all
// of them, so tracing the 400,000 rays of many_rays() takes ~15 s of CPU.
std::string many_spheres_scene() {
  std::string objects = "[";
  for (int i = 0; i < 4000; ++i) {
    if (i) objects += ", ";
    objects += R"({"type": "sphere", "radius": 0.2, "center": [)" + std::to_string(i % 80 - 40) + ", " +
               std::to_string(i / 80 - 25) + ", 10]}";
  }
  SceneText s;
  s.objects = objects + "]";
  return s.text();
}

std::string many_rays() {
  std::string rays;
  for (int i = 0; i < 400000; ++i)
    rays += "0,0,-5," + std::to_string((i % 400 - 200) * 0.005) + "," + std::to_string((i / 400 - 500) * 0.002) + ",1\n";
  return rays;
}

class Interrupt : public CliTest {
 protected:
  // Starts prism with `args` as CliTest::run does, without waiting for it.
  Started start(const std::vector<std::string>& args, const std::string& plugin_path = "") {
    Started s;
    std::vector<std::string> argv = {prism_binary().string()};
    argv.insert(argv.end(), args.begin(), args.end());
    for (const auto& a : argv) s.command += (s.command.empty() ? "" : " ") + a;
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e)
      if (std::strncmp(*e, "PRISM_PLUGIN_PATH=", 18) != 0) env.emplace_back(*e);
    if (!plugin_path.empty()) env.push_back("PRISM_PLUGIN_PATH=" + plugin_path);
    // Outside dir(): the test checks that the run left nothing in it.
    s.out = dir().parent_path() / ("bg.out." + std::to_string(++started_));
    s.err = dir().parent_path() / ("bg.err." + std::to_string(started_));
    const int rc = prism::test::spawn_with_output(argv, env, s.out, s.err, {}, s.pid);
    EXPECT_EQ(rc, 0) << "cannot start " << s.command << ": " << std::strerror(rc);
    return s;
  }

  // Waits until the run has used `cpu` seconds of CPU (past loading: it is
  // rendering or compiling its kernel); false when it ended first or never got there.
  bool wait_until_busy(const Started& s, double cpu) {
    const auto deadline = Clock::now() + std::chrono::seconds(120);
    while (Clock::now() < deadline) {
      int wstatus = 0;
      if (::waitpid(s.pid, &wstatus, WNOHANG) == s.pid) {
        finished_early_ = true;
        return false;
      }
      if (cpu_seconds(s.pid) >= cpu) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  // Sends `signal` and waits for the run; `seconds` is how long it took to end.
  RunResult interrupt(const Started& s, int signal, double& seconds) {
    const auto sent = Clock::now();
    ::kill(s.pid, signal);
    RunResult r = wait_for(s);
    seconds = std::chrono::duration<double>(Clock::now() - sent).count();
    return r;
  }

  RunResult wait_for(const Started& s) {
    RunResult r;
    r.command = s.command;
    int wstatus = 0;
    while (::waitpid(s.pid, &wstatus, 0) < 0 && errno == EINTR) {
    }
    r.exited = WIFEXITED(wstatus);
    r.status = r.exited ? WEXITSTATUS(wstatus) : -1;
    r.signal = WIFSIGNALED(wstatus) ? WTERMSIG(wstatus) : 0;
    r.out = read_file(s.out);
    r.err = read_file(s.err);
    return r;
  }

  // Ends a run the test gave up on, so it does not outlive the test.
  void kill_and_reap(const Started& s) {
    if (finished_early_) return;
    ::kill(s.pid, SIGKILL);
    wait_for(s);
  }

  // Renders the slow scene with `backend` over an existing out.png and
  // stats.json, interrupts it with `signal` once it is busy, and checks the
  // exit status, that it ended within `max_seconds`, and that the folder
  // and both old files are exactly as they were.
  void render_and_interrupt(const std::string& backend, int signal, int status, double busy_cpu, double max_seconds) {
    const std::string old = "an older picture\n";
    write("out.png", old);
    write("stats.json", old);
    const fs::path scene = write("scene.json", slow_scene());
    const auto before = list_folder(dir());
    Started s = start({"render", scene.string(), "-b", backend, "-o", path("out.png").string(), "--stats",
                       path("stats.json").string()});
    ASSERT_GT(s.pid, 0);
    if (!wait_until_busy(s, busy_cpu)) {
      kill_and_reap(s);
      FAIL() << s.command << (finished_early_ ? " ended before it was interrupted" : " never got busy") << "\n"
             << read_file(s.err);
    }
    double seconds = 0;
    RunResult r = interrupt(s, signal, seconds);
    EXPECT_TRUE(ExitedWith(r, status));
    EXPECT_TRUE(StderrHas(r, {"interrupted"}));
    EXPECT_LT(seconds, max_seconds) << r;
    EXPECT_EQ(list_folder(dir()), before) << r;  // no temporary file left behind
    EXPECT_EQ(read_file(path("out.png")), old);
    EXPECT_EQ(read_file(path("stats.json")), old);
  }

  int started_ = 0;
  bool finished_early_ = false;
};

// One test per backend the test support finds (skipped where it cannot run).
class InterruptRender : public Interrupt, public testing::WithParamInterface<std::string> {};

TEST_P(InterruptRender, SigintLeavesTheOldOutputAndExits130) {
  if (!prism::test::require_backend_or_skip(GetParam())) return;
  const bool gpu = GetParam() == "opengl" || GetParam() == "vulkan";
  // GPU backends: the signal may come while the kernel compiles (CPU time
  // on the llvmpipe/lavapipe drivers here); the run stops at the first tile.
  render_and_interrupt(GetParam(), SIGINT, 130, 1.0, gpu ? 60.0 : 10.0);
}

INSTANTIATE_TEST_SUITE_P(Backends, InterruptRender, testing::ValuesIn(prism::test::backend_names()),
                         prism::test::backend_param_name);

// A GPU kernel compile (seconds of the driver's CPU time here) looks at no
// cancel request: Ctrl-C during one ends the run at once, well inside the
// grace period, and leaves the old output. The program caches point at
// empty folders so the showcase's kernel is compiled.
class InterruptCompile : public Interrupt, public testing::WithParamInterface<std::string> {};

TEST_P(InterruptCompile, SigintDuringAKernelCompileEndsAtOnce) {
  if (!prism::test::require_backend_or_skip(GetParam())) return;
  const fs::path caches = dir().parent_path() / "compile-caches";  // outside dir(): compared below
  fs::remove_all(caches);
  ::setenv("PRISM_CACHE_DIR", (caches / "prism").c_str(), 1);
  ::setenv("MESA_SHADER_CACHE_DIR", (caches / "mesa").c_str(), 1);
  const std::string old = "an older picture\n";
  write("out.png", old);
  const auto before = list_folder(dir());
  Started s = start({"render", (prism::test::source_dir() / "scenes/showcase.json").string(), "-b", GetParam(), "-o",
                     path("out.png").string()});
  ASSERT_GT(s.pid, 0);
  const std::string notice = "compiling the " + GetParam() + " kernel for this scene";
  const auto give_up = Clock::now() + std::chrono::seconds(60);
  while (read_file(s.err).find(notice) == std::string::npos && Clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // inside the compile (seconds)
  double seconds = 0;
  RunResult r = interrupt(s, SIGINT, seconds);
  ::unsetenv("PRISM_CACHE_DIR");
  ::unsetenv("MESA_SHADER_CACHE_DIR");
  EXPECT_TRUE(ExitedWith(r, 130));
  EXPECT_TRUE(StderrHas(r, {notice, "interrupted while compiling a GPU kernel"}));
  EXPECT_LT(seconds, 1.0) << r;  // the grace period is kStopGraceSeconds, 2 s
  EXPECT_EQ(list_folder(dir()), before) << r;
  EXPECT_EQ(read_file(path("out.png")), old);
}

INSTANTIATE_TEST_SUITE_P(Backends, InterruptCompile, testing::ValuesIn(prism::test::gpu_backend_names()),
                         prism::test::backend_param_name);

// A primitive plugin whose intersect never returns: the run can never reach
// a cancel check. kStopGraceSeconds (2 s) after SIGTERM it is ended anyway,
// with 143, the older output untouched and no temporary file left.
TEST_F(Interrupt, SigtermEndsARunStuckInAPlugin) {
  const fs::path plugins = dir().parent_path() / "hang_plugins";  // outside dir(): compared below
  fs::create_directories(plugins);
  fs::copy_file(bad_plugin_folder() / "libprism_primitive_hang.so", plugins / "libprism_primitive_hang.so",
                fs::copy_options::overwrite_existing);
  const std::string old = "an older picture\n";
  write("out.png", old);
  SceneText scene_text;
  scene_text.objects = R"([{"type": "hang", "radius": 1}])";
  const fs::path scene = write("scene.json", scene_text.text());
  const auto before = list_folder(dir());
  Started s = start({"render", scene.string(), "-b", "reference", "-o", path("out.png").string()}, plugins.string());
  ASSERT_GT(s.pid, 0);
  if (!wait_until_busy(s, 0.5)) {
    kill_and_reap(s);
    FAIL() << s.command << " did not get stuck\n" << read_file(s.err);
  }
  ::kill(s.pid, SIGTERM);
  // Without the deadline it never ends: give up (and fail) after 60 s.
  int wstatus = 0;
  const auto give_up = Clock::now() + std::chrono::seconds(60);
  while (::waitpid(s.pid, &wstatus, WNOHANG) != s.pid) {
    if (Clock::now() > give_up) {
      kill_and_reap(s);
      FAIL() << s.command << " ignored SIGTERM";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 143) << "status " << wstatus << "\n" << read_file(s.err);
  EXPECT_NE(read_file(s.err).find("interrupted, and the run did not stop within the grace period"), std::string::npos) << read_file(s.err);
  EXPECT_EQ(list_folder(dir()), before);
  EXPECT_EQ(read_file(path("out.png")), old);
}

TEST_F(Interrupt, SigtermEndsARenderWith143) { render_and_interrupt("reference", SIGTERM, 143, 1.0, 10.0); }

TEST_F(Interrupt, SigintStopsATraceAndLeavesTheOldOutput) {
  const std::string old = "an older answer\n";
  write("hits.csv", old);
  const fs::path scene = write("scene.json", many_spheres_scene());
  const fs::path rays = write("rays.csv", many_rays());
  const auto before = list_folder(dir());
  Started s = start({"trace", scene.string(), "-b", "reference", "--rays", rays.string(), "-o",
                     path("hits.csv").string()});
  ASSERT_GT(s.pid, 0);
  // 1.5 s of CPU: past loading the scene and reading the rays (~0.3 s).
  if (!wait_until_busy(s, 1.5)) {
    kill_and_reap(s);
    FAIL() << s.command << (finished_early_ ? " ended before it was interrupted" : " never got busy");
  }
  double seconds = 0;
  RunResult r = interrupt(s, SIGINT, seconds);
  EXPECT_TRUE(ExitedWith(r, 130));
  EXPECT_LT(seconds, 10.0) << r;
  EXPECT_EQ(list_folder(dir()), before) << r;
  EXPECT_EQ(read_file(path("hits.csv")), old);
}

// ------------------------------------------------ outputs that cannot be written

// Each is refused with exit 1 (the spec's status for an output that cannot
// be written) before the slow scene is rendered: a render would take minutes.
class UnwritableOutput : public CliTest {
 protected:
  void expect_refused_quickly(const fs::path& output, const std::string& expect) {
    const fs::path scene = write("scene.json", slow_scene());
    const auto t0 = Clock::now();
    RunResult r = run({"render", scene.string(), "-b", "reference", "-o", output.string()});
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    EXPECT_TRUE(ExitedWith(r, 1));
    EXPECT_TRUE(StderrHas(r, {expect}));
    EXPECT_LT(seconds, 20.0) << r;
  }
};

TEST_F(UnwritableOutput, ReadOnlyFolder) {
  const fs::path folder = path("readonly");
  fs::create_directory(folder);
  fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec);
  if (::access(folder.c_str(), W_OK) == 0) {
    fs::permissions(folder, fs::perms::owner_all);
    GTEST_SKIP() << "permissions do not stop this user (root): see SystemFolderThatTakesNoFiles";
  }
  expect_refused_quickly(folder / "out.png", "readonly");
  fs::permissions(folder, fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(folder));
}

// /proc takes no new files even for root, although access(W_OK) allows it
// there: the check must try to create the file.
TEST_F(UnwritableOutput, SystemFolderThatTakesNoFiles) {
  expect_refused_quickly("/proc/prism-out.png", "/proc/prism-out.png");
}

TEST_F(UnwritableOutput, MissingFolder) { expect_refused_quickly(path("nosuch/out.png"), "does not exist"); }

TEST_F(UnwritableOutput, TargetIsAFolder) {
  fs::create_directory(path("out.png"));
  expect_refused_quickly(path("out.png"), "is a folder");
  EXPECT_TRUE(fs::is_empty(path("out.png")));
}

}  // namespace
}  // namespace prism::cli_test
