// The command line's conventions (issue 23): versions, help and unknown
// commands; the summary line and the progress bar; --threads and -v; output
// formats by extension and `-o -`; a camera given by flags; which backend
// `-b auto` picks. Bad input is exit status 2 with a message naming it.
#include <signal.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "prism/image_file.hpp"

namespace prism::cli_test {
namespace {

const std::string kCommands = "list, render, trace, view, conform, bench, plugin, version, help";

bool has_backend(const std::string& name) {
  const auto built = backends_built();
  return std::find(built.begin(), built.end(), name) != built.end();
}

class Conventions : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    scene_ = write("scene.json", SceneText{}.text()).string();
  }
  RunResult render(const std::string& out, std::vector<std::string> more = {}) {
    std::vector<std::string> args = {"render", scene_, "-b", "reference", "-o", out};
    args.insert(args.end(), more.begin(), more.end());
    return run(args);
  }
  // Exit status 2, exactly `message` on stderr after "prism: error: ", and nothing new in the folder.
  void expect_rejected(const std::vector<std::string>& args, const std::string& message) {
    const auto before = list_folder(dir());
    const RunResult r = run(args);
    EXPECT_TRUE(ExitedWith(r, 2));
    EXPECT_EQ(r.err, "prism: error: " + message + "\n");
    EXPECT_EQ(list_folder(dir()), before) << r;
  }
  std::string scene_;
};

// ------------------------------------------------------- versions and help

TEST_F(Conventions, VersionFlagAndCommandPrintTheVersions) {
  const RunResult flag = run({"--version"});
  const RunResult command = run({"version"});
  ASSERT_TRUE(ExitedWith(flag, 0));
  ASSERT_TRUE(ExitedWith(command, 0));
  EXPECT_EQ(flag.out, command.out);
  // CMakeLists.txt's project version; PRISM_PRIMITIVE_ABI_VERSION and PRISM_BACKEND_ABI_VERSION.
  EXPECT_EQ(flag.out.rfind("prism 0.1.0\nplugin ABI: primitive 6, backend 9\nbackends:\n", 0), 0u) << flag;
  // The reference backend's plugin version and what its probe says.
  EXPECT_NE(flag.out.find("\n  reference   1.0.0    "), std::string::npos) << flag;
  if (has_backend("embree")) {
    EXPECT_NE(flag.out.find("\n  embree      1.0.0 (Embree "), std::string::npos) << flag;
  }
  EXPECT_EQ(flag.err, "");
}

TEST_F(Conventions, HelpCommandPrintsTheHelp) {
  const RunResult help = run({"help"});
  const RunResult flag = run({"--help"});
  ASSERT_TRUE(ExitedWith(help, 0));
  ASSERT_TRUE(ExitedWith(flag, 0));
  EXPECT_EQ(help.out, flag.out);
  for (const char* command : {"list", "render", "trace", "version", "help"})
    EXPECT_TRUE(std::regex_search(help.out, std::regex(std::string("\n  ") + command + " +[A-Z]"))) << command << "\n" << help;
  const RunResult render_help = run({"help", "render"});
  ASSERT_TRUE(ExitedWith(render_help, 0));
  EXPECT_NE(render_help.out.find("--camera-position"), std::string::npos) << render_help;
  EXPECT_EQ(render_help.out, run({"render", "--help"}).out);
  EXPECT_NE(render_help.out.find("\nUsage: prism render [OPTIONS] scene\n"), std::string::npos) << render_help;
}

TEST_F(Conventions, UnknownCommandIsNamedAndTheCommandsListed) {
  const std::string listed = " (commands: " + kCommands + "; `prism help` describes them)";
  expect_rejected({"frobnicate"}, "unknown command 'frobnicate'" + listed);
  expect_rejected({"frobnicate", "--spp", "3"}, "unknown command 'frobnicate'" + listed);
  expect_rejected({"help", "frobnicate"}, "unknown command 'frobnicate'" + listed);
  expect_rejected({}, "a command is required" + listed);
}

