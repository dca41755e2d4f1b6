// Bad input through the command line: every class of error the scene format
// names must give exit status 2, a message with the JSON path (or line and
// column) and what is wrong, and no output file. Each bad scene is given to
// both `prism render` and `prism trace`.
#include "prism/image_file.hpp"

#include <algorithm>

#include "bad_scenes.hpp"
#include "cli_harness.hpp"

namespace prism::cli_test {
namespace {

class LoaderErrors : public CliTest, public ::testing::WithParamInterface<BadScene> {};

// The scene is rejected by both subcommands: exit 2, the message, and
// nothing written beside the inputs.
TEST_P(LoaderErrors, RejectedWithPathAndNoOutput) {
  const BadScene& c = GetParam();
  const fs::path scene = write("scene.json", c.scene);
  write("rays.csv", "0,0,-5,0,0,1\n");
  const auto before = list_folder(dir());

  RunResult render = run({"render", scene.string(), "-b", "reference", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(render, 2));
  EXPECT_TRUE(StderrHas(render, c.expect)) << "scene:\n" << c.scene;
  EXPECT_EQ(list_folder(dir()), before) << "render wrote something\n" << render;

  RunResult trace = run({"trace", scene.string(), "-b", "reference", "--rays", path("rays.csv").string(), "-o",
                         path("out.csv").string()});
  EXPECT_TRUE(ExitedWith(trace, 2));
  EXPECT_TRUE(StderrHas(trace, c.expect)) << "scene:\n" << c.scene;
  EXPECT_EQ(list_folder(dir()), before) << "trace wrote something\n" << trace;
}

INSTANTIATE_TEST_SUITE_P(Scene, LoaderErrors, ::testing::ValuesIn(bad_scenes()),
                         [](const ::testing::TestParamInfo<BadScene>& info) { return info.param.name; });

// A 5 MB key was echoed whole, in the JSON path and in the message. What a
// message quotes is cut to 60 bytes, with the length it had.
TEST_F(CliTest, AHugeKeyIsQuotedCutShort) {
  SceneText s;
  s.extra = "\"" + std::string(5'000'000, 'k') + "\": 1";
  const fs::path scene = write("scene.json", s.text());
  RunResult r = run({"render", scene.string(), "-b", "reference", "-o", path("out.png").string()});
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {std::string(60, 'k') + "… (5000000 bytes)", "unknown key"}));
  EXPECT_LT(r.err.size(), 1000u) << r.err.substr(0, 300);
}

// The valid scene the table breaks really is valid, so every rejection above
// is caused by the one change it makes.
using ValidScene = CliTest;
TEST_F(ValidScene, TheBaseSceneRenders) {
  const fs::path scene = write("scene.json", SceneText{}.text());
  RunResult r = run({"render", scene.string(), "-b", "reference", "-o", path("out.png").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
}

// Magnitudes of exactly 1e7 are allowed (the limit is inclusive), as are the
// other ends of the ranges.
TEST_F(ValidScene, ValuesAtTheLimitsAreAccepted) {
  SceneText s;
  s.camera = R"({"position": [0, 0, -1e7], "look_at": [0, 0, 10000000], "fov_y": 179.9})";
  s.image = R"({"width": 1, "height": 1, "spp": 4096, "max_depth": 64})";
  s.lights = R"([{"type": "point", "position": [0, 1e7, 0], "radius": 10000000},
                 {"type": "directional", "direction": [0, -1, 0]}])";
  s.objects = R"([{"type": "sphere", "radius": 1e7, "center": [-1e7, 0, 1e7]}])";
  s.extra = R"("materials": {"glass": {"ior": 1, "absorb": [1, 2, 3]}, "mirror": {"reflect": 1, "shininess": 1}})";
  const fs::path scene = write("scene.json", s.text());
  RunResult r = run({"render", scene.string(), "-b", "reference", "-o", path("out.png").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
}

// ---------------------------------------------------------------- textures

// Writes a w x h RGB PNG of one grey level (128) through the core's image module.
void write_png(const fs::path& file, int w, int h) {
  prism::ImageFile image{w, h, 3, {}, prism::PixelFormat::UInt8, std::vector<float>(size_t(w) * h * 3, 128.0f / 255.0f)};
  prism::write_image_file(file, image, prism::PixelFormat::UInt8);
}

class TextureErrors : public CliTest {
 protected:
  // Renders `scene`; expects exit 2 with `expect` and nothing new in the folder.
  void expect_rejected(const SceneText& scene, const std::vector<std::string>& expect) {
    const fs::path file = write("scene.json", scene.text());
    const auto before = list_folder(dir());
    RunResult r = run({"render", file.string(), "-b", "reference", "-o", path("out.png").string()});
    EXPECT_TRUE(ExitedWith(r, 2));
    EXPECT_TRUE(StderrHas(r, expect)) << scene.text();
    EXPECT_EQ(list_folder(dir()), before) << r;
  }
};

TEST_F(TextureErrors, MissingFile) {
  SceneText s;
  s.extra = R"("textures": {"wood": "nosuch.png"})";
  expect_rejected(s, {"textures.wood", "nosuch.png"});
}

TEST_F(TextureErrors, MissingFileInObjectForm) {
  SceneText s;
  s.extra = R"("textures": {"wood": {"path": "nosuch.png", "srgb": false}})";
  expect_rejected(s, {"textures.wood", "nosuch.png"});
}

TEST_F(TextureErrors, FileThatIsNotAnImage) {
  write("fake.png", "this is text, not a PNG\n");
  SceneText s;
  s.extra = R"("textures": {"fake": "fake.png"})";
  expect_rejected(s, {"textures.fake", "fake.png"});
}

TEST_F(TextureErrors, EmptyFile) {
  write("empty.exr", "");
  SceneText s;
  s.extra = R"("textures": {"empty": "empty.exr"})";
  expect_rejected(s, {"textures.empty", "empty.exr"});
}

TEST_F(TextureErrors, FolderInsteadOfFile) {
  fs::create_directory(path("folder.png"));
  SceneText s;
  s.extra = R"("textures": {"folder": "folder.png"})";
  expect_rejected(s, {"textures.folder", "folder.png"});
}

TEST_F(TextureErrors, SrgbNotABoolean) {
  write_png(path("grey.png"), 2, 2);
  SceneText s;
  s.extra = R"("textures": {"grey": {"path": "grey.png", "srgb": 0}})";
  expect_rejected(s, {"textures.grey.srgb", "true or false|boolean"});
}

TEST_F(TextureErrors, UnknownKeyInTexture) {
  write_png(path("grey.png"), 2, 2);
  SceneText s;
  s.extra = R"("textures": {"grey": {"path": "grey.png", "linear": true}})";
  expect_rejected(s, {"textures.grey.linear", "unknown key"});
}

TEST_F(TextureErrors, CubemapFacesOfDifferentSizes) {
  for (const char* face : {"px", "nx", "py", "ny", "pz"}) write_png(path(std::string(face) + ".png"), 4, 4);
  write_png(path("nz.png"), 8, 8);
  SceneText s;
  s.extra = R"("textures": {"px": "px.png", "nx": "nx.png", "py": "py.png", "ny": "ny.png", "pz": "pz.png", "nz": "nz.png"},
               "background": {"cubemap": ["px", "nx", "py", "ny", "pz", "nz"]})";
  expect_rejected(s, {"background.cubemap[5]", "size"});
}

TEST_F(TextureErrors, CubemapFaceNotSquare) {
  for (const char* face : {"px", "py", "ny", "pz", "nz"}) write_png(path(std::string(face) + ".png"), 4, 4);
  write_png(path("nx.png"), 4, 2);
  SceneText s;
  s.extra = R"("textures": {"px": "px.png", "nx": "nx.png", "py": "py.png", "ny": "ny.png", "pz": "pz.png", "nz": "nz.png"},
               "background": {"cubemap": ["px", "nx", "py", "ny", "pz", "nz"]})";
  expect_rejected(s, {"background.cubemap[1]", "square"});
}

// The same textures, well formed, render: the failures above come from the
// one thing each breaks. Relative paths resolve against the scene's folder,
// not the working directory.
TEST_F(TextureErrors, WellFormedTexturesRender) {
  fs::create_directory(path("maps"));
  for (const char* face : {"px", "nx", "py", "ny", "pz", "nz"}) write_png(path("maps") / (std::string(face) + ".png"), 4, 4);
  write_png(path("maps") / "wood.png", 3, 5);
  SceneText s;
  s.extra = R"("textures": {"px": "maps/px.png", "nx": "maps/nx.png", "py": "maps/py.png", "ny": "maps/ny.png",
                            "pz": "maps/pz.png", "nz": {"path": "maps/nz.png", "srgb": false}, "wood": "maps/wood.png"},
               "background": {"cubemap": ["px", "nx", "py", "ny", "pz", "nz"]},
               "materials": {"m": {"texture": "wood"}})";
  s.objects = R"([{"type": "sphere", "radius": 1, "material": "m"}])";
  const fs::path file = write("scene.json", s.text());
  RunResult r = run({"render", file.string(), "-b", "reference", "-o", path("out.png").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_TRUE(fs::exists(path("out.png")));
}

// ---------------------------------------------------------- command line

class CommandLineErrors : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    scene_ = write("scene.json", SceneText{}.text()).string();
    rays_ = write("rays.csv", "0,0,-5,0,0,1\n").string();
  }
  // Runs prism with `args`; expects exit `status` (2: bad input; 1: an
  // output that cannot be written, as the spec's exit statuses say),
  // `expect` in the message and nothing new in the folder.
  RunResult expect_rejected(const std::vector<std::string>& args, const std::vector<std::string>& expect,
                            int status = 2) {
    const auto before = list_folder(dir());
    RunResult r = run(args);
    EXPECT_TRUE(ExitedWith(r, status));
    EXPECT_TRUE(StderrHas(r, expect));
    EXPECT_EQ(list_folder(dir()), before) << r;
    return r;
  }
  std::vector<std::string> render(std::vector<std::string> more) {
    std::vector<std::string> args = {"render", scene_, "-b", "reference", "-o", path("out.png").string()};
    args.insert(args.end(), more.begin(), more.end());
    return args;
  }
  std::vector<std::string> trace(std::vector<std::string> more) {
    std::vector<std::string> args = {"trace", scene_, "-b", "reference", "--rays", rays_, "-o", path("out.csv").string()};
    args.insert(args.end(), more.begin(), more.end());
    return args;
  }
  std::string scene_, rays_;
};

