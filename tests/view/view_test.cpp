// `prism view` end to end: the built binary in a private Xvfb, once per
// backend. The viewer starts at the scene's camera and nothing moves it, so
// its frames must be `prism render`'s pixels exactly, outside the status
// band at the top.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include "prism/image_file.hpp"
#include "prism/scene_loader.hpp"
#include "process.hpp"
#include "test_support.hpp"
#include "x_server.hpp"

namespace prism::view_test {
namespace {

// 160x90 is sphere.json's own size; the flags are given anyway, as a user would.
constexpr int kWidth = 160, kHeight = 90;
// A 160-pixel window draws the status line at scale 1: (7 + 2 * 2) = 11 rows.
constexpr int kBandRows = 11;

fs::path scene() { return prism::test::source_dir() / "scenes" / "conformance" / "sphere.json"; }

struct Pixels {
  int width = 0, height = 0;
  std::vector<int> codes;  // 8-bit codes, RGB, row 0 at the top
  int at(int x, int y, int c) const { return codes[(size_t(y) * width + x) * 3 + c]; }
};

Pixels read_png(const fs::path& file) {
  const ImageFile image = read_image_file(file);
  Pixels p{image.width, image.height, {}};
  for (int i = 0; i < image.width * image.height; ++i)
    for (int c = 0; c < 3; ++c) p.codes.push_back(int(std::lround(image.pixels[size_t(i) * image.channels + c] * 255.0)));
  return p;
}

// Pixels of rows [y0, y1) whose codes differ.
int differing_pixels(const Pixels& a, const Pixels& b, int y0, int y1, std::string* first = nullptr) {
  int count = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < a.width; ++x) {
      bool same = true;
      for (int c = 0; c < 3; ++c) same = same && a.at(x, y, c) == b.at(x, y, c);
      if (!same && count++ == 0 && first)
        *first = "(" + std::to_string(x) + ", " + std::to_string(y) + "): " + std::to_string(a.at(x, y, 0)) + "," +
                 std::to_string(a.at(x, y, 1)) + "," + std::to_string(a.at(x, y, 2)) + " vs " +
                 std::to_string(b.at(x, y, 0)) + "," + std::to_string(b.at(x, y, 1)) + "," +
                 std::to_string(b.at(x, y, 2));
    }
  return count;
}

::testing::AssertionResult ExitedWith(const RunResult& r, int status) {
  if (r.exited && r.status == status) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected exit status " << status << "\n" << r;
}

bool wait_for_file(const fs::path& file, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (fs::exists(file)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return fs::exists(file);
}

std::vector<std::string> folder_entries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  return names;
}

class ViewFixture {
 protected:
  void make_folders() {
    root_ = prism::test::fresh_temp_dir();
    work_ = root_ / "work";
    fs::create_directories(work_);
  }
  void remove_folders(bool failed) {
    x_.reset();
    if (failed) {
      std::printf("(kept the test folder %s)\n", root_.c_str());
      return;
    }
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  RunResult prism(const std::vector<std::string>& args, std::optional<std::string> display) {
    std::vector<std::string> argv = {prism_binary().string()};
    argv.insert(argv.end(), args.begin(), args.end());
    return run(argv, RunOptions{work_, display, root_});
  }
  // A private X server for a run with `backend`. When there is none it
  // records a skip, or a failure when the backend is in PRISM_REQUIRE_BACKENDS.
  bool start_x(const std::string& backend) {
    x_ = std::make_unique<XServer>(root_ / "xvfb.log");
    if (x_->ok()) return true;
    const std::string message = "no X server for prism view: " + x_->error();
    if (prism::test::backend_required(backend)) {
      ADD_FAILURE() << message << " (backend '" << backend << "' is in PRISM_REQUIRE_BACKENDS)";
    } else {
      GTEST_MESSAGE_(message.c_str(), testing::TestPartResult::kSkip);
    }
    return false;
  }
  // `prism render` of the same scene and size: what the viewer must show.
  Pixels reference_render(const std::string& backend, int width = kWidth, int height = kHeight) {
    const fs::path out = root_ / ("render-" + backend + "-" + std::to_string(width) + ".png");
    RunResult r = prism({"render", scene().string(), "-b", backend, "-o", out.string(), "--width",
                         std::to_string(width), "--height", std::to_string(height)},
                        std::nullopt);
    EXPECT_TRUE(ExitedWith(r, 0));
    return fs::exists(out) ? read_png(out) : Pixels{};
  }

  fs::path root_, work_;
  std::unique_ptr<XServer> x_;
};

class ViewBackend : public testing::TestWithParam<std::string>, public ViewFixture {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(prism_binary())) << prism_binary() << " is not built";
    make_folders();
  }
  void TearDown() override { remove_folders(HasFailure()); }
};

