// The format's Whitted shading, once, for every CPU backend: an iterative
// loop over at most max_depth interactions with Schlick reflection,
// dielectrics, alpha pass-through, absorption and shadow rays.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "prism/cpu_render.hpp"

namespace prism {

enum RayKind { kCameraRay, kShadowRay, kReflectRay, kRefractRay, kPassRay, kShade1Ray, kRayKinds };
const char* ray_kind_name(int kind);

struct RayCounts {
  std::array<uint64_t, kRayKinds> n{};
  void add(const RayCounts& o) {
    for (int i = 0; i < kRayKinds; ++i) n[size_t(i)] += o.n[size_t(i)];
  }
};

struct SampleResult {
  glm::dvec3 radiance{0};
  int32_t first_id = kMissId;  // the `id` AOV
  uint32_t path_hash = 0;      // the `path` AOV (24 bits, exact in a float)
  // The `depth`, `normal` and `albedo` AOVs: the first hit's t, outward unit
  // normal and surface colour (a light sphere's: its colour); +inf, 0 and 0
  // on a miss.
  double first_t = kInfinity;
  glm::dvec3 first_normal{0};
  glm::dvec3 first_albedo{0};
};

// Where a frame's time goes (RenderSettings::profile), summed over threads.
enum Phase { kPhaseCameraRays, kPhaseSecondaryRays, kPhaseShadowRays, kPhaseShading, kPhases };
inline constexpr const char* kPhaseNames[] = {"camera_rays", "secondary_rays", "shadow_rays", "shading"};
struct PhaseProfile {
  std::array<double, kPhases> ms{};
  void add(const PhaseProfile& o) {
    for (size_t i = 0; i < ms.size(); ++i) ms[i] += o.ms[i];
  }
};

class Shader {
 public:
  // With a profile, the time of every query and of each whole sample is
  // added to it (shading: the sample's time less its queries). The clock
  // reads cost some 50 ns a ray, so a profiled frame runs a little slower.
  Shader(const Scene& scene, const ObjectQuery& query, RayCounts& counts, PhaseProfile* profile = nullptr)
      : scene_(scene),
        query_(query),
        counts_(counts),
        profile_(profile),
        entry_(query.entry()),
        sphere_lights_(lights_with_spheres(scene)),
        last_blocker_(scene.lights.size(), kMissId) {}
  SampleResult trace_sample(const Ray& camera_ray, int max_depth, bool want_path);
  // Closest hit with t > tmin over objects and visible light spheres (objects win ties).
  Hit closest(const Ray& ray, double tmin) const;

 private:
  struct Surface;  // shading data at one hit
  Surface surface_at(const Ray& ray, const Hit& hit) const;
  Hit with_light_spheres(const Hit& hit, const Ray& ray, double tmin) const;
  // The closest hit of a camera ray (kPhaseCameraRays) or of a secondary one.
  // `leaving`: an object a secondary ray cannot meet (left_behind), or kMissId.
  Hit closest_in_phase(const Ray& ray, Phase phase, int32_t leaving) const;
  int32_t left_behind(const Surface& s) const;
  void note_light_sphere(SampleResult& result, const Ray& ray, const Hit& hit) const;
  glm::dvec3 local_light(const Surface& s, const glm::dvec3& dir);
  glm::dvec3 shade1(const Ray& ray, int32_t leaving);
  // Whether an object blocks `ray` before `distance`; `self`: an object it cannot meet (or kMissId).
  bool shadowed(size_t light, const Ray& ray, double distance, int32_t self);
  void note(uint32_t value);

  const Scene& scene_;
  const ObjectQuery& query_;
  RayCounts& counts_;
  PhaseProfile* profile_;
  IntersectEntry entry_;  // query_.entry(), read once rather than by a virtual call per hit and shadow ray
  bool hashing_ = false;
  uint32_t hash_ = 0;
  std::vector<uint32_t> sphere_lights_;  // the lights whose sphere rays can meet
  std::vector<int32_t> last_blocker_;  // per light: the object that blocked its last shadow ray
};

}  // namespace prism