// CLI11 clutter (`INT:INT in [1 - 100000]`, `TEXT:FILE`) is gone; the defaults are said.
TEST_F(Conventions, RenderHelpShowsDefaultsWithoutTypeClutter) {
  const RunResult r = run({"render", "--help"});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_EQ(r.out.find("in ["), std::string::npos) << r;
  EXPECT_EQ(r.out.find("INT:"), std::string::npos) << r;
  EXPECT_NE(r.out.find("--frames INT "), std::string::npos) << r;
  EXPECT_NE(r.out.find("(default auto; `prism list` says which)"), std::string::npos) << r;
  EXPECT_NE(r.out.find("Samples per pixel, 1 to 4096 (default: the scene's)"), std::string::npos) << r;
}

TEST_F(Conventions, UnknownFlagsAreReportedInTheOrderGiven) {
  expect_rejected({"render", scene_, "-o", path("out.png").string(), "--zebra", "--aardvark", "--mole"},
                  "unexpected arguments: --zebra --aardvark --mole (`prism help render` lists the flags)");
  expect_rejected({"list", "--zebra"}, "unexpected argument: --zebra (`prism help list` lists the flags)");
  expect_rejected({"--versio"}, "unexpected argument: --versio (`prism help` lists the commands and options)");
}

// CLI11's other errors in Prism's form, with where to look.
TEST_F(Conventions, ParseErrorsSayWhereTheFlagsAreListed) {
  expect_rejected({"render", "-o", path("out.png").string()},
                  "scene is required (`prism help render` lists the flags)");
  expect_rejected({"render", scene_, "-o", path("out.png").string(), "--spp", "many"},
                  "Could not convert: --spp = many (`prism help render` lists the flags)");
}

// ------------------------------------------------------ summary and -q, -v

// "<number> ms" or "<number> s", then the ray rate where the backend counts rays.
const std::string kTimeAndRate = R"([0-9]+(\.[0-9])? m?s(, [0-9]+\.[0-9] [kM]rays/s)?)";

TEST_F(Conventions, ARenderEndsWithASummaryLine) {
  const std::string out = path("out.png").string();
  const RunResult r = render(out, {"--spp", "2"});
  ASSERT_TRUE(ExitedWith(r, 0));
  // stderr is not a terminal here: no bar, the summary only.
  EXPECT_TRUE(std::regex_match(r.err, std::regex("wrote " + out + ": reference, 8x6, 2 spp, " + kTimeAndRate + "\n")))
      << r;
}

TEST_F(Conventions, TheSummaryOfFramesNamesTheFirstAndLast) {
  const RunResult r = render(path("f.png").string(), {"--frames", "3"});
  ASSERT_TRUE(ExitedWith(r, 0));
  const std::string expected = "wrote 3 frames " + path("f_0000.png").string() + " to " + path("f_0002.png").string() +
                               ": reference, 8x6, 1 spp, " + kTimeAndRate + "\n";
  EXPECT_TRUE(std::regex_match(r.err, std::regex(expected))) << r;
}

TEST_F(Conventions, QuietPrintsNothing) {
  const RunResult r = render(path("out.png").string(), {"-q"});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(fs::exists(path("out.png")));
}

TEST_F(Conventions, VerbosePrintsThreadsAndPhaseTimes) {
  const RunResult r = render(path("out.png").string(), {"-v", "--threads", "1"});
  ASSERT_TRUE(ExitedWith(r, 0));
  const std::string ms = "[0-9]+\\.[0-9] ms";
  const std::string phases = "phases: load " + ms + ", build " + ms + ", compile " + ms + ", render " + ms + ", total " + ms;
  EXPECT_TRUE(std::regex_match(r.err, std::regex("threads: 1\n" + phases + "\nwrote .*\n"))) << r;
  const RunResult two = render(path("out.png").string(), {"-v", "--threads", "2"});
  ASSERT_TRUE(ExitedWith(two, 0));
  EXPECT_EQ(two.err.rfind("threads: 2\n", 0), 0u) << two;
}

TEST_F(Conventions, TraceVerbosePrintsPhaseTimes) {
  write("rays.csv", "0,0,-5,0,0,1\n");
  const RunResult r = run({"trace", scene_, "-b", "reference", "--rays", path("rays.csv").string(), "-o",
                           path("hits.csv").string(), "-v"});
  ASSERT_TRUE(ExitedWith(r, 0));
  const std::string ms = "[0-9]+\\.[0-9] ms";
  EXPECT_TRUE(std::regex_match(
      r.err, std::regex("phases: load " + ms + ", build " + ms + ", compile " + ms + ", render " + ms + ", total " + ms + "\n")))
      << r;
}

