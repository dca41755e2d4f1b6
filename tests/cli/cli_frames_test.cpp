// `prism render --frames N` and `--cameras FILE`: a numbered image sequence
// from one prepared backend; bad camera paths named by their JSON path.
#include "cli_harness.hpp"

namespace prism::cli_test {
namespace {

class Frames : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    scene_ = write("scene.json", SceneText{}.text()).string();
  }
  std::vector<std::string> render(const std::string& output) const {
    return {"render", scene_, "-b", "reference", "-o", path(output).string(), "--width", "8", "--height", "6"};
  }
  std::string scene_;
};

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST_F(Frames, AnOrbitIsNumberedAfterTheHashes) {
  ASSERT_TRUE(ExitedWith(run(render("f_##.png") + std::vector<std::string>{"--frames", "3", "--orbit", "90"}), 0));
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"f_0000.png", "f_0001.png", "f_0002.png", "scene.json"}));
  EXPECT_NE(read_file(path("f_0000.png")), read_file(path("f_0001.png"))) << "the camera did not move";
}

TEST_F(Frames, WithoutHashesTheNumberGoesBeforeTheExtension) {
  ASSERT_TRUE(ExitedWith(run(render("orbit.png") + std::vector<std::string>{"--frames", "2"}), 0));
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"orbit_0000.png", "orbit_0001.png", "scene.json"}));
}

TEST_F(Frames, ACameraPathRendersEachCamera) {
  write("path.json", R"({"cameras": [{"position": [0, 0, 5], "look_at": [0, 0, 0]},
                                      {"position": [0, 5, 0.1], "look_at": [0, 0, 0], "fov_y": 30}]})");
  ASSERT_TRUE(ExitedWith(run(render("c.png") + std::vector<std::string>{"--cameras", path("path.json").string()}), 0));
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"c_0000.png", "c_0001.png", "path.json", "scene.json"}));
}

TEST_F(Frames, ABadCameraIsNamedByItsPath) {
  write("path.json", R"({"cameras": [{"position": [0, 0, 5], "look_at": [0, 0, 0]},
                                      {"position": [1, 1, 1], "look_at": [1, 1, 1]}]})");
  const RunResult r = run(render("c.png") + std::vector<std::string>{"--cameras", path("path.json").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"path.json: cameras[1].look_at: must differ from camera.position"}));
  EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"path.json", "scene.json"}));
}

TEST_F(Frames, AnEmptyCameraPathIsRefused) {
  write("path.json", R"({"cameras": []})");
  const RunResult r = run(render("c.png") + std::vector<std::string>{"--cameras", path("path.json").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"path.json: cameras: must be a non-empty array of cameras, got an array of 0"}));
}

TEST_F(Frames, FramesAndCamerasTogetherAreRefused) {
  write("path.json", R"({"cameras": [{"position": [0, 0, 5], "look_at": [0, 0, 0]}]})");
  const RunResult r = run(render("c.png") + std::vector<std::string>{"--cameras", path("path.json").string(), "--frames", "2"});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"--frames and --cameras: give one or the other"}));
}

// A NaN orbit made every camera NaN: exit 0 and blank frames. Refused as
// `prism bench` refuses it, and nothing is written.
TEST_F(Frames, ANonFiniteOrbitIsRefused) {
  for (const std::string value : {"nan", "inf", "-inf"}) {
    const RunResult r = run(render("o.png") + std::vector<std::string>{"--frames", "2", "--orbit", value});
    EXPECT_TRUE(ExitedWith(r, 2)) << value;
    EXPECT_TRUE(StderrHas(r, {"--orbit must be a finite number of degrees"})) << value;
    EXPECT_EQ(list_folder(dir()), (std::vector<std::string>{"scene.json"})) << value;
  }
}

}  // namespace
}  // namespace prism::cli_test