class ViewCli : public testing::Test, public ViewFixture {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(prism_binary())) << prism_binary() << " is not built";
    make_folders();
  }
  void TearDown() override { remove_folders(HasFailure()); }
};

TEST_P(ViewBackend, CaptureMatchesRenderOutsideTheStatusBand) {
  const std::string backend = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  if (!start_x(backend)) return;
  const fs::path capture = root_ / "capture.png";
  RunResult r = prism({"view", scene().string(), "-b", backend, "--frames", "3", "--capture", capture.string(),
                       "--width", std::to_string(kWidth), "--height", std::to_string(kHeight)},
                      x_->display());
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_NE(r.out.find("3 frames at 160x90 with " + backend), std::string::npos) << r;
  ASSERT_TRUE(fs::exists(capture)) << r;
  const Pixels shown = read_png(capture);
  const Pixels rendered = reference_render(backend);
  ASSERT_EQ(shown.width, kWidth);
  ASSERT_EQ(shown.height, kHeight);
  ASSERT_EQ(rendered.width, kWidth);
  ASSERT_EQ(rendered.height, kHeight);
  std::string first;
  EXPECT_EQ(differing_pixels(shown, rendered, kBandRows, kHeight, &first), 0) << "first difference at " << first;
  // The band itself is drawn: darkened background and white text.
  EXPECT_GT(differing_pixels(shown, rendered, 0, kBandRows), kWidth * kBandRows / 2);
  int white = 0;
  for (int y = 0; y < kBandRows; ++y)
    for (int x = 0; x < kWidth; ++x) white += shown.at(x, y, 0) == 255 && shown.at(x, y, 1) == 255 && shown.at(x, y, 2) == 255;
  EXPECT_GT(white, 50) << "no text in the status band";
}

TEST_P(ViewBackend, WritesNothingWithoutPOrCapture) {
  const std::string backend = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  if (!start_x(backend)) return;
  RunResult r = prism({"view", scene().string(), "-b", backend, "--frames", "3"}, x_->display());
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(folder_entries(work_).empty()) << "left behind: " << testing::PrintToString(folder_entries(work_));
}

// Key presses, a drag and a resize sent as X events: P saves the frame
// (first the scene's camera: render's pixels exactly), a drag orbits (the
// next P differs), R goes back (equal again), a resized window renders at its
// new size in the window as well, Esc quits with status 0.
TEST_P(ViewBackend, KeysAndMouseDriveTheViewer) {
  const std::string backend = GetParam();
  if (!prism::test::require_backend_or_skip(backend)) return;
  if (!start_x(backend)) return;
  const Pixels rendered = reference_render(backend);
  ASSERT_EQ(rendered.width, kWidth);

  const fs::path capture = root_ / "capture.png";
  std::vector<std::string> argv = {prism_binary().string(), "view", scene().string(), "-b", backend,
                                   "--width", std::to_string(kWidth), "--height", std::to_string(kHeight),
                                   "--capture", capture.string()};
  Child child(argv, RunOptions{work_, x_->display(), root_});
  ASSERT_TRUE(child.started());
  XClient x(x_->display());
  ASSERT_TRUE(x.ok());
  const unsigned long window = x.find_window("prism view", 60);
  ASSERT_NE(window, 0u) << "no viewer window appeared\n" << child.wait(1);

  auto screenshot = [&](int n) -> Pixels {
    if (!x.tap_key(window, "p")) {
      ADD_FAILURE() << "P not delivered: " << x.last_error() << "\n" << child.wait(1);
      return {};
    }
    const fs::path file = work_ / ("prism-view-" + std::to_string(n) + ".png");
    if (!wait_for_file(file, 60)) {
      ADD_FAILURE() << file << " did not appear\n" << child.wait(1);
      return {};
    }
    return read_png(file);
  };

  const Pixels first = screenshot(1);
  ASSERT_EQ(first.width, kWidth);
  ASSERT_EQ(first.height, kHeight);
  std::string where;
  EXPECT_EQ(differing_pixels(first, rendered, 0, kHeight, &where), 0) << "first difference at " << where;

  ASSERT_TRUE(x.drag(window, 40, 45, 100, 45)) << x.last_error();  // 60 pixels right: a 0.3 radian turn
  const Pixels orbited = screenshot(2);
  ASSERT_EQ(orbited.width, kWidth);
  EXPECT_GT(differing_pixels(orbited, rendered, 0, kHeight), kWidth * kHeight / 20);

  ASSERT_TRUE(x.tap_key(window, "r")) << x.last_error();
  const Pixels reset = screenshot(3);
  ASSERT_EQ(reset.width, kWidth);
  EXPECT_EQ(differing_pixels(reset, rendered, 0, kHeight, &where), 0) << "first difference at " << where;

  // The render follows the window's size.
  ASSERT_TRUE(x.resize(window, 200, 120)) << x.last_error();
  const Pixels resized = screenshot(4);
  const Pixels rendered_resized = reference_render(backend, 200, 120);
  ASSERT_EQ(resized.width, 200);
  ASSERT_EQ(resized.height, 120);
  EXPECT_EQ(differing_pixels(resized, rendered_resized, 0, 120, &where), 0) << "first difference at " << where;

  EXPECT_TRUE(x.tap_key(window, "Escape")) << x.last_error();
  RunResult r = child.wait(60);
  EXPECT_TRUE(ExitedWith(r, 0));
  EXPECT_NE(r.out.find("saved prism-view-4.png"), std::string::npos) << r;
  EXPECT_NE(r.out.find("at 200x120 with " + backend), std::string::npos) << r;
  // The window itself (the last frame shown) follows the resize too.
  ASSERT_TRUE(fs::exists(capture)) << r;
  const Pixels shown = read_png(capture);
  ASSERT_EQ(shown.width, 200);
  ASSERT_EQ(shown.height, 120);
  EXPECT_EQ(differing_pixels(shown, rendered_resized, kBandRows, 120, &where), 0) << "first difference at " << where;
}

