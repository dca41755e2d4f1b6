// What a run shows while it works (issue 23), in a pseudo-terminal: each long
// step before the bar (loading the scene, starting the backend, preparing
// the scene) on a line of its own with its clock, then the bar, whose ray
// rate shows from the first frame on every backend. Nothing of it when
// stderr is not a terminal, or with -q.
#include <cstdlib>
#include <regex>

#include "cli_harness.hpp"

namespace prism::cli_test {
namespace {

bool have_script() { return std::system("script --version > /dev/null 2>&1") == 0; }

class Progress : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    scene_ = write("scene.json", SceneText{}.text()).string();
  }
  // What `prism ARGS` wrote to its terminal: script(1) runs it on a
  // pseudo-terminal of its own and copies the output ("\n" as "\r\n").
  std::string on_a_terminal(const std::string& args) {
    const fs::path log = path("terminal." + std::to_string(++sessions_));
    const std::string script = "script -qec '" + prism_binary().string() + " " + args + "' /dev/null < /dev/null > " +
                               log.string();
    EXPECT_EQ(std::system(script.c_str()), 0) << script;
    return read_file(log);
  }
  std::string render_args(const std::string& backend, const std::string& more = "") {
    return "render " + scene_ + " -b " + backend + " -o " + path("out.png").string() + " --width 64 --height 48 " + more;
  }
  std::string scene_;
  int sessions_ = 0;
};

// The bar's segments, each from its "\r[" to the next "\r" or "\n".
std::vector<std::string> bar_segments(const std::string& terminal) {
  std::vector<std::string> segments;
  for (size_t at = terminal.find("\r["); at != std::string::npos; at = terminal.find("\r[", at + 1))
    segments.push_back(terminal.substr(at + 1, terminal.find_first_of("\r\n", at + 1) - at - 1));
  return segments;
}

const std::string kClock = R"([0-9]+(\.[0-9])? m?s)";

// "\r<what>... <clock>\033[K": a phase line as it is drawn.
bool shows_phase(const std::string& terminal, const std::string& what) {
  const std::string start = "\r" + what + "... ";
  const size_t at = terminal.find(start);
  if (at == std::string::npos) return false;
  return std::regex_search(terminal.begin() + std::ptrdiff_t(at + start.size()), terminal.end(),
                           std::regex(kClock + "\033\\[K"), std::regex_constants::match_continuous);
}

TEST_F(Progress, EachStepBeforeTheBarShowsWithItsClock) {
  if (!have_script()) GTEST_SKIP() << "no script(1)";
  const std::string terminal = on_a_terminal(render_args("reference"));
  EXPECT_TRUE(shows_phase(terminal, "loading " + scene_)) << terminal;
  EXPECT_TRUE(shows_phase(terminal, "starting reference")) << terminal;
  EXPECT_TRUE(shows_phase(terminal, "reference: preparing the scene")) << terminal;
  // In that order, each line cleared for the next, all before the bar.
  const size_t loading = terminal.find("\rloading "), starting = terminal.find("\rstarting reference"),
               preparing = terminal.find("\rreference: preparing"), bar = terminal.find("\r[");
  ASSERT_NE(bar, std::string::npos) << terminal;
  EXPECT_LT(loading, starting);
  EXPECT_LT(starting, preparing);
  EXPECT_LT(preparing, bar);
  EXPECT_EQ(terminal.substr(bar - 4, 4), "\r\033[K") << terminal;
  EXPECT_NE(terminal.find("\r\nwrote " + path("out.png").string() + ": reference, 64x48, 1 spp, "), std::string::npos)
      << terminal;
}

TEST_F(Progress, AutoSaysItIsChoosingTheBackend) {
  if (!have_script()) GTEST_SKIP() << "no script(1)";
  const std::string terminal = on_a_terminal(render_args("auto"));
  EXPECT_TRUE(shows_phase(terminal, "choosing the backend")) << terminal;
  EXPECT_TRUE(std::regex_search(terminal, std::regex("\r[a-z]+: preparing the scene\\.\\.\\. "))) << terminal;
}

TEST_F(Progress, TraceShowsItsStepsOnATerminal) {
  if (!have_script()) GTEST_SKIP() << "no script(1)";
  write("rays.csv", "0,0,-5,0,0,1\n0,0,-5,0,1,0\n");
  const std::string terminal = on_a_terminal("trace " + scene_ + " -b reference --rays " + path("rays.csv").string() +
                                             " -o " + path("hits.csv").string());
  EXPECT_TRUE(shows_phase(terminal, "starting reference")) << terminal;
  EXPECT_TRUE(shows_phase(terminal, "reference: preparing the scene")) << terminal;
  EXPECT_TRUE(shows_phase(terminal, "reference: tracing 2 rays")) << terminal;
  // Every step's line is cleared: the terminal is left as it was.
  EXPECT_EQ(terminal.substr(terminal.size() - 4), "\r\033[K") << terminal;
}

TEST_F(Progress, QuietShowsNothingOnATerminal) {
  if (!have_script()) GTEST_SKIP() << "no script(1)";
  EXPECT_EQ(on_a_terminal(render_args("reference", "-q")), "");
}

// Not a terminal: no step lines and no bar, only the summary (trace: nothing).
TEST_F(Progress, NoStepsWhenStderrIsNotATerminal) {
  const RunResult r = run({"render", scene_, "-b", "reference", "-o", path("out.png").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_EQ(r.err.rfind("wrote ", 0), 0u) << r;
  EXPECT_EQ(r.err.find("..."), std::string::npos) << r;
  write("rays.csv", "0,0,-5,0,0,1\n");
  const RunResult t = run({"trace", scene_, "-b", "reference", "--rays", path("rays.csv").string(), "-o",
                           path("hits.csv").string()});
  ASSERT_TRUE(ExitedWith(t, 0));
  EXPECT_EQ(t.err, "");
}

// The rate is on the very first bar drawn, after the first tile, on every
// backend built; and on frame 1 of a sequence, which has no earlier frame.
TEST_F(Progress, TheRayRateShowsFromTheFirstTile) {
  if (!have_script()) GTEST_SKIP() << "no script(1)";
  const std::regex with_rate(R"(\[[# ]{40}\] +[0-9]+%  )" + kClock + "(, " + kClock + R"( left)?, [0-9]+\.[0-9] [kM]rays/s)");
  for (const std::string& backend : backends_built()) {
    SCOPED_TRACE(backend);
    const std::vector<std::string> bars = bar_segments(on_a_terminal(render_args(backend)));
    ASSERT_FALSE(bars.empty());
    EXPECT_TRUE(std::regex_search(bars.front(), with_rate)) << bars.front();
  }
  const std::vector<std::string> frames = bar_segments(on_a_terminal(render_args("reference", "--frames 2")));
  ASSERT_FALSE(frames.empty());
  EXPECT_NE(frames.front().find("rays/s, frame 1/2"), std::string::npos) << frames.front();
}

}  // namespace
}  // namespace prism::cli_test
