// The format's Whitted shading, once, for every CPU backend: an iterative
// loop over at most max_depth interactions with Schlick reflection,
// dielectrics, alpha pass-through, absorption and shadow rays.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "prism/light_lanes.hpp"
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

// Traces camera samples in waves: every path of a batch takes its first
// bounce, then every path still going its second, and so on, so that one
// kind of work runs many times in a row (the queries of a wave, then its
// shading) instead of each sample's path being followed to its end. The
// local lighting of the shading points (the ambient, diffuse and Phong terms
// and their shadow rays) is computed in batches across points (LightLanes),
// so a sample's radiance is complete only when finish() has run. Every
// radiance is the sum the scalar shading forms, term by term in the same
// order (a sample's terms are taken in the order its path makes them, wave
// by wave), so neither the waves nor the batches change a bit. A sample that
// wants its path hash is traced as a wave of its own, its lighting computed
// at once (the hash records each shadow ray's answer in the order they are
// cast).
class Shader {
 public:
  // The samples a caller traces between finish() calls, as a rule (a 16x16
  // tile at 1 spp); more cost only memory.
  static constexpr size_t kSamplesPerFinish = 256;
  // With a profile, the time of every batch of queries and of each whole
  // wave is added to it (shading: the wave's time less its queries). The
  // clock reads cost some 50 ns each, so a profiled frame runs a little slower.
  Shader(const Scene& scene, const ObjectQuery& query, RayCounts& counts, PhaseProfile* profile = nullptr);
  ~Shader();
  Shader(const Shader&) = delete;
  Shader& operator=(const Shader&) = delete;
  // The camera rays traced until the next call lie in `cone` from `eye`:
  // the light spheres none of them can meet are not tested for them.
  void set_camera_cone(const glm::dvec3& eye, const glm::dvec3& axis, double cos_half);
  // The closest hits of camera rays, light spheres included: all at once,
  // so the query can share work between them (camera_closest_batch).
  void camera_hits(std::span<const Ray> rays, Hit* hits) const;
  // Traces camera samples whose first hits camera_hits() found; their
  // results are among finish()'s. want_path[j]: sample j wants its path hash.
  void trace_samples(std::span<const Ray> camera_rays, const Hit* camera_hits, const uint8_t* want_path, int max_depth);
  // Completes every sample traced since the last finish() and returns their
  // results in the order they were traced (valid until the next trace_samples).
  std::span<const SampleResult> finish();
  // Closest hit with t > tmin over objects and visible light spheres (objects win ties).
  Hit closest(const Ray& ray, double tmin) const;