TEST_F(CommandLineErrors, WidthZero) { expect_rejected(render({"--width", "0"}), {"--width", "got 0"}); }
TEST_F(CommandLineErrors, Height16385) { expect_rejected(render({"--height", "16385"}), {"--height", "16385"}); }
TEST_F(CommandLineErrors, Spp5000) { expect_rejected(render({"--spp", "5000"}), {"--spp", "5000"}); }
TEST_F(CommandLineErrors, SppZero) { expect_rejected(render({"--spp", "0"}), {"--spp", "got 0"}); }
TEST_F(CommandLineErrors, MaxDepth65) { expect_rejected(render({"--max-depth", "65"}), {"--max-depth", "65"}); }
TEST_F(CommandLineErrors, WidthNotAnInteger) { expect_rejected(render({"--width", "1.5"}), {"--width|width", "1.5"}); }
TEST_F(CommandLineErrors, WidthNotANumber) { expect_rejected(render({"--width", "wide"}), {"--width|width", "wide"}); }

TEST_F(CommandLineErrors, UnknownBackendListsThoseFound) {
  expect_rejected({"render", scene_, "-b", "nosuch", "-o", path("out.png").string()}, {"nosuch", "reference"});
  expect_rejected({"trace", scene_, "-b", "nosuch", "--rays", rays_, "-o", path("out.csv").string()},
                  {"nosuch", "reference"});
}