PRISM_INSTANTIATE_BACKEND_TESTS(ViewBackend);

// The X client the tests drive the viewer with reports a refused event
// instead of letting Xlib end the test binary: a key sent to a window that
// does not exist is BadWindow, and false.
TEST_F(ViewCli, XClientReportsAnEventTheServerRefused) {
  if (!start_x("reference")) return;
  XClient x(x_->display());
  ASSERT_TRUE(x.ok());
  EXPECT_FALSE(x.tap_key(0x3fffff, "p"));
  EXPECT_NE(x.last_error().find("BadWindow"), std::string::npos) << x.last_error();
  EXPECT_FALSE(x.resize(0x3fffff, 10, 10));
  EXPECT_FALSE(x.drag(0x3fffff, 0, 0, 1, 1));
}

// sphere.json at 4 spp, its texture found from anywhere.
fs::path write_four_spp_scene(const fs::path& folder) {
  std::ifstream in(scene());
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = json.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) json.replace(at, from.size(), to);
  };
  replace(R"("height": 90 })", R"("height": 90, "spp": 4 })");
  replace("../textures/planet.png", (prism::test::source_dir() / "scenes" / "textures" / "planet.png").string());
  const fs::path file = folder / "four-spp.json";
  std::ofstream(file) << json;
  return file;
}

// The line of `text` that starts with `prefix`, or "".
std::string line_starting(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) return line;
  return "";
}

// Left alone, the viewer renders the view at 1, 2 and 4 spp (the scene's),
// which is `prism render`'s image, and then nothing more: keys that change
// nothing (P, C, H) and a second of waiting add no frame. C
// prints a camera member the loader reads as the scene's own camera; H
// draws the list of keys without rendering again.
TEST_F(ViewCli, RefinesToTheScenesSppThenRendersNothingMore) {
  if (!prism::test::require_backend_or_skip("reference")) return;
  if (!start_x("reference")) return;
  const fs::path file = write_four_spp_scene(root_);
  const fs::path out = root_ / "render.png";
  ASSERT_TRUE(ExitedWith(prism({"render", file.string(), "-b", "reference", "-o", out.string()}, std::nullopt), 0));
  const Pixels rendered = read_png(out);

  const fs::path capture = root_ / "capture.png";
  Child child({prism_binary().string(), "view", file.string(), "-b", "reference", "--capture", capture.string()},
              RunOptions{work_, x_->display(), root_});
  ASSERT_TRUE(child.started());
  XClient x(x_->display());
  ASSERT_TRUE(x.ok());
  const unsigned long window = x.find_window("prism view", 60);
  ASSERT_NE(window, 0u) << "no viewer window appeared\n" << child.wait(1);
  ASSERT_TRUE(x.tap_key(window, "p")) << x.last_error();  // saved once the frame reaches 4 spp
  ASSERT_TRUE(wait_for_file(work_ / "prism-view-1.png", 60)) << child.wait(1);
  const Pixels shown = read_png(work_ / "prism-view-1.png");
  std::string where;
  EXPECT_EQ(differing_pixels(shown, rendered, 0, kHeight, &where), 0) << "first difference at " << where;

  std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_TRUE(x.tap_key(window, "p")) << x.last_error();  // the frame is final: saved at once, nothing rendered
  ASSERT_TRUE(wait_for_file(work_ / "prism-view-2.png", 60)) << child.wait(1);
  ASSERT_TRUE(x.tap_key(window, "c")) << x.last_error();
  ASSERT_TRUE(x.tap_key(window, "h")) << x.last_error();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_TRUE(x.tap_key(window, "Escape")) << x.last_error();
  const RunResult r = child.wait(60);
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_NE(r.out.find("prism view: 3 frames at 160x90 with reference"), std::string::npos) << r;
  // H drew the list of keys over the image, below the status line too: ten
  // lines of text are taller than the 90-pixel window.
  const Pixels shown_last = read_png(capture);
  ASSERT_EQ(shown_last.height, kHeight);
  EXPECT_GT(differing_pixels(shown_last, rendered, kBandRows, kHeight), kWidth * (kHeight - kBandRows) / 2);

  const std::string camera = line_starting(r.out, R"("camera": {)");
  ASSERT_FALSE(camera.empty()) << r;
  Registry registry;
  const Scene printed = load_scene_from_string("{\"prism\": 1, " + camera + "}", ".", registry, "printed");
  const Scene original = load_scene(file, registry);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(printed.camera.position[i], original.camera.position[i], 1e-12) << i;
    EXPECT_NEAR(printed.camera.forward[i], original.camera.forward[i], 1e-12) << i;
    EXPECT_NEAR(printed.camera.up[i], original.camera.up[i], 1e-12) << i;
  }
  EXPECT_EQ(printed.camera.fov_y, 35.0);
}

