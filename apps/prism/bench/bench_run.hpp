// `prism bench`: frames rendered the way an interactive viewer renders them
// (scene prepared once, the camera orbiting a little every frame so no frame
// can be reused, each frame's time including the image's way back to the
// host), with the one-off costs, ray throughput per kind and the memory the
// backend holds while rendering. A library of its own so tests link it
// without the CLI.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "prism/backend.hpp"
#include "prism/registry.hpp"
#include "prism/scene.hpp"
#include "viewer/camera_controller.hpp"

namespace prism::bench {

struct Options {
  RenderSettings settings;    // image size, spp, depth (camera: set per frame)
  int frames = 20;            // measured frames
  int warmup = 2;             // frames before them (the first compiles a GPU kernel)
  double orbit_degrees = 0.25;  // camera yaw about its target per frame
  bool check = true;          // compare the last frame with a fresh render of its camera
  bool profile = false;       // time a frame's phases (RenderSettings::profile) and the image write
  Precision precision = Precision::automatic;  // --precision, set on every backend started
};

struct Memory {
  // Resident set after the scene was loaded (parse tree freed) and the
  // backend started, before prepare: the driver's own footprint is in it.
  int64_t loaded_bytes = -1;
  // Peak resident set over the measured frames (the peak is reset after the
  // warm-up, so a compiler's transient peak is left out).
  int64_t peak_bytes = -1;
  // What the backend says it holds for the scene (records, BVH, buffers); -1 unknown.
  int64_t scene_bytes = -1;
  int64_t frame_bytes = 0;  // the frame buffers: w * h * 3 floats (and the AOVs)
  int64_t growth() const { return peak_bytes - loaded_bytes; }
  // The bound: 4 x (packed scene data + frame buffers); -1 unknown.
  int64_t bound() const { return scene_bytes < 0 ? -1 : 4 * (scene_bytes + frame_bytes); }
};

struct Result {
  std::string backend;
  std::string skipped;  // why it did not run; empty when it ran
  std::string device;   // stats info.device, or the probe's description
  std::string precision;  // stats info.precision: what the intersectors computed in (--precision)
  double start_ms = 0, build_ms = 0, compile_ms = 0, first_frame_ms = 0;
  std::vector<double> frame_ms;                   // the measured frames
  // Processor time a measured frame took, all threads together (what a
  // loaded machine cannot inflate the way it inflates frame_ms).
  double cpu_ms_per_frame = 0;
  uint64_t rays = 0;                              // over the measured frames
  std::map<std::string, uint64_t> rays_by_kind;  // over the measured frames
  Memory memory;
  bool checked = false;
  double check_max_difference = 0;  // 0: bit-identical
  // With Options::profile: ms per measured frame by phase, summed over the
  // render threads ("camera_rays", ...; empty when the backend does not time
  // its phases), and the time to write the last frame as PNG and as EXR.
  std::map<std::string, double> profile_ms;
  double png_write_ms = 0, exr_write_ms = 0;

  double median_ms() const;
  double percentile_ms(double p) const;  // nearest rank over frame_ms
  double fps() const { return 1000.0 / median_ms(); }
  double rays_per_second() const;  // total rays of the measured frames over their total time
};

// InputError unless --orbit's degrees are a finite number (bench and render --frames).
void check_orbit_degrees(double degrees);

// The camera of frame `index` (0 = the scene's; negative: the other way, for
// warm-up frames): orbited about the point `prism view` orbits about, by
// `orbit_degrees` per frame.
class FrameCameras {
 public:
  FrameCameras(const Scene& scene, double orbit_degrees);
  Camera operator()(int index) const;

 private:
  Camera initial_;
  viewer::OrbitStart start_;
  double radians_per_frame_;
};

// Runs one backend. A backend that cannot run here comes back with
// `skipped` set; a failure while running throws RuntimeError.
Result run_backend(Registry& registry, const Scene& scene, const std::string& backend, const Options& options);

// Resident set size now and its peak, in bytes (Linux /proc/self/status), and
// a reset of the peak to the current size (/proc/self/clear_refs); -1 / false
// where the kernel does not offer them.
int64_t resident_bytes();
int64_t peak_resident_bytes();
bool reset_peak_resident();

}  // namespace prism::bench