TEST_F(CommandLineErrors, UnsupportedOutputExtension) {
  expect_rejected({"render", scene_, "-b", "reference", "-o", path("out.bmp").string()}, {"out.bmp", ".bmp"});
  expect_rejected({"render", scene_, "-b", "reference", "-o", path("out").string()}, {"out"});
  expect_rejected({"trace", scene_, "-b", "reference", "--rays", rays_, "-o", path("out.txt").string()},
                  {"out.txt", ".txt"});
  expect_rejected(render({"--stats", path("stats.txt").string()}), {"stats.txt", ".txt"});
}

TEST_F(CommandLineErrors, OutputFolderMissing) {
  expect_rejected({"render", scene_, "-b", "reference", "-o", path("nosuch/out.png").string()}, {"nosuch"}, 1);
  expect_rejected({"trace", scene_, "-b", "reference", "--rays", rays_, "-o", path("nosuch/out.csv").string()},
                  {"nosuch"}, 1);
  expect_rejected(render({"--stats", path("nosuch/stats.json").string()}), {"nosuch"}, 1);
  EXPECT_FALSE(fs::exists(path("nosuch")));
}

TEST_F(CommandLineErrors, OutputIsAFolder) {
  fs::create_directory(path("out.png"));
  expect_rejected(render({}), {"out.png"}, 1);
  EXPECT_TRUE(fs::is_empty(path("out.png")));
}

