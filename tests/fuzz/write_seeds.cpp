// prism_fuzz_seeds SCENE_DIR CSV_DIR: writes the seeds that live in C++
// rather than in files. SCENE_DIR gets the valid scene of the command-line
// tests and every bad scene of their table (tests/cli/bad_scenes.cpp), one
// file each; CSV_DIR gets ray files, valid and bad (those of the BadRays
// tests in tests/cli/cli_run_test.cpp among them). scripts/fuzz.sh runs it;
// scenes/**/*.json are copied beside these by the script.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "bad_scenes.hpp"

namespace fs = std::filesystem;

namespace {

void write(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

const std::vector<std::pair<std::string, std::string>>& ray_files() {
  static const std::vector<std::pair<std::string, std::string>> files = {
      {"header_and_tmin", "ox,oy,oz,dx,dy,dz,tmin\n0,0,-5,0,0,1\n0,0,-5,0,0,1,1e-3\n"},
      {"crlf_and_blank", "0,0,-5,0,0,1\r\n\r\n  \t\n0.5,-1e-7,3e6,1e-300,2,-3\r\n"},
      {"spaces", " 1 , 2 ,3\t,0x1p-3, 0 ,-1 , 7\n"},
      {"five_fields", "ox,oy,oz,dx,dy,dz\n0,0,-5,0,0,1\n0,0,-5,0,0\n0,0,-5,0,0,1\n"},
      {"eight_fields", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,-5,0,0,1,0,0\n"},
      {"not_a_number", "ox,oy,oz,dx,dy,dz\n0,0,-5,0,0,1\n0,0,-5,0,zero,1\n"},
      {"empty_field", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,,0,0,1\n"},
      {"trailing_comma", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,-5,0,0,1,\n"},
      {"zero_direction", "ox,oy,oz,dx,dy,dz,tmin\n0,0,-5,0,0,1\n1,2,3,0,0,0\n"},
      {"nan", "0,0,-5,0,0,1\n0,0,-5,0,0,1\nnan,0,-5,0,0,1\n"},
      {"infinite_origin", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,-inf,0,0,1\n"},
      {"overflow", "0,0,-5,0,0,1\n0,0,-5,0,0,1\n0,0,-5,1e999,0,1\n"},
      {"header_not_first", "0,0,-5,0,0,1\n0,0,-5,0,0,1\nox,oy,oz,dx,dy,dz\n"},
  };
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: prism_fuzz_seeds SCENE_DIR CSV_DIR\n");
    return 2;
  }
  const fs::path scenes = argv[1], rays = argv[2];
  fs::create_directories(scenes);
  fs::create_directories(rays);
  write(scenes / "cli_valid.json", prism::cli_test::SceneText{}.text());
  for (const auto& bad : prism::cli_test::bad_scenes()) write(scenes / ("cli_" + bad.name + ".json"), bad.scene);
  for (const auto& [name, text] : ray_files()) write(rays / (name + ".csv"), text);
  return 0;
}
