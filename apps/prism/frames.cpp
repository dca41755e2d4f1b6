#include "frames.hpp"

#include <cstdio>

#include "bench/bench_run.hpp"
#include "prism/errors.hpp"
#include "prism/scene_loader.hpp"

namespace prism::cli {

std::filesystem::path frame_output(const std::filesystem::path& pattern, int index, int count) {
  if (count == 0) return pattern;
  std::string name = pattern.filename().string();
  const size_t first = name.find('#');
  const int digits = std::max(4, int(std::to_string(count - 1).size()));
  char number[32];
  if (first != std::string::npos) {
    const size_t run = name.find_first_not_of('#', first) == std::string::npos ? name.size() - first
                                                                                : name.find_first_not_of('#', first) - first;
    std::snprintf(number, sizeof number, "%0*d", std::max(int(run), digits), index);
    name.replace(first, run, number);
  } else {
    std::snprintf(number, sizeof number, "_%0*d", digits, index);
    const std::string stem = pattern.stem().string(), extension = pattern.extension().string();
    name = stem + number + extension;
  }
  return pattern.parent_path() / name;
}

FramePlan plan_frames(const Scene& scene, const std::string& output, int frames, double orbit_degrees,
                      const std::string& cameras_file) {
  FramePlan plan;
  if (!cameras_file.empty()) {
    if (frames > 0) throw InputError("--frames and --cameras: give one or the other");
    plan.cameras = load_cameras(cameras_file);
  } else if (frames > 0) {
    bench::check_orbit_degrees(orbit_degrees);
    const bench::FrameCameras orbit(scene, orbit_degrees / frames);
    for (int i = 0; i < frames; ++i) plan.cameras.push_back(orbit(i));
  } else {
    plan.cameras.push_back(scene.camera);
    plan.outputs.push_back(output);
    return plan;
  }
  const int count = int(plan.cameras.size());
  for (int i = 0; i < count; ++i) plan.outputs.push_back(frame_output(output, i, count));
  return plan;
}

}  // namespace prism::cli