TEST_F(ViewCli, AutoPicksAUsableBackend) {
  if (!start_x("auto")) return;
  RunResult r = prism({"view", scene().string(), "-b", "auto", "--frames", "2"}, x_->display());
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_NE(r.out.find("2 frames at 160x90 with "), std::string::npos) << r;
}

TEST_F(ViewCli, ScaleRendersSmallerAndShowsItEnlarged) {
  if (!prism::test::require_backend_or_skip("reference")) return;
  if (!start_x("reference")) return;
  const fs::path capture = root_ / "capture.png";
  RunResult r = prism({"view", scene().string(), "-b", "reference", "--frames", "1", "--scale", "0.5", "--capture",
                       capture.string()},
                      x_->display());
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_NE(r.out.find("1 frame at 80x45 with reference"), std::string::npos) << r;
  const Pixels shown = read_png(capture);
  ASSERT_EQ(shown.width, kWidth);
  ASSERT_EQ(shown.height, kHeight);
  // Each rendered pixel covers a 2x2 block of the window.
  int odd = 0;
  for (int y = kBandRows + 1; y + 1 < kHeight; y += 2)
    for (int x = 0; x < kWidth; x += 2)
      for (int c = 0; c < 3; ++c)
        odd += shown.at(x, y, c) != shown.at(x + 1, y, c) || shown.at(x, y, c) != shown.at(x, y + 1, c);
  EXPECT_EQ(odd, 0);
}

TEST_F(ViewCli, BadFlagsExit2BeforeAnyWindow) {
  // No DISPLAY: flags are checked first, so each of these is bad input (2),
  // not the missing display (1).
  const std::vector<std::vector<std::string>> cases = {
      {"--frames", "0"},       {"--frames", "many"},  {"--spp", "0"},       {"--max-depth", "65"},
      {"--width", "0"},        {"--height", "16385"}, {"--scale", "0"},     {"--scale", "1.5"},
      {"--capture", "x.jpg"},  {"--bogus"},           {"-b", "no_such_backend"},
  };
  for (const auto& flags : cases) {
    std::vector<std::string> args = {"view", scene().string(), "-b", "reference"};
    args.insert(args.end(), flags.begin(), flags.end());
    RunResult r = prism(args, std::nullopt);
    EXPECT_TRUE(ExitedWith(r, 2));
    EXPECT_EQ(r.err.find("DISPLAY"), std::string::npos) << r;
  }
  RunResult missing = prism({"view", (work_ / "missing.json").string(), "-b", "reference"}, std::nullopt);
  EXPECT_TRUE(ExitedWith(missing, 2));
  EXPECT_TRUE(folder_entries(work_).empty());
}

TEST_F(ViewCli, NoDisplayExits1WithAClearMessage) {
  RunResult unset = prism({"view", scene().string(), "-b", "reference", "--frames", "1"}, std::nullopt);
  EXPECT_TRUE(ExitedWith(unset, 1));
  EXPECT_NE(unset.err.find("no display: the DISPLAY environment variable is not set"), std::string::npos) << unset;

  // A display number with no server behind it.
  int n = 4093;
  while (fs::exists("/tmp/.X11-unix/X" + std::to_string(n))) --n;
  const std::string nowhere = ":" + std::to_string(n);
  RunResult absent = prism({"view", scene().string(), "-b", "reference", "--frames", "1"}, nowhere);
  EXPECT_TRUE(ExitedWith(absent, 1));
  EXPECT_NE(absent.err.find("cannot open display '" + nowhere + "'"), std::string::npos) << absent;
  EXPECT_TRUE(folder_entries(work_).empty());
}

}  // namespace
}  // namespace prism::view_test