 private:
  struct Surface;  // shading data at one hit
  // A sample's radiance is a sum of terms, each coef x value: the value a
  // known radiance (the sky, a light sphere) or a shading point's local
  // light, times an absorption factor where the ray ran inside a dielectric.
  struct Radiance {
    glm::dvec3 known{0};  // the radiance, or the absorption factor
    int32_t point = -1;   // the shading point in lanes_ (-1: known)
    bool absorbed = false;
  };
  struct Term {
    glm::dvec3 coef;
    Radiance value;
    uint32_t sample;  // whose radiance it adds to (an index into results_)
  };
  // A wave ray's path: what the ray's answer is worth to its sample (w),
  // and what to do with its hit (kind: kShade1Ray ends the path there).
  struct PathRay {
    glm::dvec3 w;
    uint32_t sample;
    int32_t kind;  // a RayKind
  };
  // The rays of one bounce, structure of arrays: the rays (as the query
  // takes them), the object each cannot meet (left_behind, or kMissId), and
  // their paths.
  struct Wave {
    std::vector<Ray> rays;
    std::vector<int32_t> leaving;
    std::vector<PathRay> paths;
    size_t size() const { return rays.size(); }
    bool empty() const { return rays.empty(); }
    void reserve(size_t n) {
      rays.reserve(n);
      leaving.reserve(n);
      paths.reserve(n);
    }
    void clear() {
      rays.clear();
      leaving.clear();
      paths.clear();
    }
    // Each field written in place (see add_known_term).
    void add(const Ray& ray, int32_t left, const glm::dvec3& w, uint32_t sample, int32_t kind) {
      rays.push_back(ray);
      leaving.push_back(left);
      PathRay& path = paths.emplace_back();
      path.w = w;
      path.sample = sample;
      path.kind = kind;
    }
  };
  // The surface at an object hit, in two steps: the plugin's answer in
  // the object's frame, then the surface written field by field into `s`,
  // all but its texture's part; apply_texture (for a textured material)
  // adds that: the colour times the texel, and the texel's alpha.
  void local_surface_at(const Ray& ray, const Hit& hit, LocalSurface& local) const;
  void surface_at(const Ray& ray, const Hit& hit, const LocalSurface& local, Surface& s) const;
  void apply_texture(Surface& s) const;
  // `hit` becomes the closest of `lights`' spheres where one is closer (its
  // prim is then unread).
  void add_light_spheres(Hit& hit, const Ray& ray, double tmin, std::span<const uint32_t> lights) const;
  // wave_hits_, wave_locals_ and wave_surfaces_ at least wave_'s size.
  void fit_wave_arrays();
  // The closest hits of the wave's rays, light spheres included, into wave_hits_.
  void wave_closest();
  int32_t left_behind(const Surface& s) const;
  void note_light_sphere(SampleResult& result, const Ray& ray, const Hit& hit) const;
  // The local light at s seen along dir: a point of the batch (its index).
  int32_t local_light(const Surface& s, const glm::dvec3& dir);
  // The paths of `camera_rays` followed to their ends, wave by wave.
  void trace_wave(std::span<const Ray> camera_rays, const Hit* camera_hits, int max_depth, bool hashing);
  // A wave ray's hit shaded: its terms added, the rays it spawns appended
  // to next_wave_ (a Shade1 ray, then the path's next ray unless `depth` is
  // the last).
  // `s`: the surface at an object hit (surface_at), unread for a miss.
  void shade_hit(const Ray& ray, const PathRay& path, const Hit& hit, const Surface& s, int depth, int max_depth);
  // A Shade1 ray's hit: the radiance it brings back (a single bounce).
  void shade1_hit(const Ray& ray, const PathRay& path, const Hit& hit, const Surface& s);
  void spawn_ray(const PathRay& from, const glm::dvec3& w, const Ray& ray, int32_t kind, int32_t leaving) {
    next_wave_.add(ray, leaving, w, from.sample, kind);
  }
  // The terms are written field by field into their element, never built
  // whole on the stack and copied: such a copy's 16-byte loads straddle the
  // fields' 8-, 4- and 1-byte stores and wait for them to retire (a
  // store-forwarding stall, ~2 % of a showcase frame by perf).
  void add_known_term(uint32_t sample, const glm::dvec3& coef, const glm::dvec3& known) {
    Term& term = terms_.emplace_back();
    term.coef = coef;
    term.value.known = known;
    term.sample = sample;
  }
  // coef x batch point `point`'s light, times `absorption` where given. The
  // light is computed at once when the path hash needs its shadow rays now.
  void add_point_term(uint32_t sample, const glm::dvec3& coef, int32_t point, const glm::dvec3* absorption = nullptr) {
    Term& term = terms_.emplace_back();
    term.coef = coef;
    term.value.point = point;
    term.sample = sample;
    if (absorption) {
      term.value.known = *absorption;
      term.value.absorbed = true;
    }
    if (hashing_) light_batch();
  }
  // Computes the batch's lights and puts them into the terms that wait for them.
  void light_batch();
  // The answers of the batch's shadow rays toward light k into its lanes'
  // `blocked`: the keyed rays' from `blockers`, the others' asked here.
  void take_shadow_answers_in_order(size_t k, const uint8_t* keyed, const int32_t* blockers);
  void take_shadow_answers(size_t k, const uint8_t* keyed, const int32_t* blockers);
  Ray unkeyed_shadow_ray(size_t j) const;  // lane j's shadow ray
  // Whether an object blocks `ray` before `distance`; `self`: an object it
  // cannot meet (or kMissId); `key`: the query's light_keys for the ray.
  bool shadowed(size_t light, const Ray& ray, double distance, int32_t self, int32_t key);
  void note(uint32_t value);

  const Scene& scene_;
  const ObjectQuery& query_;
  RayCounts& counts_;
  PhaseProfile* profile_;
  IntersectEntry entry_;  // query_.entry(), read once rather than by a virtual call per hit and shadow ray
  bool hashing_ = false;
  uint32_t hash_ = 0;
  std::vector<uint32_t> sphere_lights_;  // the lights whose sphere rays can meet
  std::vector<uint32_t> camera_sphere_lights_;  // those the camera rays can meet (set_camera_cone)
  std::vector<int32_t> last_blocker_;  // per light: the object that blocked its last shadow ray
  std::unique_ptr<LightLanes> lanes_;  // the shading points waiting for their light
  std::vector<SampleResult> results_;  // the samples traced since the last finish()
  std::vector<Term> terms_;            // every sample's, in the order their paths make them
  Wave wave_, next_wave_;                  // the rays of this bounce and of the next
  std::vector<Hit> wave_hits_;             // wave_'s closest hits (the first wave_.size())
  std::vector<LocalSurface> wave_locals_;  // the plugins' answers at them (object hits only)
  std::vector<Surface> wave_surfaces_;     // the surfaces at them (object hits only)
  size_t terms_lit_ = 0;  // terms_ before this index have every light computed
  bool finished_ = false;  // results_ were handed out by finish()
};

}  // namespace prism