TEST_F(Conventions, BadThreadsOrQuietAndVerboseAreRejected) {
  expect_rejected({"render", scene_, "-b", "reference", "-o", path("out.png").string(), "--threads", "0"},
                  "--threads: must be at least 1, got 0");
  expect_rejected({"render", scene_, "-b", "reference", "-o", path("out.png").string(), "--threads", "-3"},
                  "--threads: must be at least 1, got -3");
  expect_rejected({"render", scene_, "-b", "reference", "-o", path("out.png").string(), "-q", "-v"},
                  "-q and -v: give one or the other");
  write("rays.csv", "0,0,-5,0,0,1\n");
  expect_rejected({"trace", scene_, "-b", "reference", "--rays", path("rays.csv").string(), "-o",
                   path("hits.csv").string(), "--threads", "0"},
                  "--threads: must be at least 1, got 0");
}

// The bar, in a pseudo-terminal (script(1) runs prism on one): elapsed
// time, the frame, and the ray rate (from the first tile on:
// cli_progress_test.cpp); the summary starts a line of its own.
TEST_F(Conventions, TheProgressBarInATerminal) {
  if (std::system("script --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no script(1)";
  const std::string command = prism_binary().string() + " render " + scene_ + " -b reference -o " +
                              path("f.png").string() + " --frames 2 --width 64 --height 48";
  // script runs prism on a terminal of its own and copies what prism
  // writes there (stdout and stderr, "\n" as "\r\n") to its stdout.
  const std::string script = "script -qec '" + command + "' /dev/null < /dev/null > " + path("bar.txt").string();
  ASSERT_EQ(std::system(script.c_str()), 0);
  const std::string bar = read_file(path("bar.txt"));
  EXPECT_NE(bar.find("\r["), std::string::npos) << bar;
  EXPECT_NE(bar.find("] 100%  "), std::string::npos) << bar;
  EXPECT_NE(bar.find(", frame 1/2"), std::string::npos) << bar;
  EXPECT_NE(bar.find("rays/s, frame 2/2"), std::string::npos) << bar;
  EXPECT_NE(bar.find("\nwrote 2 frames "), std::string::npos) << bar;
}

// An interrupt's message starts a line of its own, not glued to the bar
// (`] 69%prism: interrupted`). SIGINT is sent once the bar is drawn.
TEST_F(Conventions, AnInterruptInATerminalStartsANewLine) {
  if (std::system("script --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no script(1)";
  SceneText slow;  // a tile in ~0.1 s, the whole image in ~30 s: the interrupt comes first
  slow.image = R"({"width": 2048, "height": 2048, "spp": 16})";
  const fs::path scene = write("slow.json", slow.text());
  // The shell script runs says its pid (prism's, after exec) before it starts prism.
  const std::string command = "echo $$ > " + path("pid").string() + "; exec " + prism_binary().string() + " render " +
                              scene.string() + " -b reference -o " + path("out.png").string();
  const std::string script = "script -qec '" + command + "' /dev/null < /dev/null > " + path("bar.txt").string();
  int status = 0;
  std::thread session([&] { status = std::system(script.c_str()); });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (read_file(path("bar.txt")).find("\r[") == std::string::npos && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const int pid = std::atoi(read_file(path("pid")).c_str());
  if (pid > 0) ::kill(pid, SIGINT);
  session.join();
  EXPECT_NE(status, 0);
  const std::string bar = read_file(path("bar.txt"));
  const size_t message = bar.find("prism: interrupted");
  ASSERT_NE(message, std::string::npos) << bar;
  ASSERT_GT(message, 0u) << bar;
  EXPECT_NE(bar.rfind("\r[", message), std::string::npos) << "no bar drawn before the interrupt\n" << bar;
  EXPECT_EQ(bar[message - 1], '\n') << bar;
  EXPECT_FALSE(fs::exists(path("out.png")));
}

// ----------------------------------------------------------- output formats

TEST_F(Conventions, OutputFormatsFollowTheExtension) {
  ASSERT_TRUE(ExitedWith(render(path("out.png").string(), {"-q"}), 0));
  const ImageFile png = read_image_file(path("out.png"));
  for (const char* name : {"out.jpg", "out.jpeg", "out.tif", "out.tiff", "out.hdr", "OUT.JPG"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(ExitedWith(render(path(name).string(), {"-q"}), 0));
    const ImageFile image = read_image_file(path(name));
    EXPECT_EQ(image.width, 8);
    EXPECT_EQ(image.height, 6);
    EXPECT_EQ(image.channels, 3);
  }
  // TIFF holds the very 8-bit codes PNG does.
  EXPECT_EQ(read_image_file(path("out.tif")).pixels, png.pixels);
  EXPECT_EQ(read_image_file(path("out.tif")).format, PixelFormat::UInt8);
  // Radiance HDR holds linear floats: within its 8-bit shared-exponent
  // mantissa (1/128 of the largest channel) of the EXR's.
  ASSERT_TRUE(ExitedWith(render(path("out.exr").string(), {"-q"}), 0));
  const ImageFile exr = read_image_file(path("out.exr")), hdr = read_image_file(path("out.hdr"));
  ASSERT_EQ(hdr.pixels.size(), exr.pixels.size());
  for (size_t p = 0; p < exr.pixels.size(); p += 3) {
    const float largest = std::max({exr.pixels[p], exr.pixels[p + 1], exr.pixels[p + 2]});
    for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(hdr.pixels[p + c], exr.pixels[p + c], largest / 128.0f) << p;
  }
}

// JPEG and Radiance HDR have writers of Prism's own; only TIFF needs OpenImageIO.
TEST_F(Conventions, OnlyTiffLoadsOpenImageIO) {
  for (const std::string name : {"out.jpg", "out.hdr", "out.tif"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(ExitedWith(render(path(name).string(), {"-q", "--stats", path("s.json").string()}), 0));
    EXPECT_EQ(nlohmann::json::parse(read_file(path("s.json")))["loaded_libraries"]["openimageio"], name == "out.tif");
  }
}

TEST_F(Conventions, AnUnknownExtensionListsTheSupportedOnes) {
  const std::string out = path("out.bmp").string();
  expect_rejected({"render", scene_, "-b", "reference", "-o", out},
                  out + ": unsupported output type '.bmp' (expected .png, .exr, .jpg, .jpeg, .tif, .tiff, .hdr)");
  const std::string none = path("out").string();
  expect_rejected({"render", scene_, "-b", "reference", "-o", none},
                  none + ": unsupported output type '' (expected .png, .exr, .jpg, .jpeg, .tif, .tiff, .hdr)");
}

TEST_F(Conventions, DashWritesPngToStandardOutput) {
  ASSERT_TRUE(ExitedWith(render(path("out.png").string(), {"-q"}), 0));
  const RunResult r = render("-");
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_EQ(r.out, read_file(path("out.png")));
  EXPECT_TRUE(std::regex_match(r.err, std::regex("wrote PNG to standard output: reference, 8x6, 1 spp, " + kTimeAndRate + "\n")))
      << r;
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"out.png", "scene.json"}));
}

TEST_F(Conventions, DashTakesOneImageOnly) {
  expect_rejected({"render", scene_, "-b", "reference", "-o", "-", "--frames", "2"},
                  "-o -: standard output takes one image, not a sequence (--frames, --cameras)");
  expect_rejected({"render", scene_, "-b", "reference", "-o", "-", "--aov", "id"},
                  "--aov needs an .exr output (-o - writes PNG)");
}

// A failed run leaves an older file of a format OpenImageIO writes as it was.
TEST_F(Conventions, AFailedRunKeepsAnOlderTiff) {
  write("out.tif", "an older picture\n");
  const fs::path bad = write("bad.json", "{\"prism\": 1");
  const RunResult r = run({"render", bad.string(), "-b", "reference", "-o", path("out.tif").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_EQ(read_file(path("out.tif")), "an older picture\n");
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"bad.json", "out.tif", "scene.json"}));
}

// ------------------------------------------------------------ camera flags

TEST_F(Conventions, CameraFlagsRenderWhatTheSameSceneCameraRenders) {
  SceneText moved;
  moved.camera = R"({"position": [1, 2, -4], "look_at": [0, 0.5, 0], "fov_y": 50})";
  const fs::path scene = write("moved.json", moved.text());
  ASSERT_TRUE(ExitedWith(run({"render", scene.string(), "-b", "reference", "-o", path("expected.png").string(), "-q"}), 0));
  const RunResult r = render(path("out.png").string(),
                             {"-q", "--camera-position", "1,2,-4", "--look-at", "0,0.5,0", "--fov", "50"});
  ASSERT_TRUE(ExitedWith(r, 0));
  // Exactly the -o name, not a numbered frame.
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"expected.png", "moved.json", "out.png", "scene.json"}));
  EXPECT_EQ(read_file(path("out.png")), read_file(path("expected.png")));
}

