// What `prism render` renders: one image from the scene's camera, or a
// camera path (--frames N orbiting the scene, or --cameras FILE) written as
// a numbered image sequence. Shared by the single-process and MPI renders.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "prism/scene.hpp"

namespace prism::cli {

struct FramePlan {
  std::vector<Camera> cameras;                  // one per frame
  std::vector<std::filesystem::path> outputs;  // one per frame
};

// Frame `index` of `count`'s file: a run of '#' in the file name becomes the
// zero-padded index (`f_####.png` -> `f_0007.png`); without one, `_NNNN` is
// added before the extension. A single frame (count 0) is `pattern` itself.
std::filesystem::path frame_output(const std::filesystem::path& pattern, int index, int count);

// frames == 0 and no cameras file: the scene's camera to `output`. frames > 0:
// that many frames orbiting the point `prism view` orbits about, through
// `orbit_degrees` in all (frame 0 is the scene's camera). cameras_file: the
// cameras it lists (InputError names the JSON path of a bad one).
FramePlan plan_frames(const Scene& scene, const std::string& output, int frames, double orbit_degrees,
                      const std::string& cameras_file);

}  // namespace prism::cli
