// Where `prism render` reads a scene from, and what it says about a scene
// that loads but looks wrong: "-" is standard input (texture paths then
// relative to the current folder), and warnings go to stderr without
// changing the exit status.
#include <unistd.h>

#include "cli_harness.hpp"
#include "test_support.hpp"

namespace prism::cli_test {
namespace {

// Runs `prism ARGS < input` in `folder` through the shell.
RunResult run_with_stdin(const fs::path& folder, const std::string& args, const fs::path& input, const fs::path& logs) {
  const std::string command = "cd '" + folder.string() + "' && exec '" + prism_binary().string() + "' " + args +
                              " < '" + input.string() + "'";
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("PRISM_PLUGIN_PATH=", 0) != 0) env.emplace_back(*e);
  return run_result(prism::test::run_captured({"/bin/sh", "-c", command}, env, logs / "stdin.out", logs / "stdin.err"),
                    command);
}

class CliSceneInput : public CliTest {};

// sphere.json names its texture ../textures/planet.png: read from standard
// input in its own folder it finds it there, and renders the file's image.
TEST_F(CliSceneInput, DashReadsTheSceneFromStandardInput) {
  const fs::path folder = prism::test::source_dir() / "scenes" / "conformance";
  const fs::path from_file = path("file.png"), from_stdin = path("stdin.png");
  ASSERT_TRUE(ExitedWith(run({"render", (folder / "sphere.json").string(), "-b", "reference", "-o",
                              from_file.string()}),
                         0));
  const RunResult r = run_with_stdin(folder, "render - -q -b reference -o '" + from_stdin.string() + "'",
                                     folder / "sphere.json", dir().parent_path());
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(read_file(from_stdin), read_file(from_file));
}

// Elsewhere the texture path is relative to that folder, and messages name <stdin>.
TEST_F(CliSceneInput, TexturePathsAreRelativeToTheCurrentFolder) {
  const fs::path scene = prism::test::source_dir() / "scenes" / "conformance" / "sphere.json";
  const RunResult r = run_with_stdin(dir(), "render - -b reference -o out.png", scene, dir().parent_path());
  EXPECT_TRUE(ExitedWith(r, 2));
  EXPECT_TRUE(StderrHas(r, {"prism: error: <stdin>: textures.planet", "../textures/planet.png"}));
}

// -q leaves out the summary line, not the warnings.
TEST_F(CliSceneInput, WarningsGoToStderrAndTheRenderSucceeds) {
  const fs::path scene = write("bright.json", R"({"prism": 1,
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "image": {"width": 8, "height": 6},
    "lights": [{"type": "point", "position": [0, 5, 5]}],
    "materials": {"m": {"color": [255, 128, 0]}},
    "objects": [{"type": "sphere", "radius": 1, "material": "m"}, {"type": "sphere", "radius": 1, "center": [0, 0, 9]}]})");
  const RunResult r = run({"render", scene.string(), "-q", "-b", "reference", "-o", path("out.png").string()});
  ASSERT_TRUE(ExitedWith(r, 0));
  EXPECT_EQ(r.err, "prism: warning: " + scene.string() +
                       ": materials.m.color: [255, 128, 0] looks like 0-255 values; colours run from 0 to 1 "
                       "(divide by 255)\n"
                       "prism: warning: " + scene.string() +
                       ": objects[1]: entirely behind the camera (it can show only in reflections)\n");
  EXPECT_TRUE(fs::exists(path("out.png")));
}

}  // namespace
}  // namespace prism::cli_test