TEST_F(Conventions, CameraLookingStraightDownRenders) {
  EXPECT_TRUE(ExitedWith(render(path("out.png").string(), {"-q", "--camera-position", "0,5,0", "--look-at", "0,0,0"}), 0));
}

TEST_F(Conventions, BadCameraFlagsAreRejected) {
  const std::vector<std::string> base = {"render", scene_, "-b", "reference", "-o", path("out.png").string()};
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> args = base;
    args.insert(args.end(), more.begin(), more.end());
    return args;
  };
  expect_rejected(with({"--camera-position", "1,2", "--look-at", "0,0,0"}),
                  "--camera-position: expected three numbers X,Y,Z, got '1,2'");
  expect_rejected(with({"--camera-position", "1,2,3,4", "--look-at", "0,0,0"}),
                  "--camera-position: expected three numbers X,Y,Z, got '1,2,3,4'");
  expect_rejected(with({"--camera-position", "0,0,-5", "--look-at", "0,x,0"}),
                  "--look-at: expected three numbers X,Y,Z, got '0,x,0'");
  expect_rejected(with({"--camera-position", "nan,0,-5", "--look-at", "0,0,0"}),
                  "--camera-position: 'nan' is not a finite number of magnitude at most 1e7");
  expect_rejected(with({"--camera-position", "0,0,-5", "--look-at", "0,inf,0"}),
                  "--look-at: 'inf' is not a finite number of magnitude at most 1e7");
  expect_rejected(with({"--camera-position", "2e7,0,-5", "--look-at", "0,0,0"}),
                  "--camera-position: '2e7' is not a finite number of magnitude at most 1e7");
  expect_rejected(with({"--camera-position", "1,2,3", "--look-at", "1,2,3"}), "--look-at: must differ from --camera-position");
  expect_rejected(with({"--camera-position", "1,2,3"}), "--camera-position needs --look-at");
  expect_rejected(with({"--look-at", "1,2,3"}), "--look-at needs --camera-position");
  expect_rejected(with({"--fov", "0"}), "--fov: must be between 0 and 180 degrees (both excluded), got 0");
  expect_rejected(with({"--fov", "180"}), "--fov: must be between 0 and 180 degrees (both excluded), got 180");
  write("cams.json", R"({"cameras": [{"position": [0, 0, -5], "look_at": [0, 0, 0]}]})");
  expect_rejected(with({"--camera-position", "0,0,-5", "--look-at", "0,0,0", "--cameras", path("cams.json").string()}),
                  "--camera-position and --cameras: give one or the other");
}

// ------------------------------------------------------------------ -b auto

TEST_F(Conventions, ListSaysWhichBackendAutoPicks) {
  if (!has_backend("embree")) GTEST_SKIP() << "embree not built: the ranks below are embree's";
  const RunResult r = run({"list"});
  ASSERT_TRUE(ExitedWith(r, 0));
  // embree's speed rank, 50, is the highest of the built-in backends that run on any CPU.
  const std::string line = "-b auto picks embree here: the usable backend with the highest speed rank (50)\n";
  ASSERT_GE(r.out.size(), line.size());
  EXPECT_EQ(r.out.substr(r.out.size() - line.size()), line) << r;
  // And -b auto does pick it.
  ASSERT_TRUE(ExitedWith(run({"render", scene_, "-o", path("out.png").string(), "-q", "--stats", path("s.json").string()}), 0));
  EXPECT_EQ(nlohmann::json::parse(read_file(path("s.json")))["backend"], "embree");
}

}  // namespace
}  // namespace prism::cli_test