TEST_F(CommandLineErrors, AovNeedsExr) {
  expect_rejected(render({"--aov", "id"}), {"--aov", "exr"});
  expect_rejected(render({"--aov", "depth", "normal", "albedo"}), {"--aov", "exr"});
}

TEST_F(CommandLineErrors, UnknownAov) {
  expect_rejected({"render", scene_, "-b", "reference", "-o", path("out.exr").string(), "--aov", "id,roughness"},
                  {"roughness"});
}

TEST_F(CommandLineErrors, DigitsOutOfRange) {
  expect_rejected(trace({"--digits", "0"}), {"--digits|digits"});
  expect_rejected(trace({"--digits", "18"}), {"--digits|digits"});
}

TEST_F(CommandLineErrors, SceneFileMissing) {
  expect_rejected({"render", path("nosuch.json").string(), "-b", "reference", "-o", path("out.png").string()},
                  {"nosuch.json"});
}

TEST_F(CommandLineErrors, RayFileMissing) {
  expect_rejected({"trace", scene_, "-b", "reference", "--rays", path("nosuch.csv").string(), "-o",
                   path("out.csv").string()},
                  {"nosuch.csv"});
}

TEST_F(CommandLineErrors, UnknownFlagAndSubcommand) {
  expect_rejected(render({"--sppp", "4"}), {"--sppp"});
  expect_rejected({"paint", scene_}, {"paint|subcommand"});
  expect_rejected({}, {"subcommand|render"});
}

// A failed run leaves an older output file exactly as it was.
TEST_F(CommandLineErrors, ExistingOutputIsLeftUntouched) {
  const std::string old = "an older picture\n";
  write("out.png", old);
  write("out.csv", old);
  write("stats.json", old);
  const fs::path bad = write("bad.json", with_object(R"({"type": "sphere", "radius": -1})"));
  const auto before = list_folder(dir());
  const std::string stats = path("stats.json").string();

  RunResult r1 = run({"render", bad.string(), "-b", "reference", "-o", path("out.png").string(), "--stats", stats});
  EXPECT_TRUE(ExitedWith(r1, 2));
  EXPECT_TRUE(StderrHas(r1, {"objects[0].radius"}));
  RunResult r2 = run(render({"--width", "0", "--stats", stats}));
  EXPECT_TRUE(ExitedWith(r2, 2));
  RunResult r3 = run({"trace", bad.string(), "-b", "reference", "--rays", rays_, "-o", path("out.csv").string(),
                      "--stats", stats});
  EXPECT_TRUE(ExitedWith(r3, 2));
  write("badrays.csv", "0,0,-5,0,0\n");
  RunResult r4 = run({"trace", scene_, "-b", "reference", "--rays", path("badrays.csv").string(), "-o",
                      path("out.csv").string(), "--stats", stats});
  EXPECT_TRUE(ExitedWith(r4, 2));

  auto after = list_folder(dir());
  after.erase(std::remove(after.begin(), after.end(), "badrays.csv"), after.end());
  EXPECT_EQ(after, before);
  EXPECT_EQ(read_file(path("out.png")), old);
  EXPECT_EQ(read_file(path("out.csv")), old);
  EXPECT_EQ(read_file(path("stats.json")), old);
}

}  // namespace
}  // namespace prism::cli_test
